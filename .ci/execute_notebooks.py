"""Rebuild ``notebooks/X.ipynb`` from ``notebooks/py/X.py`` and execute it in place.

Usage: ``python .ci/execute_notebooks.py [STEM ...]`` (default: all; the solutions in
``notebooks/solutions/py/`` too).

What is stored, so that opening and saving a notebook in JupyterLab leaves ``git status`` clean:

- the kernelspec ipykernel writes (``KERNELSPEC``; JupyterLab rewrites any other on open);
- the widgets' state (``metadata.widgets``, nbclient ``store_widget_state``), so panels render
  before running and in static viewers;
- both files written through jupytext's contents manager (the one the Jupyter server uses,
  configured by ``[tool.jupytext]`` in pyproject.toml), so the ``.ipynb`` and its ``.py`` twin
  are byte-identical to what JupyterLab would save. The ``.py`` twin is only rewritten where
  jupytext's canonical form differs from it (usually the header's kernelspec); its cells are
  unchanged.

Low churn: cell ids are kept from the previous ``.ipynb`` (matched by content) and execution
timestamps are stripped.
"""

from __future__ import annotations

import json
import os
import re
import sys
import time
from pathlib import Path

import jupytext
import nbformat

ROOT = Path(__file__).resolve().parents[1]
TOP = ROOT / "notebooks"
#: What ipykernel's kernelspec says; JupyterLab stores exactly this on open.
KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"


def sources(root: Path = ROOT) -> dict[str, Path]:
    """``{stem: py twin}`` for notebooks/py/*.py and notebooks/solutions/py/*.py."""
    top = root / "notebooks"
    return {p.stem: p for d in (top, top / "solutions") for p in sorted((d / "py").glob("*.py"))}


def ipynb_of(py: Path) -> Path:
    """notebooks/py/X.py -> notebooks/X.ipynb (same for solutions/)."""
    return py.parent.parent / f"{py.stem}.ipynb"


def contents_manager(root: Path = ROOT):
    """Jupytext's contents manager over ``root`` — the code that saves in JupyterLab."""
    from jupyter_server.services.contents.largefilemanager import LargeFileManager
    from jupytext.sync_contentsmanager import build_sync_jupytext_contents_manager_class

    cm_class = build_sync_jupytext_contents_manager_class(LargeFileManager)
    return cm_class(root_dir=str(root))


def _js_numbers(obj):
    """Integral floats as ints, as JupyterLab's JSON (JavaScript numbers) writes them back."""
    if isinstance(obj, float) and obj.is_integer() and abs(obj) < 1e21:
        return int(obj)
    if isinstance(obj, dict):
        return {k: _js_numbers(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_js_numbers(v) for v in obj]
    return obj


def normalise(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """ipykernel's kernelspec, no execution timestamps, numbers as JupyterLab saves them.

    JupyterLab round-trips the whole notebook through JavaScript on save, where ``1.0`` is the
    number ``1``: a float slider's ``"max": 1.0`` in the saved widget state would come back as
    ``"max": 1``. Returns a new notebook.
    """
    nb.metadata["kernelspec"] = dict(KERNELSPEC)
    for cell in nb.cells:
        cell.metadata.pop("execution", None)
    return nbformat.from_dict(_js_numbers(json.loads(json.dumps(nb))))


_MODEL_ID = re.compile(r"(?<![0-9a-f])[0-9a-f]{32}(?![0-9a-f])")


def stable_widget_ids(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """Renumber the stored widget models in order of appearance (returns a new notebook).

    The kernel gives every widget model a random UUID, so each re-run would rewrite the whole
    saved widget state; numbering the models by where they are first reached (cell outputs in
    order, then the models they reference) keeps a re-run's diff to what really changed.
    """
    state = nb.metadata.get("widgets", {}).get(WIDGET_STATE, {}).get("state", {})
    if not state:
        return nb
    queue = []
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            view = out.get("data", {}).get(WIDGET_VIEW)
            if view and view.get("model_id") in state:
                queue.append(view["model_id"])
    order: list[str] = []
    seen: set[str] = set()
    while queue:
        mid = queue.pop(0)
        if mid in seen or mid not in state:
            continue
        seen.add(mid)
        order.append(mid)
        queue.extend(re.findall(r"IPY_MODEL_([0-9a-f]{32})", json.dumps(state[mid], sort_keys=True)))
    rest = sorted((m for m in state if m not in seen),
                  key=lambda m: json.dumps(state[m], sort_keys=True))
    mapping = {m: f"{i:032x}" for i, m in enumerate(order + rest)}
    text = _MODEL_ID.sub(lambda m: mapping.get(m.group(0), m.group(0)), json.dumps(nb))
    return nbformat.from_dict(json.loads(text))


def save_pair(nb: nbformat.NotebookNode, ipynb: Path, root: Path = ROOT) -> None:
    """Write ``ipynb`` and its paired ``.py`` exactly as JupyterLab's save would."""
    rel = ipynb.resolve().relative_to(root.resolve()).as_posix()
    cm = contents_manager(root)
    cm.save({"type": "notebook", "format": "json", "content": nb}, rel)
    # JupyterLab saves what it opened: jupytext adds its config to the metadata on reading
    # (e.g. notebook_metadata_filter), so store the fixed point of open -> save.
    for _ in range(3):
        before = (ipynb.read_bytes(), pair_of(ipynb).read_bytes())
        cm.save(cm.get(rel, content=True), rel)
        if (ipynb.read_bytes(), pair_of(ipynb).read_bytes()) == before:
            break


def pair_of(ipynb: Path) -> Path:
    """notebooks/X.ipynb -> notebooks/py/X.py (same for solutions/)."""
    return ipynb.parent / "py" / f"{ipynb.stem}.py"


def roundtrip_changes(ipynb: Path, root: Path = ROOT) -> list[str]:
    """Files of the pair that an open -> save in JupyterLab would change (server side simulated).

    Works on a temporary copy (``root``'s pyproject.toml and the pair); the stored files are
    not touched. Empty list: JupyterLab's save (server side) leaves ``git status`` clean.
    """
    import shutil
    import tempfile

    rel = ipynb.resolve().relative_to(root.resolve())
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / rel
        copy.parent.mkdir(parents=True)
        (copy.parent / "py").mkdir()
        shutil.copy2(root / "pyproject.toml", Path(tmp) / "pyproject.toml")
        pair = pair_of(ipynb)
        shutil.copy2(ipynb, copy)
        if pair.exists():
            shutil.copy(pair, pair_of(copy))  # newer than the notebook, as after a checkout
        cm = contents_manager(Path(tmp))
        try:
            model = cm.get(rel.as_posix(), content=True)
        except Exception as exc:  # jupytext refuses to open the pair
            return [f"{rel.as_posix()} (JupyterLab could not open it: {exc})"]
        # the browser holds the notebook as JavaScript values in between
        model["content"] = nbformat.from_dict(_js_numbers(json.loads(json.dumps(model["content"]))))
        cm.save(model, rel.as_posix())
        changed = []
        for orig, new in ((ipynb, copy), (pair, pair_of(copy))):
            if not orig.exists() or orig.read_bytes() != new.read_bytes():
                changed.append(orig.relative_to(root).as_posix())
        return changed


def load_inputs(py: Path) -> nbformat.NotebookNode:
    """The twin's cells, with the cell ids (and outputs) of the stored .ipynb where they match."""
    nb = jupytext.read(py)
    old = ipynb_of(py)
    if old.exists():
        from jupytext.combine import combine_inputs_with_outputs

        nb = combine_inputs_with_outputs(nb, nbformat.read(old, as_version=4), fmt="py:percent")
    return nb


def execute(stem: str, src: Path, root: Path = ROOT) -> float:
    """Execute ``src``'s notebook and store it with its twin; return the wall time in s."""
    from nbclient import NotebookClient

    nb = load_inputs(src)
    t0 = time.perf_counter()
    NotebookClient(nb, timeout=900, kernel_name="python3", store_widget_state=True,
                   resources={"metadata": {"path": str(src.parent.parent)}}).execute()
    seconds = time.perf_counter() - t0
    before = src.read_bytes()
    save_pair(stable_widget_ids(normalise(nb)), ipynb_of(src), root)
    if src.read_bytes() != before:
        print(f"{stem}: wrote {src.relative_to(root)} in jupytext's canonical form "
              "(same cells; JupyterLab saves it this way)")
    return seconds


def main(argv: list[str]) -> int:
    known = sources()
    stems = argv or sorted(known)
    unknown = [s for s in stems if s not in known]
    if unknown:
        print(f"no notebook source named {unknown}; known: {sorted(known)}", file=sys.stderr)
        return 2
    os.environ.pop("MPLBACKEND", None)  # never let Agg reach the kernel
    for stem in stems:
        seconds = execute(stem, known[stem])
        record_time(stem, seconds)
        print(f"{stem}: executed in {seconds:.1f} s", flush=True)
    return 0


TIMES = TOP / "execution_times.json"


def record_time(stem: str, seconds: float, path: Path = TIMES) -> None:
    """Store the wall time of ``stem``'s execution (the index's lab sheets read it), with the
    date and the machine's load, so a time measured on a busy machine says so."""
    import datetime

    times = json.loads(path.read_text()) if path.is_file() else {}
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    times[stem] = {"seconds": round(seconds, 1),
                   "executed": datetime.date.today().isoformat(),
                   "cores": os.cpu_count(), "load": round(load, 1)}
    path.write_text(json.dumps(dict(sorted(times.items())), indent=1) + "\n")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
