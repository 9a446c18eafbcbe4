"""The how-to page notebooks/_book/howto_fits.md runs, and prints what it shows.

Every fenced block opened with exactly ```` ```python ```` is executed in order in one
namespace; the fenced ```` ```text ```` block right after it must equal what the code printed
(trailing spaces ignored). ``{code-block}`` directives are shown, not run.

Regenerate the page's outputs after a deliberate change::

    .venv/bin/python tests/unit/test_howto_fits.py --update
"""

from __future__ import annotations

import contextlib
import io
import re
import sys
from pathlib import Path

PAGE = Path(__file__).resolve().parents[2] / "notebooks" / "_book" / "howto_fits.md"
_BLOCK = re.compile(r"^```python\n(.*?)^```\n\n```text\n(.*?)^```\n", re.S | re.M)


def _run(text: str) -> list[tuple[re.Match, str]]:
    ns: dict = {"__name__": "howto_fits"}
    out = []
    for m in _BLOCK.finditer(text):
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            exec(compile(m.group(1), f"{PAGE.name}:block", "exec"), ns)
        out.append((m, buf.getvalue()))
    return out


def _norm(s: str) -> str:
    return "\n".join(line.rstrip() for line in s.strip("\n").splitlines())


def test_howto_page_code_runs_and_outputs_match():
    text = PAGE.read_text(encoding="utf-8")
    n_python = len(re.findall(r"^```python$", text, re.M))
    results = _run(text)
    assert len(results) == n_python >= 5, "every python block needs a text block after it"
    for i, (m, got) in enumerate(results):
        assert _norm(got) == _norm(m.group(2)), (
            f"block {i + 1}: the page shows\n{m.group(2)}\nbut the code prints\n{got}\n"
            f"(rerun `python {Path(__file__).name} --update` if the change is intended)")


def _update() -> None:
    text = PAGE.read_text(encoding="utf-8")
    parts, last = [], 0
    for m, got in _run(text):
        parts.append(text[last:m.start(2)])
        parts.append(_norm(got) + "\n")
        last = m.end(2)
    parts.append(text[last:])
    PAGE.write_text("".join(parts), encoding="utf-8")


if __name__ == "__main__":
    if "--update" in sys.argv:
        _update()
