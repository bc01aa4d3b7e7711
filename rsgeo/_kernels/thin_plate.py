"""GDAL's thin-plate spline: solving for the weights and evaluating one point, compiled with Numba.

A port of GDAL's ``alg/thinplatespline.cpp`` (``VizGeorefSpline2D``, by VIZRT) and of the
map -> pixel direction of its transformer (``alg/gdal_tps.cpp``), so that rsgeo's spline gives
the numbers GDAL's gives, bit for bit, and can be evaluated inside the warp kernels one point at
a time (``rsgeo._kernels.transformer``). What GDAL does, and so what this module does:

**Solving** (``VizGeorefSpline2D::solve``). The n GCPs' src points (x, y) are centred on their
mean, and the spline

    u(x, y) = a0 + a1 x + a2 y + Σ w_i φ(r_i²),   φ(d) = d log d   (0 at d = 0),

the same for v, with r_i² the squared distance to GCP i, has its n + 3 coefficients from the
(n + 3) x (n + 3) system [[0, Pᵀ], [P, K]] c = [0, values], K_ij = φ(r_ij²), P_i = (1, x_i, y_i)
(d log d is 2 r² log r: GDAL's weights are half the textbook's). GDAL solves it by its own LU
decomposition with partial pivoting (``gdallinearsystem.cpp``, used when GDAL is built without
Armadillo, as rasterio's wheels are); :func:`solve` runs the same elimination, in the same order,
so the weights are GDAL's to the last bit. GCPs nearly on one line - their extents in x and y
differ by a factor of 1000, or the correlation of x and y has r² > 0.99 - are not a spline in
GDAL but a piecewise-linear interpolation along the line's direction (its
``VIZ_GEOREF_SPLINE_ONE_DIMENSIONAL`` case); that is kept too.

**Evaluating** (``VizGeorefSpline2D::get_point``). The affine part first, then the kernel terms
four GCPs at a time, ``u += ((w0 φ0 + w1 φ1) + w2 φ2) + w3 φ3``, then the last n mod 4 one by
one. On x86-64 GDAL computes the grouped terms' logarithm with its own faster, less precise
log (``FastApproxLog4Val``: fdlibm's ``__ieee754_log`` without its last polynomial term, about
5e-13 from the true log) and the remaining ones with the C library's ``log``; :func:`evaluate`
does the same, operation for operation (elsewhere every term takes ``log``, as in GDAL there:
:data:`GDAL_FAST_LOG`). The spline therefore misses its own GCPs by the
rounding of a sum of large terms (1e-12 to 1e-7 of a pixel on the course's data), as GDAL's does.

**Map -> pixel in a warp** (``GDALTPSTransform``, DstToSrc). gdalwarp fits the spline image ->
map and, for each output cell's map point, starts from a second spline fitted map -> image on
the same GCPs, then refines it by ``GDALGenericInverse2D``: Newton's method with the Jacobian
estimated once, at the start point, by forward differences of 1e-6 of the point's largest
coordinate, at most 15 steps, stopping when both coordinates are within 1e-12 of the target's
largest coordinate. A packed :data:`GDAL_INVERSE` array (:func:`pack_inverse`) holds both
splines, and :func:`evaluate` on it does exactly this.

The packed arrays (float64, 1-D), read by :func:`evaluate`::

    FULL             [0] 0, [1] n, [2] x mean, [3] y mean,
                     [4 : 4+n] src x - x mean, [4+n : 4+2n] src y - y mean,
                     [4+2n : 7+3n] u coefficients a0, a1, a2, w_1 .. w_n,
                     [7+3n : 10+4n] v coefficients, in the same order
    ONE_DIMENSIONAL  [0] 1, [1] n, [2] dx, [3] dy (the line's unit direction, GDAL's),
                     [4] x_0, [5] y_0 (the first GCP's src point), [6 : 6+n] each GCP's position
                     along the line, [6+n : 6+2n] the GCPs in increasing position (indices),
                     [6+2n : 6+3n] u values, [6+3n : 6+4n] v values
    GDAL_INVERSE     [0] 2, [1] most Newton steps (GDAL: 15), [2] length L of the next array,
                     [3 : 3+L] the spline inverted (src -> dst, a FULL or ONE_DIMENSIONAL array),
                     [3+L :] the spline fitted the other way (dst -> src), the start

References
----------
GDAL, ``alg/thinplatespline.cpp`` (VizGeorefSpline2D: solve, get_point,
VizGeorefSpline2DBase_func4), ``alg/gdallinearsystem.cpp`` (the LU solver),
``alg/gdal_tps.cpp`` (GDALCreateTPSTransformerInt, GDALTPSTransform) and
``alg/gdalgenericinverse.cpp`` (GDALGenericInverse2D), GDAL 3.10.
"""

import math
import platform
import sys

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic

from .._numba_cache import CACHE
from ..errors import GCPError
from ..language import N_, _
from ..validation import as_integer, as_points
from ._rows import run_in_row_blocks

__all__ = ["FULL", "GDAL_FAST_LOG", "GDAL_INVERSE", "GDAL_STEPS", "ONE_DIMENSIONAL", "evaluate",
           "evaluate_many", "invert_many", "pack_inverse", "solve"]

#: The kinds of packed array (their first number).
FULL, ONE_DIMENSIONAL, GDAL_INVERSE = 0, 1, 2

#: GDALGenericInverse2D's most Newton steps.
GDAL_STEPS = 15

#: Whether GDAL computes its grouped kernel terms with its faster logarithm: only where it is
#: compiled by GCC or Clang for x86-64 (``USE_OPTIMIZED_VizGeorefSpline2DBase_func4``), not by
#: MSVC and not on ARM, where every term takes the C library's ``log``.
GDAL_FAST_LOG = platform.machine().lower() in ("x86_64", "amd64") and sys.platform != "win32"


# --- Solving -------------------------------------------------------------------------------------


def solve(src, dst):
    """GDAL's thin-plate spline through the GCPs src -> dst, packed for :func:`evaluate`.

    The GCPs are used as given, in their order (GDAL's sums and pivoting
    depend on it); :func:`rsgeo.transforms.fit_transform` removes exact
    duplicates first, as GDAL's transformer does.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        The GCPs: n >= 3 src points and the dst point of each.

    Returns
    -------
    ndarray, float64, 1-D
        A :data:`FULL` (or, for GCPs nearly on one line, a
        :data:`ONE_DIMENSIONAL`) packed array; its layout is in the module's
        docstring.

    Raises
    ------
    GCPError
        If there are fewer than 3 GCPs or not one dst point per src point;
        if all src points share one x or one y (GDAL's "degenerate system");
        or if the system is singular (GDAL's "matrix not invertible":
        repeated src points).
    ValueError
        If the points are not (n, 2) finite numbers.

    Examples
    --------
    >>> src = np.array([[0.0, 0.0], [10.0, 0.0], [0.0, 10.0], [10.0, 10.0], [5.0, 4.0]])
    >>> packed = solve(src, src * 2.0 + 1.0)
    >>> [round(float(v), 9) for v in evaluate(packed, 5.0, 4.0)]
    [11.0, 9.0]
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise GCPError(_("a thin-plate spline needs one dst point per src point, got {n_src} src "
                         "and {n_dst} dst points").format(n_src=len(src), n_dst=len(dst)))
    if len(src) < 3:
        raise GCPError(_("a thin-plate spline needs at least 3 GCPs, got {n}").format(n=len(src)))
    x = np.ascontiguousarray(src[:, 0])
    y = np.ascontiguousarray(src[:, 1])
    values = np.ascontiguousarray(dst.T)
    statistics = _statistics(x, y)
    delx, dely, ssxx, ssyy, ssxy = statistics[:5]
    if ssxx * ssyy == 0.0:
        raise GCPError(_("the GCPs' src points all have the same x or the same y (GDAL: "
                         "\"degenerate system\"); a thin-plate spline needs GCPs spread over "
                         "the image in both directions"))
    if delx < 0.001 * dely or dely < 0.001 * delx or abs(ssxy * ssxy / (ssxx * ssyy)) > 0.99:
        return _one_dimensional(x, y, values, statistics)
    packed = np.empty(10 + 4 * len(x))
    # GDAL stops at a zero pivot but its last one is not checked: 0 there gives inf or NaN
    if not _solve_full(x, y, values, packed) or not np.isfinite(packed).all():
        raise GCPError(_("the thin-plate spline's system is singular (GDAL: \"matrix not "
                         "invertible\"): src points repeat; remove the repeated GCPs"))
    return packed


@njit(cache=CACHE)
def _statistics(x, y):
    """GDAL's sums over the GCPs, in its order: x and y extents and centred (co)variances."""
    n = x.shape[0]
    xmax = xmin = x[0]
    ymax = ymin = y[0]
    sumx = sumy = sumx2 = sumy2 = sumxy = 0.0
    for p in range(n):
        xx = x[p]
        yy = y[p]
        xmax = max(xmax, xx)
        xmin = min(xmin, xx)
        ymax = max(ymax, yy)
        ymin = min(ymin, yy)
        sumx += xx
        sumx2 += xx * xx
        sumy += yy
        sumy2 += yy * yy
        sumxy += xx * yy
    out = np.empty(9)
    out[0] = xmax - xmin
    out[1] = ymax - ymin
    out[2] = sumx2 - sumx * sumx / n
    out[3] = sumy2 - sumy * sumy / n
    out[4] = sumxy - sumx * sumy / n
    out[5], out[6], out[7], out[8] = sumx, sumy, sumx2, sumy2
    return out


def _one_dimensional(x, y, values, statistics):
    """GDAL's VIZ_GEOREF_SPLINE_ONE_DIMENSIONAL: interpolation along one direction."""
    n = len(x)
    sumx, sumy, sumx2, sumy2 = statistics[5:9]
    dx = n * sumx2 - sumx * sumx
    dy = n * sumy2 - sumy * sumy
    fact = 1.0 / math.sqrt(dx * dx + dy * dy)
    dx *= fact
    dy *= fact
    position = dx * (x - x[0]) + dy * (y - y[0])
    # GDAL picks the smallest unused position each time, the first of equal ones
    order = np.argsort(position, kind="stable")
    return np.concatenate([[ONE_DIMENSIONAL, n, dx, dy, x[0], y[0]], position, order,
                           values[0], values[1]]).astype(np.float64)


@njit(cache=CACHE, error_model="numpy")
def _solve_full(x, y, values, packed):
    """GDAL's full spline into ``packed``; False if the system is singular."""
    n = x.shape[0]
    m = n + 3
    x_mean = 0.0
    y_mean = 0.0
    for c in range(n):
        x_mean += x[c]
        y_mean += y[c]
    x_mean /= n
    y_mean /= n
    xc = x - x_mean
    yc = y - y_mean
    # GDALMatrix is column-major: A(row, col) at [row + col * m]; Fortran order keeps the
    # elimination's inner loop on contiguous memory
    a = np.zeros((m, m)).T
    for c in range(n):
        a[0, c + 3] = 1.0
        a[1, c + 3] = xc[c]
        a[2, c + 3] = yc[c]
        a[c + 3, 0] = 1.0
        a[c + 3, 1] = xc[c]
        a[c + 3, 2] = yc[c]
    for r in range(n):
        for c in range(r, n):
            dx = xc[c] - xc[r]
            dy = yc[c] - yc[r]
            dist = dx * dx + dy * dy
            a[r + 3, c + 3] = dist * math.log(dist) if dist != 0.0 else 0.0
            if r != c:
                a[c + 3, r + 3] = a[r + 3, c + 3]
    rhs = np.zeros((m, 2))
    for v in range(2):
        for i in range(n):
            rhs[i + 3, v] = values[v, i]
    coef = np.empty((m, 2))
    if not _lu_solve(a, rhs, coef):
        return False
    packed[0] = FULL
    packed[1] = n
    packed[2] = x_mean
    packed[3] = y_mean
    packed[4:4 + n] = xc
    packed[4 + n:4 + 2 * n] = yc
    packed[4 + 2 * n:4 + 2 * n + m] = coef[:, 0]
    packed[4 + 2 * n + m:4 + 2 * n + 2 * m] = coef[:, 1]
    return True


@njit(cache=CACHE, error_model="numpy")
def _lu_solve(a, rhs, out):
    """GDAL's ``solve()`` in gdallinearsystem.cpp: LU with partial pivoting, then LUP solve.

    Every element goes through the same operations as in GDAL, in one thread as GDAL runs
    it: a parallel elimination costs several CPU-seconds more to compile on every cold
    cache, and the serial one solves 2,000 GCPs in a few seconds. ``a`` is overwritten by
    its LU factors. False if a pivot is 0.
    """
    m = a.shape[0]
    perm = np.arange(m)
    for step in range(m - 1):
        pivot = step
        largest = abs(a[step, step])
        for i in range(step + 1, m):
            if abs(a[i, step]) > largest:
                pivot = i
                largest = abs(a[i, step])
        if largest <= 0.0:
            return False
        if pivot != step:
            perm[pivot], perm[step] = perm[step], perm[pivot]
            for col in range(m):
                a[pivot, col], a[step, col] = a[step, col], a[pivot, col]
        for row in range(step + 1, m):
            a[row, step] /= a[step, step]
        for col in range(step + 1, m):
            factor = a[step, col]
            for row in range(step + 1, m):
                a[row, col] -= a[row, step] * factor
    for col in range(rhs.shape[1]):
        for row in range(m):
            value = rhs[perm[row], col]
            for k in range(row):
                value -= a[row, k] * out[k, col]
            out[row, col] = value
        for row in range(m - 1, -1, -1):
            value = out[row, col]
            for k in range(row + 1, m):
                value -= a[row, k] * out[k, col]
            out[row, col] = value / a[row, row]
    return True


def pack_inverse(spline, start, max_steps=GDAL_STEPS):
    """The packed map -> pixel step of GDAL's TPS transformer: ``spline`` inverted from ``start``.

    Parameters
    ----------
    spline : ndarray
        The packed spline to invert (src -> dst, e.g. image -> map), from :func:`solve`.
    start : ndarray
        The packed spline fitted the other way on the same GCPs (dst -> src), the first guess.
    max_steps : int
        Newton steps at most; GDAL's :data:`GDAL_STEPS`.

    Returns
    -------
    ndarray
        A :data:`GDAL_INVERSE` packed array: :func:`evaluate` on it maps a dst
        point to the src point GDAL's ``GDALTPSTransform`` gives (DstToSrc).

    Raises
    ------
    ValueError
        If ``max_steps`` is not an integer >= 0.
    """
    steps = as_integer(max_steps, "max_steps", low=0, why=N_("Newton steps at most"))
    spline = np.asarray(spline, dtype=np.float64)
    start = np.asarray(start, dtype=np.float64)
    return np.concatenate([[GDAL_INVERSE, steps, len(spline)], spline, start])


# --- Evaluating ----------------------------------------------------------------------------------


@intrinsic
def _bits(typingctx, value):
    """The IEEE 754 bits of a float64, as an int64 (C's memcpy of a double)."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))
    return types.int64(types.float64), codegen


@intrinsic
def _from_bits(typingctx, bits):
    """The float64 with these IEEE 754 bits."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.DoubleType())
    return types.float64(types.int64), codegen


_LN2_OVER_2POW20 = 6.93147180559945286e-01 / 1048576
_1023_TIMES_2POW20 = 1023.0 * 1048576
_LG1 = 6.666666666666735130e-01
_LG2 = 3.999999999940941908e-01
_LG3 = 2.857142874366239149e-01
_LG4 = 2.222219843214978396e-01
_LG5 = 1.818357216161805012e-01
_LG6 = 1.531383769920937332e-01


@njit(cache=CACHE, inline="always", error_model="numpy")
def _approximate_log(value):
    """GDAL's FastApproxLog4Val for one value > 0 (its lanes are independent).

    fdlibm's argument reduction on the high 32 bits - value = 2^k (1 + f) with
    1 + f in [sqrt(2)/2, sqrt(2)) - and its polynomial without the Lg7 term,
    k ln 2 in one rounding. For 0 (a point on a GCP) it gives -1023 ln 2, which
    GDAL multiplies by the distance 0.
    """
    bits = _bits(value)
    high = (bits >> 32) & 0xFFFFFFFF
    k = high & 0xFFF00000
    high = high & 0x000FFFFF
    i = (high + 0x95F64) & 0x100000
    high = high | (i ^ 0x3FF00000)
    normal = _from_bits((high << 32) | (bits & 0xFFFFFFFF))
    k = k + i
    f = normal - 1.0
    s = f / (normal + 1.0)
    z = s * s
    w = z * z
    t1 = w * (_LG2 + w * (_LG4 + w * _LG6))
    t2 = z * (_LG1 + w * (_LG3 + w * _LG5))
    r = t2 + t1
    return (float(k) - _1023_TIMES_2POW20) * _LN2_OVER_2POW20 - (s * (f - r) - f)


@njit(cache=CACHE, inline="always")
def _grouped_term(packed, xs, ys, r, px, py):
    """GDAL's VizGeorefSpline2DBase_func4 for one of its four lanes: d log d."""
    dx = packed[xs + r] - px
    dy = packed[ys + r] - py
    dist = dx * dx + dy * dy
    if GDAL_FAST_LOG:
        return dist * _approximate_log(dist)
    return dist * math.log(dist) if dist != 0.0 else 0.0


@njit(cache=CACHE, error_model="numpy")
def _line(packed, start, n, x, y):
    """GDAL's ONE_DIMENSIONAL get_point: linear between the two GCPs around the position."""
    position = start + 6
    order = position + n
    us = order + n
    vs = us + n
    along = (packed[start + 2] * (x - packed[start + 4])
             + packed[start + 3] * (y - packed[start + 5]))
    if along <= packed[position + int(packed[order])]:
        left = int(packed[order])
        right = int(packed[order + 1])
    elif along >= packed[position + int(packed[order + n - 1])]:
        left = int(packed[order + n - 2])
        right = int(packed[order + n - 1])
    else:
        left = right = 0
        for r in range(1, n):
            left = int(packed[order + r - 1])
            right = int(packed[order + r])
            if packed[position + left] <= along <= packed[position + right]:
                break
    fact = ((along - packed[position + left])
            / (packed[position + right] - packed[position + left]))
    return ((1.0 - fact) * packed[us + left] + fact * packed[us + right],
            (1.0 - fact) * packed[vs + left] + fact * packed[vs + right])


@njit(cache=CACHE, error_model="numpy")
def _spline(packed, start, x, y):
    """GDAL's get_point for the FULL or ONE_DIMENSIONAL spline packed from ``start``."""
    n = int(packed[start + 1])
    if packed[start] == ONE_DIMENSIONAL:
        return _line(packed, start, n, x, y)
    px = x - packed[start + 2]
    py = y - packed[start + 3]
    xs = start + 4
    ys = xs + n
    cu = ys + n
    cv = cu + n + 3
    u = packed[cu] + packed[cu + 1] * px + packed[cu + 2] * py
    v = packed[cv] + packed[cv + 1] * px + packed[cv + 2] * py
    grouped = n & ~3
    for r in range(0, grouped, 4):
        t0 = _grouped_term(packed, xs, ys, r, px, py)
        t1 = _grouped_term(packed, xs, ys, r + 1, px, py)
        t2 = _grouped_term(packed, xs, ys, r + 2, px, py)
        t3 = _grouped_term(packed, xs, ys, r + 3, px, py)
        u += (packed[cu + 3 + r] * t0 + packed[cu + 4 + r] * t1
              + packed[cu + 5 + r] * t2 + packed[cu + 6 + r] * t3)
        v += (packed[cv + 3 + r] * t0 + packed[cv + 4 + r] * t1
              + packed[cv + 5 + r] * t2 + packed[cv + 6 + r] * t3)
    for r in range(grouped, n):
        dx = packed[xs + r] - px
        dy = packed[ys + r] - py
        dist = dx * dx + dy * dy
        term = dist * math.log(dist) if dist != 0.0 else 0.0
        u += packed[cu + 3 + r] * term
        v += packed[cv + 3 + r] * term
    return u, v


@njit(cache=CACHE, error_model="numpy")
def _gdal_inverse(packed, x, y):
    """GDALTPSTransform DstToSrc: (col, row, converged) for the dst point (x, y).

    The start spline's value, refined by GDALGenericInverse2D on the spline
    (Jacobian by forward differences at the start only, tolerance 1e-12 of the
    target's largest coordinate, no tolerance on the steps). ``converged`` is
    what GDALGenericInverse2D returns; GDAL uses the point either way.
    """
    steps = int(packed[1])
    spline = np.int64(3)            # a value, not a constant: see evaluate
    start = 3 + int(packed[2])
    x_out, y_out = _spline(packed, start, x, y)
    largest_out = max(abs(x_out), abs(y_out))
    eps = largest_out * 1e-6 if largest_out > 0 else 1e-6
    largest_in = max(abs(x), abs(y))
    tolerance = largest_in * 1e-12 if largest_in > 0 else 1e-12
    lam_x = lam_y = phi_x = phi_y = 0.0
    for i in range(steps):
        x_approx, y_approx = _spline(packed, spline, x_out, y_out)
        delta_x = x_approx - x
        delta_y = y_approx - y
        if abs(delta_x) < tolerance and abs(delta_y) < tolerance:
            return x_out, y_out, True
        if i == 0:
            x_tmp, y_tmp = _spline(packed, spline, x_out + eps, y_out)
            x_lam = (x_tmp - x_approx) / eps
            y_lam = (y_tmp - y_approx) / eps
            x_tmp, y_tmp = _spline(packed, spline, x_out, y_out + eps)
            x_phi = (x_tmp - x_approx) / eps
            y_phi = (y_tmp - y_approx) / eps
            det = x_lam * y_phi - x_phi * y_lam
            if det == 0:
                return x_out, y_out, False
            lam_x = y_phi / det
            lam_y = -x_phi / det
            phi_x = -y_lam / det
            phi_y = x_lam / det
        x_out -= delta_x * lam_x + delta_y * lam_y
        y_out -= delta_x * phi_x + delta_y * phi_y
    return x_out, y_out, False


@njit(cache=CACHE, inline="always")
def evaluate(packed, x, y):
    """The packed spline (or GDAL's inversion of one) at one point, as GDAL computes it.

    Compiled, with no allocation: what rsgeo's warp kernels call for each
    output cell.

    Parameters
    ----------
    packed : ndarray
        From :func:`solve` (the spline's value, GDAL's ``get_point``) or
        :func:`pack_inverse` (GDAL's TPS transformer, map -> pixel).
    x, y : float

    Returns
    -------
    (float, float)
    """
    if packed[0] == GDAL_INVERSE:
        u, v, _converged = _gdal_inverse(packed, x, y)
        return u, v
    # np.int64(0), a value and not a constant: Numba would compile a copy of _spline (and of
    # _line) for each constant start a caller passes, seconds each on a cold cache
    return _spline(packed, np.int64(0), x, y)


def evaluate_many(packed, points, out):
    """:func:`evaluate` at every row of ``points`` (n, 2), into ``out`` (n, 2).

    Numba's threads share the points in blocks (``rsgeo._kernels._rows``).

    Parameters
    ----------
    packed : ndarray
    points : (n, 2) float64 ndarray
    out : (n, 2) float64 ndarray
    """
    packed = _writable(packed)
    run_in_row_blocks(lambda first, stop: _evaluate_points(packed, points, out, first, stop),
                      points.shape[0], _threads(points.shape[0]))


def invert_many(packed, points, out, converged):
    """GDAL's inversion (a :data:`GDAL_INVERSE` array) at every point, with its success flag.

    Numba's threads share the points in blocks (``rsgeo._kernels._rows``).

    Parameters
    ----------
    packed : ndarray
        From :func:`pack_inverse`.
    points : (n, 2) float64 ndarray
    out : (n, 2) float64 ndarray
        The points :func:`evaluate` gives.
    converged : (n,) bool ndarray
        Whether GDALGenericInverse2D reached its tolerance within its steps.
    """
    packed = _writable(packed)
    run_in_row_blocks(
        lambda first, stop: _invert_points(packed, points, out, converged, first, stop),
        points.shape[0], _threads(points.shape[0]))


def _writable(packed):
    """``packed``, or a writable copy of a read-only one (a model's): Numba types a read-only
    array apart, and would compile the whole spline a second time for it."""
    return packed if packed.flags.writeable else packed.copy()


# points per thread below which one thread evaluates them all (a thread's start costs more)
_POINTS_PER_THREAD = 4096


def _threads(n_points):
    """As many threads as Numba would use for ``n_points`` points, one for a few."""
    import numba

    return max(1, min(numba.get_num_threads(), n_points // _POINTS_PER_THREAD))


@njit(cache=CACHE, nogil=True)
def _evaluate_points(packed, points, out, first, stop):
    for k in range(first, stop):
        out[k, 0], out[k, 1] = evaluate(packed, points[k, 0], points[k, 1])
    return 0


@njit(cache=CACHE, nogil=True)
def _invert_points(packed, points, out, converged, first, stop):
    for k in range(first, stop):
        out[k, 0], out[k, 1], converged[k] = _gdal_inverse(packed, points[k, 0], points[k, 1])
    return 0
