"""Study families: grid expansion, variant names, configs, name clashes."""

from __future__ import annotations

import pytest

from contactlab.provenance import check_study_name, results_dir
from contactlab.studies.family import (
    FamilyError,
    expand_grid,
    format_value,
    key_labels,
    split_family,
    variant_config,
)


def test_grid_expands_to_every_combination_with_names_from_the_values() -> None:
    variants = expand_grid("lam", {"receding.line.lambda": [3.0, 3.5, 4.0],
                                   "receding.line.n": [300, 500]})
    assert [v.name for v in variants] == [
        "lambda3.0_n300", "lambda3.0_n500", "lambda3.5_n300", "lambda3.5_n500",
        "lambda4.0_n300", "lambda4.0_n500"]
    assert variants[2].study == "lam/lambda3.5_n300"
    assert variants[2].values == {"receding.line.lambda": 3.5, "receding.line.n": 300}
    assert variants[2].prefix == "lambda3_5_n300"
    assert results_dir(variants[2].study) == "results/studies/lam/lambda3.5_n300/"


def test_a_variants_name_depends_on_its_values_only() -> None:
    """Adding a value to the grid renames no existing variant (their folders stay)."""
    small = expand_grid("f", {"a.x": [1, 2], "a.y": [0.5]})
    large = expand_grid("f", {"a.x": [0, 1, 2, 3], "a.y": [0.5, 1e-08]})
    assert {v.name for v in small} <= {v.name for v in large}
    assert "x3_y1e-08" in {v.name for v in large}


def test_keys_with_the_same_last_part_get_longer_labels() -> None:
    assert key_labels(["receding.line.n", "receding.patches.n", "receding.line.lambda"]) == {
        "receding.line.n": "line-n", "receding.patches.n": "patches-n",
        "receding.line.lambda": "lambda"}
    names = [v.name for v in expand_grid("f", {"receding.line.n": [10],
                                                "receding.patches.n": [20]})]
    assert names == ["line-n10_patches-n20"]


def test_named_values_name_their_variants() -> None:
    grid = {"receding.gap.w": {"coarse": {"start": 0.25, "stop": 5.0, "step": 0.25},
                               "fine": {"start": 0.125, "stop": 5.0, "step": 0.125}},
            "receding.gap.n": [50]}
    variants = expand_grid("w", grid)
    assert [v.name for v in variants] == ["coarse_n50", "fine_n50"]
    assert variants[1].values["receding.gap.w"]["step"] == 0.125


def test_values_format_exactly() -> None:
    assert [format_value(v) for v in (3, 3.0, 0.1, 1e-30, True, "hertz")] == [
        "3", "3.0", "0.1", "1e-30", "true", "hertz"]
    with pytest.raises(FamilyError, match="cannot name a variant"):
        format_value([0.3, 0.5])


@pytest.mark.parametrize(("family", "grid", "message"), [
    ("lam", {}, "grid: give at least one dotted key"),
    ("lam", {"receding.line.n": []}, "non-empty list"),
    ("lam", {"receding.line.n": 3}, "non-empty list"),
    ("lam", {"study": ["a"]}, "names the study"),
    ("lam", {"receding..n": [1]}, "not a dotted config key"),
    ("1lam", {"a.b": [1]}, "family: '1lam'"),
    ("lam", {"a.b": [1, 1]}, "both named"),
    ("lam", {"a.b": [[1, 2]]}, "cannot name a variant"),
    ("lam", {"a.b": {"bad/name": 1}}, "value name"),
])
def test_malformed_grids_are_refused_naming_the_file(family, grid, message) -> None:
    with pytest.raises(FamilyError, match=message) as error:
        expand_grid(family, grid, "config/families/x.yaml")
    assert str(error.value).startswith("config/families/x.yaml: ")


def test_variant_config_is_the_base_with_the_variants_values() -> None:
    config = {"family": "lam", "grid": {"receding.line.lambda": [3.0, 4.0]},
              "compare": ["line.a"], "receding": {"line": {"lambda": 3.5, "n": 40}},
              "tests": "t.csv"}
    family, variants, base = split_family(config)
    assert family == "lam" and "grid" not in base and "compare" not in base
    merged = variant_config(base, variants[1])
    assert merged["receding"]["line"] == {"lambda": 4.0, "n": 40}
    assert merged["study"] == "lam/lambda4.0" and merged["tests"] == "t.csv"
    assert base["receding"]["line"]["lambda"] == 3.5  # the base is left as it was


def test_a_family_run_takes_no_study_and_known_quantities_only() -> None:
    with pytest.raises(FamilyError, match="drop the key study"):
        split_family({"family": "lam", "grid": {"a.b": [1]}, "study": "x"})
    with pytest.raises(FamilyError, match="compare"):
        split_family({"family": "lam", "grid": {"a.b": [1]}, "compare": ["line.q"]})


def test_study_names_of_variants() -> None:
    assert check_study_name("lam/lambda3.5_n300") == "lam/lambda3.5_n300"
    for bad in ("lam/", "lam/a/b", "/x", "lam/.x"):
        with pytest.raises(ValueError, match="study name"):
            check_study_name(bad)
