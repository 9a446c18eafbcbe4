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
import re
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

project = "eotrack"
author = "eotrack contributors"
copyright = "eotrack contributors; code BSD-3-Clause, see Licences"

extensions = ["myst_nb", "sphinx-mathjax-offline"]

root_doc = "notebooks/00_index"
include_patterns = [
    "notebooks/*.ipynb",
    "notebooks/solutions/*.ipynb",
    "notebooks/_book/*.md",
    "papers_repro/*/REPORT.md",
]
exclude_patterns = [".venv", "build", "**/.ipynb_checkpoints", "notebooks/py",
                    "notebooks/solutions/py", "README.md", "notebooks/_book/_static"]

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


def _toctree_markdown() -> str:
    blocks = []
    for caption, folder, pat in _PARTS:
        rel = Path(folder).relative_to("notebooks")
        docs = sorted(p.stem for p in (ROOT / folder).glob("*.ipynb") if pat.match(p.name))
        if docs:
            entries = "\n".join(f"{rel / d}" if str(rel) != "." else d for d in docs)
            blocks.append(f"```{{toctree}}\n:hidden:\n:caption: {caption}\n\n{entries}\n```")
    reports = sorted(p.parent.name for p in (ROOT / "papers_repro").glob("*/REPORT.md"))
    if reports:
        entries = "\n".join(f"/papers_repro/{s}/REPORT" for s in reports)
        blocks.append(f"```{{toctree}}\n:hidden:\n:caption: Reproduction reports\n\n"
                      f"{entries}\n```")
    blocks.append("```{toctree}\n:hidden:\n:caption: About\n\n/notebooks/_book/licences\n```")
    return "\n\n".join(blocks)


_CONTROL = re.compile(r"Slider|Dropdown|Checkbox|ToggleButton|RadioButtons|interactive\(")
_PANEL_NOTE = ("<div class=\"admonition note eotrack-widget-note\"><p class=\"admonition-title\">"
               "Interactive panel</p><p>This panel needs a live Python kernel. Open the notebook "
               "in JupyterLab (<code>make lab</code>) to move the controls; the static book "
               "shows only its saved outputs.</p></div>")
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"


def _static_widgets(nb: dict) -> None:
    """Replace widget outputs that carry no saved state (see the module docstring)."""
    has_state = bool(nb.get("metadata", {}).get("widgets"))
    if has_state:
        return
    for cell in nb.get("cells", []):
        outs = []
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if WIDGET_VIEW in data:
                text = "".join(data.get("text/plain", ""))
                if _CONTROL.search(text) or "eotrack-panel" in text or text.startswith("VBox"):
                    outs.append({"output_type": "display_data", "metadata": {},
                                 "data": {"text/html": _PANEL_NOTE,
                                          "text/plain": "interactive panel"}})
                continue  # progress bars and other state-less widgets: nothing to show
            outs.append(out)
        if "outputs" in cell:
            cell["outputs"] = outs


def _on_source_read(app, docname: str, source: list[str]) -> None:
    if not docname.startswith("notebooks/"):
        return
    path = ROOT / f"{docname}.ipynb"
    if not path.is_file():
        return
    nb = json.loads(source[0])
    _static_widgets(nb)
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


def setup(app):
    app.connect("source-read", _on_source_read)
    app.connect("build-finished", _redirect)
    return {"parallel_read_safe": True}
