"""Fixtures of the receding-contact tests."""

from __future__ import annotations

from pathlib import Path

import pytest


@pytest.fixture(scope="session")
def published_summary_file(tmp_path_factory: pytest.TempPathFactory, repo: Path) -> Path:
    """A stiffness summary of the thesis's tests from their published fits, as `contactlab
    stiffness summarize-published` writes it."""
    from contactlab.stiffness.errors import ErrorModel
    from contactlab.stiffness.summary import summarize_published

    path = tmp_path_factory.mktemp("summary") / "summary.nc"
    summarize_published(repo / "config" / "tests.csv", path,
                        model=ErrorModel(tangential_pressure="multiply"))
    return path
