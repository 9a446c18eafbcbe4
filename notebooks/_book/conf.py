"""Sphinx configuration of the eotrack book (``make book``).

Built with the repository root as Sphinx's source directory (so the notebooks' links to
``papers_repro/<slug>/REPORT.md`` resolve) and this folder as the configuration directory::

    sphinx-build -b html -E -a -W --keep-going -c notebooks/_book . build/book

* The stored notebooks are rendered as they are: nothing is executed (``nb_execution_mode``
  is ``"off"``), so the book shows exactly the outputs committed with each notebook.
* ``notebooks/00_index`` is the root page. Its table of contents is added here, at build
  time (``_on_source_read``), so the notebook itself stays a plain landing page in JupyterLab.
* LaTeX is typeset by MathJax 3 served from the book itself (``sphinx-mathjax-offline``):
  no page loads anything from the internet.
* Widgets: a notebook executed by ``.ci/execute_notebooks.py`` stores its widgets' state
  (``metadata.widgets``); the book renders it with ``@jupyter-widgets/html-manager``'s
  ``embed.js``, vendored in ``_static/widgets/`` (2 MB, committed: the npm registry is not
  reachable when the book is built or read). The panels then show their controls and the
  figure drawn at the stored setting; moving a control needs a live kernel (``make lab``).
  A notebook stored without widget state gets a note in place of each panel instead of an
  empty box, and its progress bars are dropped.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

project = "eotrack"
author = "eotrack contributors"
copyright = "eotrack contributors; code BSD-3-Clause, see Licences"

extensions = ["myst_nb", "sphinx-mathjax-offline", "sphinx.ext.autodoc", "sphinx.ext.napoleon"]

root_doc = "notebooks/00_index"
include_patterns = [
    "notebooks/*.ipynb",
    "notebooks/solutions/*.ipynb",
    "notebooks/_book/*.md",
    "notebooks/_book/api/*.md",
    "papers_repro/*/REPORT.md",
]
exclude_patterns = [".venv", "build", "**/.ipynb_checkpoints", "notebooks/py",
                    "notebooks/solutions/py", "README.md", "notebooks/_book/_static"]

# a book for a class: EOTRACK_BOOK_NO_SOLUTIONS=1 leaves the worked solutions out
NO_SOLUTIONS = os.environ.get("EOTRACK_BOOK_NO_SOLUTIONS", "") not in ("", "0")
if NO_SOLUTIONS:
    include_patterns.remove("notebooks/solutions/*.ipynb")
    exclude_patterns.append("notebooks/solutions")

# --- notebooks: render the stored outputs, execute nothing ---------------------------------
nb_execution_mode = "off"
nb_merge_streams = True
nb_ipywidgets_js = {"widgets/embed.js": {}}  # vendored; the default loads from a CDN
nb_render_markdown_format = "myst"  # Markdown outputs (computed tables, links) as MyST
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
# Jupyter renders $$...$$ inside a paragraph as display math; so must the book
myst_dmath_double_inline = True
# equation numbers are the paper's, written as \tag{} in the notebooks: no automatic numbering
mathjax3_config = {"tex": {"tags": "none"}}

# --- API reference (notebooks/_book/api/: one page per subpackage, numpydoc docstrings) ----
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True  # "Attributes" as a field list: no second description of dataclass fields
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "description"
autodoc_member_order = "groupwise"
autodoc_mock_imports: list[str] = []
suppress_warnings = ["autodoc.import_object"]

# --- HTML -----------------------------------------------------------------------------------
html_theme = "sphinx_book_theme"
html_title = "eotrack — EO space-tracking papers, reproduced"
html_static_path = ["_static"]
html_css_files = ["eotrack.css"]
html_theme_options = {
    "home_page_in_toc": True,
    "show_toc_level": 2,
    "use_download_button": True,
    "use_fullscreen_button": False,
    "navigation_with_keys": False,
    "show_navbar_depth": 1,
    # the index's tables need the width; other pages keep their "Contents" column
    "secondary_sidebar_items": {"**": ["page-toc"], "notebooks/00_index": []},
}
html_last_updated_fmt = None
html_copy_source = True  # the download button offers each page's .ipynb

# the book's sidebar, in reading order; solutions and reports are their own parts
_PARTS = [
    ("The course", "notebooks", re.compile(r"^\d\d_(?!index).*\.ipynb$")),
    ("Worked solutions", "notebooks/solutions", re.compile(r"^\d\d_.*\.ipynb$")),
]
if NO_SOLUTIONS:
    _PARTS.pop()


def _toctree_markdown() -> str:
    blocks = []
    for caption, folder, pat in _PARTS:
        rel = Path(folder).relative_to("notebooks")
        docs = sorted(p.stem for p in (ROOT / folder).glob("*.ipynb") if pat.match(p.name))
        if docs:
            entries = "\n".join(f"{rel / d}" if str(rel) != "." else d for d in docs)
            blocks.append(f"```{{toctree}}\n:hidden:\n:caption: {caption}\n\n{entries}\n```")
    reports = course_reports()
    if reports:
        entries = "\n".join(f"{title} </papers_repro/{slug}/REPORT>" for slug, title in reports)
        blocks.append(f"```{{toctree}}\n:hidden:\n:caption: Reproduction reports\n\n"
                      f"{entries}\n```")
    howtos = sorted(p.stem for p in HERE.glob("howto_*.md"))
    if howtos:  # how-to pages (e.g. howto_fits: real FITS frames through the pipeline)
        entries = "\n".join(f"/notebooks/_book/{h}" for h in howtos)
        blocks.append(f"```{{toctree}}\n:hidden:\n:caption: How-to guides\n\n{entries}\n```")
    blocks.append("```{toctree}\n:hidden:\n:caption: For teachers\n\n/notebooks/_book/teachers\n```")
    blocks.append("```{toctree}\n:hidden:\n:caption: Reference\n\n/notebooks/_book/api/index\n"
                  "/notebooks/_book/licences\n```")
    return "\n\n".join(blocks)


_CITATION = re.compile(r"^#\s*Reproduction report:\s*(?P<author>[^,]+),\s*(?P<second>[A-Z][a-z]+ [A-Z]\.)?")
_YEAR = re.compile(r"\b(?:19|20)\d\d\b")


def course_reports() -> list[tuple[str, str]]:
    """``(slug, sidebar title)`` of every REPORT, in the course's order (the order of the
    worked-solutions notebooks ``NN_<slug>_solutions``) and titled by paper: ``"01 · Yan L.J.
    et al. (2019)"``. Reports with no notebook come last, alphabetically."""
    order = {}
    for p in (ROOT / "notebooks" / "solutions").glob("[0-9][0-9]_*_solutions.ipynb"):
        order[p.stem[3:].removesuffix("_solutions")] = p.stem[:2]
    out = []
    for rep in sorted((ROOT / "papers_repro").glob("*/REPORT.md")):
        slug = rep.parent.name
        first = rep.read_text(encoding="utf-8").splitlines()[0] if rep.stat().st_size else ""
        m = _CITATION.match(first)
        years = _YEAR.findall(first.split("DOI")[0])
        paper = (f"{m['author'].strip()}{' et al.' if m['second'] else ''}"
                 f"{f' ({years[-1]})' if years else ''}") if m else slug
        nn = order.get(slug)
        out.append((nn or "99", slug, f"{nn} · {paper}" if nn else paper))
    return [(slug, title) for _, slug, title in sorted(out)]


_CONTROL = re.compile(r"Slider|Dropdown|Checkbox|ToggleButton|RadioButtons|interactive\(")
_PANEL_NOTE = ("<div class=\"admonition note eotrack-widget-note\"><p class=\"admonition-title\">"
               "Interactive panel</p><p>This panel needs a live Python kernel. Open the notebook "
               "in JupyterLab (<code>make lab</code>) to move the controls; the static book "
               "shows only its saved outputs.</p></div>")
#: the line under every panel whose saved state the book does render (controls shown, inert)
_LIVE_NOTE = ("<p class=\"eotrack-kernel-note\"><em>The controls of this panel need a live "
              "kernel: open the notebook in JupyterLab (<code>make lab</code>) to move them; "
              "here they show the saved setting only.</em></p>")
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"


def _is_panel(data: dict) -> bool:
    text = "".join(data.get("text/plain", ""))
    return bool(_CONTROL.search(text) or "eotrack-panel" in text or text.startswith("VBox"))


def _kernel_notes(nb: dict) -> None:
    """Put the live-kernel line under every panel rendered from saved widget state."""
    for cell in nb.get("cells", []):
        outs = []
        for out in cell.get("outputs", []):
            outs.append(out)
            data = out.get("data", {})
            if WIDGET_VIEW in data and _is_panel(data):
                outs.append({"output_type": "display_data", "metadata": {},
                             "data": {"text/html": _LIVE_NOTE,
                                      "text/plain": "needs a live kernel (make lab)"}})
        if "outputs" in cell:
            cell["outputs"] = outs


_HEADING = re.compile(r"^#{1,4}\s+(.+)$", re.MULTILINE)


def _alt_texts(nb: dict) -> None:
    """Alt text for every figure: its titles (the plain-text output that
    ``eotrack.plotting.register_figure_descriptions`` stores, "Figure: …"), else the section
    it stands under. Given to myst-nb as the cell's image option."""
    heading = nb.get("metadata", {}).get("title", "")
    for cell in nb.get("cells", []):
        if cell.get("cell_type") == "markdown":
            found = _HEADING.findall("".join(cell.get("source", "")))
            if found:
                heading = found[-1].strip()
            continue
        alts = []
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if not any(k.startswith("image/") for k in data):
                continue
            text = "".join(data.get("text/plain", "")).strip()
            if text.startswith("Figure"):
                alts.append(text)
            else:
                alts.append(f"Figure under “{heading}”" if heading else "Figure")
        if alts:
            md = cell.setdefault("metadata", {}).setdefault("mystnb", {})
            md.setdefault("image", {}).setdefault("alt", " / ".join(dict.fromkeys(alts)))


def _static_widgets(nb: dict) -> None:
    """Replace widget outputs that carry no saved state (see the module docstring)."""
    has_state = bool(nb.get("metadata", {}).get("widgets"))
    if has_state:
        _kernel_notes(nb)
        return
    for cell in nb.get("cells", []):
        outs = []
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if WIDGET_VIEW in data:
                if _is_panel(data):
                    outs.append({"output_type": "display_data", "metadata": {},
                                 "data": {"text/html": _PANEL_NOTE,
                                          "text/plain": "interactive panel"}})
                continue  # progress bars and other state-less widgets: nothing to show
            outs.append(out)
        if "outputs" in cell:
            cell["outputs"] = outs


#: what the kernel stores with each figure for the figure lint (eotrack.plotting.LINT_MIMETYPE;
#: not imported: the book builds without importing the library's plotting stack)
LINT_MIMETYPE = "application/vnd.eotrack.figure-lint+json"


def _drop_lint_records(nb: dict) -> None:
    """The figure lint's records are for ``tests/figures``, not for readers: drop them (myst-nb
    would warn about an output type it cannot show)."""
    for cell in nb.get("cells", []):
        for out in cell.get("outputs", []):
            out.get("data", {}).pop(LINT_MIMETYPE, None)


_REPORT_IMG = re.compile(r"!\[(?P<stem>[A-Za-z0-9_]+)\]\((?P<path>figures/[^)]+\.png)\)")


def _report_alt(source: str, paper: str) -> str:
    """REPORT figures: ``![fig1_min_samples](…)`` → alt text naming the paper and the figure."""
    def alt(m: re.Match) -> str:
        words = m["stem"].replace("_", " ")
        words = re.sub(r"^fig(\d)", r"Fig. \1", words)
        return f"![{paper}: {words}]({m['path']})"
    return _REPORT_IMG.sub(alt, source)


def _on_source_read(app, docname: str, source: list[str]) -> None:
    if docname.startswith("papers_repro/") and docname.endswith("/REPORT"):
        slug = docname.split("/")[1]
        titles = dict(course_reports())
        source[0] = _report_alt(source[0], titles.get(slug, slug).split(" · ")[-1])
        return
    if not docname.startswith("notebooks/"):
        return
    path = ROOT / f"{docname}.ipynb"
    if not path.is_file():
        return
    nb = json.loads(source[0])
    _drop_lint_records(nb)
    _static_widgets(nb)
    _alt_texts(nb)
    if docname == root_doc:
        nb["cells"].append({"cell_type": "markdown", "metadata": {}, "id": "eotrack-book-toc",
                            "source": _toctree_markdown()})
    source[0] = json.dumps(nb)


def _redirect(app, exc) -> None:
    """``build/book/index.html`` → the index notebook's page."""
    if exc is None and app.builder.name == "html":
        target = f"{root_doc}.html"
        (Path(app.outdir) / "index.html").write_text(
            f"<!DOCTYPE html><meta charset=\"utf-8\"><title>eotrack</title>"
            f"<meta http-equiv=\"refresh\" content=\"0; url={target}\">"
            f"<a href=\"{target}\">eotrack book</a>\n")


_TAG = re.compile(r"\\tag\*?\{[^{}]*\}")


def _tags_outside_split(app, doctree) -> None:
    """Display math with ``\\tag`` (the paper's equation numbers): Sphinx wraps a block that
    holds ``\\\\`` in ``split``, where MathJax refuses ``\\tag`` ("\\tag not allowed in
    split environment"). Such blocks are written out whole instead: ``equation*`` around a
    ``split`` of the body, the tag after the ``split``."""
    from docutils import nodes

    for node in list(doctree.findall(nodes.math_block)):
        if node.get("nowrap") or node.get("no-wrap"):
            continue
        text = node.astext()
        tags = _TAG.findall(text)
        if not tags:
            continue
        body = _TAG.sub("", text).strip()
        parts = [p.strip() for p in body.split("\n\n") if p.strip()]
        inner = " \\\\\n".join(parts)
        latex = (f"\\begin{{equation*}}\\begin{{split}}{inner}\\end{{split}}{tags[-1]}"
                 f"\\end{{equation*}}")
        node[:] = [nodes.Text(latex)]
        node["nowrap"] = True


def _escape_bars(app, what, name, obj, options, lines) -> None:
    """``|x − mean|`` in a docstring is an absolute value, not a reST substitution: escape the
    bars outside inline code and roles (so ``:math:`|x|``` keeps its bars)."""
    for i, line in enumerate(lines):
        if "|" not in line:
            continue
        parts = line.split("`")
        for k in range(0, len(parts), 2):
            parts[k] = re.sub(r"(?<!\\)\|", r"\\|", parts[k])
        lines[i] = "`".join(parts)


_SECTIONS = {"Parameters", "Other Parameters", "Returns", "Yields", "Raises", "Warns",
             "Attributes"}
_PARAM_LINE = re.compile(r"^[\w*][\w*, ]*(\s*:.*)?$")


def _stray_paragraphs(app, what, name, obj, options, lines) -> None:
    """A prose paragraph written inside a numpydoc field section (after the last parameter, at
    the section's indentation) breaks napoleon's field list ("Field list ends without a blank
    line"); give it a ``Notes`` heading of its own (runs before napoleon)."""
    section = None
    i = 0
    while i < len(lines):
        line = lines[i]
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() in _SECTIONS and set(nxt.strip()) == {"-"}:
            section = line.strip()
            i += 2
            continue
        if line.strip() and set(nxt.strip()) == {"-"}:
            section = None
        elif (section and line.strip() and not line.startswith((" ", "\t")) and i > 0
              and not lines[i - 1].strip() and not _PARAM_LINE.match(line.strip())):
            lines[i:i] = ["Notes", "-----"]
            section = None
            i += 2
        i += 1


def setup(app):
    app.connect("source-read", _on_source_read)
    app.connect("autodoc-process-docstring", _stray_paragraphs, priority=100)
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("doctree-read", _tags_outside_split)
    app.connect("build-finished", _redirect)
    return {"parallel_read_safe": True}
