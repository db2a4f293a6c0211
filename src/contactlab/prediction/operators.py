"""Surface compliance of two identical elastic half-spaces on a non-periodic grid, by FFT.

The interface of a test (thesis ch. 2) is cut into ``nx x ny`` equal cells carrying
uniform tractions. The relative surface displacement of the two bodies is the
convolution of the tractions with the closed-form cell coefficients of
:mod:`contactlab.asperity.influence` (Boussinesq for pressure, Cerruti for shear),
doubled for two bodies of the same material. The window is not periodic: the
convolution runs on a grid zero-padded to ``2nx x 2ny`` (Hockney's method), so
tractions outside the window are zero and no periodic images act.

For identical materials the normal and tangential problems decouple (Dundurs'
beta = 0): shear causes no relative normal displacement and pressure no relative
tangential one (Johnson 1985, sec. 5.2). Units are the caller's: lengths in um and
tractions in kN/mm^2 (= GPa, like the moduli) give displacements in um.

``mean_free=True`` gives the operator of a window cut from a large, nominally flat
interface: the window's mean traction is the nominal one, uniform over the whole
interface, and its deformation is the bulk field that the thesis's DIC removes with
the lines fitted to the pad and the specimen (sec. 2.3.2); it does not deform the
window. Only the fluctuations act: ``u' = P G P t`` with ``P`` removing the window
mean, so displacements are measured from their window mean too (the interface
displacement). This is the non-periodic counterpart of the periodic cell, whose
Green's function has no q = 0 term, without the periodic images (scans are not
periodic).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.fft as sfft
from numpy.typing import NDArray

from contactlab.asperity.influence import boussinesq, cerruti

Array = NDArray[np.float64]


def _offsets(n: int, h: float) -> Array:
    """Cell offsets in FFT order on a padded axis of ``2n`` points: 0..n-1, -n..-1 (times h)."""
    k = np.arange(2 * n)
    return np.where(k < n, k, k - 2 * n) * h


@dataclass
class PairCompliance:
    """FFT-accelerated influence operators of the pair on an ``nx x ny`` window.

    ``youngs_modulus`` and ``poissons_ratio`` are those of each body; the relative
    displacement is twice one body's, i.e. the composite modulus
    ``E* = E / (2 (1 - nu^2))`` for pressure and ``G / 2`` with Cerruti's
    kernel for shear. ``tangential=False`` skips the shear kernels.
    """

    nx: int
    ny: int
    dx: float
    dy: float
    youngs_modulus: float
    poissons_ratio: float
    tangential: bool = True
    mean_free: bool = False
    _hat: dict[str, Array] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if self.nx < 2 or self.ny < 2 or self.dx <= 0 or self.dy <= 0:
            raise ValueError("compliance grid: need at least 2 x 2 cells of positive size")
        if self.youngs_modulus <= 0 or not 0 <= self.poissons_ratio < 0.5:
            raise ValueError("compliance: E must be positive and 0 <= nu < 0.5")
        x = _offsets(self.nx, self.dx)[:, None]
        y = _offsets(self.ny, self.dy)[None, :]
        nu = self.poissons_ratio
        e_one = self.youngs_modulus / (1.0 - nu**2)
        kernels = {"zz": 2.0 * boussinesq(x, y, self.dx, self.dy, e_one)}
        if self.tangential:
            shear = self.youngs_modulus / (2.0 * (1.0 + nu))
            kxx, kxy, kyy = cerruti(x, y, self.dx, self.dy, shear, nu)
            kernels.update(xx=2.0 * kxx, xy=2.0 * kxy, yy=2.0 * kyy)
        self._hat = {key: sfft.rfft2(k) for key, k in kernels.items()}

    @property
    def cell_area(self) -> float:
        return self.dx * self.dy

    @property
    def e_star(self) -> float:
        """Composite contact modulus ``E / (2 (1 - nu^2))`` of the pair."""
        return self.youngs_modulus / (2.0 * (1.0 - self.poissons_ratio**2))

    def _out(self, window: Array) -> Array:
        return window - window.mean() if self.mean_free else window

    def _hat_of(self, values: Array) -> Array:
        """Spectrum of ``values`` zero-padded to ``2nx x 2ny`` (``rfft2``'s layout); the
        rows of padding are zero, so the first transform runs on the window's rows only."""
        if values.shape != (self.nx, self.ny):
            raise ValueError(f"traction field of shape {values.shape}, grid is "
                             f"{(self.nx, self.ny)}")
        if self.mean_free:
            values = values - values.mean()
        return sfft.fft(sfft.rfft(values, n=2 * self.ny, axis=1), n=2 * self.nx, axis=0)

    def _window(self, spectrum: Array) -> Array:
        """The window ``[:nx, :ny]`` of the inverse of a padded spectrum (the second
        transform on the window's rows only)."""
        rows = sfft.ifft(spectrum, axis=0)[: self.nx]
        return sfft.irfft(rows, n=2 * self.ny, axis=1)[:, : self.ny]

    def _convolve(self, field_hat: Array, key: str) -> Array:
        return self._out(self._window(field_hat * self._hat[key]))

    def normal(self, pressure: Array) -> Array:
        """Relative normal displacement (closing positive) of the pair due to ``pressure``."""
        return self._convolve(self._hat_of(pressure), "zz")

    def tangential_x(self, qx: Array) -> Array:
        """Relative ``u_x`` due to the shear traction ``qx`` alone (``q_y = 0``)."""
        return self._convolve(self._hat_of(qx), "xx")

    def tangential_xy(self, qx: Array, qy: Array) -> tuple[Array, Array]:
        """Relative ``(u_x, u_y)`` due to the shear tractions ``(qx, qy)``."""
        hx, hy = self._hat_of(qx), self._hat_of(qy)
        ux = self._window(hx * self._hat["xx"] + hy * self._hat["xy"])
        uy = self._window(hx * self._hat["xy"] + hy * self._hat["yy"])
        return self._out(ux), self._out(uy)
