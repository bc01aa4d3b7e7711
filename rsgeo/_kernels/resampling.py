"""GDAL's warp kernels, one per-pixel loop per method, compiled by Numba.

For each output pixel: find its position in the source (the model evaluated inside the loop,
``rsgeo._kernels.transformer``), take the 1 (nearest), 4 (bilinear) or 16 (cubic)
neighbours, weight them, round, store; GDAL's ``alg/gdalwarpkernel.cpp`` operation by operation
(see :mod:`rsgeo.resample` for what "bit for bit" covers). The public verbs are
:func:`rsgeo.resample.interpolate` and :func:`rsgeo.resample.warp`.
"""

import numpy as np
from numba import njit

from .._numba_cache import CACHE
from ..errors import RsgeoError
from ..language import _
from ._rows import run_in_row_blocks
from .transformer import ARRAYS, pixel_centre, row_positions, to_source

__all__ = ["METHODS", "WARP_METHODS", "keys_weights", "cubic_kernel", "bilinear_weights",
           "GDAL_INDEX_EPSILON", "RADIUS", "resample_pixels", "kernel_dtype", "BLOCK",
           "COMPUTED_AS",
           "NO_POSITIONS", "POSITIONS_GIVEN"]

METHODS = ("nearest", "bilinear", "cubic")
# warp also averages: each output cell is the area-weighted mean of the source
# pixels it covers (GDAL's "average"), which needs the cell's corners, not a point
WARP_METHODS = METHODS + ("average",)

# A margin GDAL adds before truncating a position to a pixel index, so that a
# coordinate computed as 9.999999999999998 for 10 lands on pixel 10.
GDAL_INDEX_EPSILON = 1e-10


def keys_weights(t, a=-0.5):
    """Cubic convolution weights of the four pixels around a fractional offset.

    Keys' kernel (Keys 1981, eq. 15; lecture, slide "Convolução cúbica") for
    the pixels at offsets -1, 0, 1, 2 from the pixel left of the position,
    written as GDAL's ``GWKCubicComputeWeights`` writes it when a = -0.5.

    Parameters
    ----------
    t : float or array_like
        Fractional distance in [0, 1) from the pixel on the left.
    a : float, optional
        Kernel parameter; -0.5 (GDAL, Keys) by default. -0.75 is OpenCV's.

    Returns
    -------
    weights : ndarray, shape (4,) + shape of t
        Weights that sum to 1 for every t.

    Raises
    ------
    ValueError
        If ``t`` cannot be read as floating-point numbers (NumPy's error).
        Nothing else is checked: an offset outside [0, 1) gives the kernel's
        values there.

    References
    ----------
    Keys, R. G. (1981), "Cubic convolution interpolation for digital image
    processing", IEEE Transactions on Acoustics, Speech, and Signal Processing
    29(6), 1153-1160.

    GDAL, ``alg/gdalwarpkernel.cpp``: ``GWKCubicComputeWeights``.

    Examples
    --------
    >>> keys_weights(0.0) + 0.0          # + 0.0 turns -0. into 0.
    array([0., 1., 0., 0.])
    >>> keys_weights(0.5)
    array([-0.0625,  0.5625,  0.5625, -0.0625])
    """
    t = np.asarray(t, dtype=np.float64)
    if a == -0.5:
        return _cubic_weights_of_array(t.ravel()).reshape((4,) + t.shape)
    return np.stack([cubic_kernel(t + 1, a), cubic_kernel(t, a),
                     cubic_kernel(1 - t, a), cubic_kernel(2 - t, a)])


@njit(cache=CACHE, inline="always")
def _cubic_weights(t):
    """GDAL's GWKCubicComputeWeights for one offset t, operation for operation.

    GDAL writes w0 = ½t·(−1 + t·(2 − t)), w1 = 1 + ½t²·(−5 + 3t),
    w2 = ½t·(1 + t·(4 − 3t)), w3 = ½t²·(−1 + t); the steps below only swap
    the operands of additions and products, which is exact in floating point,
    so the weights are GDAL's to the last bit.
    """
    half_t = 0.5 * t
    three_t = 3.0 * t
    half_t2 = half_t * t
    w0 = ((2.0 - t) * t - 1.0) * half_t
    w1 = (three_t - 5.0) * half_t2 + 1.0
    w2 = ((4.0 - three_t) * t + 1.0) * half_t
    w3 = (t - 1.0) * half_t2
    return w0, w1, w2, w3


@njit(cache=CACHE)
def _cubic_weights_of_array(t):
    """The four weights of every offset in a 1-D array t, as a (4, t.size) array."""
    weights = np.empty((4, t.size))
    for k in range(t.size):
        weights[0, k], weights[1, k], weights[2, k], weights[3, k] = _cubic_weights(t[k])
    return weights


def cubic_kernel(s, a=-0.5):
    """Keys' cubic convolution kernel W(s) (Keys 1981, eq. 4).

    Parameters
    ----------
    s : float or array_like
        Distance from the pixel centre, in pixels.
    a : float, optional
        Kernel parameter, -0.5 by default.

    Returns
    -------
    ndarray
        W(s): 1 at s = 0, 0 at every other integer, 0 for ``|s| >= 2``.

    Raises
    ------
    ValueError
        If ``s`` cannot be read as floating-point numbers (NumPy's error).

    References
    ----------
    Keys, R. G. (1981), "Cubic convolution interpolation for digital image
    processing", IEEE Transactions on Acoustics, Speech, and Signal Processing
    29(6), 1153-1160.

    Examples
    --------
    >>> float(cubic_kernel(0.0)), float(cubic_kernel(1.0)), float(cubic_kernel(1.5))
    (1.0, 0.0, -0.0625)
    """
    s = np.abs(np.asarray(s, dtype=np.float64))
    near = (a + 2) * s**3 - (a + 3) * s**2 + 1
    far = a * s**3 - 5 * a * s**2 + 8 * a * s - 4 * a
    return np.where(s <= 1, near, np.where(s < 2, far, 0.0))


def bilinear_weights(t):
    """Bilinear weights of the two pixels around a fractional offset t in [0, 1).

    Parameters
    ----------
    t : float or array_like
        Fractional distance in [0, 1) from the pixel on the left (or above).

    Returns
    -------
    weights : ndarray, shape (2,) + shape of t
        ``1 - t`` for the pixel on the left, ``t`` for the one on the right.

    Raises
    ------
    ValueError
        If ``t`` cannot be read as floating-point numbers (NumPy's error).

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``: ``GWKBilinearResample4Sample``.

    Examples
    --------
    >>> bilinear_weights(0.25)
    array([0.75, 0.25])
    """
    t = np.asarray(t, dtype=np.float64)
    return np.stack([1.0 - t, t])



# A 1-D list of positions is shared among threads in blocks of this many.
BLOCK = 4096
# "No affine mapping": the positions come as arrays (see _source_position).
# the packed transformer of positions given as arrays (rsgeo._kernels.transformer's kind ARRAYS)
POSITIONS_GIVEN = np.zeros(10)
NO_POSITIONS = np.empty(0)
# "No source validity mask": every source pixel is valid.
_NO_MASK = np.empty((0, 0, 0), dtype=np.uint8)
# The types GDAL 3.10 warps with its no-mask kernels when there is no destination nodata
# (GWK*NoMasksOrDstDensityOnly*); every other type goes through GWKRealCase.
_NO_MASK_TYPES = ("uint8", "int16", "uint16", "float32")
# Float types Numba cannot compute in are computed in this type, then cast back.
COMPUTED_AS = {np.dtype(np.float16): np.dtype(np.float32),
                np.dtype(np.longdouble): np.dtype(np.float64)}
# Nearest copies values: it runs on the image's bits, an unsigned integer as wide as its type.
_BITS_OF_SIZE = {1: np.dtype(np.uint8), 2: np.dtype(np.uint16), 4: np.dtype(np.uint32),
                 8: np.dtype(np.uint64)}


def kernel_dtype(dtype, method):
    """The type a method's loop reads an image of ``dtype`` in: few types, few compilations.

    Numba compiles a loop once per type of its arguments, some 2 CPU-s each on a cold
    cache. The interpolating loops weigh every pixel in float64 whatever its type (as GDAL
    does), so reading an image as float64 gives the same pixels: they run on uint8 (the
    type of most imagery, read as it is to spare memory) or on float64 (every other type;
    64-bit integers are checked to lie within +-2**53 first). Nearest copies values, so it
    runs on their bits: an unsigned integer type of the same width.

    Parameters
    ----------
    dtype : numpy.dtype
        The image's type, as computed (after ``COMPUTED_AS``), in native byte order.
    method : str
        One of ``WARP_METHODS``.

    Returns
    -------
    numpy.dtype
    """
    if method == "nearest":
        return _BITS_OF_SIZE[dtype.itemsize]
    return dtype if dtype == np.uint8 else np.dtype(np.float64)


def _in_kernel_dtype(values, computed, kernel):
    """``values`` (of type ``computed``) as the loop reads them (``kernel``): cast or bits."""
    values = np.ascontiguousarray(values, dtype=computed)
    if kernel.kind == "u" and kernel.itemsize == computed.itemsize and kernel != computed:
        return values.view(kernel)
    return values.astype(kernel, copy=False)


def resample_pixels(image, method, nodata, num_threads, cols, rows, packed, size, row_length,
              scale=(1.0, 1.0), valid=None):
    """Run one method's kernel over ``size`` output pixels; return (out, pixels inside).

    ``out`` is (bands, size) in ``image``'s dtype. Positions come from the
    arrays ``cols``, ``rows`` (``packed`` is ``POSITIONS_GIVEN``) or are
    computed row by row by the packed transformer (``rsgeo._kernels.transformer``)
    for an output grid ``row_length`` pixels wide. ``valid``:
    the source validity mask (``_validity``), or None for none. ``num_threads``
    threads share the rows (``run_in_row_blocks``).
    """
    bands = image if image.ndim == 3 else image[np.newaxis]
    dtype = bands.dtype
    computed = COMPUTED_AS.get(dtype, dtype.newbyteorder("="))  # Numba needs native order
    kernel_type = kernel_dtype(computed, method)
    bands = _in_kernel_dtype(bands, computed, kernel_type)
    out = np.empty((bands.shape[0], size), dtype=kernel_type)
    if size == 0:
        return np.empty((bands.shape[0], 0), dtype=dtype), 0
    # no nodata (gdalwarp without -dstnodata): outside is 0 and no AvoidNoData nudge,
    # which comparing with NaN (never equal) turns off
    avoid = nodata is not None
    nodata = nodata if avoid else 0
    fill = np.array([nodata], dtype=computed)
    is_int = computed.kind in "ui"
    if is_int:
        info = np.iinfo(computed)
        # the next value away from nodata, GDAL's AvoidNoData
        step = np.array([nodata + 1 if nodata == info.min else nodata - 1], dtype=computed)
        # GDAL's clamp to the dtype's range; a 64-bit maximum has no float64 (2**63 - 1
        # rounds up to 2**63, which overflows the cast), so the clamp stops at the largest
        # float64 below it (64-bit images are checked to stay within +-2**53, so only the
        # bottom of uint64's range, 0, can be reached: _check_exact_in_float64)
        low = float(info.min)
        high = (float(info.max) if computed.itemsize < 8
                else float(np.nextafter(float(info.max), 0)))
    else:
        step = np.array([np.nextafter(computed.type(nodata), computed.type(np.inf))],
                        dtype=computed)
        low, high = -np.inf, np.inf
    fill = _in_kernel_dtype(fill, computed, kernel_type)
    step = _in_kernel_dtype(step, computed, kernel_type)
    n_rows = -(-size // row_length)
    compare = float(nodata) if avoid else np.nan
    if valid is None:
        valid = _NO_MASK
    xscale, yscale = scale
    widened = method != "nearest" and not (xscale >= 0.95 and yscale >= 0.95)
    if widened and method != "average" and valid.size != 0:
        raise RsgeoError(_(
            "src_nodata with {method} widened for downsampling (scale {scale} below 0.95) is "
            "not supported; give scale=1 for the plain {method} kernel, use "
            "method='average' (which leaves src_nodata pixels out), or fill the nodata "
            "pixels first").format(method=method, scale=(xscale, yscale)))
    cols, rows = np.ascontiguousarray(cols), np.ascontiguousarray(rows)
    head = (bands, cols, rows, packed)
    tail = (row_length, out, fill, step, compare, is_int, low, high)
    if method == "average":
        margins = [2 * max(1, int(np.ceil(1.0 / value))) for value in scale]

        def loop(first, stop):
            return _average_loop(*head, first, stop, *tail, margins[0], margins[1], valid)
    elif widened:
        def loop(first, stop):
            return _widened_loop(*head, first, stop, *tail, RADIUS[method], float(xscale),
                                 float(yscale))
    elif method == "nearest":
        def loop(first, stop):
            return _nearest_loop(*head, first, stop, *tail, valid)
    else:
        # GDAL's general path (GWKRealCase) with a destination nodata, and for the types
        # without a specialised no-mask kernel (float16 is computed as float32, as warp
        # converts it)
        masked = avoid or computed.name not in _NO_MASK_TYPES
        kernel = _bilinear_loop if method == "bilinear" else _cubic_loop

        def loop(first, stop):
            return kernel(*head, first, stop, *tail, masked, valid)
    inside = run_in_row_blocks(loop, n_rows, num_threads)
    if out.dtype == dtype:
        return out, inside
    if method == "nearest" and computed.itemsize == out.dtype.itemsize:
        return out.view(computed).astype(dtype, copy=False), inside
    return out.astype(dtype), inside


# -- the kernels: one loop over output pixels per method ----------------------
#
# Each is compiled by Numba (cache=True keeps the machine code between
# sessions; no fastmath, so every floating-point operation happens in the order
# written here, which is GDAL's). Each runs over output rows first_row .. stop_row - 1
# and returns how many of their pixels it found inside the source; threads share a
# warp's rows in blocks (rsgeo._kernels._rows).
#
# Small helpers are inlined (inline="always"); each inlining is compiled again in every
# loop that uses it, so the larger pieces (the three bilinear kernels, which the cubic loop
# also falls back to) are calls: a chapter's first run on a cold cache compiles them once.


@njit(cache=CACHE, inline="always")
def _u(index):
    """An index known to be in range, unsigned: Numba then skips its negative-index
    wrap-around test, which made the nearest kernel three times slower."""
    return np.uint64(index)


@njit(cache=CACHE, inline="always")
def _pixel(bands, band, row, col):
    """The source value ``bands[band, row, col]``, for indices inside the image."""
    return bands[_u(band), _u(row), _u(col)]


@njit(cache=CACHE, inline="always")
def _row_positions(i, row_length, size, cols, rows, packed, row_cols, row_rows, width, height):
    """Where the pixels of output row i fall in the source; returns how many pixels it has.

    Either read from the arrays of positions (kind ARRAYS), or computed by
    the packed transformer (``rsgeo._kernels.transformer.row_positions``: the
    output pixel's centre (j + 0.5, i + 0.5) through the output grid's
    geotransform and the model, as GDAL's transformer does for a row, exactly
    or with GDAL's approximation, then its second try near the source's
    edges, :func:`_exact_near_edges`). The last row of a strip may be short.
    """
    first = i * row_length
    n = min(row_length, size - first)
    if packed[0] == ARRAYS:
        for j in range(n):
            row_cols[j] = cols[_u(first + j)]
            row_rows[j] = rows[_u(first + j)]
    else:
        row_positions(packed, i, n, row_cols, row_rows)
        if packed[1] > 0.0:
            _exact_near_edges(packed, i, n, row_cols, row_rows, width, height)
    return n


@njit(cache=CACHE)
def _exact_near_edges(packed, i, n, row_cols, row_rows, width, height):
    """GDAL's second try: an approximated position just outside the source is made exact.

    An approximated position less than a pixel outside an edge may be an
    approximation's error: GDAL transforms that pixel again, alone, exactly,
    and tests it again (GWKCheckAndComputeSrcOffsets). The edges are tested
    in GDAL's order (left, top, right, bottom); the first one the position
    fails decides.
    """
    for j in range(n):
        col, row = row_cols[j], row_rows[j]
        if col < 0.0:
            again = col > -1.0
        elif row < 0.0:
            again = row > -1.0
        elif col + GDAL_INDEX_EPSILON > width:
            again = col < width + 1.0
        elif row + GDAL_INDEX_EPSILON > height:
            again = row < height + 1.0
        else:
            again = False
        if again:
            row_cols[j], row_rows[j] = to_source(packed, pixel_centre(packed, j),
                                                 (i + 0.5) + packed[11])


@njit(cache=CACHE, inline="always")
def _is_inside(col, row, width, height):
    """GDAL's rule: a position is in the image if it is in [0, W) x [0, H)."""
    return (col >= 0.0 and row >= 0.0
            and np.floor(col + GDAL_INDEX_EPSILON) < width
            and np.floor(row + GDAL_INDEX_EPSILON) < height)


@njit(cache=CACHE, inline="always")
def _store(out, band, k, value, step, nodata, is_int, low, high):
    """Write an interpolated value: GDAL's GWKClampValueT, then AvoidNoData.

    Integers are rounded half up, floor(v + 0.5), and clamped to the dtype's
    range; floats are cast. A valid pixel that comes out equal to nodata moves
    one step away from it (``step``), so that it does not read as "outside the
    image": integers are compared after rounding, floats before the cast.
    (The comparison is made before the store, in float64: reading the stored
    value back would halve the kernel's speed. It is exact for every integer
    dtype up to 32 bits and for 64-bit values within ±2**53.)
    """
    if is_int:
        value = np.floor(value + 0.5)
        if value < low:
            value = low
        elif value > high:
            value = high
    if value == nodata:
        out[_u(band), _u(k)] = step[0]
    else:
        out[_u(band), _u(k)] = value


@njit(cache=CACHE, nogil=True)
def _nearest_loop(bands, cols, rows, packed, first_row, stop_row, row_length, out, fill,
                  step, nodata, is_int, low, high, valid):
    """Nearest neighbour (GDAL's GWKNearest), pixel by pixel.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata; otherwise copy the value of the pixel
    that contains it, the one whose corner-based indices are floor(col) and
    floor(row). Values are copied as they are: no rounding, no AvoidNoData.
    With a source validity mask (``valid``, uint8 (bands, rows, cols); empty
    for none), a band whose pixel is invalid gets nodata (GDAL's
    ``-srcnodata``). Returns the number of output pixels that fell inside the
    source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = 0
    for i in range(first_row, stop_row):
        row_cols = np.empty(row_length)
        row_rows = np.empty(row_length)
        n = _row_positions(i, row_length, size, cols, rows, packed, row_cols, row_rows, width,
                           height)
        for j in range(n):
            k = i * row_length + j
            col, row = row_cols[j], row_rows[j]
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed += 1
            # positive here, so truncation is floor; GDAL adds the same tiny margin
            c = int(col + GDAL_INDEX_EPSILON)
            r = int(row + GDAL_INDEX_EPSILON)
            for band in range(n_bands):
                if valid.size != 0 and valid[_u(band), _u(r), _u(c)] == 0:
                    out[_u(band), _u(k)] = fill[0]
                else:
                    out[_u(band), _u(k)] = _pixel(bands, band, r, c)
    return landed


@njit(cache=CACHE, inline="always")
def _bilinear_window(col, row):
    """(left, top, ratio_x, ratio_y) of the 2 x 2 window around (col, row), as GDAL computes it.

    The pixel centres are at half-integers, so the window starts at floor(col - 0.5),
    floor(row - 0.5); ratio_x and ratio_y are the weights of its left column and top row.
    """
    left_f = np.floor(col - 0.5)
    top_f = np.floor(row - 0.5)
    return int(left_f), int(top_f), 1.5 - (col - left_f), 1.5 - (row - top_f)


@njit(cache=CACHE, inline="always")
def _masked_bilinear_window(col, row):
    """``_bilinear_window`` as GDAL's masked kernels take it: a window hanging off the left
    (top) edge by one column (row) starts at 0 with ratio 1."""
    left, top, ratio_x, ratio_y = _bilinear_window(col, row)
    if left == -1:
        left = 0
        ratio_x = 1.0
    if top == -1:
        top = 0
        ratio_y = 1.0
    return left, top, ratio_x, ratio_y


@njit(cache=CACHE)
def _bilinear_at(bands, band, col, row):
    """Bilinear value at (col, row): GDAL's GWKBilinearResampleNoMasks4SampleT.

    The path gdalwarp takes without a destination nodata for Byte, Int16,
    UInt16 and Float32. The pixel centres are at half-integers, so the 2 x 2
    window starts at floor(col - 0.5), floor(row - 0.5); ratio_x and ratio_y
    are the weights of its left column and top row. Inside, each row is
    interpolated along x, then the two rows along y. At the border, pixels
    outside the image are left out and the weights of the others
    renormalised (GDAL's order: upper left, upper right, lower right, lower
    left).
    """
    height, width = bands.shape[1], bands.shape[2]
    left, top, ratio_x, ratio_y = _bilinear_window(col, row)
    if left >= 0 and left < width - 1 and top >= 0 and top < height - 1:
        other_x = 1.0 - ratio_x
        upper = (_pixel(bands, band, top, left) * ratio_x
                 + _pixel(bands, band, top, left + 1) * other_x)
        lower = (_pixel(bands, band, top + 1, left) * ratio_x
                 + _pixel(bands, band, top + 1, left + 1) * other_x)
        return upper * ratio_y + lower * (1.0 - ratio_y)
    accumulator = 0.0
    divisor = 0.0
    for corner in range(4):
        dx = 0 if corner == 0 or corner == 3 else 1
        dy = 0 if corner < 2 else 1
        if corner == 0:
            weight = ratio_x * ratio_y
        elif corner == 1:
            weight = (1.0 - ratio_x) * ratio_y
        elif corner == 2:
            weight = (1.0 - ratio_x) * (1.0 - ratio_y)
        else:
            weight = ratio_x * (1.0 - ratio_y)
        c, r = left + dx, top + dy
        if c >= 0 and c < width and r >= 0 and r < height:
            divisor += weight
            accumulator += _pixel(bands, band, r, c) * weight
    if divisor == 1.0:
        return accumulator
    return accumulator / (divisor if divisor != 0.0 else 1.0)


@njit(cache=CACHE)
def _bilinear_masked_at(bands, band, col, row):
    """Bilinear value at (col, row): GDAL's GWKBilinearResample4Sample.

    The path gdalwarp takes (GWKRealCase) when the output has a destination
    nodata (its validity mask) and, always, for the types without a
    specialised kernel (Int8, Int32, UInt32, Int64, UInt64, Float64). The
    same window and ratios as ``_bilinear_at``, computed in another
    order: each pixel's weight is the product ratio_x * ratio_y first, and
    the four weighted pixels are added one by one (upper left, upper right,
    lower left, lower right) beside the sum of the weights, which divides
    the total unless it is exactly 1. A window hanging off the left (top)
    edge by one column (row) starts at 0 with ratio 1. The exact .5 ties of
    an enlargement round differently in the two orders.
    """
    height, width = bands.shape[1], bands.shape[2]
    left, top, ratio_x, ratio_y = _masked_bilinear_window(col, row)
    accumulator = 0.0
    divisor = 0.0
    if top < height:
        weight_left = ratio_x * ratio_y
        weight_right = (1.0 - ratio_x) * ratio_y
        if left < width:
            divisor += weight_left
            accumulator += _pixel(bands, band, top, left) * weight_left
        if left + 1 < width:
            divisor += weight_right
            accumulator += _pixel(bands, band, top, left + 1) * weight_right
    if top + 1 < height:
        weight_left = ratio_x * (1.0 - ratio_y)
        weight_right = (1.0 - ratio_x) * (1.0 - ratio_y)
        if left < width:
            divisor += weight_left
            accumulator += _pixel(bands, band, top + 1, left) * weight_left
        if left + 1 < width:
            divisor += weight_right
            accumulator += _pixel(bands, band, top + 1, left + 1) * weight_right
    if divisor == 1.0:
        return accumulator
    return accumulator / (divisor if divisor != 0.0 else 1.0)


@njit(cache=CACHE)
def _bilinear_valid_at(bands, valid, band, col, row):
    """``_bilinear_masked_at`` over the valid pixels only: (value, found).

    GDAL's GWKBilinearResample4Sample with a source validity mask
    (``-srcnodata``): the same window, ratios and order of sums, but a pixel
    that ``valid`` marks invalid adds neither its value nor its weight, so
    the weights of the valid ones are renormalised. ``found`` is False (the
    output pixel is left at nodata) when the weights of the valid pixels add
    up to less than 0.00001, GDAL's threshold.
    """
    height, width = bands.shape[1], bands.shape[2]
    left, top, ratio_x, ratio_y = _masked_bilinear_window(col, row)
    accumulator = 0.0
    divisor = 0.0
    if top < height:
        weight_left = ratio_x * ratio_y
        weight_right = (1.0 - ratio_x) * ratio_y
        if left < width and valid[_u(band), _u(top), _u(left)] != 0:
            divisor += weight_left
            accumulator += _pixel(bands, band, top, left) * weight_left
        if left + 1 < width and valid[_u(band), _u(top), _u(left + 1)] != 0:
            divisor += weight_right
            accumulator += _pixel(bands, band, top, left + 1) * weight_right
    if top + 1 < height:
        weight_left = ratio_x * (1.0 - ratio_y)
        weight_right = (1.0 - ratio_x) * (1.0 - ratio_y)
        if left < width and valid[_u(band), _u(top + 1), _u(left)] != 0:
            divisor += weight_left
            accumulator += _pixel(bands, band, top + 1, left) * weight_left
        if left + 1 < width and valid[_u(band), _u(top + 1), _u(left + 1)] != 0:
            divisor += weight_right
            accumulator += _pixel(bands, band, top + 1, left + 1) * weight_right
    if divisor == 1.0:
        return accumulator, True
    if divisor < 0.00001:
        return 0.0, False
    return accumulator / divisor, True


@njit(cache=CACHE, inline="always")
def _centre_is_invalid(valid, col, row):
    """GDAL's check of the source pixel that contains (col, row) in its unified mask.

    GDAL skips an output pixel whose containing source pixel is invalid in
    every band (its unified validity mask) before interpolating
    (GWKGeneralCaseThread); each band then interpolates over its own valid
    pixels (UNIFIED_SRC_NODATA's default).
    """
    if valid.size == 0:
        return False
    c = int(col + GDAL_INDEX_EPSILON)
    r = int(row + GDAL_INDEX_EPSILON)
    for band in range(valid.shape[0]):
        if valid[_u(band), _u(r), _u(c)] != 0:
            return False
    return True


@njit(cache=CACHE, nogil=True)
def _bilinear_loop(bands, cols, rows, packed, first_row, stop_row, row_length, out, fill,
                   step, nodata, is_int, low, high, masked, valid):
    """Bilinear interpolation, pixel by pixel.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata; otherwise take the 2 x 2 neighbours
    whose centres surround it, weight each by how close it is along the row
    and along the column (``_bilinear_at``, or ``_bilinear_masked_at``
    when ``masked``: GDAL's path with a destination nodata), round and store
    the sum. With a source validity mask (``valid``, empty for none), only
    the valid neighbours count (``_bilinear_valid_at``). Returns the number
    of output pixels that fell inside the source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = 0
    for i in range(first_row, stop_row):
        row_cols = np.empty(row_length)
        row_rows = np.empty(row_length)
        n = _row_positions(i, row_length, size, cols, rows, packed, row_cols, row_rows, width,
                           height)
        for j in range(n):
            k = i * row_length + j
            col, row = row_cols[j], row_rows[j]
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed += 1
            if _centre_is_invalid(valid, col, row):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            for band in range(n_bands):
                if valid.size != 0:
                    value, found = _bilinear_valid_at(bands, valid, band, col, row)
                    if not found:
                        out[_u(band), _u(k)] = fill[0]
                        continue
                elif masked:
                    value = _bilinear_masked_at(bands, band, col, row)
                else:
                    value = _bilinear_at(bands, band, col, row)
                _store(out, band, k, value, step, nodata, is_int, low, high)
    return landed


@njit(cache=CACHE, inline="always")
def _cubic_convolution(d, f0, f1, f2, f3):
    """GDAL's CubicConvolution macro: Keys (a = -0.5) at the offset d from f1.

    f1 + ½(d(f2 − f0) + d²(2f0 − 5f1 + 4f2 − f3) + d³(3(f1 − f2) + f3 − f0)),
    with d² = d·d and d³ = d²·d, evaluated left to right as GDAL does.
    """
    d2 = d * d
    d3 = d2 * d
    return f1 + 0.5 * (d * (f2 - f0) + d2 * (2.0 * f0 - 5.0 * f1 + 4.0 * f2 - f3)
                       + d3 * (3.0 * (f1 - f2) + f3 - f0))


@njit(cache=CACHE, inline="always")
def _cubic_window_is_valid(valid, band, top, left):
    """Whether all 16 pixels of the 4 x 4 window at (top - 1, left - 1) are valid."""
    for r in range(top - 1, top + 3):
        for c in range(left - 1, left + 3):
            if valid[_u(band), _u(r), _u(c)] == 0:
                return False
    return True


@njit(cache=CACHE)
def _bilinear_fallback(bands, valid, band, col, row, masked):
    """The bilinear value cubic falls back to near the edges or invalid pixels: (value, found).

    ``_bilinear_valid_at`` with a source validity mask, else ``_bilinear_masked_at`` or
    ``_bilinear_at`` as in the bilinear loop; the cubic loop falls back at two places.
    """
    if valid.size != 0:
        return _bilinear_valid_at(bands, valid, band, col, row)
    if masked:
        return _bilinear_masked_at(bands, band, col, row), True
    return _bilinear_at(bands, band, col, row), True


@njit(cache=CACHE, nogil=True)
def _cubic_loop(bands, cols, rows, packed, first_row, stop_row, row_length, out, fill,
                step, nodata, is_int, low, high, masked, valid):
    """Cubic convolution, pixel by pixel.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata. Otherwise take the 4 x 4 neighbours
    around it: the pixel left of and above the position (GDAL truncates
    col - 0.5 and row - 0.5 towards zero) and one more on each side. Weight
    each row of four with Keys' weights of the offset dx along the row
    (GDAL's CONVOL4, in its order of additions), then combine the four row
    sums down the column: with the weights of dy by CONVOL4 again when
    ``masked`` (GDAL's GWKCubicResample4Sample, its path with a destination
    nodata), else by GDAL's CubicConvolution formula in dy, dy², dy³
    (GWKCubicResampleNoMasks4SampleT). Round and store. Where the 4 x 4
    window leaves the image, fall back to the same path's bilinear, as GDAL
    does. With a source validity mask (``valid``, empty for none), a window
    holding an invalid pixel falls back to the bilinear of the valid pixels
    (GDAL's GWKCubicResample4Sample). Returns the number of output pixels
    that fell inside the source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = 0
    for i in range(first_row, stop_row):
        row_cols = np.empty(row_length)
        row_rows = np.empty(row_length)
        n = _row_positions(i, row_length, size, cols, rows, packed, row_cols, row_rows, width,
                           height)
        for j in range(n):
            k = i * row_length + j
            col, row = row_cols[j], row_rows[j]
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed += 1
            if _centre_is_invalid(valid, col, row):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            left_f = np.trunc(col - 0.5)
            top_f = np.trunc(row - 0.5)
            dx = col - 0.5 - left_f
            dy = row - 0.5 - top_f
            left, top = int(left_f), int(top_f)
            if not (left >= 1 and left + 2 < width and top >= 1 and top + 2 < height):
                for band in range(n_bands):
                    value, found = _bilinear_fallback(bands, valid, band, col, row, masked)
                    if found:
                        _store(out, band, k, value, step, nodata, is_int, low, high)
                    else:
                        out[_u(band), _u(k)] = fill[0]
                continue
            wx0, wx1, wx2, wx3 = _cubic_weights(dx)
            wy0, wy1, wy2, wy3 = _cubic_weights(dy)
            c = left - 1
            for band in range(n_bands):
                if valid.size != 0 and not _cubic_window_is_valid(valid, band, top, left):
                    value, found = _bilinear_fallback(bands, valid, band, col, row, masked)
                    if found:
                        _store(out, band, k, value, step, nodata, is_int, low, high)
                    else:
                        out[_u(band), _u(k)] = fill[0]
                    continue
                # CONVOL4 along each of the four rows
                r = top - 1
                along0 = (wx0 * _pixel(bands, band, r, c) + wx1 * _pixel(bands, band, r, c + 1)
                          + wx2 * _pixel(bands, band, r, c + 2)
                          + wx3 * _pixel(bands, band, r, c + 3))
                r += 1
                along1 = (wx0 * _pixel(bands, band, r, c) + wx1 * _pixel(bands, band, r, c + 1)
                          + wx2 * _pixel(bands, band, r, c + 2)
                          + wx3 * _pixel(bands, band, r, c + 3))
                r += 1
                along2 = (wx0 * _pixel(bands, band, r, c) + wx1 * _pixel(bands, band, r, c + 1)
                          + wx2 * _pixel(bands, band, r, c + 2)
                          + wx3 * _pixel(bands, band, r, c + 3))
                r += 1
                along3 = (wx0 * _pixel(bands, band, r, c) + wx1 * _pixel(bands, band, r, c + 1)
                          + wx2 * _pixel(bands, band, r, c + 2)
                          + wx3 * _pixel(bands, band, r, c + 3))
                # then down the column
                if masked:
                    value = wy0 * along0 + wy1 * along1 + wy2 * along2 + wy3 * along3
                else:
                    value = _cubic_convolution(dy, along0, along1, along2, along3)
                _store(out, band, k, value, step, nodata, is_int, low, high)
    return landed


# GDAL's filter radius of each method (anGWKFilterRadius), in source pixels at scale 1
RADIUS = {"nearest": 0, "bilinear": 1, "cubic": 2}


@njit(cache=CACHE, inline="always")
def _filter_weight(x, radius):
    """GDAL's GWKBilinear (radius 1) or CubicKernel (radius 2, Keys with a = -0.5) at x."""
    ax = abs(x)
    if radius == 1:
        return 1.0 - ax if ax <= 1.0 else 0.0
    if ax <= 1.0:
        return x * x * (1.5 * ax - 2.5) + 1.0
    if ax <= 2.0:
        return x * x * (-0.5 * ax + 2.5) - 4.0 * ax + 2.0
    return 0.0


@njit(cache=CACHE, nogil=True)
def _widened_loop(bands, cols, rows, packed, first_row, stop_row, row_length, out, fill,
                  step, nodata, is_int, low, high, radius, xscale, yscale):
    """Bilinear or cubic widened by 1/scale when downsampling: GDAL's GWKResample.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata. Otherwise take the pixel left of and
    above the position (floor of col - 0.5, row - 0.5) and the taps from
    ``first`` to ``n`` around it along each axis, n = ceil(radius / scale)
    (the kernel stretched over 1/scale source pixels; the taps that fall off
    the image are dropped). Each tap weighs K((i - dx) * scale), with no factor
    of scale; each row's taps are summed left to right, weighted by its own
    K((j - dy) * scale) and added top to bottom, with the sum of the weights
    alongside. The sum is divided by the weights' sum unless that is within
    1e-5 of 1; below 1e-6 the pixel is left at nodata. Round and store.
    Returns the number of output pixels that fell inside the source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    x_below_1 = xscale < 1.0
    y_below_1 = yscale < 1.0
    x_radius = int(np.ceil(radius / xscale)) if x_below_1 else radius
    y_radius = int(np.ceil(radius / yscale)) if y_below_1 else radius
    # the window's first tap depends on the parity of the radius (GDAL's nFiltInit)
    x_first = ((radius + 1) % 2) - x_radius
    y_first = ((radius + 1) % 2) - y_radius
    landed = 0
    for i in range(first_row, stop_row):
        weights_x = np.empty(2 * x_radius + 2)
        row_cols = np.empty(row_length)
        row_rows = np.empty(row_length)
        n = _row_positions(i, row_length, size, cols, rows, packed, row_cols, row_rows, width,
                           height)
        for j in range(n):
            k = i * row_length + j
            col, row = row_cols[j], row_rows[j]
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed += 1
            left = int(np.floor(col - 0.5))
            top = int(np.floor(row - 0.5))
            dx = col - 0.5 - left
            dy = row - 0.5 - top
            i_min = max(x_first, -left)
            i_max = min(x_radius, width - left - 1)
            j_min = max(y_first, -top)
            j_max = min(y_radius, height - top - 1)
            for t in range(i_min, i_max + 1):
                x = (t - dx) * xscale if x_below_1 else t - dx
                weights_x[t - i_min] = _filter_weight(x, radius)
            for band in range(n_bands):
                total = 0.0
                total_weight = 0.0
                for tr in range(j_min, j_max + 1):
                    y = (tr - dy) * yscale if y_below_1 else tr - dy
                    weight_y = _filter_weight(y, radius)
                    along = 0.0
                    along_weight = 0.0
                    for t in range(i_min, i_max + 1):
                        weight_x = weights_x[t - i_min]
                        along += _pixel(bands, band, top + tr, left + t) * weight_x
                        along_weight += weight_x
                    total += along * weight_y
                    total_weight += along_weight * weight_y
                if total_weight < 0.000001:
                    out[_u(band), _u(k)] = fill[0]
                    continue
                if total_weight < 0.99999 or total_weight > 1.00001:
                    total = total / total_weight
                _store(out, band, k, total, step, nodata, is_int, low, high)
    return landed


@njit(cache=CACHE, inline="always")
def _cell_span(low, high, size):
    """GDAL's source pixels under a cell edge to edge: (first, stop, low, high), or first = -1.

    The cell spans [low, high) along one axis (swapped if reversed); pixels
    from floor(low) to ceil(high), within [0, size), a margin of 1e-10
    against rounding; at least one pixel. first = -1 if the span misses.
    """
    if low > high:
        low, high = high, low
    if not (high > -1e-10 and low < size + 1e-10):
        return -1, 0, low, high
    first = int(max(np.floor(low + 1e-10), 0.0))
    stop = int(min(np.ceil(high - 1e-10), float(size)))
    if first == stop and stop < size:
        stop += 1
    return first, stop, low, high


@njit(cache=CACHE, inline="always")
def _edge_weight(index, first, stop, low, high):
    """GDAL's COMPUTE_WEIGHT along one axis: the part of pixel ``index`` inside the cell."""
    if index == first:
        return 1.0 if first + 1 == stop else 1.0 - (low - first)
    if index + 1 == stop:
        return 1.0 - (stop - high)
    return 1.0


@njit(cache=CACHE, nogil=True)
def _average_loop(bands, cols, rows, packed, first_row, stop_row, row_length, out, fill,
                  step, nodata, is_int, low, high, x_margin, y_margin, valid):
    """Area-weighted average (GDAL's GWKAverageOrMode, "average"), cell by cell.

    For each output cell: take its top-left and bottom-right corners to the
    source (by the packed transformer, or from the arrays of corner positions, a
    (n_rows + 1) x (row_length + 1) grid); a cell whose corners are more than
    a margin (2 ceil(1/scale) pixels) outside the image gets nodata. The
    source pixels between the corners each weigh the fraction of their
    width and height inside the cell (1 inside, less on the cell's edges);
    the mean is updated pixel by pixel, row by row, as GDAL's weighted
    incremental mean: total += w; mean += (w / total) * (v - mean). Round
    and store; a cell with no weight gets nodata. With a source validity
    mask (``valid``, empty for none), invalid pixels are left out, as GDAL
    leaves out ``-srcnodata`` pixels.
    Returns the number of output cells that were averaged.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = 0
    for i in range(first_row, stop_row):
        for j in range(row_length):
            k = i * row_length + j
            if k >= size:
                break
            if packed[0] == ARRAYS:
                corner = i * (row_length + 1) + j
                x1, y1 = cols[_u(corner)], rows[_u(corner)]
                x2, y2 = cols[_u(corner + row_length + 2)], rows[_u(corner + row_length + 2)]
            else:
                # the cell's corners, exactly (GDAL approximates them too: not followed)
                x1, y1 = to_source(packed, j + packed[10], i + packed[11])
                x2, y2 = to_source(packed, (j + 1.0) + packed[10], (i + 1.0) + packed[11])
            near = (x1 >= -x_margin and x2 >= -x_margin and y1 >= -y_margin
                    and y2 >= -y_margin and x1 - width <= x_margin and x2 - width <= x_margin
                    and y1 - height <= y_margin and y2 - height <= y_margin)
            first_x, stop_x, x_min, x_max = _cell_span(x1, x2, width)
            first_y, stop_y, y_min, y_max = _cell_span(y1, y2, height)
            if not near or first_x < 0 or first_y < 0:
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            found = False
            for band in range(n_bands):
                total = 0.0
                mean = 0.0
                for r in range(first_y, stop_y):
                    weight_y = _edge_weight(r, first_y, stop_y, y_min, y_max)
                    for c in range(first_x, stop_x):
                        if c == first_x:
                            weight = (weight_y if first_x + 1 == stop_x
                                      else weight_y * (1.0 - (x_min - first_x)))
                        elif c + 1 == stop_x:
                            weight = weight_y * (1.0 - (stop_x - x_max))
                        else:
                            weight = weight_y
                        if valid.size != 0 and valid[_u(band), _u(r), _u(c)] == 0:
                            continue
                        if weight > 0.0:
                            total += weight
                            mean += (weight / total) * (_pixel(bands, band, r, c) - mean)
                if total > 0.0:
                    found = True
                    _store(out, band, k, mean, step, nodata, is_int, low, high)
                else:
                    out[_u(band), _u(k)] = fill[0]
            if found:
                landed += 1
    return landed

