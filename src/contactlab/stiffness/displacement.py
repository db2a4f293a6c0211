"""Contact displacement from DIC displacement fields (thesis sec. 2.3.2, Fig. 2.5; sec. 2.5.4).

For each frame a plane ``u = a + b x + c y`` is fitted by least squares to the valid vectors
of the pad and another to those of the specimen, and the contact displacement is the step
between the two planes at the centre of the mask and the mean y of the rows used. Fitting
planes removes the bulk deformation of pad and specimen from the step (the ``b x`` term:
strain across the interface; the ``c y`` term: shear, rotation, Poisson contraction along
it). With every vector valid this is the thesis's construction exactly: the vectors of equal
x averaged, a line fitted to each side's mean profile, their step at the mask centre. Where
vectors are rejected in some rows only (DIC), the plane keeps the y-dependence of the
displacement out of the step, which averaging each column's valid vectors would shift.

Signs (sec. 2.3.2): ``uc`` is the normal displacement of the specimen minus that of the pad,
along the normal pointing from pad to specimen, so it is negative while the normal load
closes the interface; ``vc`` is the tangential displacement of the specimen minus that of
the pad, along the direction a positive Qt (specimen pulled down, sec. 2.6) moves the
specimen, so it is positive in tangential loading steps.

The same construction per pixel row (points of equal y) gives the per-row contact
displacements behind the mean-row stiffness of sec. 2.5.4.

Everything is vectorised over frames (and rows): least-squares lines and planes from masked
sums.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.stiffness.readers import Geometry, geometry_of

__all__ = ["contact_displacement", "contact_displacement_rows", "step_between_lines",
           "step_between_planes"]


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


def _plane_value(x: np.ndarray, y: np.ndarray, values: np.ndarray, use: np.ndarray,
                 at_x: float, at_y: np.ndarray) -> np.ndarray:
    """Least-squares plane ``a + b x + c y`` through ``values[..., y, x]`` in the columns
    ``use``, evaluated at (``at_x``, ``at_y``), one per leading index (frame).

    NaN in ``values`` is ignored. Where the used vectors lie in one row only, ``c`` is
    undetermined and the plane is the line through that row; NaN where they lie in fewer
    than two columns (or on one straight line across rows and columns).
    """
    ok = np.isfinite(values) & use[None, None, :]
    w = ok.astype(float)
    vals = np.where(ok, values, 0.0)
    n = w.sum(axis=(-2, -1))
    with np.errstate(invalid="ignore", divide="ignore"):
        mx = (w * x).sum(axis=(-2, -1)) / n
        my = (w * y[:, None]).sum(axis=(-2, -1)) / n
        mv = vals.sum(axis=(-2, -1)) / n
        dx = x[None, None, :] - mx[:, None, None]
        dy = y[None, :, None] - my[:, None, None]
        dv = np.where(ok, values - mv[:, None, None], 0.0)
        sxx, syy, sxy = ((w * a * b).sum(axis=(-2, -1)) for a, b in
                         ((dx, dx), (dy, dy), (dx, dy)))
        sxv, syv = ((a * dv).sum(axis=(-2, -1)) for a in (dx, dy))
        det = sxx * syy - sxy * sxy
        one_row = ~(syy > 1e-12 * np.maximum(sxx, 1e-300))
        plane = det > 1e-12 * np.maximum(sxx * syy, 1e-300)
        b = np.where(one_row, sxv / sxx, (syy * sxv - sxy * syv) / det)
        c = np.where(one_row, 0.0, (sxx * syv - sxy * sxv) / det)
        value = mv + b * (at_x - mx) + c * (at_y - my)
    columns = ok.any(axis=-2).sum(axis=-1)
    good = (columns >= 2) & (one_row | plane)
    return np.where(good, value, np.nan)


def step_between_planes(x: np.ndarray, y: np.ndarray, values: np.ndarray,
                        geometry: Geometry) -> np.ndarray:
    """Specimen plane minus pad plane at the mask centre, per frame of ``values[frame, y,
    x]``, at the mean y of the rows holding a valid vector on either side."""
    on_pad = (x >= geometry.pad_x_min) & (x <= geometry.pad_x_max)
    on_specimen = (x >= geometry.specimen_x_min) & (x <= geometry.specimen_x_max)
    used = (np.isfinite(values) & (on_pad | on_specimen)[None, None, :]).any(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        at_y = (used * y[None, :]).sum(axis=-1) / used.sum(axis=-1)
    at = geometry.interface_x
    return (_plane_value(x, y, values, on_specimen, at, at_y)
            - _plane_value(x, y, values, on_pad, at, at_y))


def contact_displacement(fields: xr.Dataset) -> xr.Dataset:
    """uc and vc per frame from the planes fitted to each side's valid vectors (sec. 2.3.2;
    module docstring), um."""
    geometry = geometry_of(fields)
    x = fields["x"].to_numpy()
    y = fields["y"].to_numpy()
    uc = geometry.normal_sign * step_between_planes(x, y, fields["u"].to_numpy(), geometry)
    vc = geometry.qt_positive * step_between_planes(x, y, fields["v"].to_numpy(), geometry)
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
