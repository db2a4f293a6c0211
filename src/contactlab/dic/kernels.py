"""The inner loops of the correlation, compiled with numba: B-spline samples, the reference
subsets' sums and the IC-GN iterations of every subset.

The method is that of :mod:`contactlab.dic.correlate` (its docstring has the equations);
here it runs subset by subset in one compiled loop, so that no warped subset, grey level or
residual is ever stored for all subsets at once and a converged subset costs nothing more.

B-spline samples: the interpolant ``g(x, y) = sum_kl c_kl b(x - l) b(y - k)`` of
:mod:`contactlab.dic.bspline` at a point, from the coefficients ``c`` with a mirrored border
of :data:`BORDER` pixels (:func:`bordered`: the ``mirror`` boundary of
:func:`scipy.ndimage.map_coordinates`, so the values are those of
``map_coordinates(c, ..., prefilter=False, mode='mirror')`` to rounding). With ``t`` the
fractional part of a coordinate, the weights of the ``order + 1`` coefficients from
``floor(x) - (order - 1)/2`` on are the B-spline at ``t + (order - 1)/2 - j``, written out
from the truncated-power form of :func:`contactlab.dic.bspline.bspline`.

Why compiled: each IC-GN iteration samples the deformed image at every pixel of every
active subset, 36 coefficients per sample for the quintic spline, which is most of the
work of a frame; a loop over subsets and pixels does it without intermediate arrays, and
no well-kept library evaluates a B-spline at scattered points faster (``docs/dic.md``,
"Why numba").
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["BORDER", "bordered", "icgn", "reference_sums", "sample"]

#: mirrored border of the coefficients (pixels): a quintic spline at a pixel centre half a
#: pixel outside the image reaches 3 coefficients beyond it; one more for rounding
BORDER = 4
#: floating-point freedoms of the compiled loops: only the sign of zero. Sums in any order
#: and fused multiply-adds are left out: with them a kernel compiled in the running process
#: and the same kernel loaded from numba's cache round differently (a result would depend
#: on whether its process found a cache); NaN and infinity keep their meaning (flags).
FAST = {"nsz"}
#: index into (1, dx, dy, dx^2, dx dy, dy^2) of the product of (1, dx, dy)[p] and [q]
_MOMENT = np.array([[0, 1, 2], [1, 3, 4], [2, 4, 5]])
#: status codes, as :data:`contactlab.dic.correlate.STATUS_MEANINGS`
_VALID, _TEXTURELESS, _LEFT_IMAGE, _NOT_CONVERGED, _LOW_ZNCC = 0, 1, 2, 4, 5


def bordered(coeffs: np.ndarray) -> np.ndarray:
    """B-spline coefficients with a mirrored border of :data:`BORDER` pixels (float64)."""
    return np.pad(np.asarray(coeffs, dtype=np.float64), BORDER, mode="reflect")


@njit(cache=True, nogil=True, fastmath=FAST, error_model="numpy")
def _value(c: np.ndarray, order: int, x: float, y: float) -> float:
    """The interpolant at (x, y) (x along columns) from bordered coefficients ``c``."""
    fx = np.floor(x)
    fy = np.floor(y)
    t = x - fx
    s = y - fy
    if order == 5:
        col = int(fx) - 2 + BORDER
        row = int(fy) - 2 + BORDER
        t1, t2, t3 = 1.0 - t, 2.0 - t, 3.0 - t
        u1, u2 = 1.0 + t, 2.0 + t
        a0 = t1**5 / 120.0
        a1 = (t2**5 - 6.0 * t1**5) / 120.0
        a2 = (t3**5 - 6.0 * t2**5 + 15.0 * t1**5) / 120.0
        a3 = (u2**5 - 6.0 * u1**5 + 15.0 * t**5) / 120.0
        a4 = (u1**5 - 6.0 * t**5) / 120.0
        a5 = t**5 / 120.0
        s1, s2, s3 = 1.0 - s, 2.0 - s, 3.0 - s
        v1, v2 = 1.0 + s, 2.0 + s
        b = ((s1**5) / 120.0, (s2**5 - 6.0 * s1**5) / 120.0,
             (s3**5 - 6.0 * s2**5 + 15.0 * s1**5) / 120.0,
             (v2**5 - 6.0 * v1**5 + 15.0 * s**5) / 120.0, (v1**5 - 6.0 * s**5) / 120.0,
             s**5 / 120.0)
        total = 0.0
        for k in range(6):
            r = row + k
            total += b[k] * (a0 * c[r, col] + a1 * c[r, col + 1] + a2 * c[r, col + 2]
                             + a3 * c[r, col + 3] + a4 * c[r, col + 4] + a5 * c[r, col + 5])
        return total
    col = int(fx) - 1 + BORDER
    row = int(fy) - 1 + BORDER
    t1 = 1.0 - t
    a0 = t1**3 / 6.0
    a1 = ((2.0 - t) ** 3 - 4.0 * t1**3) / 6.0
    a2 = ((1.0 + t) ** 3 - 4.0 * t**3) / 6.0
    a3 = t**3 / 6.0
    s1 = 1.0 - s
    b3 = (s1**3 / 6.0, ((2.0 - s) ** 3 - 4.0 * s1**3) / 6.0,
          ((1.0 + s) ** 3 - 4.0 * s**3) / 6.0, s**3 / 6.0)
    total = 0.0
    for k in range(4):
        r = row + k
        total += b3[k] * (a0 * c[r, col] + a1 * c[r, col + 1] + a2 * c[r, col + 2]
                          + a3 * c[r, col + 3])
    return total


@njit(cache=True, nogil=True, fastmath=FAST, error_model="numpy")
def sample(c: np.ndarray, order: int, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The interpolant at the points (``x``, ``y``), 1-D arrays, from bordered
    coefficients ``c`` (points at most half a pixel outside the image)."""
    out = np.empty(x.size)
    for i in range(x.size):
        out[i] = _value(c, order, x[i], y[i])
    return out


@njit(cache=True, nogil=True, fastmath=FAST, error_model="numpy")
def reference_sums(image: np.ndarray, gx: np.ndarray, gy: np.ndarray, col0: np.ndarray,
                   row0: np.ndarray, subset: int, mean: np.ndarray, spread: np.ndarray,
                   hessian: np.ndarray) -> None:
    """Per subset (top-left pixel ``col0``, ``row0``, ``subset`` pixels square): the mean
    and the spread ``sqrt(sum (f - f_m)^2)`` of its grey levels and the Gauss-Newton
    Hessian ``H = sum J^T J`` with ``J = (fx, fx dx, fx dy, fy, fy dx, fy dy)``, into
    ``mean``, ``spread`` and ``hessian`` (subsets x 6 x 6).

    ``H`` is assembled from the sums of ``fx fx``, ``fx fy`` and ``fy fy`` times
    ``(1, dx, dy, dx^2, dx dy, dy^2)``: 18 sums instead of 36 products per pixel.
    """
    half = (subset - 1) / 2.0
    m = subset * subset
    sums = np.empty((3, 6))
    for a in range(col0.size):
        c0, r0 = col0[a], row0[a]
        total = 0.0
        for k in range(subset):
            for j in range(subset):
                total += image[r0 + k, c0 + j]
        mu = total / m
        squares = 0.0
        sums[:, :] = 0.0
        for k in range(subset):
            dy = k - half
            for j in range(subset):
                dx = j - half
                d = image[r0 + k, c0 + j] - mu
                squares += d * d
                fx = gx[r0 + k, c0 + j]
                fy = gy[r0 + k, c0 + j]
                for w, product in enumerate((fx * fx, fx * fy, fy * fy)):
                    sums[w, 0] += product
                    sums[w, 1] += product * dx
                    sums[w, 2] += product * dy
                    sums[w, 3] += product * dx * dx
                    sums[w, 4] += product * dx * dy
                    sums[w, 5] += product * dy * dy
        h = hessian[a]
        for p in range(3):  # (1, dx, dy) x (1, dx, dy) -> the six moments
            for q in range(3):
                moment = _MOMENT[p, q]
                h[p, q] = sums[0, moment]
                h[p, q + 3] = sums[1, moment]
                h[p + 3, q] = sums[1, moment]
                h[p + 3, q + 3] = sums[2, moment]
        mean[a] = mu
        spread[a] = np.sqrt(squares)


@njit(cache=True, nogil=True, fastmath=FAST, error_model="numpy")
def _compose(p: np.ndarray, dp: np.ndarray) -> None:
    """``p`` <- the parameters of ``W(p) o W(dp)^-1`` (affine warps), in place."""
    a11, a12, a21, a22 = 1.0 + p[1], p[2], p[4], 1.0 + p[5]
    b11, b12, b21, b22 = 1.0 + dp[1], dp[2], dp[4], 1.0 + dp[5]
    det = b11 * b22 - b12 * b21
    i11, i12, i21, i22 = b22 / det, -b12 / det, -b21 / det, b11 / det
    tx = -(i11 * dp[0] + i12 * dp[3])
    ty = -(i21 * dp[0] + i22 * dp[3])
    p[1] = a11 * i11 + a12 * i21 - 1.0
    p[2] = a11 * i12 + a12 * i22
    p[4] = a21 * i11 + a22 * i21
    p[5] = a21 * i12 + a22 * i22 - 1.0
    p[0] = p[0] + a11 * tx + a12 * ty
    p[3] = p[3] + a21 * tx + a22 * ty


@njit(cache=True, nogil=True, fastmath=FAST, error_model="numpy")
def icgn(c: np.ndarray, order: int, image: np.ndarray, gx: np.ndarray, gy: np.ndarray,
         mean: np.ndarray, spread: np.ndarray, hinv: np.ndarray, textureless: np.ndarray,
         col0: np.ndarray, row0: np.ndarray, xc: np.ndarray, yc: np.ndarray, subset: int,
         subsets: np.ndarray, p: np.ndarray, max_iterations: int, tolerance: float,
         zncc: np.ndarray, iterations: np.ndarray, increment: np.ndarray,
         status: np.ndarray) -> None:
    """IC-GN of the reference subsets ``subsets`` in the deformed image of bordered
    coefficients ``c`` (image ``rows x cols`` = ``c.shape - 2 BORDER``), from the start
    parameters ``p`` (len(subsets) x 6), updated in place.

    The reference enters by its prefiltered grey levels ``image``, their spline gradients
    ``gx``, ``gy`` and per reference subset ``mean``, ``spread``, the inverse Hessian
    ``hinv``, ``textureless``, the top-left pixel ``col0``, ``row0`` and the centre
    ``xc``, ``yc``. Writes per subset ``zncc``, ``iterations``, ``increment`` and
    ``status`` (flags of :mod:`contactlab.dic.correlate`; ``low_zncc`` below ``zncc_min``
    is the caller's).
    """
    rows = c.shape[0] - 2 * BORDER
    cols = c.shape[1] - 2 * BORDER
    half = (subset - 1) / 2.0
    m = subset * subset
    g = np.empty(m)
    b = np.empty(6)
    dp = np.empty(6)
    for a in range(subsets.size):
        s = subsets[a]
        pa = p[a]
        zncc[a] = np.nan
        iterations[a] = 0
        increment[a] = np.nan
        if textureless[s]:
            status[a] = _TEXTURELESS
            continue
        status[a] = _VALID
        c0, r0 = col0[s], row0[s]
        df = spread[s]
        fm = mean[s]
        done = False
        for _ in range(max_iterations):
            cx = xc[s] + pa[0]
            cy = yc[s] + pa[3]
            ex = (abs(1.0 + pa[1]) + abs(pa[2])) * half
            ey = (abs(pa[4]) + abs(1.0 + pa[5])) * half
            if not (cx - ex >= -0.5 and cx + ex <= cols - 0.5 and cy - ey >= -0.5
                    and cy + ey <= rows - 0.5):
                status[a] = _LEFT_IMAGE if np.isfinite(cx + cy) else _NOT_CONVERGED
                done = True
                break
            total = 0.0
            for k in range(subset):
                dy = k - half
                for j in range(subset):
                    dx = j - half
                    y = pa[4] * dx + (1.0 + pa[5]) * dy + cy
                    x = (1.0 + pa[1]) * dx + pa[2] * dy + cx
                    value = _value(c, order, x, y)
                    g[k * subset + j] = value
                    total += value
            gm = total / m
            squares = 0.0
            cross = 0.0
            for k in range(subset):
                for j in range(subset):
                    d = g[k * subset + j] - gm
                    g[k * subset + j] = d
                    squares += d * d
                    cross += (image[r0 + k, c0 + j] - fm) * d
            dg = np.sqrt(squares)
            flat = not dg > 0
            if flat:
                dg = 1.0
            zncc[a] = cross / (df * dg)
            ratio = -(df / dg)
            b[:] = 0.0
            for k in range(subset):
                dy = k - half
                for j in range(subset):
                    dx = j - half
                    e = g[k * subset + j] * ratio + (image[r0 + k, c0 + j] - fm)
                    ex_ = gx[r0 + k, c0 + j] * e
                    ey_ = gy[r0 + k, c0 + j] * e
                    b[0] += ex_
                    b[1] += ex_ * dx
                    b[2] += ex_ * dy
                    b[3] += ey_
                    b[4] += ey_ * dx
                    b[5] += ey_ * dy
            h = hinv[s]
            for i in range(6):
                acc = 0.0
                for j in range(6):
                    acc += h[i, j] * b[j]
                dp[i] = -acc
            _compose(pa, dp)
            iterations[a] += 1
            step = np.sqrt(dp[0] ** 2 + dp[3] ** 2
                           + half**2 * (dp[1] ** 2 + dp[2] ** 2 + dp[4] ** 2 + dp[5] ** 2))
            increment[a] = step
            lost = not step < subset / 2
            if flat:
                status[a] = _LOW_ZNCC
            elif lost:
                status[a] = _NOT_CONVERGED
            if step < tolerance or flat or lost:
                done = True
                break
        if not done:
            status[a] = _NOT_CONVERGED
