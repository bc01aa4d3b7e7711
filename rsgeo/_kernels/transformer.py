"""GDAL's transformer inside the warp kernels: a model packed into numbers, evaluated per pixel.

gdalwarp does not evaluate its model for a whole image first: for each output
row it asks its *transformer* where the row's pixel centres fall in the
source (``GDALGenImgProjTransform``: output pixel -> map by the output grid's
geotransform, then map -> source pixel by the source's geotransform, GCP
polynomial, thin-plate spline or RPC), and the warp kernel interpolates there
at once. This module does the same for rsgeo's kernels
(:mod:`rsgeo.resample`): a mapping that can be compiled is *packed* into one
float64 array (:func:`pack`), and :func:`row_positions`, compiled with Numba,
fills one output row's source positions from it, inside the kernel's loop,
with no array of positions for the whole grid.

The packed array::

    [0]      kind: ARRAYS (positions given as arrays), AFFINE, POLYNOMIAL, PROJECTIVE, TPS
    [1]      error threshold in source pixels (0: exact; see below)
    [2], [3] source window offset (col, row): subtracted from every position
    [4:10]   the output grid's geotransform, GDAL order (c, a, b, f, d, e)
    [10:12]  the output window's offset (col, row) in that grid: pixel (j, i) of the window
             is pixel (j + col, i + row) of the grid, its centre at (j + 0.5) + col, as
             GDAL's warp kernel computes a chunk's pixels (iDstX + 0.5 + nDstXOff)
    [12:]    the model's parameters (its ``kernel_form``):
             AFFINE      the source's inverse geotransform (map -> pixel), GDAL order
             POLYNOMIAL  order, origin x, origin y, scale, m, then m coefficients of col and
                         m of row, for coordinates centred on the origin and divided by scale
                         (:class:`rsgeo.transforms.PolynomialModel`)
             PROJECTIVE  the 3 x 3 matrix, row by row
             TPS         ``rsgeo._kernels.thin_plate``'s packed spline

A model offers its packing through a ``kernel_form()`` method returning
``(kind, parameters)``; a mapping without one (any Python callable) is
evaluated by :func:`rsgeo.resample.warp` in NumPy, strip by strip, as before.

**GDAL's approximation.** gdalwarp wraps its transformer in
``GDALApproxTransform`` with an error threshold of 0.125 pixel unless told
otherwise (``-et``): for a row it computes the exact positions of the first,
middle and last pixels only; if the middle one is within the threshold
(``|dcol| + |drow|``) of the straight line through the other two, the whole row
is interpolated linearly from the first; otherwise each half is treated the
same way, and a half of 5 pixels or fewer is computed exactly.
:func:`row_positions` with a threshold > 0 follows it step by step (the same
sample pixels, the same formulas and order), so that rsgeo's approximated
warps equal GDAL's approximated ones pixel for pixel.

References
----------
GDAL, ``alg/gdaltransformer.cpp`` (``GDALGenImgProjTransform``,
``GDALApproxTransform``, ``GDALApproxTransformInternal``) and
``alg/gdalwarpkernel.cpp`` (each row's pixel centres at j + 0.5, i + 0.5).
"""

import affine
import numpy as np
from numba import njit

from .._numba_cache import CACHE
from . import thin_plate

__all__ = ["ARRAYS", "AFFINE", "POLYNOMIAL", "PROJECTIVE", "TPS", "pack", "row_positions",
           "pixel_centre", "positions", "to_source",
           "polynomial_parameters", "polynomial_point", "polynomial_many"]

ARRAYS, AFFINE, POLYNOMIAL, PROJECTIVE, TPS = 0, 1, 2, 3, 4
_KINDS = {"affine": AFFINE, "polynomial": POLYNOMIAL, "projective": PROJECTIVE, "tps": TPS}
_HEADER = 12
# the most halvings of a row before a segment is 5 pixels or fewer: 2 per level, 64 levels
_STACK = 128


def pack(mapping, dst_transform, src_offset=(0.0, 0.0), error_threshold=0.0,
         dst_offset=(0.0, 0.0)):
    """The packed transformer of a mapping, or None if it cannot be compiled.

    Parameters
    ----------
    mapping : affine.Affine or model
        Map (x, y) -> source (col, row): an ``affine.Affine`` or an object
        with a ``kernel_form()`` method (rsgeo's polynomial, projective and
        thin-plate spline models).
    dst_transform : affine.Affine
        The output grid's geotransform (pixel -> map).
    src_offset : (float, float)
        The source window's first column and row: the image given to the
        kernel starts there in the full source.
    error_threshold : float
        GDAL's approximation threshold in source pixels; 0 for exact.
    dst_offset : (float, float)
        The output window's first column and row in the grid of ``dst_transform``.

    Returns
    -------
    ndarray or None
        The packed float64 array (see the module's docstring).
    """
    kind, parameters = _kernel_form(mapping)
    if kind is None:
        return None
    header = [float(kind), float(error_threshold), float(src_offset[0]), float(src_offset[1]),
              *map(float, dst_transform.to_gdal()), float(dst_offset[0]), float(dst_offset[1])]
    return np.concatenate([np.array(header), np.asarray(parameters, dtype=np.float64)])


def _kernel_form(mapping):
    """(kind code, parameters) of a mapping, or (None, None)."""
    if isinstance(mapping, affine.Affine):
        return AFFINE, np.array(mapping.to_gdal(), dtype=np.float64)
    form = getattr(mapping, "kernel_form", None)
    if form is None:
        return None, None
    result = form()
    if result is None:
        return None, None
    kind, parameters = result
    return _KINDS[kind], parameters


def positions(packed, shape):
    """Every output pixel's source (col, row) for a grid of ``shape``: for tests and plots.

    Parameters
    ----------
    packed : ndarray
        From :func:`pack`.
    shape : (rows, cols)

    Returns
    -------
    cols, rows : ndarray, shape ``shape``
        What the kernels use (NaN where the model has no value, such as a
        projective model's vanishing line).
    """
    cols = np.empty(shape)
    rows = np.empty(shape)
    _fill_positions(packed, shape[0], shape[1], cols, rows)
    return cols, rows


@njit(cache=CACHE)
def _fill_positions(packed, n_rows, n_cols, cols, rows):
    for i in range(n_rows):
        row_positions(packed, i, n_cols, cols[i], rows[i])


# -- the models, one point at a time ------------------------------------------


def polynomial_parameters(order, origin, scale, coefficients):
    """The packed parameters of a polynomial (see the module's docstring).

    Parameters
    ----------
    order : int
    origin : (2,) array_like
    scale : float
    coefficients : (2, m) array_like
        For coordinates centred on ``origin`` and divided by ``scale``, in
        rsgeo's term order (1, x, y, xy, x², y², x²y, xy², x³, y³).

    Returns
    -------
    ndarray
    """
    coefficients = np.asarray(coefficients, dtype=np.float64)
    m = coefficients.shape[1]
    head = np.array([order, origin[0], origin[1], scale, m], dtype=np.float64)
    return np.concatenate([head, coefficients[0], coefficients[1]])


@njit(cache=CACHE, inline="always")
def _polynomial_uv(order, x0, y0, scale, a, b, x, y):
    """The polynomial with coefficients ``a`` (col) and ``b`` (row) at (x, y)."""
    tx = (x - x0) / scale
    ty = (y - y0) / scale
    u = a[0] + a[1] * tx + a[2] * ty
    v = b[0] + b[1] * tx + b[2] * ty
    if order >= 2:
        xy = tx * ty
        xx = tx * tx
        yy = ty * ty
        u = u + a[3] * xy + a[4] * xx + a[5] * yy
        v = v + b[3] * xy + b[4] * xx + b[5] * yy
        if order >= 3:
            u = u + a[6] * (xx * ty) + a[7] * (tx * yy) + a[8] * (xx * tx) + a[9] * (yy * ty)
            v = v + b[6] * (xx * ty) + b[7] * (tx * yy) + b[8] * (xx * tx) + b[9] * (yy * ty)
    return u, v


@njit(cache=CACHE)
def polynomial_point(parameters, x, y):
    """A polynomial at one point (x, y): the terms in rsgeo's order, summed left to right.

    Parameters
    ----------
    parameters : ndarray
        From :func:`polynomial_parameters`.
    x, y : float
        The point.

    Returns
    -------
    (float, float)
        The polynomial's two outputs (col, row for a map -> image model).
    """
    m = int(parameters[4])
    return _polynomial_uv(int(parameters[0]), parameters[1], parameters[2], parameters[3],
                          parameters[5:5 + m], parameters[5 + m:5 + 2 * m], x, y)


@njit(cache=CACHE)
def polynomial_many(parameters, points):
    """A polynomial at (n, 2) points (what the model's ``__call__`` returns).

    Parameters
    ----------
    parameters : ndarray
        From :func:`polynomial_parameters`.
    points : (n, 2) ndarray of float64

    Returns
    -------
    ndarray, shape (n, 2)
    """
    out = np.empty((points.shape[0], 2))
    for k in range(points.shape[0]):
        out[k, 0], out[k, 1] = polynomial_point(parameters, points[k, 0], points[k, 1])
    return out


@njit(cache=CACHE, inline="always")
def projective_point(matrix, x, y):
    """A 3 x 3 homogeneous matrix at (x, y).

    Parameters
    ----------
    matrix : ndarray, shape (9,)
        The matrix row by row.
    x, y : float

    Returns
    -------
    (float, float)
        The mapped point; (NaN, NaN) on the vanishing line, where it has no value.
    """
    w = matrix[6] * x + matrix[7] * y + matrix[8]
    if abs(w) < 1e-12:
        return np.nan, np.nan
    return ((matrix[0] * x + matrix[1] * y + matrix[2]) / w,
            (matrix[3] * x + matrix[4] * y + matrix[5]) / w)


@njit(cache=CACHE)
def to_source(packed, px, py):
    """Output pixel (px, py) -> source (col, row), exactly: GDAL's GenImgProjTransform.

    The output grid's geotransform first (GDALApplyGeoTransform's
    c + px a + py b), then the model, then the source window's offset.

    Parameters
    ----------
    packed : ndarray
        From :func:`pack`.
    px, py : float
        A position in the output grid's pixels (a cell's centre is
        (j + 0.5, i + 0.5)).

    Returns
    -------
    (float, float)
        (col, row) in the source.
    """
    x = packed[4] + px * packed[5] + py * packed[6]
    y = packed[7] + px * packed[8] + py * packed[9]
    kind = int(packed[0])
    model = packed[_HEADER:]
    if kind == AFFINE:
        col = model[0] + x * model[1] + y * model[2]
        row = model[3] + x * model[4] + y * model[5]
    elif kind == POLYNOMIAL:
        col, row = polynomial_point(model, x, y)
    elif kind == PROJECTIVE:
        col, row = projective_point(model, x, y)
    else:
        col, row = thin_plate.evaluate(model, x, y)
    return col - packed[2], row - packed[3]


# -- one row of the output grid -------------------------------------------------


@njit(cache=CACHE)
def row_positions(packed, i, n, cols, rows):
    """Source positions of the first ``n`` pixels of output row ``i`` into ``cols``, ``rows``.

    Exact (every pixel through :func:`to_source`) unless ``packed`` holds an
    error threshold > 0 and the row has more than 5 pixels: then GDAL's
    approximation (``_approximate_row``).

    Parameters
    ----------
    packed : ndarray
        From :func:`pack`.
    i : int
        The row, in the output window.
    n : int
        Its pixels.
    cols, rows : ndarray of float64, at least ``n`` long
        Filled with the positions.
    """
    py = (i + 0.5) + packed[11]
    if packed[1] > 0.0 and n > 5:
        _approximate_row(packed, py, n, cols, rows)
    else:
        # np.int64(0), a value and not a constant: Numba compiles a copy of a function for
        # each constant argument a caller passes (rsgeo._kernels.thin_plate.evaluate)
        _exact(packed, py, cols, rows, np.int64(0), n)


@njit(cache=CACHE)
def pixel_centre(packed, j):
    """The x of pixel j's centre in the output grid: (j + 0.5) + the window's column offset.

    Parameters
    ----------
    packed : ndarray
        From :func:`pack`.
    j : int
        The column, in the output window.

    Returns
    -------
    float
    """
    return (j + 0.5) + packed[10]


@njit(cache=CACHE)
def _exact(packed, py, cols, rows, first, stop):
    """Exact positions of pixels first .. stop - 1 of the row.

    :func:`to_source`'s operations, with the model's kind and numbers read once
    for the row rather than at every pixel (the per-pixel dispatch cost a
    nearest-neighbour warp through a polynomial half its time).
    """
    kind = int(packed[0])
    model = packed[_HEADER:]
    c, a, b, f, d, e = packed[4], packed[5], packed[6], packed[7], packed[8], packed[9]
    col_off, row_off, x_off = packed[2], packed[3], packed[10]
    if kind == AFFINE:
        m0, m1, m2, m3, m4, m5 = model[0], model[1], model[2], model[3], model[4], model[5]
        for j in range(first, stop):
            px = (j + 0.5) + x_off
            x = c + px * a + py * b
            y = f + px * d + py * e
            cols[j] = (m0 + x * m1 + y * m2) - col_off
            rows[j] = (m3 + x * m4 + y * m5) - row_off
    elif kind == POLYNOMIAL:
        order, m = int(model[0]), int(model[4])
        x0, y0, scale = model[1], model[2], model[3]
        ca, cb = model[5:5 + m], model[5 + m:5 + 2 * m]
        for j in range(first, stop):
            px = (j + 0.5) + x_off
            x = c + px * a + py * b
            y = f + px * d + py * e
            u, v = _polynomial_uv(order, x0, y0, scale, ca, cb, x, y)
            cols[j] = u - col_off
            rows[j] = v - row_off
    else:
        for j in range(first, stop):
            cols[j], rows[j] = to_source(packed, pixel_centre(packed, j), py)


@njit(cache=CACHE)
def _finite(a, b):
    return np.isfinite(a) and np.isfinite(b)


@njit(cache=CACHE)
def _approximate_row(packed, py, n, cols, rows):
    """GDALApproxTransform on one row of n > 5 pixels at height ``py``.

    GDAL's recursion (GDALApproxTransformInternal) kept as a stack of
    segments, each (start, length) with the exact positions of its start,
    middle and end pixels. A segment whose middle is within the threshold of
    the line from its start to its end is interpolated, from its last pixel
    back to its first, as start + delta * (x - x_start); otherwise its two
    halves (the first ``middle`` pixels, and the rest) are either computed
    exactly (5 pixels or fewer) or pushed with the exact positions of their
    own middles and ends. A model with no value at a sample (NaN) makes the
    rest of that segment exact, as a failed transform does in GDAL.
    """
    threshold = packed[1]
    middle = (n - 1) // 2
    c0, r0 = to_source(packed, pixel_centre(packed, np.int64(0)), py)
    c1, r1 = to_source(packed, pixel_centre(packed, middle), py)
    c2, r2 = to_source(packed, pixel_centre(packed, n - 1), py)
    if not (_finite(c0, r0) and _finite(c1, r1) and _finite(c2, r2)):
        _exact(packed, py, cols, rows, np.int64(0), n)
        return
    starts = np.empty(_STACK, dtype=np.int64)
    lengths = np.empty(_STACK, dtype=np.int64)
    samples = np.empty((_STACK, 6))
    top = 0
    starts[0], lengths[0] = 0, n
    samples[0, 0], samples[0, 1], samples[0, 2] = c0, c1, c2
    samples[0, 3], samples[0, 4], samples[0, 5] = r0, r1, r2
    top = 1
    while top > 0:
        top -= 1
        start = starts[top]
        count = lengths[top]
        sc0, sc1, sc2 = samples[top, 0], samples[top, 1], samples[top, 2]
        sr0, sr1, sr2 = samples[top, 3], samples[top, 4], samples[top, 5]
        middle = (count - 1) // 2
        x_first = pixel_centre(packed, start)
        x_last = pixel_centre(packed, start + count - 1)
        x_middle = pixel_centre(packed, start + middle)
        delta_c = (sc2 - sc0) / (x_last - x_first)
        delta_r = (sr2 - sr0) / (x_last - x_first)
        error = (abs((sc0 + delta_c * (x_middle - x_first)) - sc1)
                 + abs((sr0 + delta_r * (x_middle - x_first)) - sr1))
        if not error > threshold:   # GDAL's test (a NaN error interpolates)
            for k in range(count - 1, -1, -1):
                distance = pixel_centre(packed, start + k) - x_first
                cols[start + k] = sc0 + delta_c * distance
                rows[start + k] = sr0 + delta_r * distance
            continue
        exact_first = middle <= 5
        exact_second = count - middle <= 5
        # the samples the halves need: first half's middle and end, second half's middle
        a = start + (middle - 1) // 2
        b = start + middle - 1
        c = start + middle + (count - middle - 1) // 2
        ac = ar = bc = br = cc = cr = 0.0
        failed = False
        if not exact_first:
            ac, ar = to_source(packed, pixel_centre(packed, a), py)
            bc, br = to_source(packed, pixel_centre(packed, b), py)
            failed = not (_finite(ac, ar) and _finite(bc, br))
        if not exact_second and not failed:
            cc, cr = to_source(packed, pixel_centre(packed, c), py)
            failed = not _finite(cc, cr)
        if failed:
            # GDAL: both halves exact, the three known samples kept
            _exact(packed, py, cols, rows, start + 1, start + middle)
            _exact(packed, py, cols, rows, start + middle + 1, start + count - 1)
            cols[start], rows[start] = sc0, sr0
            cols[start + middle], rows[start + middle] = sc1, sr1
            cols[start + count - 1], rows[start + count - 1] = sc2, sr2
            continue
        if exact_second:
            _exact(packed, py, cols, rows, start + middle + 1, start + count - 1)
            cols[start + middle], rows[start + middle] = sc1, sr1
            cols[start + count - 1], rows[start + count - 1] = sc2, sr2
        else:
            starts[top], lengths[top] = start + middle, count - middle
            samples[top, 0], samples[top, 1], samples[top, 2] = sc1, cc, sc2
            samples[top, 3], samples[top, 4], samples[top, 5] = sr1, cr, sr2
            top += 1
        if exact_first:
            _exact(packed, py, cols, rows, start + 1, start + middle)
            cols[start], rows[start] = sc0, sr0
        else:
            starts[top], lengths[top] = start, middle
            samples[top, 0], samples[top, 1], samples[top, 2] = sc0, ac, bc
            samples[top, 3], samples[top, 4], samples[top, 5] = sr0, ar, br
            top += 1
