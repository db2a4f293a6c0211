"""Contact displacement from DIC displacement fields (thesis sec. 2.3.2, Fig. 2.5; sec. 2.5.4).

For each frame the vectors of equal x are averaged on each side of the masked interface,
a straight line is fitted to the mean profile on the pad and another on the specimen, and
the contact displacement is the step between the two lines at the centre of the mask.
Fitting lines removes the bulk deformation of pad and specimen from the step.

Signs (sec. 2.3.2): ``uc`` is the normal displacement of the specimen minus that of the pad,
along the normal pointing from pad to specimen, so it is negative while the normal load
closes the interface; ``vc`` is the tangential displacement of the specimen minus that of
the pad, along the direction a positive Qt (specimen pulled down, sec. 2.6) moves the
specimen, so it is positive in tangential loading steps.

The same construction per pixel row (points of equal y) gives the per-row contact
displacements behind the mean-row stiffness of sec. 2.5.4.

Everything is vectorised over frames (and rows): a least-squares line from masked sums.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.stiffness.readers import Geometry, geometry_of

__all__ = ["contact_displacement", "contact_displacement_rows", "step_between_lines"]


def _line_value(x: np.ndarray, values: np.ndarray, use: np.ndarray, at: float) -> np.ndarray:
    """Least-squares straight line through ``values[..., use]`` evaluated at ``at``.

    ``values`` has x as its last axis and may hold NaN (ignored). Returns NaN where fewer
    than two finite points lie in ``use``.
    """
    ok = np.isfinite(values) & use
    w = ok.astype(float)
    xs = x - at  # centre on the evaluation point: the intercept is the value there
    s0 = w.sum(axis=-1)
    sx = (w * xs).sum(axis=-1)
    sxx = (w * xs * xs).sum(axis=-1)
    vals = np.where(ok, values, 0.0)
    sy = vals.sum(axis=-1)
    sxy = (vals * xs).sum(axis=-1)
    det = s0 * sxx - sx * sx
    # distinct x positions are needed for a line; det > 0 exactly when there are two
    good = (s0 >= 2) & (det > 1e-12 * np.maximum(sxx * s0, 1e-300))
    with np.errstate(invalid="ignore", divide="ignore"):
        intercept = (sy * sxx - sx * sxy) / det
    return np.where(good, intercept, np.nan)


def step_between_lines(x: np.ndarray, values: np.ndarray, geometry: Geometry) -> np.ndarray:
    """Specimen line minus pad line at the mask centre, for profiles ``values[..., x]``."""
    on_pad = (x >= geometry.pad_x_min) & (x <= geometry.pad_x_max)
    on_specimen = (x >= geometry.specimen_x_min) & (x <= geometry.specimen_x_max)
    at = geometry.interface_x
    return _line_value(x, values, on_specimen, at) - _line_value(x, values, on_pad, at)


def contact_displacement(fields: xr.Dataset) -> xr.Dataset:
    """uc and vc per frame from the mean displacement field (sec. 2.3.2), um."""
    geometry = geometry_of(fields)
    x = fields["x"].to_numpy()
    with np.errstate(invalid="ignore"), _quiet():
        u_mean = np.nanmean(fields["u"].to_numpy(), axis=1)  # average vectors of equal x
        v_mean = np.nanmean(fields["v"].to_numpy(), axis=1)
    uc = geometry.normal_sign * step_between_lines(x, u_mean, geometry)
    vc = geometry.qt_positive * step_between_lines(x, v_mean, geometry)
    return _as_dataset(fields, uc, vc, ("frame",))


def contact_displacement_rows(fields: xr.Dataset) -> xr.Dataset:
    """uc and vc per frame and pixel row (points of equal y), for sec. 2.5.4, um."""
    geometry = geometry_of(fields)
    x = fields["x"].to_numpy()
    uc = geometry.normal_sign * step_between_lines(x, fields["u"].to_numpy(), geometry)
    vc = geometry.qt_positive * step_between_lines(x, fields["v"].to_numpy(), geometry)
    return _as_dataset(fields, uc, vc, ("frame", "y"))


def _as_dataset(fields: xr.Dataset, uc: np.ndarray, vc: np.ndarray,
                dims: tuple[str, ...]) -> xr.Dataset:
    where = "per pixel row " if "y" in dims else ""
    return xr.Dataset(
        {
            "uc": (dims, uc, {"long_name": f"normal contact displacement {where}(sec. 2.3.2)",
                              "units": "um"}),
            "vc": (dims, vc, {"long_name": f"tangential contact displacement {where}"
                                           "(sec. 2.3.2)", "units": "um"}),
        },
        coords={dim: fields[dim] for dim in dims},
    )


class _quiet:
    """Silence numpy's 'mean of empty slice' warnings (columns inside the mask)."""

    def __enter__(self) -> None:
        import warnings

        self._ctx = warnings.catch_warnings()
        self._ctx.__enter__()
        warnings.simplefilter("ignore", category=RuntimeWarning)

    def __exit__(self, *exc: object) -> None:
        self._ctx.__exit__(*exc)
