"""The .frd/.sta readers on a hand-written CalculiX result file."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from contactlab.fe.frd import read_frd, read_sta

FRD = """\
    1C
    2C                             2                                     1
 -1         1 0.00000E+00 0.00000E+00 0.00000E+00
 -1         2 1.00000E+00 0.00000E+00 0.00000E+00
 -3
  100CL  101 5.00000E-01           2                     0    1           1
 -4  DISP        4    1
 -5  D1          1    2    1    0
 -5  D2          1    2    2    0
 -5  D3          1    2    3    0
 -5  ALL         1    2    0    0    1ALL
 -1         1 1.00000E-03-2.00000E-03 0.00000E+00
 -1         2 3.00000E-03-4.00000E-03 0.00000E+00
 -3
  100CL  102 1.00000E+00           2                     0    2           1
 -4  DISP        4    1
 -5  D1          1    2    1    0
 -5  D2          1    2    2    0
 -5  D3          1    2    3    0
 -5  ALL         1    2    0    0    1ALL
 -1         1 2.00000E-03-4.00000E-03 0.00000E+00
 -1         2 6.00000E-03-8.00000E-03 0.00000E+00
 -3
 9999
"""

STA = """\
SUMMARY OF JOB INFORMATION
  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME
     1          1     1U   60  0.000000E+00  0.000000E+00  0.250000E+00
     1          1     2    12  0.250000E+00  0.250000E+00  0.250000E+00
     1          2     1     8  0.100000E+01  0.100000E+01  0.750000E+00
"""


def test_read_frd_blocks(tmp_path: Path) -> None:
    path = tmp_path / "job.frd"
    path.write_text(FRD)
    frd = read_frd(path)
    assert sorted(frd.coords) == [1, 2]
    assert np.allclose(frd.coords[2], [1.0, 0.0, 0.0])
    assert [b.time for b in frd.series("DISP")] == [0.5, 1.0]
    last = frd.last("DISP")
    assert list(last.nodes) == [1, 2]
    assert np.allclose(last.values["D2"], [-4e-3, -8e-3])  # fixed-width, no blank separator
    assert "ALL" not in last.values
    with pytest.raises(KeyError):
        frd.last("CONTACT")


def test_read_sta(tmp_path: Path) -> None:
    path = tmp_path / "job.sta"
    path.write_text(STA)
    sta = read_sta(path)
    assert sta["increments"] == 3 and sta["iterations"] == 80
    assert sta["final_time"] == 1.0
    assert read_sta(tmp_path / "missing.sta")["increments"] == 0


def test_missing_frd_is_a_file_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"missing\.frd"):
        read_frd(tmp_path / "missing.frd")
