"""The figure lint on every figure of the library: REPORT figures (a quick run of each paper,
cached) and lint cases (``cases.py``), and a check that every public figure function is drawn by
one of them. Figures the owners have not fixed yet are in ``xfail.py``, owner named."""

from __future__ import annotations

import pytest
from eotrack.plotting import lint_figure

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


@pytest.mark.parametrize("fid", REPORT_IDS)
def test_report_figure(fid, request, lint_rows):
    slug, stem = fid.split("/")
    res = report_lint(slug)
    assert stem in res["lint"], (f"{slug}: the REPORT has figures/{stem}.png but a quick run of "
                                 f"reproduce() draws no figure of that name")
    problems = list(res["lint"][stem]) + _stored_png_problems(slug, stem)
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
    if slug in report_slugs():
        drawn = {f for f, stems in report_lint(slug)["drew"].items() if stems}
    missing = sorted(n for n in funcs if n not in drawn and f"{slug}.{n}" not in CASES)
    known = [n for n in missing if f"nocase:{slug}.{n}" in XFAIL]
    if missing and len(known) == len(missing):
        request.applymarker(pytest.mark.xfail(
            reason=f"no lint case yet for {', '.join(known)} (owner {OWNERS.get(slug, '?')})",
            strict=False))
    assert not missing, (f"{slug}: public figure functions drawn by no REPORT figure and no lint "
                         f"case (add one to tests/figures/cases_{slug}.py): {missing}")
