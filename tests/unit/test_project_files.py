"""LICENSE and CITATION.cff exist and agree with pyproject (licence, version)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]


def test_license_is_bsd3_as_declared():
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("BSD 3-Clause License")
    assert "eotrack contributors" in text
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert meta["license"] == "BSD-3-Clause"  # an SPDX expression (PEP 639)
    assert meta["license-files"] == ["LICENSE"]


def test_citation_cff_core_fields():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert cff["cff-version"] == "1.2.0"
    assert {"message", "title", "authors"} <= set(cff)
    assert cff["license"] == "BSD-3-Clause"
    assert str(cff["version"]) == meta["version"]
    assert all("name" in a or "family-names" in a for a in cff["authors"])
    for ref in cff.get("references", []):
        assert {"type", "title", "authors"} <= set(ref), ref.get("title")
