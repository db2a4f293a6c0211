"""How the *-crop.* files were made from SurfaceTopography's example files.

The originals (test/file_format_examples/ of github.com/ContactEngineering/SurfaceTopography,
MIT licence, see LICENSE-SurfaceTopography.md) are 4.0, 3.2 and 3.2 MB. These crops keep the
instrument's own file layout and metadata and only cut the height matrix, so the reader,
the filling of undefined points and the texture analysis meet the same kind of file:

- opd-1.opd (Wyko Vision, 640 x 480, 116 undefined points): x pixels 0-255 and the 192
  rows that hold the largest cluster of undefined points (95 points); the secondary
  arrays (SecArr_0, Modulation, Image) are given zero length, which the format allows.
- x3p-2.x3p (MountainsMap export, 650 x 650 doubles): the first 320 x 320 points, with the
  sizes and both MD5 checksums of ISO 5436-2 updated.
- plu-1.plu (Sensofar PLu neox, 768 x 576 float32 heights in um): the first 256 x 192
  points (x, y), with the point counts of the header and the layer updated; the colour
  image and the other blocks after the height layer, which no reader of this project
  uses, are left out.

Run as ``python crop_examples.py ORIGINALS_DIR`` from this directory.
"""

from __future__ import annotations

import hashlib
import re
import struct
import sys
import zipfile
from pathlib import Path

import numpy as np

OPD_X = slice(0, 256)  # x pixels kept (file order: x index first)
OPD_Y = slice(0, 192)  # rows kept in file order (the reader flips y)
OPD_DROPPED = (b"SecArr_0", b"Modulation", b"Image")
X3P_SIZE = 320
PLU_X, PLU_Y = 256, 192  # points kept along x and y
#: Byte offsets of Sensofar's SPM layout (SurfaceTopography's IO/PLU.py, Gwyddion's sensofar.c):
#: date (128 s), time (I), comment (256 s), then the calibration block.
PLU_CALIBRATION = 388


def crop_opd(source: Path, target: Path) -> None:
    """Rewrite a Wyko OPD file with the Raw array cropped and the secondary arrays dropped."""
    data = source.read_bytes()
    length = struct.unpack("<16shlH", data[2:26])[2]  # the directory block lists itself first
    entries = [list(struct.unpack("<16shlH", data[2 + 24 * i:26 + 24 * i]))
               for i in range(length // 24)]
    offset = 2 + length
    payloads = []
    for entry in entries[1:]:
        size = entry[2]
        payload = data[offset:offset + size] if size > 0 else b""
        offset += max(size, 0)
        label = entry[0].split(b"\0")[0]
        if label == b"Raw":
            nx, ny, itemsize = struct.unpack("<HHH", payload[:6])
            raw = np.frombuffer(payload[6:], "<f4").reshape(nx, ny)[OPD_X, OPD_Y]
            payload = struct.pack("<HHH", *raw.shape, itemsize) + raw.tobytes()
        elif label in OPD_DROPPED:
            payload = b""
        entry[2] = len(payload)
        payloads.append(payload)
    head = data[:2] + b"".join(struct.pack("<16shlH", *e) for e in entries)
    target.write_bytes(head + b"".join(payloads))


def crop_x3p(source: Path, target: Path) -> None:
    """Rewrite an ISO 5436-2 X3P file (double heights, x fastest) with the matrix cropped."""
    with zipfile.ZipFile(source) as archive:
        xml = archive.read("main.xml").decode()
        nx = int(re.search(r"<SizeX>(\d+)</SizeX>", xml).group(1))
        ny = int(re.search(r"<SizeY>(\d+)</SizeY>", xml).group(1))
        heights = np.frombuffer(archive.read("bindata/data.bin"), "<f8").reshape(ny, nx)
    cropped = np.ascontiguousarray(heights[:X3P_SIZE, :X3P_SIZE]).tobytes()
    xml = re.sub(r"<SizeX>\d+</SizeX>", f"<SizeX>{X3P_SIZE}</SizeX>", xml)
    xml = re.sub(r"<SizeY>\d+</SizeY>", f"<SizeY>{X3P_SIZE}</SizeY>", xml)
    xml = re.sub(r"<MD5ChecksumPointData>\w+</MD5ChecksumPointData>",
                 f"<MD5ChecksumPointData>{hashlib.md5(cropped).hexdigest().upper()}"
                 "</MD5ChecksumPointData>", xml)
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("bindata/data.bin", cropped)
        archive.writestr("main.xml", xml)
        archive.writestr("md5checksum.hex",
                         f"{hashlib.md5(xml.encode()).hexdigest()} *main.xml\n")


def crop_plu(source: Path, target: Path) -> None:
    """Rewrite a Sensofar PLU topography (one layer) with the height matrix cropped.

    Counts are stored as y then x (calibration, layer) and as y, x, y, x in the
    scan settings; the matrix is float32 with x fastest. Only the sizes change.
    """
    data = bytearray(source.read_bytes())
    ny, nx, n_tall = struct.unpack_from("<3I", data, PLU_CALIBRATION)
    struct.pack_into("<3I", data, PLU_CALIBRATION, PLU_Y, PLU_X, PLU_X)
    area_type = struct.unpack_from("<I", data, PLU_CALIBRATION + 40 + 16)[0]
    if area_type == 6 or n_tall != nx:  # coordinates area: a different settings block
        raise ValueError(f"{source}: layout not handled by this script")
    settings = PLU_CALIBRATION + 40 + 20
    assert struct.unpack_from("<4I", data, settings) == (ny, nx, ny, nx)
    struct.pack_into("<4I", data, settings, PLU_Y, PLU_X, PLU_Y, PLU_X)
    layer = settings + 40 + 12
    assert data[settings + 40 + 1] == 1, "one layer expected"
    assert struct.unpack_from("<2I", data, layer) == (ny, nx)
    struct.pack_into("<2I", data, layer, PLU_Y, PLU_X)
    start = layer + 8
    heights = np.frombuffer(bytes(data[start:start + 4 * nx * ny]), "<f4").reshape(ny, nx)
    min_max = data[start + 4 * nx * ny:start + 4 * nx * ny + 8]
    cropped = np.ascontiguousarray(heights[:PLU_Y, :PLU_X]).tobytes()
    target.write_bytes(bytes(data[:start]) + cropped + bytes(min_max))


if __name__ == "__main__":
    originals = Path(sys.argv[1])
    crop_opd(originals / "opd-1.opd", Path("opd-1-crop.opd"))
    crop_x3p(originals / "x3p-2.x3p", Path("x3p-2-crop.x3p"))
    crop_plu(originals / "plu-1.plu", Path("plu-1-crop.plu"))
