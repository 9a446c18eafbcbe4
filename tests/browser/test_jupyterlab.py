"""A real browser: JupyterLab in headless Chromium runs every notebook and moves every panel.

For each ``notebooks/0[1-9]*.ipynb`` (a copy in a temporary tree shaped like the repository, so
``../papers_repro`` paths resolve): clear the outputs, run all cells, then

- no error and no stderr output anywhere (cell outputs and the panels' output widgets; Python
  warnings go to stderr, so a warning fails too — its text is in the failure message);
- no stray ``<function ...>`` or ``(<Figure size ...>`` text;
- every cell nbval checks (``# NBVAL_CHECK_OUTPUT``) has the stored notebook's outputs, compared
  as nbval compares them (``stored_outputs.py``: nbval's own stream joining, sanitizers and
  comparison); ``.ci/run`` runs this stage with AVX-512 off where the host has it, which makes
  this the AVX-512-off comparison of the lessons. The kernel must see this process's
  ``.ci/avx512_off.py`` variables, and numpy in it must report those targets off;
- every panel (``.eotrack-panel``, and ``.widget-interact`` for notebooks not yet converted):
  move each of its controls ``$EOTRACK_BROWSER_MOVES`` times (default 3; slider: one step
  right, then back left, ...; dropdown: the next option, as many times as it has options if
  that is more; toggle: click), and after each move the figure image must change. Each
  change-to-settled time (image replaced and the kernel idle again, from the user's action) is
  recorded; the median and the slowest move per control are printed as a table at the end of
  the run, also written to ``$EOTRACK_BROWSER_LATENCY`` (default
  ``/tmp/eotrack-browser-latency.txt``). A benchmark, not a timed assertion.
  ``test_panel_floor`` times a panel whose figure costs almost nothing the same way: the
  front end's share of every other row.

Notebooks run in one JupyterLab server, ``$EOTRACK_BROWSER_PARALLEL`` at a time (default 2),
each in its own tab, longest first (``tests/file_durations.json``); the panels are timed
afterwards, one notebook at a time, with every other kernel idle.
``EOTRACK_BROWSER_NOTEBOOKS="02_epipolar_association 00_index"`` limits the notebooks (of these
tests and of the open-and-save ones) to those stems, for development.

``test_open_save_keeps_files`` opens each stored notebook (and a small panel notebook executed
by ``.ci/execute_notebooks.py``) with its ``.py`` twin and the repository's jupytext pairing,
and saves it with Ctrl+S: neither file may change, and the notebook must not be marked
modified on open (once its kernel's info and spec are in). All are opened, one after the other,
in one JupyterLab page.

Needs Debian's ``chromium`` (``apt-get install chromium``) and the ``playwright`` Python package
(driving that Chromium through ``executable_path``; ``playwright install`` is never used, it
downloads). Without Chromium the tests are skipped with that message, unless
``EOTRACK_REQUIRE_BROWSER=1`` (set by CI), which turns the skip into a failure.
"""

from __future__ import annotations

import difflib
import importlib.util
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from stored_outputs import compare_cells

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
# EOTRACK_BROWSER_NOTEBOOKS="02_epipolar_association 00_index": only these (stems; development)
_ONLY = set(os.environ.get("EOTRACK_BROWSER_NOTEBOOKS", "").replace(",", " ").split())
NOTEBOOKS = [p for p in sorted((ROOT / "notebooks").glob("0[1-9]*.ipynb"))
             if not _ONLY or p.stem in _ONLY]
STORED = [p for p in sorted((ROOT / "notebooks").glob("[0-9]*.ipynb"))  # the index too
          if not _ONLY or p.stem in _ONLY]
# the variables .ci/avx512_off.py may set; the kernels must see the same values as this process
AVX512_OFF_VARS = ("NPY_DISABLE_CPU_FEATURES", "OPENBLAS_CORETYPE", "OPENCV_CPU_DISABLE")
KERNEL_CPU_CHECK = """\
import json, os
try:
    from numpy._core._multiarray_umath import __cpu_features__ as f
except ImportError:
    from numpy.core._multiarray_umath import __cpu_features__ as f
names = os.environ.get("NPY_DISABLE_CPU_FEATURES", "").split()
print(json.dumps({"env": {k: os.environ.get(k) for k in VARS},
                  "off": [n for n in names if not f.get(n)],
                  "still_on": [n for n in names if f.get(n)]}))
""".replace("VARS", repr(AVX512_OFF_VARS))
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync"]
PARALLEL = max(1, int(os.environ.get("EOTRACK_BROWSER_PARALLEL", "2")))
RUN_TIMEOUT_S = float(os.environ.get("EOTRACK_BROWSER_RUN_TIMEOUT", "1200"))
SETTLE_TIMEOUT_S = 60.0
MOVES = max(1, int(os.environ.get("EOTRACK_BROWSER_MOVES", "3")))
PANELS = ".eotrack-panel, .widget-interact"
STRAY = ("<function ", "(<Figure size")
TOKEN = "eotrack-browser-test"
# JupyterLab settings for the test server: every cell in the DOM, no autosave, no news toast
LAB_SETTINGS = {
    "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {"windowingMode": "none"},
    "@jupyterlab/docmanager-extension/plugin.jupyterlab-settings": {"autosave": False},
    "@jupyterlab/apputils-extension/notification.jupyterlab-settings": {
        "fetchNews": "false", "checkForUpdates": False},
}

# -- JavaScript run in the JupyterLab page (the app is exposed: expose_app_in_browser) ------
JS_STATUS = """() => {
  const app = window.jupyterapp;
  const p = app && app.shell.currentWidget;
  if (!p || !p.content || !p.sessionContext) return null;
  const s = p.sessionContext.session;
  const k = s && s.kernel;
  const cells = p.content.widgets.filter(c => c.model.type === 'code');
  return {kernel: k ? k.status : 'none',
          total: cells.length,
          done: cells.filter(c => c.model.executionCount !== null).length,
          running: cells.filter(c => c.model.executionState === 'running').length,
          dirty: p.context.model.dirty};
}"""
JS_SETTLED = """([panel, before]) => {
  const imgs = panel.querySelectorAll('img');
  const src = imgs.length ? imgs[imgs.length - 1].getAttribute('src') : null;
  const p = window.jupyterapp.shell.currentWidget;
  const k = p.sessionContext.session.kernel;
  if (src && src !== before && k.status === 'idle') return performance.now();
  return false;
}"""
JS_CELLS = """() => window.jupyterapp.shell.currentWidget.content.widgets
  .filter(c => c.model.type === 'code')
  .map(c => ({source: c.model.sharedModel.getSource(), outputs: c.model.outputs.toJSON()}))"""
JS_KERNEL_RUN = """async (code) => {
  const k = window.jupyterapp.shell.currentWidget.sessionContext.session.kernel;
  let out = '';
  const f = k.requestExecute({code, store_history: false});
  f.onIOPub = m => {
    if (m.header.msg_type === 'stream') out += m.content.text;
    if (m.header.msg_type === 'error') out += m.content.ename + ': ' + m.content.evalue;
  };
  await f.done;
  return out;
}"""
JS_TOP_PANELS = """(sel) => Array.from(document.querySelectorAll(sel))
  .filter(el => !(el.parentElement && el.parentElement.closest(sel)))
  .map((el, i) => { el.setAttribute('data-eotrack-panel', String(i)); return i; })"""


def _chromium() -> str | None:
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _ci_module(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / ".ci" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def chromium() -> str:
    path = _chromium()
    if path is None:
        msg = ("browser test skipped: Chromium not found. To run it: `sudo apt-get install "
               "chromium` (Debian/Ubuntu), then `make browser`.")
        if os.environ.get("EOTRACK_REQUIRE_BROWSER") == "1":
            pytest.fail(msg)
        pytest.skip(msg)
    pytest.importorskip("playwright", reason="the playwright Python package is not installed")
    return path


@dataclass
class Lab:
    base: str
    work: Path


@pytest.fixture(scope="module")
def lab(chromium, tmp_path_factory):
    """One JupyterLab server over a temporary tree shaped like the repository."""
    work = tmp_path_factory.mktemp("lab")
    (work / "notebooks").mkdir()
    for nb in NOTEBOOKS:
        shutil.copy(nb, work / "notebooks" / nb.name)
    for d in ("papers_repro", "data"):
        if (ROOT / d).is_dir():
            shutil.copytree(ROOT / d, work / d)
    settings = tmp_path_factory.mktemp("lab-settings")
    for rel, value in LAB_SETTINGS.items():
        f = settings / rel
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text(json.dumps(value))
    port = _free_port()
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}  # kernels plot inline
    env["EOTRACK_PAPERS_REPRO"] = str(work / "papers_repro")  # a notebook never writes the repo
    cmd = [sys.executable, "-m", "jupyterlab", "--no-browser", f"--port={port}",
           "--ip=127.0.0.1", f"--IdentityProvider.token={TOKEN}",
           f"--ServerApp.root_dir={work}", "--LabApp.expose_app_in_browser=True",
           f"--LabApp.user_settings_dir={settings}",
           f"--LabApp.workspaces_dir={tmp_path_factory.mktemp('lab-workspaces')}"]
    if os.geteuid() == 0:
        cmd.append("--allow-root")
    log = open(work.parent / "lab-server.log", "wb")
    proc = subprocess.Popen(cmd, cwd=work, env=env, stdout=log, stderr=subprocess.STDOUT)
    base = f"http://127.0.0.1:{port}"
    deadline = time.time() + 120
    while time.time() < deadline:
        try:
            urllib.request.urlopen(f"{base}/api/status?token={TOKEN}", timeout=2)
            break
        except OSError:
            if proc.poll() is not None:
                raise RuntimeError((work.parent / "lab-server.log").read_text()) from None
            time.sleep(0.5)
    else:
        proc.kill()
        raise RuntimeError("JupyterLab did not start within 120 s")
    yield Lab(base, work)
    proc.terminate()
    try:
        proc.wait(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
    log.close()


@pytest.fixture(scope="module")
def browser(lab, chromium):
    from playwright.sync_api import sync_playwright

    pw = sync_playwright().start()
    b = pw.chromium.launch(executable_path=chromium, args=CHROMIUM_FLAGS)
    yield b
    b.close()
    pw.stop()


def _open(browser, lab: Lab, rel: str, workspace: str):
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.set_default_timeout(120_000)
    page.goto(f"{lab.base}/lab/workspaces/{workspace}/tree/{rel}?token={TOKEN}")
    page.locator(".jp-NotebookPanel").first.wait_for()
    page.wait_for_function(f"({JS_STATUS})() && ({JS_STATUS})().kernel === 'idle'",
                           timeout=180_000)
    page.wait_for_timeout(2000)  # let the kernel connection settle before queueing cells
    return page


@dataclass
class Run:
    name: str
    page: object = None
    started: float = 0.0
    quiet: float = 0.0  # since when nothing has changed
    seconds: float = float("nan")
    status: dict = field(default_factory=dict)
    error: str = ""


def _selected(request) -> list[str]:
    names = []
    for item in request.session.items:
        cs = getattr(item, "callspec", None)
        if item.module.__name__ == __name__ and cs and "notebook" in cs.params:
            names.append(cs.params["notebook"])
    return names


@pytest.fixture(scope="module")
def runs(request, browser, lab, run_rows, book_build) -> dict[str, Run]:
    """Open the selected notebooks and run all their cells, PARALLEL tabs at a time (and build
    the book meanwhile if its tests are selected: it is done before any panel is timed)."""
    if not os.environ.get("EOTRACK_BOOK_DIR") and any(
            Path(str(it.fspath)).name == "test_book.py" for it in request.session.items):
        book_build.start()
    # longest first (seconds per notebook from tests/file_durations.json, `make durations`): the
    # two tabs finish together instead of one long notebook running alone at the end
    seconds = json.loads((ROOT / "tests" / "file_durations.json").read_text())["seconds"]
    queue = [Run(n) for n in sorted(_selected(request),
                                    key=lambda n: -seconds.get(f"notebooks/{n}", 1e9))]
    active: list[Run] = []
    done: dict[str, Run] = {}
    t_all = time.perf_counter()
    while queue or active:
        while queue and len(active) < PARALLEL:
            r = queue.pop(0)
            try:
                r.page = _open(browser, lab, f"notebooks/{r.name}", r.name.split("_")[0])
                # (no `return`: execute's promise resolves only when every cell has run)
                r.page.evaluate("async () => { await window.jupyterapp.commands.execute("
                                "'notebook:clear-all-cell-outputs'); }")
                r.page.evaluate("() => { window.jupyterapp.commands.execute("
                                "'notebook:run-all-cells'); }")
                r.started = r.quiet = time.perf_counter()
                active.append(r)
            except Exception as exc:
                r.error = f"could not open and start {r.name}: {exc}"
                done[r.name] = r
        time.sleep(0.5)
        for r in list(active):
            st = r.page.evaluate(JS_STATUS) or {}
            now = time.perf_counter()
            busy = st.get("kernel") != "idle" or st.get("running", 1) > 0
            if busy or st != r.status:
                r.quiet = now
            r.status = st
            # every cell run and the kernel idle: done (one more poll to see it stays so); an
            # error stops the run with cells unrun: done after 3 s without change
            wait = 0.4 if st.get("total") and st.get("done") == st.get("total") else 3.0
            finished = not busy and now - r.quiet > wait
            if finished or now - r.started > RUN_TIMEOUT_S:
                r.seconds = now - r.started - (wait if finished else 0.0)
                if not finished:
                    r.error = f"{r.name}: still running after {RUN_TIMEOUT_S:.0f} s ({st})"
                active.remove(r)
                done[r.name] = r
    wall = time.perf_counter() - t_all
    print(f"\n[browser] ran {len(done)} notebook(s) in {wall:.0f} s ({PARALLEL} tab(s) at a time)")
    if book_build.started():  # (its result is checked by test_book.py)
        t0 = time.perf_counter()
        book_build.wait()
        print(f"[browser] waited {time.perf_counter() - t0:.0f} s for the book build")
    run_rows.extend({"notebook": r.name, "run_s": r.seconds} for r in done.values())
    run_rows.append({"notebook": f"(all, {PARALLEL} tabs at a time)", "run_s": wall})
    yield done
    for r in done.values():
        if r.page is not None:
            r.page.close()


def _output_problems(page) -> list[str]:
    problems = []
    stderr = page.locator(".jp-NotebookPanel .jp-OutputArea-output"
                          "[data-mime-type='application/vnd.jupyter.stderr']")
    for i in range(stderr.count()):
        text = stderr.nth(i).inner_text()
        kind = "error" if "Traceback" in text or "Error" in text.split("\n")[0] else "stderr"
        problems.append(f"{kind} output: {text.strip()[:600]}")
    outputs = page.locator(".jp-NotebookPanel .jp-OutputArea-output")
    texts = outputs.evaluate_all("els => els.map(e => e.innerText)")
    for text in texts:
        for s in STRAY:
            if s in text:
                line = next(x for x in text.splitlines() if s in x)
                problems.append(f"stray repr in an output: {line.strip()[:200]}")
    return problems


@dataclass
class Control:
    """One control of a panel: ``prepare()`` (untimed look-ups and focus), then ``move(k)``, the
    user's k-th action (slider: one step right, then back left, ...; dropdown: the next
    option, cycling; toggle and checkbox: a click), ``moves`` times."""
    what: str
    prepare: object
    move: object
    moves: int
    element: object = None

    def disabled(self) -> bool:
        return bool(self.element.evaluate(
            "el => el.matches('[disabled]') || !!el.querySelector('[disabled]')"))


def _controls(page, panel) -> list[Control]:
    found = panel.locator(".widget-slider, .widget-toggle-button, .widget-checkbox, "
                          ".widget-dropdown")
    if found.count() == 0:
        raise AssertionError("panel has no slider, toggle, checkbox or dropdown")
    out = []
    for j in range(found.count()):
        control = found.nth(j)
        classes = control.get_attribute("class") or ""
        label = control.locator(".widget-label").first
        name = label.inner_text().strip() if label.count() else "?"
        if "widget-slider" in classes:
            handle = control.locator(".noUi-handle").first
            now, hi = handle.get_attribute("aria-valuenow"), handle.get_attribute("aria-valuemax")
            keys = ("ArrowLeft", "ArrowRight") if now is not None and now == hi else \
                ("ArrowRight", "ArrowLeft")
            out.append(Control(f"slider {name!r} {keys[0]}/{keys[1]}", handle.focus,
                               lambda k, keys=keys: page.keyboard.press(keys[k % 2]), MOVES,
                               control))
        elif "widget-dropdown" in classes:
            select = control.locator("select")
            n = select.locator("option").count()
            i = select.evaluate("s => s.selectedIndex")
            out.append(Control(f"dropdown {name!r} (all {n} options)", lambda: None,
                               lambda k, select=select, i=i, n=n:
                               select.select_option(index=(i + 1 + k) % n), max(MOVES, n),
                               control))
        elif "widget-checkbox" in classes:
            box = control.locator("input")
            out.append(Control(f"checkbox {name!r}", lambda: None,
                               lambda k, box=box: box.click(), MOVES, control))
        else:
            out.append(Control(f"toggle {control.inner_text().strip()!r}", lambda: None,
                               lambda k, control=control: control.click(), MOVES, control))
    return out


def _settle(page) -> None:
    """Wait (untimed) for the kernel to finish what a move started."""
    page.wait_for_timeout(400)
    page.wait_for_function(f"({JS_STATUS})().kernel === 'idle'", timeout=SETTLE_TIMEOUT_S * 1000)
    page.wait_for_timeout(300)


def _enable(page, panel, c: Control):
    """A greyed-out control (``enabled_when``): select other dropdowns' options (untimed) until
    it is enabled. Returns a function restoring them, or None if no option enables it."""
    selects = panel.locator(".widget-dropdown select")
    for j in range(selects.count()):
        select = selects.nth(j)
        i0 = select.evaluate("s => s.selectedIndex")
        for i in range(select.locator("option").count()):
            if i == i0:
                continue
            select.select_option(index=i)
            _settle(page)
            if not c.disabled():
                def restore(select=select, i0=i0):
                    select.select_option(index=i0)
                    _settle(page)
                return restore
        select.select_option(index=i0)
        _settle(page)
    return None


def _panel_latencies(page, notebook: str, rows: list[dict]) -> list[str]:
    """Move every control of every panel; record each change-to-settled time."""
    problems = []
    n = len(page.evaluate(JS_TOP_PANELS, PANELS))
    if n == 0:
        problems.append("no widget panel found (.eotrack-panel / .widget-interact)")
    for i in range(n):
        panel = page.locator(f"[data-eotrack-panel='{i}']")
        panel.scroll_into_view_if_needed()
        imgs = panel.locator("img")
        deadline = time.time() + 60
        while imgs.count() == 0 and time.time() < deadline:
            page.wait_for_timeout(250)
        if imgs.count() == 0:
            problems.append(f"panel {i}: shows no figure")
            continue
        try:
            controls = _controls(page, panel)
        except Exception as exc:
            problems.append(f"panel {i}: could not find a control: {exc}")
            continue
        for c in controls:
            times = []
            restore = None
            if c.disabled():
                restore = _enable(page, panel, c)
                if restore is None:
                    problems.append(f"panel {i}: {c.what} is disabled in every state reached")
                    continue
                c.what += " (enabled first)"
            for k in range(c.moves):
                before = imgs.last.get_attribute("src")
                c.prepare()
                page.wait_for_timeout(300)
                t0 = page.evaluate("performance.now()")
                try:
                    c.move(k)
                except Exception as exc:
                    problems.append(f"panel {i}: could not move {c.what}: {exc}")
                    break
                try:
                    t1 = page.wait_for_function(JS_SETTLED, arg=[panel.element_handle(), before],
                                                polling="raf", timeout=SETTLE_TIMEOUT_S * 1000)
                    times.append((t1.json_value() - t0) / 1000)
                except Exception:
                    times.append(float("nan"))
                    problems.append(f"panel {i}: the figure did not change within "
                                    f"{SETTLE_TIMEOUT_S:.0f} s after move {k + 1} of {c.what}")
                    break
            if times:
                rows.append({"notebook": notebook, "panel": i, "control": c.what,
                             "settled_s": times})
            if restore is not None:
                restore()
    return problems


def _kernel_cpu_problems(page, notebook: str) -> list[str]:
    """The notebook's kernel sees this process's AVX-512-off variables, and numpy in it
    reports the named dispatch targets off (as .ci/run checks in its own process)."""
    try:
        info = json.loads(page.evaluate(JS_KERNEL_RUN, KERNEL_CPU_CHECK))
    except Exception as exc:
        return [f"could not read the kernel's CPU features: {exc}"]
    want = {k: os.environ.get(k) for k in AVX512_OFF_VARS}
    problems = []
    if info["env"] != want:
        problems.append(f"the kernel's environment {info['env']} is not this process's {want}")
    if info["still_on"]:
        problems.append(f"numpy in the kernel still uses {info['still_on']}: "
                        "NPY_DISABLE_CPU_FEATURES had no effect")
    if want["NPY_DISABLE_CPU_FEATURES"]:
        print(f"\n[browser] {notebook}: kernel numpy reports switched off: "
              f"{' '.join(info['off']) or 'nothing'}")
    return problems


@pytest.mark.parametrize("notebook", [p.name for p in NOTEBOOKS])
def test_notebook_runs_and_panels_redraw(notebook, runs, latency_rows):
    r = runs[notebook]
    if r.error:
        pytest.fail(r.error)
    st = r.status
    problems = []
    if st.get("done") != st.get("total"):
        problems.append(f"only {st.get('done')} of {st.get('total')} code cells ran "
                        "(an error stopped the run?)")
    problems += _output_problems(r.page)
    # the text of every NBVAL_CHECK_OUTPUT cell against the stored notebook, as nbval compares
    # it (with AVX-512 off where .ci/run exported .ci/avx512_off.py's variables)
    problems += compare_cells(ROOT / "notebooks" / notebook, r.page.evaluate(JS_CELLS))
    problems += _kernel_cpu_problems(r.page, notebook)
    problems += _panel_latencies(r.page, notebook, latency_rows)
    problems += [f"after moving the panels: {p}" for p in _output_problems(r.page)
                 if p not in problems]
    print(f"\n[browser] {notebook}: all cells in {r.seconds:.0f} s; "
          f"{sum(row['notebook'] == notebook for row in latency_rows)} panel(s) moved")
    # shut the kernel down: frees its memory for the notebooks still to be checked
    r.page.evaluate("() => window.jupyterapp.shell.currentWidget.sessionContext.shutdown()")
    assert not problems, f"{notebook}:\n  " + "\n  ".join(problems)


FLOOR_TWIN = """\
# %%
import matplotlib.pyplot as plt

from eotrack.notebook import float_slider, panel, setup_notebook

setup_notebook()


def draw(s):
    fig, ax = plt.subplots(figsize=(7, 3.2))
    ax.plot([0, 1], [0, s])
    return fig


floor = panel(draw, s=float_slider("s (m)", 0.0, 1.0, 0.1, 0.5))
"""


def test_panel_floor(browser, lab, latency_rows):
    """The front end's share: a panel whose figure (one line) costs almost nothing to draw."""
    import jupytext

    d = lab.work / "floor"
    d.mkdir()
    nb = jupytext.reads(FLOOR_TWIN, fmt="py:percent")
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3 (ipykernel)",
                                 "language": "python"}
    jupytext.write(nb, d / "floor.ipynb")
    page = _open(browser, lab, "floor/floor.ipynb", "floor")
    try:
        page.evaluate("async () => { await window.jupyterapp.commands.execute("
                      "'notebook:run-all-cells'); }")
        page.locator(".eotrack-panel img").first.wait_for(timeout=120_000)
        page.wait_for_function(f"({JS_STATUS})().kernel === 'idle'", timeout=120_000)
        problems = _output_problems(page)
        problems += _panel_latencies(page, "(floor: one-line figure)", latency_rows)
        page.evaluate("() => window.jupyterapp.shell.currentWidget.sessionContext.shutdown()")
    finally:
        page.close()
    assert not problems, "\n".join(problems)


PANEL_TWIN = """\
# %% [markdown]
# # A panel, stored with its widget state

# %%
import matplotlib.pyplot as plt

from eotrack.notebook import float_slider, panel, toggle


def draw(s, flip):
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [0, -s if flip else s])
    return fig


explore = panel(draw, s=float_slider("s (m)", 0.0, 1.0, 0.005, 0.5), flip=toggle("flip", False))
"""


def _hygiene_fails() -> bool:
    """The switch at the top of .ci/check_twins.py (False while notebooks are re-executed)."""
    m = re.search(r"^HYGIENE_FAILS\s*=\s*(True|False)", (ROOT / ".ci" / "check_twins.py")
                  .read_text(), re.MULTILINE)
    return bool(m) and m.group(1) == "True"


# open a notebook in the page's JupyterLab, as the file browser does; its panel's id
JS_OPEN_DOC = """async (path) => {
  const w = await window.jupyterapp.commands.execute('docmanager:open',
                                                     {path, factory: 'Notebook'});
  await w.context.ready;
  await w.sessionContext.ready;
  return w.id;
}"""
# the kernel's info and spec in (JupyterLab writes language_info and kernelspec from them),
# then a moment for the model to take them: is the notebook marked modified?
JS_OPENED = """async () => {
  const w = window.jupyterapp.shell.currentWidget;
  const k = w.sessionContext.session && w.sessionContext.session.kernel;
  if (k) { await k.info; await k.spec; }
  await new Promise(r => setTimeout(r, 500));
  return w.context.model.dirty;
}"""
JS_LAST_MODIFIED = """() => {
  const c = window.jupyterapp.shell.currentWidget.context;
  return c.contentsModel ? c.contentsModel.last_modified : null;
}"""
JS_CLOSE_DOC = """async () => {
  const w = window.jupyterapp.shell.currentWidget;
  if (!w || !w.sessionContext) return;
  await w.sessionContext.shutdown();
  w.dispose();
}"""


@pytest.fixture(scope="module")
def save_page(browser, lab):
    """One JupyterLab page for every open-and-save round trip (each opens its notebook in it,
    as from the file browser, and closes it after)."""
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.set_default_timeout(120_000)
    page.goto(f"{lab.base}/lab/workspaces/roundtrip?reset&token={TOKEN}")
    page.wait_for_function("() => window.jupyterapp && window.jupyterapp.shell")
    page.evaluate("async () => { await window.jupyterapp.restored; }")
    yield page
    page.close()


@pytest.mark.parametrize("which", ["panel", *(f"stored:{p.name}" for p in STORED)])
def test_open_save_keeps_files(which, save_page, lab, monkeypatch):
    """Ctrl+S in JupyterLab changes neither file of a notebook's pair (so `git status` stays clean).

    ``panel``: a small solutions notebook with a panel, executed by .ci/execute_notebooks.py
    (so its saved widget state is part of the round trip). ``stored:X``: the repository's
    notebook X exactly as committed, with its twin — expected to fail (xfail) until it has been
    re-executed with .ci/execute_notebooks.py, while ``HYGIENE_FAILS`` in .ci/check_twins.py
    is False.
    """
    ex = _ci_module("execute_notebooks")
    # (a directory and a JupyterLab workspace name: letters, digits, '-' and '_' only)
    repo = lab.work / ("roundtrip-" + re.sub(r"[^A-Za-z0-9_-]", "-", which))
    repo.mkdir()
    shutil.copy(ROOT / "pyproject.toml", repo / "pyproject.toml")
    if which.startswith("stored:"):
        src = ROOT / "notebooks" / which.split(":", 1)[1]
        ipynb = repo / "notebooks" / src.name
        py = ex.pair_of(ipynb)
        py.parent.mkdir(parents=True)
        shutil.copy(src, ipynb)
        if not ex.pair_of(src).exists():
            pytest.fail(f"{src.name} has no twin {ex.pair_of(src).relative_to(ROOT)}")
        shutil.copy(ex.pair_of(src), py)
        os.utime(py)  # as after a checkout: the twin is not older than the notebook
    else:
        ipynb = repo / "notebooks" / "solutions" / "99_panel_solutions.ipynb"
        py = ex.pair_of(ipynb)
        py.parent.mkdir(parents=True)
        py.write_text(PANEL_TWIN)
        monkeypatch.delenv("MPLBACKEND", raising=False)  # the kernel must plot inline
        ex.execute(ipynb.stem, py, repo)
        assert ex.WIDGET_STATE in ipynb.read_text(), "no widget state stored"
    before = {f: f.read_bytes() for f in (ipynb, py)}
    mtime = ipynb.stat().st_mtime_ns
    rel = ipynb.relative_to(lab.work).as_posix()
    page = save_page
    try:
        wid = page.evaluate(JS_OPEN_DOC, rel)
        page.wait_for_function(f"({JS_STATUS})() && ({JS_STATUS})().kernel === 'idle'",
                               timeout=180_000)
        dirty_on_open = page.evaluate(JS_OPENED)
        lm0 = page.evaluate(JS_LAST_MODIFIED)
        page.locator(f"[id='{wid}'] .jp-Notebook").click(position={"x": 5, "y": 5})
        page.keyboard.press("Control+s")
        try:  # the server has written both files of the pair when it answers the save
            page.wait_for_function(f"(lm0) => ({JS_LAST_MODIFIED})() !== lm0 && "
                                   f"!({JS_STATUS})().dirty", arg=lm0, timeout=60_000)
        except Exception:
            pass
        saved = ipynb.stat().st_mtime_ns != mtime
    finally:
        page.evaluate(JS_CLOSE_DOC)
    problems = [] if saved else ["Ctrl+S did not save the notebook"]
    if dirty_on_open:
        problems.append("JupyterLab marked the notebook modified on open")
    diffs = []
    for f, old in before.items():
        new = f.read_bytes()
        if new != old:
            d = difflib.unified_diff(old.decode().splitlines(), new.decode().splitlines(),
                                     str(f.relative_to(repo)), "after Ctrl+S", lineterm="", n=1)
            diffs.append("\n".join(list(d)[:40]))
    if diffs:
        problems.append("open + save changed the pair:\n" + "\n".join(diffs))
    if problems and which.startswith("stored:") and not _hygiene_fails():
        pytest.xfail("not yet re-executed with .ci/execute_notebooks.py: " + problems[0][:300])
    assert not problems, "\n".join(problems)
