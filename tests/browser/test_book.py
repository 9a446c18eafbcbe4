"""The book (``make book``): it builds with no warnings, and in headless Chromium every notebook
page shows its figures and typeset equations, loading nothing from the internet.

The book is built fresh into a temporary folder (about 15 s) from the stored notebooks; set
``EOTRACK_BOOK_DIR`` to test an already built book instead. Browser parts need Debian's
``chromium`` and the ``playwright`` package (as in ``test_jupyterlab.py``); without Chromium
they are skipped with that message unless ``EOTRACK_REQUIRE_BROWSER=1``. A screenshot of the
index is saved to ``build/book-index.png``.
"""

from __future__ import annotations

import functools
import json
import os
import re
import shutil
import threading
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = ROOT / "notebooks"
SCREENSHOT = ROOT / "build" / "book-index.png"
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync"]
# anything that would make a reader's browser fetch from the internet (links to click are fine)
REMOTE = re.compile(r"""<(?:script|img|iframe|source|audio|video|embed)\b[^>]*\ssrc\s*=\s*["']"""
                    r"""(?:https?:)?//|<link\b[^>]*\shref\s*=\s*["'](?:https?:)?//""", re.I)


def _pages() -> list[Path]:
    """Every notebook the book renders (lessons and solutions), relative to the repository."""
    nbs = sorted(NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"))
    nbs += sorted((NOTEBOOKS / "solutions").glob("[0-9][0-9]_*.ipynb"))
    return [p.relative_to(ROOT) for p in nbs]


def _image_outputs(nb_path: Path) -> int:
    nb = json.loads((ROOT / nb_path).read_text())
    return sum(1 for c in nb["cells"] for o in c.get("outputs", [])
               if any(k.startswith("image/") for k in o.get("data", {})))


def _widget_views(nb_path: Path) -> int:
    """Widget views whose state is saved in the notebook (0 when no state is stored)."""
    nb = json.loads((ROOT / nb_path).read_text())
    state = nb.get("metadata", {}).get("widgets", {}).get(
        "application/vnd.jupyter.widget-state+json", {}).get("state", {})
    if not state:
        return 0
    return sum(1 for c in nb["cells"] for o in c.get("outputs", [])
               if "application/vnd.jupyter.widget-view+json" in o.get("data", {}))


def _has_math(nb_path: Path) -> bool:
    nb = json.loads((ROOT / nb_path).read_text())
    return any(c["cell_type"] == "markdown" and ("$" in "".join(c["source"]))
               for c in nb["cells"])


@pytest.fixture(scope="module")
def book(book_build) -> Path:
    """The book, built by ``book_build`` (conftest.py: started while the JupyterLab tests run
    the lessons, or here if they did not run)."""
    given = os.environ.get("EOTRACK_BOOK_DIR")
    if given:
        out = Path(given)
        assert (out / "index.html").is_file(), f"EOTRACK_BOOK_DIR={given} has no index.html"
        return out
    code, err = book_build.wait()
    assert code == 0, f"the book build failed or warned:\n{err[-4000:]}"
    return book_build.out


def test_book_has_every_page_and_nothing_remote(book):
    assert (book / "index.html").is_file()
    pages = _pages()
    assert any(p.name == "00_index.ipynb" for p in pages), "notebooks/00_index.ipynb is missing"
    for nb in pages:
        html = book / nb.with_suffix(".html")
        assert html.is_file(), f"no page for {nb}"
    offenders = []
    for html in book.rglob("*.html"):
        for m in REMOTE.finditer(html.read_text(errors="replace")):
            offenders.append(f"{html.relative_to(book)}: {m.group(0)}")
    assert not offenders, "pages load from the internet:\n" + "\n".join(offenders[:20])
    assert (book / "_static" / "mathjax" / "tex-chtml.js").is_file(), "MathJax is not vendored"


# --- static checks of the built HTML (issue 23) ---------------------------------------------
#: every public subpackage (and module) of the library but the per-paper experiments
_LIB = ROOT / "lib" / "eotrack"
SUBPACKAGES = tuple(sorted(
    ({p.parent.name for p in _LIB.glob("*/__init__.py")} | {p.stem for p in _LIB.glob("*.py")})
    - {"experiments"} - {p.stem for p in _LIB.glob("_*.py")}))
#: pages whose figures are still shown below 80 % of their size (wider than 900 px), until
#: their owners redraw them narrower (house style: at most ~8.2 in at 110 dpi); value: owner
WIDE_FIGURES_XFAIL: dict[str, str] = {
}
MAX_NATIVE_PX = 900  # the 720 px column / 0.8


def _main(html: Path) -> str:
    t = html.read_text(errors="replace")
    return t[t.find("<main"):] if "<main" in t else t


def _content_pages() -> list[str]:
    pages = [p.with_suffix("").as_posix() for p in _pages()]
    pages += [f"papers_repro/{p.parent.name}/REPORT"
              for p in sorted((ROOT / "papers_repro").glob("*/REPORT.md"))]
    return pages


def test_no_tag_inside_split(book):
    """MathJax refuses \\tag inside split ("\\tag not allowed in split environment")."""
    bad = []
    for html in book.rglob("*.html"):
        for block in re.findall(r'<div class="math[^"]*"[^>]*>(.*?)</div>', html.read_text(
                errors="replace"), re.S):
            if re.search(r"\\begin\{split\}(?:(?!\\end\{split\}).)*\\tag", block, re.S):
                bad.append(f"{html.relative_to(book)}: {block[:80]}")
    assert not bad, "\\tag inside split (a MathJax error in the browser):\n" + "\n".join(bad[:10])


@pytest.mark.parametrize("nb", _pages(), ids=lambda p: p.stem)
def test_every_panel_says_it_needs_a_kernel(book, nb):
    data = json.loads((ROOT / nb).read_text())
    panels = sum(1 for c in data["cells"] for o in c.get("outputs", [])
                 if "application/vnd.jupyter.widget-view+json" in o.get("data", {})
                 and re.search(r"Slider|Dropdown|Checkbox|ToggleButton|VBox|interactive",
                               "".join(o["data"].get("text/plain", ""))))
    main = _main(book / nb.with_suffix(".html"))
    notes = main.count("eotrack-kernel-note") + main.count("eotrack-widget-note")
    assert notes >= panels, f"{nb}: {panels} panels but {notes} lines saying a kernel is needed"
    if panels:
        assert "make lab" in main


def test_api_reference_and_general_index(book):
    api = book / "notebooks" / "_book" / "api"
    for sub in SUBPACKAGES:
        page = api / f"eotrack.{sub}.html"
        assert page.is_file(), f"no API page for eotrack.{sub}"
        assert f'id="eotrack.{sub}.' in page.read_text(errors="replace"), (  # a documented object
            f"the API page of eotrack.{sub} documents no object")
    index = (book / "notebooks" / "00_index.html").read_text(errors="replace")
    assert "_book/api/index.html" in index, "the index does not link the API reference"
    gen = (book / "genindex.html").read_text(errors="replace")
    assert gen.count("<li><a href=") > 200, "the general index is (nearly) empty"


def test_reports_titled_by_paper_in_course_order(book):
    index = (book / "notebooks" / "00_index.html").read_text(errors="replace")
    links = re.findall(r'href="\.\./papers_repro/([a-z_]+)/REPORT\.html">([^<]+)<', index)
    titles = list(dict(links).items())
    assert titles, "the sidebar lists no reproduction report"
    numbers = [t.split(" · ")[0] for _, t in titles]
    assert numbers == sorted(numbers), f"reports not in the course's order: {titles}"
    for slug, title in titles:
        assert slug not in title and " · " in title, f"report {slug} titled {title!r}, not by paper"


def _lessons() -> list[Path]:
    return [p for p in _pages() if p.parent.name == "notebooks" and not p.name.startswith("00")]


@pytest.mark.parametrize("nb", _lessons(), ids=lambda p: p.stem)
def test_lesson_opens_and_ends_with_navigation(book, nb):
    """← previous · index · next →, as the first and the last thing of every lesson."""
    lessons = _lessons()
    i = lessons.index(nb)
    prev = lessons[i - 1].with_suffix(".html").name if i else "00_index.html"
    nxt = lessons[i + 1].with_suffix(".html").name if i + 1 < len(lessons) else None
    main = _main(book / nb.with_suffix(".html"))
    navs = [m.start() for m in re.finditer(r"<p>←", main)]
    assert len(navs) >= 2, f"{nb}: {len(navs)} navigation lines (want one first, one last)"
    # sections of the lesson: every h2 but the page's "Contents" and the introduction's
    # "Learning objectives" (the header: title, paper, objectives, then the navigation)
    headings = [m.start() for m in re.finditer(r"<h2[^>]*>(.*?)</h2>", main, re.S)
                if not re.search(r"Contents|Learning objectives", m.group(1))]
    assert navs[0] < headings[0] and navs[-1] > headings[-1], (
        f"{nb}: the navigation is not before the first and after the last section")
    for at in (navs[0], navs[-1]):
        line = main[at:main.find("</p>", at)]
        want = [prev, "00_index.html"] + ([nxt] if nxt else [])
        missing = [w for w in want if f'href="{w}' not in line]
        assert not missing, f"{nb}: navigation line lacks links to {missing}: {line[:200]}"


#: lessons stored before the navigation linked the API reference (issue 23): their next
#: execution (.ci/execute_notebooks.py) adds the link; then delete the entry. Empty since 03,
#: 04 and 07 were executed with the link (the check xpassed on a fresh clone, 2026-12-02).
API_LINK_PENDING: dict[str, str] = {}


@pytest.mark.parametrize("nb", _lessons(), ids=lambda p: p.stem)
def test_lesson_navigation_links_the_api_reference(book, nb, request):
    """Both navigation lines of a lesson end with a link to the API reference, and the link
    resolves to the reference's index page in the book."""
    if nb.stem in API_LINK_PENDING:
        request.applymarker(pytest.mark.xfail(
            reason=f"stored before the API link; owner {API_LINK_PENDING[nb.stem]} re-executes",
            strict=False))
    main = _main(book / nb.with_suffix(".html"))
    navs = [m.start() for m in re.finditer(r"<p>←", main)]
    lines = [main[at:main.find("</p>", at)] for at in (navs[0], navs[-1])] if navs else []
    assert lines and all(re.search(r'href="_book/api/index.html"><span[^>]*>API reference', ln)
                         for ln in lines), (
        f"{nb}: a navigation line lacks the API reference link")
    assert (book / "notebooks" / "_book" / "api" / "index.html").is_file()


def test_index_has_a_lab_sheet_per_lesson(book):
    main = _main(book / "notebooks" / "00_index.html")
    at = main.find('id="lab-sheets"')
    assert at >= 0, "the index has no Lab sheets section"
    table = main[at:main.find("</table>", at)]
    head = re.sub(r"<[^>]+>", "", table[:table.find("</thead>")]).lower()
    for col in ("run time", "difficulty", "prerequisites", "exercises to hand in"):
        assert col in head, f"the lab sheets have no column {col!r}"
    rows = []
    for tr in re.findall(r"<tr[^>]*>(.*?)</tr>", table[table.find("<tbody"):], re.S):
        rows.append([re.sub(r"<[^>]+>", "", c).strip()
                     for c in re.findall(r"<td[^>]*>(.*?)</td>", tr, re.S)])
    numbers = [r[0] for r in rows]
    assert numbers == [p.name[:2] for p in _lessons()], f"lab sheet rows {numbers}"
    for cells in rows:
        assert re.search(r"\d+(\.\d+)? min", cells[1]), f"lab {cells[0]}: no measured run time"
        assert cells[-1] not in ("", "—"), f"lab {cells[0]}: no exercises to hand in"
    assert "Rubric" in main and "full marks" in main, "the index has no grading rubric"
    assert "_book/teachers.html" in main, "the index does not link the teachers' page"


@pytest.mark.parametrize("page", _content_pages())
def test_figures_have_alt_text_and_full_size(book, page, request):
    from PIL import Image

    html = book / f"{page}.html"
    main = _main(html)
    imgs = re.findall(r"<img\b[^>]*>", main)
    no_alt = [i for i in imgs if not re.search(r'alt="[^"]+"', i)]
    assert not no_alt, f"{page}: {len(no_alt)} of {len(imgs)} figures have no alt text"
    wide = []
    for tag in imgs:
        m = re.search(r'src="([^"]+\.png)"', tag)
        path = (html.parent / m.group(1)).resolve() if m else None
        if path is not None and path.is_file():
            w = Image.open(path).width
            if w > MAX_NATIVE_PX:
                wide.append(w)
    if wide and page in WIDE_FIGURES_XFAIL:
        request.applymarker(pytest.mark.xfail(
            reason=f"figures still too wide, owner {WIDE_FIGURES_XFAIL[page]}", strict=False))
    assert not wide, (f"{page}: figures {wide} px wide are shown below 80 % of their size in the "
                      f"{MAX_NATIVE_PX * 0.8:.0f} px column")


@pytest.fixture(scope="module")
def chromium() -> str:
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        msg = ("browser test skipped: Chromium not found. To run it: `sudo apt-get install "
               "chromium` (Debian/Ubuntu), then `make browser`.")
        if os.environ.get("EOTRACK_REQUIRE_BROWSER") == "1":
            pytest.fail(msg)
        pytest.skip(msg)
    pytest.importorskip("playwright", reason="the playwright Python package is not installed")
    return path


@pytest.fixture(scope="module")
def server(book):
    handler = functools.partial(_QuietHandler, directory=str(book))
    httpd = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()
    httpd.server_close()


class _QuietHandler(SimpleHTTPRequestHandler):
    def log_message(self, *args) -> None:  # keep pytest's output clean
        pass


@pytest.fixture(scope="module")
def browser(chromium):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=chromium, args=CHROMIUM_FLAGS)
        yield b
        b.close()


# the page's prose (code cells and typeset math removed): raw LaTeX must not survive in it
_PROSE_TEXT = """() => {
  const main = document.querySelector("main").cloneNode(true);
  main.querySelectorAll("pre, code, script, mjx-container, .cell_input").forEach(e => e.remove());
  return main.innerText;
}"""


def _open(browser, url: str):
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.set_default_timeout(60_000)
    requests: list[str] = []
    page.on("request", lambda r: requests.append(r.url))
    resp = page.goto(url, wait_until="load")
    assert resp is not None and resp.ok, f"{url}: HTTP {resp.status if resp else 'no answer'}"
    # MathJax 3 typesets asynchronously; Sphinx loads it only on pages with math
    if page.locator("script[src*='mathjax']").count():
        page.wait_for_function(
            "() => window.MathJax && MathJax.startup && MathJax.startup.promise")
        page.evaluate("() => MathJax.startup.promise.then(() => true)")
    return page, requests


def _mathjax_errors(page) -> list[str]:
    return page.eval_on_selector_all("main mjx-merror", "els => els.map(e => e.getAttribute("
                                     "'data-mjx-error') || e.textContent)")


def test_reference_and_teacher_pages_typeset_without_error(browser, server, book):
    """The pages that are neither notebooks nor reports (API reference, teachers, licences):
    every equation typeset, no MathJax error."""
    pages = sorted(p for p in (book / "notebooks" / "_book").rglob("*.html"))
    assert pages, "the book has no reference or teachers' pages"
    bad = []
    for html in pages:
        if 'class="math' not in html.read_text(errors="replace"):
            continue
        page, _ = _open(browser, f"{server}/{html.relative_to(book).as_posix()}")
        try:
            n_math = page.locator("main .math").count()
            n_typeset = page.locator("main mjx-container").count()
            errors = _mathjax_errors(page)
            if errors or n_typeset < n_math:
                bad.append(f"{html.relative_to(book)}: {n_math} equations, {n_typeset} typeset, "
                           f"errors {errors[:3]}")
        finally:
            page.close()
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("nb", _pages(), ids=lambda p: p.stem)
def test_page_shows_figures_and_typeset_math(browser, server, nb):
    page, requests = _open(browser, f"{server}/{nb.with_suffix('.html').as_posix()}")
    try:
        text = page.evaluate(_PROSE_TEXT)
        assert "$$" not in text, f"{nb}: raw $$ left in the page"
        assert not re.search(r"\\\[|\\begin\{", text), f"{nb}: raw LaTeX left in the page"
        n_math = page.locator("main .math").count()
        n_typeset = page.locator("main mjx-container").count()
        if _has_math(nb):
            assert n_math > 0, f"{nb}: the notebook has LaTeX but the page no math elements"
        assert n_typeset >= n_math, f"{nb}: {n_math} equations but {n_typeset} typeset by MathJax"
        errors = _mathjax_errors(page)
        assert not errors, f"{nb}: MathJax errors: {errors[:5]}"
        want = _image_outputs(nb)
        imgs = page.eval_on_selector_all(
            "main img", "els => els.filter(e => e.complete && e.naturalWidth > 0).length")
        if want:
            assert imgs >= want, f"{nb}: {want} image outputs, {imgs} images shown"
        if _widget_views(nb):  # saved widget state is rendered by the vendored html-manager
            page.locator("main .jupyter-widgets").first.wait_for(state="attached")
        # data: and blob: URLs are made in the page (a panel's saved PNG becomes a blob: URL)
        remote = [u for u in requests if not u.startswith((server, "data:", f"blob:{server}"))]
        assert not remote, f"{nb}: requests left the machine: {remote[:5]}"
    finally:
        page.close()


@pytest.mark.parametrize("slug", sorted(p.parent.name for p in
                                        (ROOT / "papers_repro").glob("*/REPORT.md")))
def test_report_pages_show_their_figures(browser, server, slug):
    page, requests = _open(browser, f"{server}/papers_repro/{slug}/REPORT.html")
    try:
        want = len(re.findall(r"!\[", (ROOT / "papers_repro" / slug / "REPORT.md").read_text()))
        shown = page.eval_on_selector_all(
            "main img", "els => els.filter(e => e.complete && e.naturalWidth > 0).length")
        assert shown >= want, f"{slug}: REPORT links {want} figures, the page shows {shown}"
        errors = _mathjax_errors(page)
        assert not errors, f"{slug}: MathJax errors: {errors[:5]}"
        assert all(u.startswith(server) or u.startswith("data:") for u in requests)
    finally:
        page.close()


def test_index_page_links_every_notebook_and_screenshot(browser, server):
    page, _ = _open(browser, f"{server}/index.html")  # the redirect lands on the index
    try:
        page.wait_for_url("**/notebooks/00_index.html")
        assert "start here" in page.title().lower() or "eotrack" in page.title().lower()
        nav = page.locator("nav.bd-links a.reference.internal")
        hrefs = {a.get_attribute("href") for a in nav.all()}
        for nb in _pages():
            if nb.stem == "00_index":
                continue
            name = nb.with_suffix(".html").name
            assert any(h and h.endswith(name) for h in hrefs), f"sidebar has no link to {nb}"
        tables = page.locator("main table")
        assert tables.count() >= 2, "the index should show the learning path and the scorecard"
        SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SCREENSHOT), full_page=False)
        assert SCREENSHOT.stat().st_size > 10_000
    finally:
        page.close()
