"""LICENSE, pyproject.toml and CITATION.cff agree; the CFF is checked in full
by `cffconvert --validate` (README, "Licence and citation")."""

from __future__ import annotations

import tomllib
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[1]


def test_licence_and_citation_agree() -> None:
    licence = (REPO / "LICENSE").read_text()
    assert licence.startswith("MIT License") and "The contactlab contributors" in licence
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    cff = yaml.safe_load((REPO / "CITATION.cff").read_text())
    assert project["license"] == cff["license"] == "MIT"
    assert cff["cff-version"] == "1.2.0" and cff["version"] == project["version"]
    (thesis,) = [r for r in cff["references"] if r["type"] == "thesis"]
    assert thesis["thesis-type"] == "PhD thesis"
