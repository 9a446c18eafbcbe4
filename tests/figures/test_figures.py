"""The figure lint on every figure of the library: REPORT figures and lint cases (``cases.py``),
and a check that every public figure function is drawn by one of them. Figures the owners have
not fixed yet are in ``xfail.py``, owner named.

A REPORT figure is checked from its sidecars, written by ``make repro`` beside the PNG
(:func:`eotrack.repro.report.write_lint_sidecar`): ``figures/<stem>.fig.gz``, the pickled Figure
saved, and ``<stem>.lint.json`` with the PNG's SHA-256. The figure is loaded, must render to
exactly the committed PNG, and is linted with the current rules (no paper is run). Without the
pickled figure the stored verdict counts only if the current lint version wrote it. A figure
without any sidecar fails (``no-sidecar``). The check that the pickle renders to the very PNG
compares file hashes, so it holds for the pinned matplotlib (environment.txt): after a
matplotlib or freetype upgrade every REPORT figure reads ``stale-figure`` until ``make repro``
has rewritten them.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest
from eotrack.plotting import LINT_VERSION, lint_figure

from .cache import ROOT
from .cases import all_cases
from .owners import OWNERS
from .runs import (
    experiment_slugs,
    figure_functions,
    report_figure_stems,
    report_lint,
    report_slugs,
)
from .xfail import XFAIL

REPORT_IDS = [f"{s}/{f}" for s in report_slugs() for f in report_figure_stems(s)]
CASES = all_cases()


def _check(key: str, owner: str, problems: list, request) -> None:
    if key in XFAIL:
        request.applymarker(pytest.mark.xfail(reason=f"not fixed yet, owner {XFAIL[key]}",
                                              strict=False))
    assert not problems, f"{key} (owner {owner}): {len(problems)} problems\n" + "\n".join(
        f"  [{r}] {m}" for r, m in problems[:25])


def _stored_png_problems(slug: str, stem: str) -> list[tuple[str, str]]:
    """The committed PNG is what the book shows: it must fit the column as well (a report
    written before its figure function was fixed fails here although the quick run passes)."""
    from eotrack.plotting import BOOK_COLUMN_PX
    from eotrack.plotting.lint import MIN_BOOK_SCALE
    from PIL import Image

    path = ROOT / "papers_repro" / slug / "figures" / f"{stem}.png"
    with Image.open(path) as im:
        width = im.width
    limit = BOOK_COLUMN_PX / MIN_BOOK_SCALE
    if width > limit:
        return [("too-wide", f"the committed {path.name} is {width} px wide: the book shows it at "
                 f"{100 * BOOK_COLUMN_PX / width:.0f} % (at most {limit:.0f} px); regenerate "
                 f"the report (python -m eotrack.repro {slug})")]
    return []


def _sidecar(slug: str, stem: str) -> Path:
    return ROOT / "papers_repro" / slug / "figures" / f"{stem}.lint.json"


def has_sidecars(slug: str) -> bool:
    """Every committed REPORT figure of ``slug`` has its lint sidecar."""
    return all(_sidecar(slug, s).is_file() for s in report_figure_stems(slug))


def _render_sha(fig, dpi: int) -> str:
    """SHA-256 of ``fig`` saved as ``write_report`` saves it (PNG, ``bbox_inches="tight"``)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    return hashlib.sha256(buf.getvalue()).hexdigest()


def sidecar_problems(side: Path, slug: str = "<slug>") -> list[tuple[str, str]]:
    """The lint's verdict on the committed PNG, with the current rules.

    With the pickled Figure beside it (``<stem>.fig.gz``, written by ``make repro``): the
    figure is loaded, must render to exactly the committed PNG (else ``stale-figure``), and is
    linted now — so neither a verdict of an older lint nor an edited sidecar can pass. Without
    it, the stored verdict counts only if the current lint wrote it (else ``stale-sidecar``)."""
    import gzip
    import pickle

    stem = side.name.removesuffix(".lint.json")
    rec = json.loads(side.read_text(encoding="utf-8"))
    png = side.with_name(f"{stem}.png")
    regen = f"regenerate the report (python -m eotrack.repro {slug})"
    missing = [k for k in ("png", "sha256", "problems") if k not in rec]
    if missing or rec["png"] != png.name:
        return [("bad-sidecar", f"{side.name} lacks {missing} or names another PNG "
                 f"({rec.get('png')!r}): {regen}")]
    sha = hashlib.sha256(png.read_bytes()).hexdigest()
    pkl = side.with_name(f"{stem}.fig.gz")
    if rec.get("figure") and not pkl.is_file():
        return [("missing-figure", f"{side.name} names {rec['figure']!r}, which is not there: "
                 f"{regen}")]
    if "figure" in rec and not rec["figure"] and not pkl.is_file() \
            and not rec.get("figure_error"):
        return [("bad-sidecar", f"{side.name} declares no pickled figure and gives no reason "
                 f"(figure_error): {regen}")]
    if pkl.is_file():  # (a pickle beside a sidecar that says none is linted all the same)
        fig = pickle.loads(gzip.decompress(pkl.read_bytes()))
        try:
            drawn = _render_sha(fig, int(rec.get("dpi", 110)))
            if drawn != sha:
                return [("stale-figure", f"{pkl.name} does not render to the committed "
                         f"{png.name} (sha256 {drawn[:12]}… vs {sha[:12]}…): {regen}")]
            return [(p.rule, p.message) for p in lint_figure(fig, bbox="tight")]
        finally:
            import matplotlib.pyplot as plt

            plt.close(fig)
    if rec.get("sha256") != sha:
        return [("stale-sidecar", f"{side.name} was written for another {png.name} (sha256 "
                 f"{str(rec.get('sha256'))[:12]}…, the committed PNG's is {sha[:12]}…): {regen}")]
    if rec.get("lint") != LINT_VERSION:
        return [("stale-sidecar", f"{side.name}: verdict of another lint version "
                 f"({rec.get('lint')}, current {LINT_VERSION}) and no pickled figure to lint "
                 f"again ({rec.get('figure_error', 'none written')}): {regen}")]
    return [(r, m) for r, m in rec.get("problems", [])]


@pytest.mark.parametrize("fid", REPORT_IDS)
def test_report_figure(fid, request, lint_rows):
    slug, stem = fid.split("/")
    if _sidecar(slug, stem).is_file():
        problems = sidecar_problems(_sidecar(slug, stem), slug)
    else:  # a quick-run redraw is not the committed PNG: no pass without the sidecars
        problems = [("no-sidecar", f"no {stem}.lint.json / {stem}.fig.gz beside the committed "
                     f"PNG: regenerate the report (python -m eotrack.repro {slug})")]
    problems += _stored_png_problems(slug, stem)
    lint_rows.append((f"report:{fid}", OWNERS.get(slug, "?"), problems))
    _check(f"report:{fid}", OWNERS.get(slug, "?"), problems, request)


@pytest.mark.parametrize("cid", sorted(CASES))
def test_case(cid, request, lint_rows):
    slug, _kind, case = CASES[cid]
    problems = [(p.rule, p.message) for p in lint_figure(case())]
    lint_rows.append((f"case:{cid}", OWNERS.get(slug, "?"), problems))
    _check(f"case:{cid}", OWNERS.get(slug, "?"), problems, request)


@pytest.mark.parametrize("slug", experiment_slugs())
def test_every_figure_function_is_linted(slug, request):
    funcs = figure_functions(slug)
    drawn = set()
    if slug in report_slugs() and has_sidecars(slug):
        drawn = report_calls(slug, funcs)  # no redraw: the report code's calls
    elif slug in report_slugs():
        print(f"{slug}: REPORT figures without lint sidecars; which function drew which "
              f"figure is read from a quick-run redraw")
        drawn = {f for f, stems in report_lint(slug)["drew"].items() if stems}
    missing = sorted(n for n in funcs if n not in drawn and f"{slug}.{n}" not in CASES)
    known = [n for n in missing if f"nocase:{slug}.{n}" in XFAIL]
    if missing and len(known) == len(missing):
        request.applymarker(pytest.mark.xfail(
            reason=f"no lint case yet for {', '.join(known)} (owner {OWNERS.get(slug, '?')})",
            strict=False))
    assert not missing, (f"{slug}: public figure functions drawn by no REPORT figure and no lint "
                         f"case (add one to tests/figures/cases_{slug}.py): {missing}")


def report_calls(slug: str, funcs: dict) -> set[str]:
    """Figure functions the experiment's report code calls: named as ``name(`` in a module of
    ``eotrack.experiments.<slug>`` other than ``figures.py``, or called inside ``figures.py``
    by a function so reached (a composite figure's panels). With the report's figures checked
    from their sidecars, these are the functions a REPORT figure draws."""
    import ast

    pkg = ROOT / "lib" / "eotrack" / "experiments" / slug
    src = "\n".join(p.read_text(encoding="utf-8") for p in sorted(pkg.rglob("*.py"))
                    if p.name != "figures.py")
    called = {n.id if isinstance(n, ast.Name) else n.attr
              for n in ast.walk(ast.parse(src)) if isinstance(n, ast.Call)
              for n in [n.func] if isinstance(n, ast.Name | ast.Attribute)}
    inner: dict[str, set[str]] = {}
    for node in ast.parse((pkg / "figures.py").read_text(encoding="utf-8")).body:
        if isinstance(node, ast.FunctionDef):
            inner[node.name] = {c.func.id for c in ast.walk(node)
                                if isinstance(c, ast.Call) and isinstance(c.func, ast.Name)}
    reached = {n for n in inner if n in called}
    todo = list(reached)
    while todo:
        for n in inner.get(todo.pop(), ()):
            if n not in reached:
                reached.add(n)
                todo.append(n)
    return {n for n in funcs if n in reached}


def test_sidecar_is_the_saved_figures_verdict(tmp_path):
    """make repro's sidecar holds the PNG's hash and the pickled Figure: the test lints that
    figure again with the current rules; a PNG changed afterwards makes it stale, an edited
    verdict changes nothing, and a verdict without the figure counts only if the current lint
    wrote it."""
    import matplotlib.pyplot as plt
    from eotrack.repro.report import write_lint_sidecar

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    fig.savefig(tmp_path / "f.png", dpi=110, bbox_inches="tight")
    side = write_lint_sidecar(fig, tmp_path / "f.png")
    assert side.name == "f.lint.json" and (tmp_path / "f.fig.gz").is_file()
    assert {r for r, _ in sidecar_problems(side)} == {"axis-label", "title"}
    rec = json.loads(side.read_text())
    side.write_text(json.dumps({**rec, "problems": []}))  # a hand-edited verdict
    assert {r for r, _ in sidecar_problems(side)} == {"axis-label", "title"}
    ax.set(xlabel="time (s)", ylabel="height (m)", title="a line")
    fig.savefig(tmp_path / "f.png", dpi=110, bbox_inches="tight")
    assert [r for r, _ in sidecar_problems(side)] == ["stale-figure"]
    write_lint_sidecar(fig, tmp_path / "f.png")
    assert sidecar_problems(side) == []
    (tmp_path / "f.fig.gz").unlink()  # no figure (with a reason): the stored verdict, if current
    rec = {**json.loads(side.read_text()), "figure": None, "figure_error": "too large"}
    side.write_text(json.dumps(rec))
    assert sidecar_problems(side) == []
    side.write_text(json.dumps({**rec, "lint": "0123456789ab"}))
    assert [r for r, _ in sidecar_problems(side)] == ["stale-sidecar"]
    side.write_text(json.dumps({**rec, "figure": None, "figure_error": None}))  # no reason
    assert [r for r, _ in sidecar_problems(side)] == ["bad-sidecar"]


def test_sidecar_without_its_pickle_fails(tmp_path):
    """The sidecar names a pickled figure that is not there: fails, whatever its verdict; a
    pickle beside a sidecar that declares none is linted all the same."""
    import matplotlib.pyplot as plt
    from eotrack.repro.report import write_lint_sidecar

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    fig.savefig(tmp_path / "f.png", dpi=110, bbox_inches="tight")
    side = write_lint_sidecar(fig, tmp_path / "f.png")
    rec = json.loads(side.read_text())
    side.write_text(json.dumps({**rec, "figure": None, "figure_error": "x", "problems": []}))
    assert {r for r, _ in sidecar_problems(side)} == {"axis-label", "title"}
    (tmp_path / "f.fig.gz").unlink()
    side.write_text(json.dumps({**rec, "problems": []}))
    assert [r for r, _ in sidecar_problems(side)] == ["missing-figure"]


def test_sidecar_of_a_figure_too_large_to_keep(tmp_path, monkeypatch):
    """A pickled figure over the size cap is not written: the verdict alone, which counts
    only while the lint that wrote it is current."""
    import matplotlib.pyplot as plt
    from eotrack.repro import report

    monkeypatch.setattr(report, "MAX_FIGURE_BYTES", 100)
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    ax.set(xlabel="time (s)", ylabel="height (m)", title="a line")
    fig.savefig(tmp_path / "f.png", dpi=110, bbox_inches="tight")
    side = report.write_lint_sidecar(fig, tmp_path / "f.png")
    rec = json.loads(side.read_text())
    assert rec["figure"] is None and "MB >" in rec["figure_error"]
    assert not (tmp_path / "f.fig.gz").exists() and sidecar_problems(side) == []
