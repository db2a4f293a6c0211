"""DIC fields from a LaVision DaVis vector set, through the optional ``lvpyio``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.stiffness.readers.geometry import Geometry
from contactlab.stiffness.readers.grid import normalise_fields

_LENGTH_TO_UM = {"um": 1.0, "µm": 1.0, "micrometer": 1.0, "mm": 1e3, "m": 1e6, "nm": 1e-3}


def read_fields_davis(path: str | Path, geometry: Geometry | None = None) -> xr.Dataset:
    """Read a LaVision DaVis vector set (directory of ``.vc7``) through ``lvpyio``.

    ``lvpyio`` is optional (``pip install contactlab[davis]``); it is imported here only.
    Frame ids are the 1-based buffer numbers. Vectors that DaVis marks invalid (``MASK`` or
    ``ENABLED`` = 0) are masked. Positions and displacements are scaled with the set's own
    scales (units mm, um or m). The geometry is taken from ``geometry`` or from a sidecar
    ``contactlab.json`` in the set directory with the keys of :class:`Geometry`.
    """
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: DaVis vector set not found")
    try:
        import lvpyio  # optional vendor reader, imported lazily
    except ImportError:
        raise ValueError(f"{path}: reading DaVis sets needs the optional package lvpyio "
                         "(pip install 'contactlab[davis]')") from None
    if geometry is None:
        sidecar = (path if path.is_dir() else path.parent) / "contactlab.json"
        if not sidecar.is_file():
            raise FileNotFoundError(f"{path}: no geometry given and no sidecar {sidecar}")
        try:
            geometry = Geometry(**json.loads(sidecar.read_text(encoding="utf-8")))
        except (TypeError, json.JSONDecodeError) as exc:
            raise ValueError(f"{sidecar}: bad geometry sidecar: {exc}") from None
    vector_set = lvpyio.read_set(str(path))
    if isinstance(vector_set, list):
        raise ValueError(f"{path}: is a DaVis multi-set; pass one of its sets")
    us, vs, valids = [], [], []
    x = y = None
    for index in range(len(vector_set)):
        frame = vector_set[index][0]
        arr = frame.as_masked_array()
        scales, grid = frame.scales, frame.grid
        factor = _LENGTH_TO_UM.get(scales.i.unit.strip(), None)
        pos = _LENGTH_TO_UM.get(scales.x.unit.strip(), None)
        if factor is None or pos is None:
            raise ValueError(f"{path}: buffer {index + 1}: unsupported DaVis units "
                             f"({scales.x.unit!r}, {scales.i.unit!r}); need mm, um or m")
        ny, nx = arr.shape
        xs = ((np.arange(nx) + 0.5) * grid.x * scales.x.slope + scales.x.offset) * pos
        ys = ((np.arange(ny) + 0.5) * grid.y * scales.y.slope + scales.y.offset) * pos
        if x is None:
            x, y = xs, ys
        elif xs.shape != x.shape or ys.shape != y.shape or not (
            np.allclose(xs, x) and np.allclose(ys, y)
        ):
            raise ValueError(f"{path}: buffer {index + 1}: vector grid differs from buffer 1")
        mask = np.ma.getmaskarray(arr["u"]) | np.ma.getmaskarray(arr["v"])
        us.append(np.where(mask, np.nan, arr["u"].filled(np.nan) * factor))
        vs.append(np.where(mask, np.nan, arr["v"].filled(np.nan) * factor))
        valids.append(~mask)
    if x is None or y is None:
        raise ValueError(f"{path}: DaVis set has no buffers")
    ds = xr.Dataset(
        {"u": (("frame", "y", "x"), np.array(us)), "v": (("frame", "y", "x"), np.array(vs)),
         "valid": (("frame", "y", "x"), np.array(valids))},
        coords={"frame": np.arange(1, len(us) + 1), "y": y, "x": x},
    )
    return normalise_fields(ds, geometry, str(path))
