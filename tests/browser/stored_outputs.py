"""nbval's output comparison, applied to the cells a JupyterLab tab has just run.

The browser test runs every lesson in JupyterLab; where the host has AVX-512, ``.ci/run`` starts
that run with AVX-512 switched off (``.ci/avx512_off.py``), so the kernels' text outputs are the
AVX-512-off comparison that an nbval pass would otherwise repeat. To be that comparison, it uses
nbval's own code (the installed ``nbval.plugin``), not a copy of its rules:

- which cells: those nbval checks under ``--nbval-lax`` (a ``# NBVAL_CHECK_OUTPUT`` comment or an
  ``nbval-check-output`` tag; ``NBVAL_IGNORE_OUTPUT``/``NBVAL_SKIP`` as nbval reads them), and
  only if the stored cell was run (a stored cell with no execution count is not compared; one
  with outputs too is an error, as in nbval);
- streams: ``coalesce_streams`` (every stdout chunk of a cell joined, ``\\r``/``\\b`` applied);
- what is compared: ``IPyNbCell.compare_outputs`` — every output field and MIME type except
  nbval's ``skip_compare`` (metadata, traceback, output_type, name, execution_count, widget
  model ids, and PNG/JPEG images as without ``--nbdime``), after the regex replacements of
  ``tests/notebooks/sanitize.cfg`` (``get_sanitize_patterns``), per key in order.

A mismatch is reported with nbval's message and a unified diff of the sanitized text.
"""

from __future__ import annotations

import difflib
from collections import OrderedDict, defaultdict
from pathlib import Path
from types import SimpleNamespace

import nbformat
from nbval import plugin as nbv

SANITIZE_CFG = Path(__file__).resolve().parents[1] / "notebooks" / "sanitize.cfg"
# nbval 0.11 IPyNbFile.__init__ (without --nbdime): the fields it never compares
SKIP_COMPARE = ("metadata", "traceback", "prompt_number", "output_type", "name",
                "execution_count", "application/vnd.jupyter.widget-view+json",
                "image/png", "image/jpeg")


def _join(v):
    return "".join(v) if isinstance(v, list) else v


def _node(output: dict) -> nbformat.NotebookNode:
    """An output as nbformat reads it from a file (multi-line strings joined)."""
    out = {k: _join(v) if k == "text" else v for k, v in output.items() if k != "transient"}
    if "data" in out:
        out["data"] = {k: _join(v) for k, v in out["data"].items()}
    return nbformat.from_dict(out)


class _Comparer:
    """The parts of nbval's ``IPyNbCell`` that ``compare_outputs`` uses; nbval's pytest-bound
    formatter is replaced by one that keeps both sides for a diff."""

    compare_outputs = nbv.IPyNbCell.compare_outputs
    sanitize = nbv.IPyNbCell.sanitize
    colors = nbv.nocolors

    def __init__(self, patterns):
        self.parent = SimpleNamespace(skip_compare=SKIP_COMPARE, sanitize_patterns=patterns)
        self.comparison_traceback: list[str] = []

    def format_output_compare(self, key, left, right):
        self.comparison_traceback.append(f"mismatch {key!r}")


def _sanitized_by_key(c: _Comparer, outputs) -> dict[str, list]:
    """What compare_outputs compares, per key (for the diff)."""
    by_key = defaultdict(list)
    for o in nbv.transform_streams_for_comparison(outputs):
        for key, value in o.items():
            if key in SKIP_COMPARE:
                continue
            if key == "data":
                for k, v in value.items():
                    if k not in SKIP_COMPARE:
                        by_key[k].append(c.sanitize(v))
            else:
                by_key[key].append(c.sanitize(value))
    return by_key


def _diff(c: _Comparer, ref, test) -> str:
    r, t = _sanitized_by_key(c, ref), _sanitized_by_key(c, test)
    lines = []
    for key in sorted(set(r) | set(t)):
        a = "\n".join(str(v) for v in r.get(key, []))
        b = "\n".join(str(v) for v in t.get(key, []))
        if a != b:
            lines += difflib.unified_diff(a.splitlines(), b.splitlines(),
                                          f"stored {key}", f"run in the browser {key}",
                                          lineterm="", n=2)
    return "\n".join(lines)


def checked(cell) -> bool:
    """Whether nbval --nbval-lax compares this (stored) code cell's outputs."""
    options = defaultdict(bool, nbv.find_metadata_tags(cell.get("metadata", {})))
    options.update(dict(nbv.find_comment_markers(_join(cell["source"]))))
    return bool(options["check"])


def compare_cells(stored: Path, ran: list[dict], sanitize_cfg: Path = SANITIZE_CFG) -> list[str]:
    """Problems found comparing ``ran`` (per code cell, in order: ``{"source", "outputs"}``, the
    outputs as JupyterLab's ``outputs.toJSON()`` gives them) with the stored notebook."""
    nb = nbformat.read(stored, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    if len(code) != len(ran):
        return [f"{len(ran)} code cells ran, the stored notebook has {len(code)}"]
    c = _Comparer(OrderedDict(nbv.get_sanitize_patterns(sanitize_cfg.read_text())))  # as nbval
    problems = []
    for i, (ref_cell, cell) in enumerate(zip(code, ran, strict=True)):
        if _join(cell["source"]) != ref_cell.source:
            problems.append(f"code cell {i}: its source differs from the stored notebook's")
            continue
        if not checked(ref_cell):
            continue
        if ref_cell.execution_count is None:
            if ref_cell.outputs:
                problems.append(f"code cell {i}: unrun reference cell has outputs")
            continue
        ref = nbv.coalesce_streams([nbformat.from_dict(dict(o)) for o in ref_cell.outputs])
        test = nbv.coalesce_streams([_node(o) for o in cell["outputs"]])
        c.comparison_traceback = []
        if not c.compare_outputs(test, ref):
            first = ref_cell.source.strip().splitlines()[0][:80]
            problems.append(f"code cell {i} ({first!r}): outputs differ from the stored "
                            f"notebook's (nbval: {'; '.join(c.comparison_traceback)})\n"
                            + _diff(c, ref, test))
    return problems
