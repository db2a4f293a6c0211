"""Helpers for workflow/rules/receding.smk: sweep values, chunks and profile names.

Plain functions of the ``receding.gap`` config section (they never read files), kept here
so that the rule file holds rules only and the helpers are tested.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence


def sweep_values(spec: Mapping[str, float] | Sequence[float]) -> list[float]:
    """Values from a {start, stop, step} range (stop included) or an explicit list."""
    if isinstance(spec, Mapping):
        count = round((spec["stop"] - spec["start"]) / spec["step"]) + 1
        if count < 1:
            raise ValueError(f"empty sweep range {dict(spec)}")
        return [round(spec["start"] + i * spec["step"], 10) for i in range(count)]
    return [float(v) for v in spec]


def chunk_values(values: Sequence[float], chunk: int, chunks: int) -> list[str]:
    """The values of one chunk, interleaved (balances cheap and dear points), as CLI words."""
    return [str(v) for v in values[int(chunk) :: chunks]]


def profile_name(point: Mapping[str, float]) -> str:
    """File stem of a profile point, e.g. ``w2.5_f0.5``."""
    return f"w{point['w']:g}_f{point['f']:g}"


def profile_point(points: Sequence[Mapping[str, float]], name: str) -> Mapping[str, float]:
    """The configured profile point with this file stem."""
    for point in points:
        if profile_name(point) == name:
            return point
    raise ValueError(f"no receding.gap.profiles entry named {name!r}")


def liftoff_profile_name(point: Mapping[str, float] | float, law: str = "line") -> str:
    """File stem of a line/patch profile: ``line_f0.5`` or ``patch_uniform_w1_f0.3``."""
    if isinstance(point, Mapping):
        return f"patch_{point['law']}_w{point['w']:g}_f{point['f']:g}"
    return f"{law}_f{float(point):g}"


def liftoff_profile_point(points: Sequence[Mapping[str, float]], name: str
                          ) -> Mapping[str, float]:
    """The configured patch profile point with this file stem."""
    for point in points:
        if liftoff_profile_name(point) == name:
            return point
    raise ValueError(f"no receding.patches.profiles entry named {name!r}")
