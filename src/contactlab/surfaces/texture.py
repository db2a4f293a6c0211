"""Texture of one surface from its scans, as in sec. 2.3.4 (Tables A.1, A.26, A.27, 2.6).

Areal scan -> least-squares plane removed (F-operator) -> Gaussian L-filter at
lambda_c (ISO 16610-61, end-corrected) -> Sa, Sq, Sp, Str, fractal dimension,
height histogram and radially averaged power spectrum.

Profile scan -> 5 lines along the stated direction, each of the stated profile
length -> least-squares line removed -> Gaussian filter at lambda_c -> 10 % of
the length discarded at each end (as the Alicona does, sec. 2.3.4) -> Ra, Rq, Rz
per sampling length (the sheet's ``sampling_length_um``, by default lambda_c as ISO
4288 pairs them), averaged over the sampling lengths and over the lines.

Undefined scan points are filled when reading (:mod:`contactlab.surfaces.scans`),
and the filled fraction is recorded. A parameter the standard leaves undefined for
a scan is NaN with an ``undefined_reason`` attribute, never a number.

A scan the analysis refuses (unreadable, too many undefined points, smaller than
lambda_c or the profile length) leaves its parameters NaN and its reason in the
result (``refused_<kind>_scan``), so a summary can list every surface with its
parameters or why they are missing; :func:`refused_scans` turns that into an error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from contactlab.io import variable
from contactlab.surfaces.filters import mean_surface, remove_line, remove_plane, roughness_profile
from contactlab.surfaces.parameters import (
    UndefinedParameter,
    arithmetic_mean_height,
    box_counting_dimension,
    maximum_peak_height,
    profile_parameters,
    texture_aspect_ratio,
)
from contactlab.surfaces.scans import Scan, read_scan
from contactlab.surfaces.sheet import END_FRACTION, SurfaceSpec

#: Profile lines per surface (sec. 2.3.4: "the average of the values of 5 measurements").
N_PROFILES = 5
#: Largest side of the stored height map used for the report picture (pixels).
MAP_PIXELS = 256

SCAN_KINDS = ("areal", "profile")
AREAL = ("Sa", "Sq", "Sp", "Str", "fractal_dimension")
PROFILE = ("Ra", "Rq", "Rz")
ATTRS = {
    "Sa": ("arithmetic mean height Sa (ISO 25178-2)", "um"),
    "Sq": ("root mean square height Sq (ISO 25178-2)", "um"),
    "Sp": ("maximum peak height Sp (ISO 25178-2)", "um"),
    "Str": ("texture aspect ratio Str, ACF threshold s = 0.2 (ISO 25178-2)", "1"),
    "fractal_dimension": ("fractal dimension, cube counting", "1"),
    "Ra": ("arithmetic mean deviation Ra (ISO 4287), mean of sampling lengths and lines", "um"),
    "Rq": ("root mean square deviation Rq (ISO 4287), mean of sampling lengths and lines", "um"),
    "Rz": ("maximum height Rz (ISO 4287), mean of sampling lengths and lines", "um"),
}

SAMPLING_LENGTH = {"long_name": "sampling length of Ra, Rq, Rz (ISO 4287/4288)", "units": "um"}
#: What changes the limit of undefined points, named in a refusal.
FILL_SETTING = ("surfaces: max_undefined_fraction in the workflow config, "
                "--max-undefined-fraction of contactlab surfaces texture")
FILLED = {kind: {"long_name": f"fraction of the {kind} scan's points that were undefined and "
                              "filled by harmonic interpolation", "units": "1"}
          for kind in ("areal", "profile")}


@dataclass
class SurfaceTexture:
    """Parameters and spectra of one surface (NaN where a scan is absent).

    ``undefined`` maps a parameter left NaN for a scan to the reason; ``filled``
    maps ``areal``/``profile`` to the fraction of that scan's points filled;
    ``refused`` maps ``areal``/``profile`` to why that scan was not evaluated.
    """

    spec: SurfaceSpec
    values: dict[str, float] = field(default_factory=dict)
    areal: dict[str, np.ndarray] = field(default_factory=dict)
    profile: dict[str, np.ndarray] = field(default_factory=dict)
    synthetic: bool = False
    undefined: dict[str, str] = field(default_factory=dict)
    filled: dict[str, float] = field(default_factory=dict)
    refused: dict[str, str] = field(default_factory=dict)
    max_undefined_fraction: float = field(kw_only=True)


def _check_cut_off(extent_um: float, lambda_c: float, what: str, scan: Scan) -> None:
    if extent_um < lambda_c:
        raise ValueError(
            f"{scan.path}: {what} of {extent_um:.4g} um is smaller than the cut-off "
            f"lambda_c = {lambda_c:.4g} um; the L-filter cannot separate roughness from form"
        )


def _defined_spectrum(q: np.ndarray, psd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The bins of a (masked) spectrum with a finite, positive q and a finite PSD.

    CF forbids missing values in a coordinate, so empty bins are dropped, not kept as NaN.
    """
    q_data, psd_data = np.ma.getdata(q).astype(float), np.ma.getdata(psd).astype(float)
    ok = ~(np.ma.getmaskarray(q) | np.ma.getmaskarray(psd))
    ok &= np.isfinite(q_data) & np.isfinite(psd_data) & (q_data > 0)
    return q_data[ok], psd_data[ok]


def _maybe(undefined: dict[str, str], name: str, compute: Callable[[], float]) -> float:
    """``compute()``, or NaN with the reason stored in ``undefined[name]``."""
    try:
        return compute()
    except UndefinedParameter as exc:
        undefined[name] = str(exc)
        return float("nan")


def areal_texture(scan: Scan, lambda_c: float, histogram_bins: int = 80) -> dict:
    """Areal parameters of a scan after plane removal and the lambda_c Gaussian filter.

    Returns ``values`` (NaN where undefined), ``undefined`` (reasons) and ``arrays``.
    """
    from SurfaceTopography import Topography

    sx, sy = scan.size_um
    if scan.heights.shape[1] < 2:
        raise ValueError(f"{scan.path}: a line scan cannot give areal parameters")
    _check_cut_off(min(sx, sy), lambda_c, "the smaller side of the scan", scan)
    form_removed = remove_plane(scan.heights)
    rough = form_removed - mean_surface(form_removed, lambda_c, scan.dx, scan.dy)
    rough -= rough.mean()
    topography = Topography(rough, physical_sizes=(sx, sy), unit="um", periodic=False)
    q, psd = _defined_spectrum(*topography.power_spectrum_from_area(nb_points_per_decade=10))
    counts, edges = np.histogram(rough, bins=histogram_bins, density=True)
    step_x = max(1, int(np.ceil(rough.shape[0] / MAP_PIXELS)))
    step_y = max(1, int(np.ceil(rough.shape[1] / MAP_PIXELS)))
    undefined: dict[str, str] = {}
    values = {
        "Sa": arithmetic_mean_height(rough),
        "Sq": float(topography.Sq()),
        "Sp": maximum_peak_height(rough),
        "Str": _maybe(undefined, "Str", lambda: texture_aspect_ratio(rough, scan.dx, scan.dy)),
        "fractal_dimension": _maybe(undefined, "fractal_dimension", lambda: box_counting_dimension(
            rough, 0.5 * (scan.dx + scan.dy))),
    }
    arrays = {
        "q": q, "psd": psd, "density": counts, "edges": edges,
        "map": rough[::step_x, ::step_y], "map_dx": scan.dx * step_x, "map_dy": scan.dy * step_y,
        "dx": scan.dx, "dy": scan.dy, "size_x": sx, "size_y": sy,
    }
    return {"values": values, "undefined": undefined, "arrays": arrays}


def profile_lines(scan: Scan, axis: str, length_um: float,
                  n_lines: int = N_PROFILES) -> tuple[np.ndarray, float]:
    """``n_lines`` lines of ``length_um`` along ``axis``, evenly spaced across the scan.

    Returns (lines of shape (points, n_lines), spacing along the lines). A scan
    with fewer lines than asked gives all it has.
    """
    heights = scan.heights if axis == "x" else scan.heights.T
    spacing = scan.dx if axis == "x" else scan.dy
    along, across = heights.shape
    points = round(length_um / spacing)
    if points > along + 1:
        raise ValueError(
            f"{scan.path}: profile length {length_um / 1000:.4g} mm is longer than the scan "
            f"along {axis} ({along * spacing / 1000:.4g} mm)"
        )
    points = min(points, along)
    start = (along - points) // 2
    if across <= n_lines:
        columns = np.arange(across)
    else:
        columns = np.rint(np.linspace(0, across - 1, n_lines + 2)[1:-1]).astype(int)
    return heights[start:start + points, columns], spacing


def profile_texture(scan: Scan, axis: str, length_um: float, lambda_c: float,
                    sampling_length: float | None = None) -> dict:
    """Ra, Rq, Rz of ``N_PROFILES`` lines (ISO 4287/4288 as in sec. 2.3.4) and their PSD.

    The parameters are means over sampling lengths of ``sampling_length`` um
    (default lambda_c) in each line's evaluation length, then over the lines;
    ``undefined`` gives the reason for a NaN (all lines share the sampling).
    """
    from SurfaceTopography import Topography, UniformLineScan

    sampling_length = lambda_c if sampling_length is None else sampling_length
    lines, spacing = profile_lines(scan, axis, length_um)
    points = lines.shape[0]
    trim = round(END_FRACTION * points)
    evaluation_um = (points - 2 * trim) * spacing
    what = f"the evaluation length of a profile ({100 * (1 - 2 * END_FRACTION):g} % of its length)"
    _check_cut_off(evaluation_um, lambda_c, what, scan)
    if evaluation_um < sampling_length:
        raise ValueError(f"{scan.path}: {what} of {evaluation_um:.4g} um is shorter than the "
                         f"sampling length of {sampling_length:.4g} um")
    results, rough_lines = [], []
    for k in range(lines.shape[1]):
        rough = roughness_profile(remove_line(lines[:, k]), lambda_c, spacing)
        evaluation = rough[trim:points - trim]
        rough_lines.append(evaluation)
        results.append(profile_parameters(evaluation, spacing, sampling_length))
    rough = np.stack(rough_lines, axis=1)
    if rough.shape[1] > 1:
        topography = Topography(rough, physical_sizes=(rough.shape[0] * spacing,
                                                       rough.shape[1] * spacing),
                                unit="um", periodic=False)
    else:
        topography = UniformLineScan(rough[:, 0], physical_sizes=rough.shape[0] * spacing,
                                     unit="um", periodic=False)
    q, psd = _defined_spectrum(*topography.power_spectrum_from_profile(nb_points_per_decade=10))
    values = {name: float(np.mean([getattr(r, name) for r in results])) for name in PROFILE}
    arrays = {
        "q": q, "psd": psd, "lines": rough, "spacing": spacing,
        "n_lines": rough.shape[1], "n_sampling_lengths": results[0].n_sampling_lengths,
        "sampling_length": sampling_length,
    }
    return {"values": values, "undefined": dict(results[0].undefined), "arrays": arrays}


def surface_texture(spec: SurfaceSpec, histogram_bins: int, max_undefined_fraction: float,
                    record_refused: bool = False) -> SurfaceTexture:
    """Everything the sheet asks for one surface.

    Scans with at most ``max_undefined_fraction`` undefined points are filled
    (:func:`contactlab.surfaces.scans.read_scan`); more is refused. A refused
    scan raises ValueError naming the file, or with ``record_refused`` leaves
    its parameters NaN and the message in ``refused[kind]``.
    """
    texture = SurfaceTexture(spec, dict.fromkeys(AREAL + PROFILE, np.nan),
                             max_undefined_fraction=max_undefined_fraction)
    for kind in SCAN_KINDS:
        path = spec.areal_scan if kind == "areal" else spec.profile_scan
        if path is None:
            continue
        try:
            scan = read_scan(path, max_undefined_fraction, FILL_SETTING)
            if kind == "areal":
                result = areal_texture(scan, spec.lambda_c_um, histogram_bins)
            else:
                assert spec.profile_length_um is not None
                result = profile_texture(scan, spec.profile_axis, spec.profile_length_um,
                                         spec.lambda_c_um, spec.sampling_length)
        except ValueError as exc:
            if not record_refused:
                raise
            texture.refused[kind] = str(exc)
            continue
        texture.synthetic |= scan.synthetic
        texture.filled[kind] = scan.filled_fraction
        texture.values.update(result["values"])
        texture.undefined.update(result["undefined"])
        setattr(texture, kind, result["arrays"])
    return texture


def surface_dataset(texture: SurfaceTexture) -> xr.Dataset:
    """The CF-style dataset of ``results/surfaces/<surface>.nc``."""
    spec = texture.spec
    data: dict[str, xr.Variable] = {}
    for name in AREAL + PROFILE:
        reason = texture.undefined.get(name)
        data[name] = variable((), texture.values[name], *ATTRS[name],
                              **{"undefined_reason": reason} if reason else {})
    for kind, fraction in texture.filled.items():
        data[f"filled_fraction_{kind}"] = xr.Variable((), fraction, FILLED[kind])
    data["lambda_c"] = xr.Variable((), spec.lambda_c_um,
                                   {"long_name": "Gaussian cut-off wavelength", "units": "um"})
    coords: dict[str, xr.Variable] = {}
    if texture.areal:
        a = texture.areal
        centres = 0.5 * (a["edges"][1:] + a["edges"][:-1])
        coords["roughness_height"] = xr.Variable("roughness_height", centres, {
            "long_name": "height from the mean plane (bin centre)", "units": "um"})
        data["height_density"] = xr.Variable("roughness_height", a["density"], {
            "long_name": "probability density of the roughness heights", "units": "1/um"})
        coords["q_areal"] = xr.Variable("q_areal", a["q"], {
            "long_name": "wavevector magnitude", "units": "1/um"})
        data["psd_areal"] = xr.Variable("q_areal", a["psd"], {
            "long_name": "radially averaged areal power spectral density of the roughness "
                         "surface", "units": "um^4"})
        nx, ny = a["map"].shape
        coords["map_x"] = xr.Variable("map_x", np.arange(nx) * a["map_dx"], {
            "long_name": "x position in the scan (subsampled)", "units": "um"})
        coords["map_y"] = xr.Variable("map_y", np.arange(ny) * a["map_dy"], {
            "long_name": "y position in the scan (subsampled)", "units": "um"})
        data["roughness_map"] = xr.Variable(("map_x", "map_y"), a["map"].astype(np.float32), {
            "long_name": "roughness surface after form removal and the lambda_c filter "
                         "(subsampled for display)", "units": "um"})
        for key, name in (("dx", "pixel_x"), ("dy", "pixel_y")):
            data[name] = xr.Variable((), a[key], {
                "long_name": f"areal scan sampling distance along {name[-1]}", "units": "um"})
    if texture.profile:
        p = texture.profile
        coords["q_profile"] = xr.Variable("q_profile", p["q"], {
            "long_name": "wavevector", "units": "1/um"})
        data["psd_profile"] = xr.Variable("q_profile", p["psd"], {
            "long_name": "power spectral density of the roughness profiles (mean of lines)",
            "units": "um^3"})
        lines = p["lines"]
        coords["s"] = xr.Variable("s", np.arange(lines.shape[0]) * p["spacing"], {
            "long_name": "position along the evaluation length", "units": "um"})
        data["profile_first"] = xr.Variable("s", lines[:, 0].astype(np.float32), {
            "long_name": "first roughness profile over the evaluation length", "units": "um"})
        data["n_profiles"] = xr.Variable((), p["n_lines"], {
            "long_name": "number of profile lines averaged", "units": "1"})
        data["n_sampling_lengths"] = xr.Variable((), p["n_sampling_lengths"], {
            "long_name": "sampling lengths per profile", "units": "1"})
        data["sampling_length"] = xr.Variable((), p["sampling_length"], SAMPLING_LENGTH)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(
        surface=spec.surface,
        objective=spec.objective,
        areal_scan=str(spec.areal_scan or ""),
        profile_scan=str(spec.profile_scan or ""),
        profile_axis=spec.profile_axis,
        profile_direction=spec.profile_direction or "",
        profile_length_mm=(spec.profile_length_um or 0.0) / 1000.0,
        synthetic_scans=int(texture.synthetic),
        max_undefined_fraction=texture.max_undefined_fraction,
        **{f"refused_{kind}_scan": reason for kind, reason in texture.refused.items()},
    )
    return ds


def _scalar(ds: xr.Dataset, name: str) -> float:
    return float(ds[name]) if name in ds else np.nan


def summary_dataset(datasets: list[xr.Dataset]) -> xr.Dataset:
    """Parameters of every surface, one row per surface (``results/surfaces/texture.nc``).

    Built from the ``<surface>.nc`` datasets of :func:`surface_dataset`;
    ``undefined_reason`` (surface, parameter) is empty where a parameter is defined.
    """
    if not datasets:
        raise ValueError("no surface results to summarise")
    limits = {ds.attrs["max_undefined_fraction"] for ds in datasets}
    if len(limits) > 1:
        raise ValueError(f"surface results made with different max_undefined_fraction {limits}; "
                         "rerun them with one setting")
    surfaces = np.array([ds.attrs["surface"] for ds in datasets], dtype=object)
    data = {
        name: variable("surface", np.array([float(ds[name]) for ds in datasets]), *ATTRS[name])
        for name in AREAL + PROFILE
    }
    data["undefined_reason"] = xr.Variable(
        ("surface", "parameter"),
        np.array([[ds[name].attrs.get("undefined_reason", "") for name in AREAL + PROFILE]
                  for ds in datasets], dtype=object),
        {"long_name": "why the parameter is NaN (ISO leaves it undefined for the scan); "
                      "empty if defined"})
    data["refused_reason"] = xr.Variable(
        ("surface", "scan"),
        np.array([[ds.attrs.get(f"refused_{kind}_scan", "") for kind in SCAN_KINDS]
                  for ds in datasets], dtype=object),
        {"long_name": "why the scan was not evaluated (its parameters are NaN); empty if it "
                      "was evaluated or the sheet names no such scan"})
    for kind in SCAN_KINDS:
        data[f"filled_fraction_{kind}"] = xr.Variable(
            "surface", [_scalar(ds, f"filled_fraction_{kind}") for ds in datasets], FILLED[kind])
    data["lambda_c"] = xr.Variable("surface", [float(ds["lambda_c"]) for ds in datasets], {
        "long_name": "Gaussian cut-off wavelength", "units": "um"})
    data["sampling_length"] = xr.Variable(
        "surface", [_scalar(ds, "sampling_length") for ds in datasets], SAMPLING_LENGTH)
    data["profile_length"] = xr.Variable(
        "surface", [ds.attrs["profile_length_mm"] or np.nan for ds in datasets],
        {"long_name": "profile line length", "units": "mm"})
    data["profile_direction"] = xr.Variable(
        "surface", np.array([ds.attrs["profile_direction"] for ds in datasets], dtype=object),
        {"long_name": "profile direction relative to the lay or pattern"})
    data["synthetic"] = xr.Variable(
        "surface", np.array([ds.attrs["synthetic_scans"] for ds in datasets], dtype=np.int8),
        {"long_name": "1 if a scan of the surface is labelled SYNTHETIC", "units": "1"})
    data["objective"] = xr.Variable(
        "surface", np.array([ds.attrs["objective"] for ds in datasets], dtype=object),
        {"long_name": "profilometer objective"})
    summary = xr.Dataset(data, coords={
        "surface": ("surface", surfaces, {"long_name": "surface id"}),
        "parameter": ("parameter", np.array(AREAL + PROFILE, dtype=object),
                      {"long_name": "texture parameter"}),
        "scan": ("scan", np.array(SCAN_KINDS, dtype=object), {"long_name": "kind of scan"}),
    })
    summary.attrs["max_undefined_fraction"] = limits.pop()
    return summary


def refused_scans(summary: xr.Dataset) -> list[tuple[str, str, str]]:
    """(surface, scan kind, reason) of every refused scan in a texture summary."""
    reasons = summary["refused_reason"]
    return [(str(surface), str(kind), str(reasons.sel(surface=surface, scan=kind).item()))
            for surface in summary["surface"].values for kind in summary["scan"].values
            if reasons.sel(surface=surface, scan=kind).item()]
