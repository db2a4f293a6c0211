"""The one rule-helper module: report files a rule declares beside its tables and figures."""

from __future__ import annotations

from contactlab.rulehelpers import pdf_files, table_files


def test_tables_and_figures_come_with_their_copies() -> None:
    assert table_files("r/tables/a.csv", "r/tables/b.csv") == [
        "r/tables/a.csv", "r/tables/a.md", "r/tables/b.csv", "r/tables/b.md"]
    assert pdf_files("r/figures/a.png") == ["r/figures/a.pdf"]


def test_rough_interface_runs_take_one_c_t_for_both_sides() -> None:
    """The FE runs of receding.rough.fe get C_T = ratio x C explicitly (the DDT reads it
    from the run), the Mindlin ratio at receding.rough.nu when no ratio is given; profile
    names and their points round-trip; no FE run without fe.enabled."""
    import pytest

    from contactlab.receding.core.interface import mindlin_ratio
    from contactlab.rulehelpers import (
        rough_ct_ratio,
        rough_fe_run,
        rough_fe_runs,
        rough_pairs_summary,
        rough_profile_name,
        rough_profile_point,
    )

    rough = {"ct_ratios": [], "nu": 0.25,
             "fe": {"problems": ["line"], "C": [0.3, 1.0], "h": [0.05, 0.025]},
             "profiles": [{"problem": "line", "f": 0.5, "C": 1.0},
                          {"problem": "uniform", "w": 1.0, "f": 0.3, "C": 0.3}],
             "pairs": {"tests": {"S3": {"from_test": "S3"}}}}
    config = {"receding": {"rough": rough}, "fe": {"enabled": True}}
    assert rough_ct_ratio(rough) == pytest.approx(1.0 / mindlin_ratio(0.25))
    assert rough_ct_ratio({**rough, "ct_ratios": [2.0, 3.0]}) == 2.0
    assert rough_fe_runs(config, "r/") == [
        "r/fe/rough/line_C0.3_h0.05.nc", "r/fe/rough/line_C0.3_h0.025.nc",
        "r/fe/rough/line_C1_h0.05.nc", "r/fe/rough/line_C1_h0.025.nc"]
    assert rough_fe_runs({**config, "fe": {"enabled": False}}) == []
    run = rough_fe_run(config, "line", "0.3", "0.025")
    assert run == {"problem": "line", "compliance": 0.3,
                   "compliance_t": pytest.approx(0.3 / mindlin_ratio(0.25)), "h": 0.025,
                   "level": "h0.025"}
    with pytest.raises(ValueError, match=r"line_C3_h0\.05 is not in receding\.rough\.fe"):
        rough_fe_run(config, "line", "3", "0.05")
    names = [rough_profile_name(p) for p in rough["profiles"]]
    assert names == ["line_f0.5_C1", "uniform_w1_f0.3_C0.3"]
    assert rough_profile_point(rough["profiles"], names[1]) == {
        "problem": "uniform", "f": 0.3, "C": 0.3, "w_hat": 1.0}
    assert rough_pairs_summary(rough, "r/") == ["r/stiffness/summary.nc"]
    assert rough_pairs_summary({"pairs": {"tests": {"X": {"beta_n_per_um": 1}}}}) == []
