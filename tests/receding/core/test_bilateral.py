"""Bilateral tractions of the gap problem, eqs (5.1)-(5.2), against Flamant integration."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.receding.core.bilateral import (
    Patch,
    bilateral_tractions,
    gap_bilateral,
    gap_patches,
)


def printed_eq_5_1(x: np.ndarray, w: float) -> np.ndarray:
    """Eq. (5.1) as printed, with the principal-value arctan."""
    out = np.zeros_like(x)
    for a in (w + x, w - x):
        out += (a - (a * a + 1) * np.arctan(1.0 / a)) / (np.pi * (a * a + 1))
    return out


@pytest.mark.parametrize("w", [0.5, 2.5])
def test_closed_form_matches_flamant_integration(w: float) -> None:
    x = np.array([0.0, 0.3, w - 0.1, w + 0.1, w + 3.0, -w - 2.0, 25.0])
    shear, normal = gap_bilateral(x, w)
    num_shear, num_normal = bilateral_tractions(x, gap_patches(w))
    assert np.allclose(shear, num_shear, atol=1e-10)
    assert np.allclose(normal, num_normal, atol=1e-10)


def test_printed_eq_5_1_holds_only_inside_the_gap() -> None:
    """Misprint: with arctan(1/A) the printed (5.1) is off by p for |x| > w."""
    w = 2.0
    inside = np.array([0.0, 1.0, 1.9])
    outside = np.array([2.5, 4.0, -3.0])
    assert np.allclose(printed_eq_5_1(inside, w), gap_bilateral(inside, w)[1])
    assert np.allclose(printed_eq_5_1(outside, w) - gap_bilateral(outside, w)[1], 1.0)


def test_limits_symmetry_and_equilibrium() -> None:
    w = 1.5
    shear, normal = gap_bilateral(np.array([0.0, 1e4, -1e4]), w)
    assert shear[0] == 0.0
    assert normal[1:] == pytest.approx(-1.0, abs=1e-4)
    x = np.linspace(0.1, 8, 50)
    s_pos, n_pos = gap_bilateral(x, w)
    s_neg, n_neg = gap_bilateral(-x, w)
    assert np.allclose(n_pos, n_neg) and np.allclose(s_pos, -s_neg)
    assert np.all(n_pos < 0) and np.all(s_pos < 0)
    # the load missing over the gap (2 w p) is the deficit of compression on y = 0
    grid = np.linspace(-400, 400, 400001)
    _, normal = gap_bilateral(grid, w)
    assert np.trapezoid(normal + 1.0, grid) == pytest.approx(2 * w, rel=1e-3)


def test_general_patches() -> None:
    # a uniform pressure everywhere is the uniform state sigma_yy = -p, sigma_xy = 0
    shear, normal = bilateral_tractions(np.array([-3.0, 0.0, 7.0]), [Patch(-np.inf, np.inf)])
    assert np.allclose(normal, -1.0) and np.allclose(shear, 0.0, atol=1e-12)
    # a finite patch with a linear pressure integrates to the right total force
    patch = Patch(-1.0, 2.0, pressure=lambda x: 1.0 + 0.5 * x)
    tail = np.geomspace(12.0, 3000.0, 400)
    grid = np.concatenate([-tail[::-1], np.linspace(-11.0, 11.0, 1101), tail])
    _, normal = bilateral_tractions(grid, [patch])
    assert np.trapezoid(normal, grid) == pytest.approx(-(3.0 + 0.25 * 3.0), rel=2e-3)
    with pytest.raises(ValueError):
        Patch(1.0, 1.0)


def test_line_load_and_patch_closed_forms() -> None:
    """Eqs (6.6)-(6.7) and (7.1)-(7.2) against Flamant integration; the gap problem is the
    uniform state minus the patch."""
    from contactlab.receding.core.bilateral import line_load_bilateral, patch_bilateral

    x = np.array([-3.0, -0.5, 0.0, 0.9, 1.1, 4.0])
    # a line load as the limit of a narrow patch of the same resultant
    eps = 1e-3
    shear, normal = bilateral_tractions(x, [Patch(-eps, eps, pressure=1.0 / (2 * eps))])
    ls, ln = line_load_bilateral(x)
    assert np.allclose(shear, ls, atol=1e-6) and np.allclose(normal, ln, atol=1e-6)
    w = 1.0
    ps, pn = patch_bilateral(x, w)
    ns, nn = bilateral_tractions(x, [Patch(-w, w)])
    assert np.allclose(ps, ns, atol=1e-10) and np.allclose(pn, nn, atol=1e-10)
    gs, gn = gap_bilateral(x, w)
    assert np.allclose(gs, -ps) and np.allclose(gn, -1.0 - pn)
    # the printed (7.1): arctan terms plus the unsimplified rational terms
    printed = -(1 / np.pi) * (
        -np.arctan(x - w) + np.arctan2(w + x, 1.0) + 2 * (w - x) / ((x - w) ** 2 + 1)
        + ((w - x) ** 2 + 1) * (x - w) / ((x - w) ** 2 + 1) ** 2 + (w + x) / ((w + x) ** 2 + 1)
    )
    assert np.allclose(printed, pn)
