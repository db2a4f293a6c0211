"""The surface sheet ``config/surfaces.csv``: which scan measures which surface, and how.

One row per measured surface (the rows of Tables A.1, A.26, A.27 and 2.6). The
test sheet names the two surfaces of each test's interface (specimen + side and
pad + side, see :func:`contactlab.testsheet.surface_id`); this sheet names their
scan files and the measurement settings of sec. 2.3.4. Keeping it apart from the
test sheet lets one surface serve several tests (a specimen side is shared by
three tests) without repeating its scans.

Columns: ``src/contactlab/schemas/surfaces.schema.yaml`` (documented in ``config/README.md``,
"The surface sheet"; a test keeps the schema and :data:`COLUMNS`, :data:`OPTIONAL`,
:data:`OBJECTIVES`, :data:`DIRECTIONS` in step). ``profile_length_mm`` is read in mm and
kept in um (:attr:`SurfaceSpec.profile_length_um`); a blank ``sampling_length_um`` (or no
such column) is lambda_c, as ISO 4288 pairs them: Ra, Rq, Rz are means over the whole
sampling lengths in the evaluation length (80 % of the profile length), so it may not exceed
that. The 100x rows of Table 2.6 use 160 um, a fifth of their 0.8 mm evaluation length (see
the comment in config/surfaces.csv).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from contactlab.config_check import nearest_first

COLUMNS = ("surface", "objective", "areal_scan", "profile_scan", "profile_axis",
           "profile_direction", "profile_length_mm", "lambda_c_um", "sampling_length_um")
#: Columns a sheet may leave out (blank in every row).
OPTIONAL = ("sampling_length_um",)
DIRECTIONS = ("lengthwise", "normal_to_pattern", "parallel_to_pattern")
#: Values of the ``objective`` column (docs/findings/surfaces.md).
OBJECTIVES = ("20x", "100x", "other")
#: Ids that would collide with other files in results/surfaces/.
RESERVED = ("seq", "texture", "demo_scans")
#: Fraction of each profile line discarded at each end (sec. 2.3.4, Alicona); the rest is
#: the evaluation length.
END_FRACTION = 0.1
_ID = re.compile(r"^[A-Za-z][A-Za-z0-9_-]*$")


@dataclass(frozen=True)
class SurfaceSpec:
    """Scans and measurement settings of one surface."""

    surface: str
    objective: str
    areal_scan: Path | None
    profile_scan: Path | None
    profile_axis: str
    profile_direction: str | None
    profile_length_um: float | None
    lambda_c_um: float
    sampling_length_um: float | None = None  # None: lambda_c (ISO 4288)
    line: int | None = field(default=None, compare=False)  # the row's line in the sheet

    @property
    def scans(self) -> list[Path]:
        """The surface's scan files, areal first."""
        return [p for p in (self.areal_scan, self.profile_scan) if p is not None]

    @property
    def sampling_length(self) -> float:
        """Sampling length of the profile parameters, um: the sheet's, else lambda_c."""
        return self.lambda_c_um if self.sampling_length_um is None else self.sampling_length_um


def _text(value: object) -> str | None:
    if value is None or (isinstance(value, float) and pd.isna(value)):
        return None
    text = str(value).strip()
    return text or None


def read_surface_sheet(path: str | Path) -> list[SurfaceSpec]:
    """Read and check the surface sheet; errors name the file, line and column."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: surface sheet not found")
    try:
        table = pd.read_csv(path, dtype=str, keep_default_na=False, comment="#")
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: cannot parse as CSV: {exc}") from exc
    unknown = [c for c in table.columns if c not in COLUMNS]
    missing = [c for c in COLUMNS if c not in table.columns and c not in OPTIONAL]
    if unknown or missing:
        raise ValueError(f"{path}: unknown column(s) {unknown}, missing column(s) {missing}; "
                         f"expected {list(COLUMNS)}")
    specs: list[SurfaceSpec] = []
    seen: set[str] = set()
    for column in OPTIONAL:
        if column not in table.columns:
            table[column] = ""
    lines = _data_lines(path)
    for line, row in zip(lines[1:], table.to_dict("records"), strict=True):
        where = f"{path}: line {line}"
        surface = _text(row["surface"]) or ""
        if not _ID.match(surface):
            raise ValueError(f"{where}, column 'surface': invalid surface id {surface!r}")
        if surface in RESERVED:
            raise ValueError(f"{where}, column 'surface': {surface!r} is reserved "
                             f"(results/surfaces/{surface}.nc is another result)")
        if surface in seen:
            raise ValueError(f"{where}, column 'surface': duplicate surface id {surface!r}")
        seen.add(surface)
        objective = _text(row["objective"])
        if objective not in OBJECTIVES:
            raise ValueError(f"{where} ({surface}), column 'objective': {(objective or '')!r} is "
                             f"not one of {list(OBJECTIVES)} ('other' for an instrument or lens "
                             "the thesis did not use)")
        areal, profile = _text(row["areal_scan"]), _text(row["profile_scan"])
        if areal is None and profile is None:
            raise ValueError(f"{where} ({surface}): neither 'areal_scan' nor 'profile_scan' given")
        axis = _text(row["profile_axis"]) or "x"
        if axis not in ("x", "y"):
            raise ValueError(f"{where} ({surface}), column 'profile_axis': {axis!r} is not x or y")
        direction = _text(row["profile_direction"])
        if profile is not None and direction not in DIRECTIONS:
            raise ValueError(f"{where} ({surface}), column 'profile_direction': {direction!r} "
                             f"is not one of {list(DIRECTIONS)}")
        lambda_c = _number(row["lambda_c_um"], f"{where} ({surface}), column 'lambda_c_um'")
        length = _text(row["profile_length_mm"])
        length_um = None
        if profile is not None:
            length_um = 1000.0 * _number(length, f"{where} ({surface}), column 'profile_length_mm'")
        sampling = _text(row["sampling_length_um"])
        sampling_um = None
        if sampling is not None:
            column = f"{where} ({surface}), column 'sampling_length_um'"
            sampling_um = _number(sampling, column)
            if length_um is None:
                raise ValueError(f"{column}: a sampling length without a 'profile_scan'")
            evaluation = (1.0 - 2 * END_FRACTION) * length_um
            if sampling_um > evaluation:
                raise ValueError(f"{column}: {sampling_um:g} um is longer than the evaluation "
                                 f"length ({evaluation:g} um, {100 * (1 - 2 * END_FRACTION):g} "
                                 f"% of the profile length)")
        specs.append(SurfaceSpec(
            surface=surface,
            objective=objective,
            areal_scan=Path(areal) if areal else None,
            profile_scan=Path(profile) if profile else None,
            profile_axis=axis,
            profile_direction=direction,
            profile_length_um=length_um,
            lambda_c_um=lambda_c,
            sampling_length_um=sampling_um,
            line=line,
        ))
    if not specs:
        raise ValueError(f"{path}: no surfaces")
    return specs


def _data_lines(path: Path) -> list[int]:
    """Line numbers (from 1) of the header and rows, as pandas reads them with
    ``comment="#"``: blank lines and lines that are only a comment are skipped."""
    with path.open(encoding="utf-8", errors="replace") as handle:
        return [number for number, text in enumerate(handle, start=1)
                if text.split("#", 1)[0].strip()]


def _number(value: object, where: str) -> float:
    text = _text(value)
    try:
        number = float(text) if text is not None else float("nan")
    except ValueError:
        number = float("nan")
    if not number > 0:
        raise ValueError(f"{where}: expected a positive number, got {text!r}")
    return number


def check_scan_files(specs: list[SurfaceSpec], sheet_path: str | Path,
                     generated: list[Path] | tuple[Path, ...] = (), root: str | Path = ".") -> None:
    """Raise FileNotFoundError naming the sheet and surface if a scan file is missing.

    ``generated`` lists scans a workflow rule will write (the demo scans).
    """
    made = {Path(p) for p in generated}
    for spec in specs:
        for column, path in (("areal_scan", spec.areal_scan), ("profile_scan", spec.profile_scan)):
            if path is None or path in made:
                continue
            if not (Path(root) / path).is_file():
                raise FileNotFoundError(
                    f"{sheet_path}: surface {spec.surface}, column '{column}': "
                    f"scan file not found: {path}"
                )


def scan_paths(specs: list[SurfaceSpec]) -> list[Path]:
    """Every scan file the sheet names, in sheet order, without repeats."""
    paths: list[Path] = []
    for spec in specs:
        paths.extend(path for path in spec.scans if path not in paths)
    return paths



#: The published tables the SYNTHETIC demo scans take their statistics from, per scan kind
#: (:func:`contactlab.surfaces.demo.published_targets`); 100x profiles: Table 2.6 by test.
DEMO_TABLES = {"areal": ("A.1", "A.27"), "profile": ("A.1", "A.26", "2.6")}


def published_surfaces(published_dir: str | Path | None = None) -> dict[str, list[str]]:
    """Scan kind (``areal``, ``profile``) -> surface ids with published statistics to
    synthesise a demo scan from, in table order (:data:`DEMO_TABLES`)."""
    from contactlab.published import read_published

    directory = Path(published_dir) if published_dir is not None else None
    names: dict[str, list[str]] = {}
    for kind, tables in DEMO_TABLES.items():
        found = names.setdefault(kind, [])
        for table in tables:
            frame = read_published(table, directory)
            if table == "2.6":  # the 100x profiles of the structured specimens, by test
                found.extend(f"{test}_specimen_100x" for test in frame["test"])
            else:
                found.extend(frame["surface"])
    return names


def check_demo_scan_surfaces(specs: list[SurfaceSpec], sheet_path: str | Path,
                             demo_dir: str | Path, published_dir: str | Path) -> None:
    """Raise ValueError naming the sheet, line, surface and column of a row whose scan is a
    SYNTHETIC demo scan (a file in ``demo_dir``, written by the workflow's demo rule from the
    published statistics) of a surface the published tables do not have; the message lists
    the ones they have, nearest first. Rows with scans of their own are not checked."""
    known: dict[str, list[str]] | None = None
    for spec in specs:
        for kind, path in (("areal", spec.areal_scan), ("profile", spec.profile_scan)):
            if path is None or Path(path).parent != Path(demo_dir):
                continue
            known = known if known is not None else published_surfaces(published_dir)
            if spec.surface in known[kind]:
                continue
            tables = ", ".join(f"table_{t}.csv" for t in DEMO_TABLES[kind])
            raise ValueError(
                f"{sheet_path}: line {spec.line or '?'}, column 'surface': {spec.surface!r} has "
                f"its {kind} scan in {demo_dir}/ (a SYNTHETIC demo scan made from the published "
                f"statistics), but {Path(published_dir)}/{{{tables}}} have no surface "
                f"{spec.surface!r}; give it a scan of your own, or use a published name, "
                f"nearest first: {nearest_first(spec.surface, known[kind])}")
