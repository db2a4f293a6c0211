"""Result files of small workflow targets, one or more per branch: reproducible, CF-valid.

Small targets built from scratch in a fresh directory must be byte-identical to the same
files of the end-to-end run (no wall-clock values or paths in results). The CF checker reads every
netCDF file of the end-to-end run (tests/test_workflow.py); here it is shown that it can fail.
"""

from __future__ import annotations

import filecmp
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from cf_check import cf_errors

from contactlab.io import stamp, write_netcdf

pytestmark = pytest.mark.filterwarnings("ignore:The ioos_sos checker:DeprecationWarning")

#: One or more small targets per branch: surfaces, stiffness, dic (the image demo's frames
#: and their fields), asperity, receding (a chunk gather and a profile) and finite elements.
TARGETS = (
    "results/surfaces/seq.nc",
    "results/stiffness/RU1.nc",
    "results/dic/RU1i/fields.nc",
    "results/asperity/grid.nc",
    "results/asperity/bem/coulomb.nc",
    "results/asperity/grid_bem.nc",
    "results/receding/gap.nc",
    "results/receding/line.nc",
    "results/receding/profiles/gap_w2.5_f0.5.nc",
    "results/fe/runs/line_coarse.nc",
)


def _files(root: Path) -> list[str]:
    """The results (the store's entries aside: links to these very files and each job's
    record of when it ran)."""
    return sorted(p.relative_to(root).as_posix() for p in (root / "results").rglob("*")
                  if p.is_file() and "store" not in p.relative_to(root / "results").parts[:1])


def _equal_but_ccx_iterations(a: Path, b: Path) -> bool:
    """An FE run equal in every value but CalculiX's contact iteration count.

    ccx's count of contact iterations varies between identical runs (29-32 seen for
    line_coarse, the same input deck and binary); every displacement and stress it writes
    is bitwise equal. The count stays in the result as a diagnostic of the run.
    """
    if a.suffix != ".nc" or a.parent.name != "runs" or a.parent.parent.name != "fe":
        return False
    with xr.open_dataset(a) as one, xr.open_dataset(b) as two:
        one, two = one.load(), two.load()
    return one.drop_vars("iterations").identical(two.drop_vars("iterations"))


def test_cf_checker_finds_a_fill_value_on_a_coordinate(tmp_path: Path) -> None:
    """The check below can fail: xarray's default _FillValue on a coordinate is an error."""
    ds = xr.Dataset({"v": ("f", np.arange(3.0), {"long_name": "v", "units": "1"})},
                    coords={"f": ("f", [0.1, 0.2, 0.3], {"long_name": "f", "units": "1"})})
    stamp(ds, title="t", source="test", history="test")
    ds.to_netcdf(tmp_path / "plain.nc")
    assert any("'f' must not have the _FillValue" in m for m in cf_errors(tmp_path / "plain.nc"))
    write_netcdf(ds, tmp_path / "ours.nc")
    assert cf_errors(tmp_path / "ours.nc") == []


@pytest.mark.slow
def test_small_targets_rebuild_byte_identical(e2e_copy: Path, e2e_run: Path,
                                              snakemake) -> None:
    """The targets built on their own, in another directory, equal the end-to-end run's.

    Every job is a process of its own with its own string hash seed: a result that depended
    on the process (a set's order, for one) would differ."""
    workflow_copy = e2e_copy
    run = snakemake(workflow_copy, "-j2", *TARGETS)
    assert run.returncode == 0, run.stderr[-3000:]
    files = _files(workflow_copy)
    assert "results/surfaces/texture.nc" in files and len(files) > 50
    assert not set(files) - set(_files(e2e_run))
    differ = [f for f in files
              if not filecmp.cmp(e2e_run / f, workflow_copy / f, shallow=False)
              and not _equal_but_ccx_iterations(e2e_run / f, workflow_copy / f)]
    assert differ == []
    # the timings are in the logs instead (the progress report's final line)
    log = (workflow_copy / "logs" / "surfaces" / "texture.log").read_text()
    assert re.search(r" INFO contactlab\.surfaces\.cli: surface texture: done, "
                     r"\d+/\d+ surfaces in \d+\.\d s", log), log[-2000:]
