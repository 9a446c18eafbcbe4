"""A lesson's first and last lines: where it sits in the course and the computed verdict.

Every notebook ``NN_*.ipynb`` calls :func:`lesson_header` in its first code cell and
:func:`lesson_footer` in its last, so a student can always go back to the index or on to the
next lesson, and the verdict on the paper's central claim(s) is read from the scorecard that
``make repro`` wrote — never typed.
"""

from __future__ import annotations

import os
import re

__all__ = ["lesson_footer", "lesson_header", "lesson_navigation"]


def _number(nn: str | int) -> str:
    if isinstance(nn, bool) or not isinstance(nn, str | int):
        raise TypeError(f"nn must be a notebook number such as '01' or 1, got {type(nn).__name__}")
    s = f"{nn:02d}" if isinstance(nn, int) else nn
    if not re.fullmatch(r"\d\d", s):
        raise ValueError(f"nn must be a two-digit notebook number such as '01', got {nn!r}")
    return s


def lesson_navigation(nn: str | int, notebooks: str | os.PathLike[str] | None = None) -> str:
    """Markdown ``← previous · index · next → · API reference`` for notebook ``nn`` (the last
    link when the book's API reference ``notebooks/_book/api/index.md`` exists).

    Parameters
    ----------
    nn : str or int
        The notebook's number (``"01"`` or ``1``).
    notebooks : path, optional
        The notebooks folder; default: the repository's ``notebooks/``.

    Raises
    ------
    ValueError
        If no notebook ``nn`` exists.
    """
    from eotrack.repro.collection import collection_notebooks

    num = _number(nn)
    nbs = collection_notebooks(notebooks)
    rows = nbs.to_dict("records")
    idx = [k for k, r in enumerate(rows) if r["number"] == num]
    if not idx:
        raise ValueError(f"no notebook {num}_*.ipynb; present: {[r['number'] for r in rows]}")
    k = idx[0]

    def link(r: dict) -> str:
        return f"[{r['number']} · {r['title']}]({r['path']})"

    parts = []
    if k > 0:
        parts.append("← " + link(rows[k - 1]))
    index = [r for r in rows if r["number"] == "00"]
    if index and num != "00" and (k == 0 or rows[k - 1]["number"] != "00"):
        parts.append(f"[index]({index[0]['path']})")
    if k + 1 < len(rows):
        parts.append(link(rows[k + 1]) + " →")
    from eotrack.repro.collection import _notebooks_dir

    if (_notebooks_dir(notebooks) / API_INDEX).is_file():
        parts.append(f"[API reference]({API_INDEX})")
    return " · ".join(parts)


#: The book's API reference, relative to the notebooks folder (linked from every lesson's
#: navigation line when it exists).
API_INDEX = "_book/api/index.md"


def _slug_of(num: str, notebooks: str | os.PathLike[str] | None) -> str | None:
    """The paper slug whose experiment notebook ``num`` imports (read from the notebook's code,
    without importing any experiment)."""
    from eotrack.repro.claims import papers_repro_dir
    from eotrack.repro.collection import collection_notebooks, notebook_for_slug

    stems = collection_notebooks(notebooks)
    stem = stems.loc[stems["number"] == num, "stem"]
    if stem.empty:
        return None
    for card in sorted(papers_repro_dir().glob("*/claims.toml")):
        slug = card.parent.name
        if notebook_for_slug(slug, notebooks) == stem.iloc[0]:
            return slug
    return None


def lesson_header(nn: str | int, notebooks: str | os.PathLike[str] | None = None,
                  *, show: bool = True) -> str:
    """Navigation plus the computed verdict on the paper's central claim(s).

    Parameters
    ----------
    nn : str or int
        The notebook's number.
    notebooks : path, optional
        The notebooks folder; default: the repository's ``notebooks/``.
    show : bool
        Display the Markdown (in a notebook); the text is returned either way.
    """
    from eotrack.repro.collection import central_verdict

    num = _number(nn)
    lines = [lesson_navigation(num, notebooks)]
    slug = _slug_of(num, notebooks)
    if slug is not None:
        try:
            verdict = central_verdict(slug)
        except ValueError:
            verdict = "no scorecard yet — run `make repro`"
        lines.append(f"**Verdict of the last `make repro` on this paper** ({slug}): {verdict}.")
    text = "\n\n".join(lines)
    if show:
        _display(text)
    return text


def lesson_footer(nn: str | int, notebooks: str | os.PathLike[str] | None = None,
                  *, show: bool = True) -> str:
    """The navigation line again, for the end of the lesson (see :func:`lesson_header`)."""
    text = lesson_navigation(_number(nn), notebooks)
    if show:
        _display(text)
    return text


def _display(text: str) -> None:
    try:
        from IPython.display import Markdown, display
    except ImportError:  # pragma: no cover - IPython is a dependency of the notebooks
        print(text)
        return
    display(Markdown(text))
