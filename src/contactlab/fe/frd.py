"""A small reader for CalculiX result files (``.frd``, ASCII, ``.dat``) and ``.sta`` summaries.

Only what the cross-checks need: node coordinates and the nodal result blocks (DISP,
STRESS, CONTACT, ...) of every increment. The ``.frd`` layout is fixed-width: a
record ``-1`` carries a node number (10 characters) and values of 12 characters each;
``-4`` opens a block with its name, ``-5`` names a component, ``-3`` ends a block.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


@dataclass
class FrdBlock:
    """One nodal result block: ``name`` (e.g. DISP), the step time, components by name."""

    name: str
    time: float
    step: int
    nodes: np.ndarray
    values: dict[str, np.ndarray]


@dataclass
class FrdResult:
    """Node coordinates (id -> xyz) and every nodal result block, in file order."""

    coords: dict[int, np.ndarray] = field(default_factory=dict)
    blocks: list[FrdBlock] = field(default_factory=list)

    def last(self, name: str) -> FrdBlock:
        """The last block called ``name`` (the end of the last increment)."""
        for block in reversed(self.blocks):
            if block.name == name:
                return block
        raise KeyError(f"no {name} block in the .frd file")

    def series(self, name: str) -> list[FrdBlock]:
        """All blocks called ``name``, one per written increment."""
        return [b for b in self.blocks if b.name == name]


def _floats(line: str, start: int, count: int) -> list[float]:
    out = []
    for k in range(count):
        text = line[start + 12 * k:start + 12 * (k + 1)]
        if not text.strip():
            break
        out.append(float(text))
    return out


def read_frd(path: str | os.PathLike[str]) -> FrdResult:
    """Read an ASCII ``.frd`` file (CalculiX 2.x) into a :class:`FrdResult`."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: CalculiX result file not found")
    result = FrdResult()
    lines = path.read_text(errors="replace").splitlines()
    i, n = 0, len(lines)
    time, step = 0.0, 0
    while i < n:
        line = lines[i]
        key = line.strip()[:5]
        if key.startswith("2C"):  # node coordinates
            i += 1
            while i < n and not lines[i].startswith(" -3"):
                rec = lines[i]
                if rec.startswith(" -1"):
                    result.coords[int(rec[3:13])] = np.array(_floats(rec, 13, 3))
                i += 1
        elif key == "100CL":  # result header: time value, ..., step number
            parts = line.split()
            try:
                time = float(parts[2])
                step = int(parts[-2])
            except (IndexError, ValueError):
                pass
            i += 1
            name = lines[i][5:13].strip() if i < n else ""
            comps: list[str] = []
            i += 1
            while i < n and lines[i].startswith(" -5"):
                comps.append(lines[i][5:13].strip())
                i += 1
            ids: list[int] = []
            rows: list[list[float]] = []
            while i < n and not lines[i].startswith(" -3"):
                rec = lines[i]
                if rec.startswith(" -1"):
                    ids.append(int(rec[3:13]))
                    rows.append(_floats(rec, 13, 6))
                elif rec.startswith(" -2") and rows:  # continuation of a long record
                    rows[-1].extend(_floats(rec, 13, 6))
                i += 1
            width = max((len(r) for r in rows), default=0)
            data = np.full((len(rows), width), np.nan)
            for r, row in enumerate(rows):
                data[r, :len(row)] = row
            values = {c: data[:, k] for k, c in enumerate(comps[:width]) if c != "ALL"}
            result.blocks.append(FrdBlock(name, time, step, np.array(ids, dtype=int), values))
        i += 1
    return result


def read_sta(path: str | os.PathLike[str]) -> dict[str, float]:
    """Increments, attempts and iterations from a ``.sta`` file (0 if it is missing)."""
    path = Path(path)
    out = {"increments": 0.0, "attempts": 0.0, "iterations": 0.0, "final_time": 0.0}
    if not path.exists():
        return out
    for line in path.read_text(errors="replace").splitlines():
        parts = line.split()
        if len(parts) >= 6 and parts[0].isdigit():
            try:
                out["increments"] += 1
                out["attempts"] += float(parts[2].rstrip("U"))
                out["iterations"] += float(parts[3])
                out["final_time"] = float(parts[5])
            except ValueError:
                continue
    return out


def read_dat_displacements(dat: str) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Node ids and (u_x, u_y, u_z) rows of each ``*NODE PRINT`` set's last displacement
    block in a ``.dat`` text. The ``.dat`` carries 7 significant digits, the ``.frd`` 6: a
    separation that is a small difference of two displacements needs them."""
    out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    lines = dat.splitlines()
    i = 0
    while i < len(lines):
        words = lines[i].split()
        if len(words) > 4 and words[0] == "displacements" and words[2] == "for":
            name = words[4]
            i += 1
            ids, rows = [], []
            while i < len(lines) and not lines[i].strip():  # blank line after the header
                i += 1
            while i < len(lines) and lines[i].strip():
                parts = lines[i].split()
                ids.append(int(parts[0]))
                rows.append([float(v) for v in parts[1:4]])
                i += 1
            out[name] = (np.array(ids, dtype=int), np.array(rows, dtype=float))
            continue
        i += 1
    return out
