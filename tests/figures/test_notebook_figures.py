"""The figure lint on the notebooks' own figures, as they are stored (and shown in the book).

A notebook's figures are mostly drawn by the library's figure functions (linted by
``test_figures.py``), but a notebook also composes them (two panels side by side, a figure size
of its own), and that composite is what a reader sees. When a notebook is executed with the
house style on (``setup_notebook()``), every figure it shows is linted in the kernel and the
verdict is stored with the figure's output (``eotrack.plotting.LINT_MIMETYPE``, see
:func:`eotrack.plotting.register_figure_descriptions`). This test reads those records from the
stored ``.ipynb`` files: a figure with problems, one stored without a record (executed before
the lint was recorded), or one whose record another version of the lint wrote (``stale-lint``:
the current rules were never applied to it) fails. Fix the figure, re-execute the notebook
(``.ci/execute_notebooks.py``) and the record follows. Nothing is executed here.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from eotrack.plotting import LINT_MIMETYPE, LINT_VERSION

from .cache import ROOT
from .xfail import XFAIL

NOTEBOOKS = ROOT / "notebooks"
#: who owns a notebook's figures, by its number (the solutions go with their lesson)
NOTEBOOK_OWNERS = {"00": "LEAD", "01": "P01", "02": "P02", "03": "P03", "04": "P04",
                   "05": "P05", "06": "P06", "07": "CAP"}


def notebook_paths() -> list[Path]:
    """Every notebook of the course and its worked solutions (as the book renders them)."""
    return (sorted(NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"))
            + sorted((NOTEBOOKS / "solutions").glob("[0-9][0-9]_*.ipynb")))


def figure_records(path: Path) -> list[tuple[int, str, dict | None]]:
    """``(cell number, figure's text, lint record or None)`` for every image output of the
    notebook's cells (panels' saved widget images are drawn by figure functions the lint
    cases cover). The record gets the stored PNG's size as ``"_stored_px"``."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    out = []
    for i, cell in enumerate(nb.get("cells", [])):
        for o in cell.get("outputs", []):
            data = o.get("data", {})
            if any(k.startswith("image/") for k in data):
                text = "".join(data.get("text/plain", "")).strip()
                rec = data.get(LINT_MIMETYPE)
                if rec is not None and "image/png" in data:
                    rec = {**rec, "_stored_px": _png_size(data["image/png"])}
                out.append((i, text, rec))
    return out


def _png_size(b64: str | list[str]) -> tuple[int, int]:
    import base64
    import io

    from PIL import Image

    raw = base64.b64decode("".join(b64) if isinstance(b64, list) else b64)
    with Image.open(io.BytesIO(raw)) as im:
        return im.size


def _stored_png_problems(where: str, rec: dict) -> list[tuple[str, str]]:
    """The record must describe the PNG stored beside it (its size, ±3 px: an edited or swapped
    image, or a record copied from another figure, fails), and that PNG must fit the book's
    column (as the committed REPORT PNGs must)."""
    from eotrack.plotting import BOOK_COLUMN_PX
    from eotrack.plotting.lint import MIN_BOOK_SCALE

    stored, want = rec.get("_stored_px"), rec.get("png_px")
    out = []
    if stored is None:
        return out
    if not want or any(abs(a - b) > 3 for a, b in zip(stored, want, strict=True)):
        out.append(("stale-record", f"{where}: the lint record describes a {want} px PNG, the "
                    f"stored one is {list(stored)} px; re-execute the notebook"))
    limit = BOOK_COLUMN_PX / MIN_BOOK_SCALE
    if stored[0] > limit:
        out.append(("too-wide", f"{where}: the stored PNG is {stored[0]} px wide: the book shows "
                    f"it at {100 * BOOK_COLUMN_PX / stored[0]:.0f} % (at most {limit:.0f} px)"))
    return out


def notebook_problems(path: Path) -> list[tuple[str, str, list[tuple[str, str]]]]:
    """``(figure id, owner, problems)`` per stored figure of the notebook."""
    owner = NOTEBOOK_OWNERS.get(path.name[:2], "?")
    rel = path.relative_to(NOTEBOOKS).with_suffix("").as_posix()
    rows = []
    for k, (cell, text, rec) in enumerate(figure_records(path), 1):
        fid = f"notebook:{rel}#{k}"
        if rec is None:
            problems = [("not-linted", f"cell {cell} ({text[:50] or 'figure'}): stored without "
                         f"the lint's record; re-execute the notebook")]
        else:
            problems = [(r, f"cell {cell} ({text[:50] or 'figure'}): {m}")
                        for r, m in rec.get("problems", [])]
            if rec.get("lint") != LINT_VERSION:
                problems.append(("stale-lint", f"cell {cell} ({text[:50] or 'figure'}): "
                                 f"verdict of another lint version ({rec.get('lint')}, current "
                                 f"{LINT_VERSION}); re-execute the notebook"))
            problems += _stored_png_problems(f"cell {cell} ({text[:50] or 'figure'})", rec)
        rows.append((fid, owner, problems))
    return rows


@pytest.mark.parametrize("path", notebook_paths(),
                         ids=lambda p: p.relative_to(NOTEBOOKS).with_suffix("").as_posix())
def test_notebook_figures(path, request, lint_rows):
    rows = notebook_problems(path)
    lint_rows.extend(rows)
    key = f"notebook:{path.relative_to(NOTEBOOKS).with_suffix('').as_posix()}"
    owner = NOTEBOOK_OWNERS.get(path.name[:2], "?")
    if key in XFAIL:
        request.applymarker(pytest.mark.xfail(reason=f"not fixed yet, owner {XFAIL[key]}",
                                              strict=False))
    bad = [(fid, p) for fid, _, probs in rows for p in probs]
    assert not bad, (f"{key} (owner {owner}): {len(bad)} problems in "
                     f"{len({f for f, _ in bad})} of {len(rows)} figures\n"
                     + "\n".join(f"  {fid.split('#')[1]} [{r}] {m}" for fid, (r, m) in bad[:25]))



def test_lint_record_of_a_figure():
    """What the kernel stores: the lint's problems as ``[rule, message]``; a failing lint is
    recorded as a problem, never raised into the notebook."""
    import matplotlib.pyplot as plt
    from eotrack.plotting import figure_lint_record

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    rules = {r for r, _ in figure_lint_record(fig)["problems"]}
    assert {"axis-label", "title"} <= rules
    ax.set(xlabel="time (s)", ylabel="height (m)", title="a line")
    from eotrack.plotting import LINT_VERSION

    rec = figure_lint_record(fig)
    assert rec["problems"] == [] and rec["lint"] == LINT_VERSION
    import io

    from PIL import Image

    buf = io.BytesIO()
    fig.savefig(buf, format="png", bbox_inches="tight", dpi=fig.dpi)  # as the inline backend
    assert all(abs(a - b) <= 3 for a, b in zip(rec["png_px"], Image.open(buf).size, strict=True))


def test_a_record_must_describe_the_png_beside_it(tmp_path):
    """A stored figure whose PNG was swapped (or whose record was copied from another figure)
    fails, and a stored PNG wider than the column fails."""
    import base64
    import io

    import matplotlib.pyplot as plt
    from eotrack.plotting import figure_lint_record
    from PIL import Image

    def png(w, h):
        buf = io.BytesIO()
        Image.new("RGB", (w, h), "white").save(buf, format="png")
        return base64.b64encode(buf.getvalue()).decode()

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    ax.set(xlabel="time (s)", ylabel="height (m)", title="a line")
    rec = figure_lint_record(fig)
    w, h = rec["png_px"]
    nb = {"cells": [{"outputs": [{"data": {"image/png": png(w, h), LINT_MIMETYPE: rec,
                                            "text/plain": "Figure: a line"}}]}]}
    path = tmp_path / "01_x.ipynb"
    path.write_text(json.dumps(nb))

    def problems():
        (_, _, rec), = figure_records(path)
        return _stored_png_problems("cell 0", rec)

    assert problems() == []
    nb["cells"][0]["outputs"][0]["data"]["image/png"] = png(3000, 50)  # swapped, too wide
    path.write_text(json.dumps(nb))
    assert {r for r, _ in problems()} == {"stale-record", "too-wide"}
    rec = figure_lint_record("not a figure")
    assert rec["problems"][0][0] == "lint-error" and "TypeError" in rec["problems"][0][1]


def test_book_drops_the_records_it_cannot_show():
    """The book's conf.py removes the records under the same name (myst-nb warns, and ``-W``
    fails, on an output type it cannot show)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("_book_conf", ROOT / "notebooks/_book/conf.py")
    conf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conf)
    assert conf.LINT_MIMETYPE == LINT_MIMETYPE
    nb = {"cells": [{"outputs": [{"data": {"image/png": "x", LINT_MIMETYPE: {"problems": []}}}]}]}
    conf._drop_lint_records(nb)
    assert nb["cells"][0]["outputs"][0]["data"] == {"image/png": "x"}
