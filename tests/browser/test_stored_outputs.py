"""The browser run's output comparison (stored_outputs.compare_cells) fails where nbval would.

No browser needed: the "ran" cells are built here, as JupyterLab's ``outputs.toJSON()`` gives
them, from a small notebook and from a stored lesson.
"""

from __future__ import annotations

import copy
import re
from pathlib import Path

import nbformat
import pytest
from nbval.plugin import get_sanitize_patterns
from stored_outputs import SANITIZE_CFG, compare_cells

ROOT = Path(__file__).resolve().parents[2]


def _stream(text, name="stdout"):
    return {"output_type": "stream", "name": name, "text": text}


def _notebook(tmp_path, cells) -> Path:
    nb = nbformat.v4.new_notebook()
    for i, (source, outputs) in enumerate(cells):
        c = nbformat.v4.new_code_cell(source, execution_count=i + 1)
        c.outputs = [nbformat.from_dict(o) for o in outputs]
        nb.cells.append(c)
    path = tmp_path / "nb.ipynb"
    nbformat.write(nb, path)
    return path


def _ran(cells):
    return [{"source": s, "outputs": copy.deepcopy(o)} for s, o in cells]


CELLS = [
    ("# NBVAL_CHECK_OUTPUT\nprint(r)", [_stream("recall 0.931 in 12.3 s\nat 0x7f3a2b\n")]),
    ("x = 1  # not checked\nprint(x)", [_stream("1.000\n")]),
    ("# NBVAL_CHECK_OUTPUT\nfig", [{"output_type": "display_data", "metadata": {},
                                    "data": {"image/png": "iVBORw0KGgo=",
                                             "text/plain": "<Figure>"}}]),
]


def test_same_outputs_pass(tmp_path):
    assert compare_cells(_notebook(tmp_path, CELLS), _ran(CELLS)) == []


def test_a_changed_digit_is_reported_with_a_diff(tmp_path):
    ran = _ran(CELLS)
    ran[0]["outputs"][0]["text"] = "recall 0.932 in 12.3 s\nat 0x7f3a2b\n"
    problems = compare_cells(_notebook(tmp_path, CELLS), ran)
    assert len(problems) == 1
    assert "code cell 0" in problems[0] and "mismatch 'stdout'" in problems[0]
    assert "-recall 0.932 in DURATION" not in problems[0]  # the diff: stored minus, browser plus
    assert "-recall 0.931 in DURATION" in problems[0]
    assert "+recall 0.932 in DURATION" in problems[0]


def test_sanitized_and_unchecked_and_image_differences_pass(tmp_path):
    ran = _ran(CELLS)
    ran[0]["outputs"][0]["text"] = "recall 0.931 in 99 ms\nat 0xdeadbeef\n"  # sanitize.cfg
    ran[1]["outputs"][0]["text"] = "2.000\n"  # no NBVAL_CHECK_OUTPUT
    ran[2]["outputs"][0]["data"]["image/png"] = "AAAA"  # nbval skips PNG
    ran[2]["outputs"][0]["metadata"] = {"image/png": {"width": 3}}
    assert compare_cells(_notebook(tmp_path, CELLS), ran) == []


def test_streams_are_joined_as_nbval_joins_them(tmp_path):
    ran = _ran(CELLS)
    ran[0]["outputs"] = [_stream("recall 0.931 in 12.3 s\n"), _stream(["at ", "0x7f3a2b\n"])]
    assert compare_cells(_notebook(tmp_path, CELLS), ran) == []
    ran[0]["outputs"].append(_stream("warning\n", "stderr"))
    assert "Unexpected output fields" in compare_cells(_notebook(tmp_path, CELLS), ran)[0]


def test_other_text_fields_are_compared(tmp_path):
    ran = _ran(CELLS)
    ran[2]["outputs"][0]["data"]["text/plain"] = "<Figure size 640x480>"
    ran[2]["outputs"][0]["data"]["text/html"] = "<b>x</b>"
    problems = compare_cells(_notebook(tmp_path, CELLS), ran)
    assert len(problems) == 1 and "code cell 2" in problems[0]


def test_a_changed_source_or_cell_count_is_reported(tmp_path):
    ran = _ran(CELLS)
    ran[1]["source"] = "x = 2"
    assert "source differs" in compare_cells(_notebook(tmp_path, CELLS), ran)[0]
    assert "2 code cells ran" in compare_cells(_notebook(tmp_path, CELLS), ran[:2])[0]


def _lesson_with_checked_digits() -> Path:
    for nb in sorted((ROOT / "notebooks").glob("0[1-9]*.ipynb")):
        for c in nbformat.read(nb, as_version=4).cells:
            if (c.cell_type == "code" and "NBVAL_CHECK_OUTPUT" in c.source and c.outputs
                    and re.search(r"\d", "".join(o.get("text", "") for o in c.outputs))):
                return nb
    pytest.skip("no stored lesson has a checked cell with digits")


def test_a_stored_lesson_against_itself_and_with_one_digit_changed():
    nb_path = _lesson_with_checked_digits()
    nb = nbformat.read(nb_path, as_version=4)
    ran = [{"source": c.source, "outputs": [dict(copy.deepcopy(o)) for o in c.outputs]}
           for c in nb.cells if c.cell_type == "code"]
    assert compare_cells(nb_path, ran) == []
    patterns = dict(get_sanitize_patterns(SANITIZE_CFG.read_text())).items()

    def sanitized(text):
        for regex, replace in patterns:
            text = re.sub(regex, replace, text)
        return text

    for cell in ran:
        if "NBVAL_CHECK_OUTPUT" not in cell["source"]:
            continue
        for o in cell["outputs"]:
            text = o.get("text", "") if o.get("output_type") == "stream" else ""
            for m in re.finditer(r"\d", text):  # a digit the sanitizers keep
                changed = text[:m.start()] + str((int(m.group()) + 1) % 10) + text[m.end():]
                if sanitized(changed) != sanitized(text):
                    o["text"] = changed
                    problems = compare_cells(nb_path, ran)
                    assert len(problems) == 1 and "outputs differ" in problems[0], problems
                    return
    pytest.fail(f"{nb_path.name}: no digit of a checked output survives the sanitizers")
