"""Resampling: nearest neighbour, bilinear and cubic convolution, as GDAL does them.

The lecture's last step of georeferencing (slide "Reamostragem"): for every cell
of the output grid, find where it falls in the distorted image and interpolate a
value there. The three interpolators follow GDAL's warp kernel
(``alg/gdalwarpkernel.cpp``) operation by operation, so that for the same source
positions rsgeo and ``gdalwarp`` give the same pixels, bit for bit:

* positions are GDAL's continuous (col, row) with the image's top-left corner at
  (0, 0); the centre of ``image[r, c]`` is (c + 0.5, r + 0.5);
* a position outside ``[0, W) x [0, H)`` gets ``nodata``;
* nearest takes the pixel that contains the position (floor);
* bilinear interpolates on (col - 0.5, row - 0.5) over the 2 x 2 window, and at
  the image edge renormalises the weights of the pixels that exist (which is
  the same as clamping to the edge);
* cubic is Keys' cubic convolution with a = -0.5 (Keys 1981) over the 4 x 4
  window, separable (rows first, then the column), falling back to bilinear
  wherever the 4 x 4 window leaves the image;
* integer outputs are rounded as floor(v + 0.5) and clamped to the dtype's
  range; float outputs are cast;
* for bilinear and cubic, a valid output equal to ``nodata`` moves one step
  away from it (nodata - 1, or nodata + 1 at the bottom of the range): GDAL's
  "AvoidNoData", which keeps the footprint of valid pixels visible in the
  values. Nearest copies source values untouched, as GDAL does.

Each method is one loop over the output pixels, as GDAL's GWK functions and
the lecture describe it: for each output pixel, find its position in the
source, take the 1 (nearest), 4 (bilinear) or 16 (cubic) neighbours, weight
them, round, store. The loops are compiled by Numba (``cache=True``, so the
machine code is kept between sessions; no ``fastmath``, so the floating-point
operations and their order stay GDAL's) and share the output rows among
``num_threads`` threads (1 by default; the result does not depend on it).

GDAL widens the kernels when it downsamples (output pixels larger than 1/0.95
input pixels); these are the plain 2 x 2 and 4 x 4 kernels, which GDAL uses when
the scale is 0.95 or more. So "bit for bit" holds under these conditions only:
an integer image (float32 outputs agree within one unit in the last place), a
scale of 0.95 or more (upsampling or about the same scale), a destination nodata
(gdalwarp's ``-dstnodata``), float64 arithmetic, and GDAL's exact transformer
(``-et 0``; its default approximate transformer moves sample positions of
non-linear mappings by up to 0.125 pixel).

:func:`warp` refuses the two classic silent mistakes: a mapping in the wrong
direction (image -> map, e.g. a raster's own geotransform instead of its
inverse), which would give an image of nothing but nodata, and a bands-last
(rows, cols, 3) array.
"""

import os

# Numba's OpenMP threading layer, when it is the one chosen, loads GNU OpenMP at
# the first parallel call; by default its idle threads spin, which on a machine
# shared with other work makes two threads slower than one. Wait passively
# instead, unless the user chose otherwise (set before OpenMP loads).
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import affine  # noqa: E402
import numba  # noqa: E402
import numpy as np  # noqa: E402
from numba import njit, prange  # noqa: E402

from ._checks import as_image, check_choice

__all__ = [
    "METHODS", "keys_weights", "cubic_kernel", "bilinear_weights", "interpolate",
    "check_num_threads", "check_nodata", "check_bands_first", "check_shape", "grid_positions",
    "warp",
]

METHODS = ("nearest", "bilinear", "cubic")

# A margin GDAL adds before truncating a position to a pixel index, so that a
# coordinate computed as 9.999999999999998 for 10 lands on pixel 10.
_GDAL_INDEX_EPSILON = 1e-10


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


@njit(cache=True, inline="always")
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


@njit(cache=True)
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


def interpolate(image, cols, rows, method="nearest", nodata=0, num_threads=1):
    """Values of an image at continuous (col, row) positions, by GDAL's rules.

    Parameters
    ----------
    image : ndarray
        2-D (rows, cols) or 3-D (bands, rows, cols) image, any integer or float dtype.
    cols, rows : array_like
        Continuous pixel coordinates (GDAL's pixel, line), same shape; (0, 0) is
        the image's top-left corner.
    method : {"nearest", "bilinear", "cubic"}
        Interpolator (lecture, slide "Reamostragem").
    nodata : int or float
        Value given to positions outside the image; must fit the dtype.
    num_threads : int
        Threads that share the rows of positions (the last axis of ``cols`` is
        a row); 1 by default, for reproducible timings. The result does not
        depend on it.

    Returns
    -------
    ndarray
        Same dtype as ``image``, shape ``cols.shape`` (or ``(bands,) + cols.shape``).

    Raises
    ------
    ValueError
        If the image is not 2-D or 3-D (or looks bands last, (rows, cols, 3)),
        the method is unknown, cols and rows differ in shape or hold NaN or
        infinity, nodata does not fit the dtype, or num_threads is not a whole
        number from 1 to the number of threads Numba may use.

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``: its nearest-neighbour kernels,
    ``GWKBilinearResample4Sample`` and ``GWKCubicResampleNoMasks4SampleT``.

    Keys, R. G. (1981), "Cubic convolution interpolation for digital image
    processing", IEEE Transactions on Acoustics, Speech, and Signal Processing
    29(6), 1153-1160.

    Examples
    --------
    >>> image = np.array([[0, 100], [100, 200]], dtype=np.uint8)
    >>> interpolate(image, [1.0], [1.0], "bilinear")
    array([100], dtype=uint8)
    >>> interpolate(image, [1.5, 5.0], [0.5, 0.5], "nearest", nodata=255)
    array([100, 255], dtype=uint8)
    """
    image = check_bands_first(as_image(image))
    check_choice(method, "method", METHODS)
    num_threads = check_num_threads(num_threads)
    cols, rows = _check_positions(cols, rows)
    nodata = check_nodata(nodata, image.dtype)

    shape = (image.shape[0],) + cols.shape if image.ndim == 3 else cols.shape
    # rows of positions for the threads: the last axis, or blocks of a long 1-D list
    row_length = cols.shape[-1] if cols.ndim >= 2 else min(cols.size, _BLOCK)
    out, _ = _resample(image, method, nodata, num_threads, cols.ravel(), rows.ravel(),
                       _NO_AFFINE, cols.size, row_length)
    return out.reshape(shape)


def _check_positions(cols, rows):
    """cols and rows as float64 arrays of one shape, finite; else ValueError."""
    cols = np.asarray(cols, dtype=np.float64)
    rows = np.asarray(rows, dtype=np.float64)
    if cols.shape != rows.shape:
        raise ValueError(f"cols and rows must have the same shape, got {cols.shape} and {rows.shape}")
    if not (np.isfinite(cols).all() and np.isfinite(rows).all()):
        raise ValueError("cols and rows hold NaN or infinite positions; every position must be finite "
                         "(mark points you do not want with a position outside the image instead)")
    return cols, rows


# A 1-D list of positions is shared among threads in blocks of this many.
_BLOCK = 4096
# "No affine mapping": the positions come as arrays (see _source_position).
_NO_AFFINE = np.empty(0)
_NO_POSITIONS = np.empty(0)
# Float types Numba cannot compute in are computed in this type, then cast back.
_COMPUTED_AS = {np.dtype(np.float16): np.dtype(np.float32),
                np.dtype(np.longdouble): np.dtype(np.float64)}


def check_num_threads(num_threads):
    """Return ``num_threads`` as an int from 1 to Numba's thread count, else raise ValueError.

    Parameters
    ----------
    num_threads : int
        Threads to share a kernel's rows; a whole-valued float is accepted.

    Returns
    -------
    int
        ``num_threads`` as an int.

    Raises
    ------
    ValueError
        If ``num_threads`` is not a whole number from 1 to
        ``numba.config.NUMBA_NUM_THREADS``.

    Examples
    --------
    >>> check_num_threads(1)
    1
    >>> check_num_threads(0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: num_threads must be a whole number from 1 to ...
    """
    most = numba.config.NUMBA_NUM_THREADS
    try:
        ok = float(num_threads).is_integer() and 1 <= num_threads <= most
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ValueError(f"num_threads must be a whole number from 1 to {most} (the threads "
                         f"Numba may use here, NUMBA_NUM_THREADS), got {num_threads!r}")
    return int(num_threads)


def _resample(image, method, nodata, num_threads, cols, rows, to_source, size, row_length):
    """Run one method's kernel over ``size`` output pixels; return (out, pixels inside).

    ``out`` is (bands, size) in ``image``'s dtype. Positions come from the
    arrays ``cols``, ``rows`` or, when ``to_source`` holds the six numbers of an
    affine map (output pixel -> source pixel), are computed pixel by pixel
    from an output grid ``row_length`` pixels wide.
    """
    bands = image if image.ndim == 3 else image[np.newaxis]
    dtype = bands.dtype
    work = _COMPUTED_AS.get(dtype, dtype.newbyteorder("="))  # Numba needs native byte order
    bands = np.ascontiguousarray(bands, dtype=work)
    out = np.empty((bands.shape[0], size), dtype=work)
    if size == 0:
        return out.astype(dtype), 0
    fill = np.array([nodata], dtype=work)
    if work.kind in "ui":
        info = np.iinfo(work)
        # the next value away from nodata, GDAL's AvoidNoData
        step = np.array([nodata + 1 if nodata == info.min else nodata - 1], dtype=work)
        low, high = (float(info.min), float(info.max)) if work.itemsize < 8 else (-np.inf, np.inf)
    else:
        step = np.array([np.nextafter(work.type(nodata), work.type(np.inf))], dtype=work)
        low, high = -np.inf, np.inf
    n_rows = -(-size // row_length)
    kernel = {"nearest": _nearest_loop, "bilinear": _bilinear_loop, "cubic": _cubic_loop}[method]
    previous = numba.get_num_threads()
    numba.set_num_threads(num_threads)
    try:
        inside = kernel(bands, np.ascontiguousarray(cols), np.ascontiguousarray(rows), to_source,
                        n_rows, row_length, out, fill, step, float(nodata), work.kind in "ui",
                        low, high)
    finally:
        numba.set_num_threads(previous)
    return (out if work == dtype else out.astype(dtype)), inside


def check_nodata(nodata, dtype):
    """Return ``nodata`` if it is representable in ``dtype``, else raise ValueError.

    Parameters
    ----------
    nodata : int or float
        The value for positions outside the image.
    dtype : numpy dtype or str
        The image's dtype.

    Returns
    -------
    int or float
        ``nodata`` as an int for an integer dtype, unchanged otherwise.

    Raises
    ------
    ValueError
        If ``dtype`` is an integer type and ``nodata`` is not a finite whole
        number inside its range, or ``dtype`` is float32 and ``nodata`` is
        finite but beyond float32's largest value.

    Examples
    --------
    >>> check_nodata(255.0, np.uint8)
    255
    >>> check_nodata(-1, np.uint8)
    Traceback (most recent call last):
    ...
    ValueError: nodata=-1 does not fit dtype uint8 (needs an integer in [0, 255])
    """
    dtype = np.dtype(dtype)
    if dtype.kind in "ui":
        info = np.iinfo(dtype)
        if not (np.isfinite(nodata) and float(nodata).is_integer() and info.min <= nodata <= info.max):
            raise ValueError(f"nodata={nodata!r} does not fit dtype {dtype} "
                             f"(needs an integer in [{info.min}, {info.max}])")
        return int(nodata)
    if dtype == np.float32 and np.isfinite(nodata) and abs(nodata) > np.finfo(np.float32).max:
        raise ValueError(f"nodata={nodata!r} does not fit dtype float32")
    return nodata


# -- the kernels: one loop over output pixels per method ----------------------
#
# Each is compiled by Numba (cache=True keeps the machine code between
# sessions; no fastmath, so every floating-point operation happens in the order
# written here, which is GDAL's). Threads share the output rows (prange).


@njit(cache=True, inline="always")
def _u(index):
    """An index known to be in range, unsigned: Numba then skips its negative-index
    wrap-around test, which made the nearest kernel three times slower."""
    return np.uint64(index)


@njit(cache=True, inline="always")
def _pixel(bands, band, row, col):
    """The source value ``bands[band, row, col]``, for indices inside the image."""
    return bands[_u(band), _u(row), _u(col)]


@njit(cache=True, inline="always")
def _source_position(k, i, j, cols, rows, to_source):
    """Where output pixel k (row i, column j of the output grid) falls in the source.

    Either read from the arrays of positions, or computed from the affine map
    output pixel -> source pixel at the cell's centre (j + 0.5, i + 0.5), with
    the operations of :func:`grid_positions`.
    """
    if to_source.size == 0:
        return cols[_u(k)], rows[_u(k)]
    x = j + 0.5
    y = i + 0.5
    return (to_source[0] * x + (to_source[1] * y + to_source[2]),
            to_source[3] * x + (to_source[4] * y + to_source[5]))


@njit(cache=True, inline="always")
def _is_inside(col, row, width, height):
    """GDAL's rule: a position is in the image if it is in [0, W) x [0, H)."""
    return (col >= 0.0 and row >= 0.0
            and np.floor(col + _GDAL_INDEX_EPSILON) < width
            and np.floor(row + _GDAL_INDEX_EPSILON) < height)


@njit(cache=True, inline="always")
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


@njit(cache=True, parallel=True)
def _nearest_loop(bands, cols, rows, to_source, n_rows, row_length, out, fill, step, nodata,
                  is_int, low, high):
    """Nearest neighbour (GDAL's GWKNearest), pixel by pixel.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata; otherwise copy the value of the pixel
    that contains it, the one whose corner-based indices are floor(col) and
    floor(row). Values are copied as they are: no rounding, no AvoidNoData.
    Returns the number of output pixels that fell inside the source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
        for j in range(row_length):
            k = i * row_length + j
            if k >= size:
                break
            col, row = _source_position(k, i, j, cols, rows, to_source)
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed_in_row += 1
            # positive here, so truncation is floor; GDAL adds the same tiny margin
            c = int(col + _GDAL_INDEX_EPSILON)
            r = int(row + _GDAL_INDEX_EPSILON)
            for band in range(n_bands):
                out[_u(band), _u(k)] = _pixel(bands, band, r, c)
        landed[i] = landed_in_row
    return landed.sum()


@njit(cache=True, inline="always")
def _bilinear_at(bands, band, col, row):
    """Bilinear value at (col, row): GDAL's GWKBilinearResampleNoMasks4SampleT.

    The pixel centres are at half-integers, so the 2 x 2 window starts at
    floor(col - 0.5), floor(row - 0.5); ratio_x and ratio_y are the weights of
    its left column and top row. At the border, pixels outside the image are
    left out and the weights of the others renormalised (GDAL's order: upper
    left, upper right, lower right, lower left).
    """
    height, width = bands.shape[1], bands.shape[2]
    left_f = np.floor(col - 0.5)
    top_f = np.floor(row - 0.5)
    ratio_x = 1.5 - (col - left_f)
    ratio_y = 1.5 - (row - top_f)
    left, top = int(left_f), int(top_f)
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


@njit(cache=True, parallel=True)
def _bilinear_loop(bands, cols, rows, to_source, n_rows, row_length, out, fill, step, nodata,
                   is_int, low, high):
    """Bilinear interpolation, pixel by pixel.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata; otherwise take the 2 x 2 neighbours
    whose centres surround it, weight each by how close it is along the row
    and along the column (:func:`_bilinear_at`), round and store the sum.
    Returns the number of output pixels that fell inside the source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
        for j in range(row_length):
            k = i * row_length + j
            if k >= size:
                break
            col, row = _source_position(k, i, j, cols, rows, to_source)
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed_in_row += 1
            for band in range(n_bands):
                value = _bilinear_at(bands, band, col, row)
                _store(out, band, k, value, step, nodata, is_int, low, high)
        landed[i] = landed_in_row
    return landed.sum()


@njit(cache=True, parallel=True)
def _cubic_loop(bands, cols, rows, to_source, n_rows, row_length, out, fill, step, nodata,
                is_int, low, high):
    """Cubic convolution (GDAL's GWKCubicResampleNoMasks4SampleT), pixel by pixel.

    For each output pixel: find its position (col, row) in the source; if it
    is outside the image, write nodata. Otherwise take the 4 x 4 neighbours
    around it: the pixel left of and above the position (GDAL truncates
    col - 0.5 and row - 0.5 towards zero) and one more on each side. Weight
    each row of four with Keys' weights of the offset dx along the row, then
    the four row sums with the weights of dy (GDAL's CONVOL4, in its order of
    additions); round and store. Where the 4 x 4 window leaves the image,
    fall back to bilinear, as GDAL does.
    Returns the number of output pixels that fell inside the source.
    """
    n_bands, height, width = bands.shape
    size = out.shape[1]
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
        for j in range(row_length):
            k = i * row_length + j
            if k >= size:
                break
            col, row = _source_position(k, i, j, cols, rows, to_source)
            if not _is_inside(col, row, width, height):
                for band in range(n_bands):
                    out[_u(band), _u(k)] = fill[0]
                continue
            landed_in_row += 1
            left_f = np.trunc(col - 0.5)
            top_f = np.trunc(row - 0.5)
            dx = col - 0.5 - left_f
            dy = row - 0.5 - top_f
            left, top = int(left_f), int(top_f)
            if not (left >= 1 and left + 2 < width and top >= 1 and top + 2 < height):
                for band in range(n_bands):
                    value = _bilinear_at(bands, band, col, row)
                    _store(out, band, k, value, step, nodata, is_int, low, high)
                continue
            wx0, wx1, wx2, wx3 = _cubic_weights(dx)
            wy0, wy1, wy2, wy3 = _cubic_weights(dy)
            c = left - 1
            for band in range(n_bands):
                r = top - 1
                # CONVOL4 along each of the four rows, then down the column
                along = wx0 * _pixel(bands, band, r, c)
                along += wx1 * _pixel(bands, band, r, c + 1)
                along += wx2 * _pixel(bands, band, r, c + 2)
                along += wx3 * _pixel(bands, band, r, c + 3)
                value = wy0 * along
                r += 1
                along = wx0 * _pixel(bands, band, r, c)
                along += wx1 * _pixel(bands, band, r, c + 1)
                along += wx2 * _pixel(bands, band, r, c + 2)
                along += wx3 * _pixel(bands, band, r, c + 3)
                value += wy1 * along
                r += 1
                along = wx0 * _pixel(bands, band, r, c)
                along += wx1 * _pixel(bands, band, r, c + 1)
                along += wx2 * _pixel(bands, band, r, c + 2)
                along += wx3 * _pixel(bands, band, r, c + 3)
                value += wy2 * along
                r += 1
                along = wx0 * _pixel(bands, band, r, c)
                along += wx1 * _pixel(bands, band, r, c + 1)
                along += wx2 * _pixel(bands, band, r, c + 2)
                along += wx3 * _pixel(bands, band, r, c + 3)
                value += wy3 * along
                _store(out, band, k, value, step, nodata, is_int, low, high)
        landed[i] = landed_in_row
    return landed.sum()


def check_bands_first(image, name="image"):
    """Raise ValueError if a 3-D image looks bands-last (rows, cols, 3 or 4).

    rsgeo, like rasterio and GDAL, stores several bands first: (bands, rows,
    cols). An RGB array from matplotlib, Pillow or OpenCV is (rows, cols, 3);
    read bands first, it would be 351 "bands" of 369 x 3 pixels, and a warp or
    a GeoTIFF made from it is silently wrong.

    Parameters
    ----------
    image : ndarray
        The image to check.
    name : str
        Its name in the error message.

    Returns
    -------
    ndarray
        ``image`` unchanged.

    Raises
    ------
    ValueError
        If ``image`` is 3-D, its last axis has 3 or 4 entries and its first
        two axes are both more than four times longer.

    Examples
    --------
    >>> check_bands_first(np.zeros((3, 40, 50))).shape
    (3, 40, 50)
    >>> check_bands_first(np.zeros((40, 50, 3)))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: image has shape (40, 50, 3), which looks like bands last ...
    """
    shape = np.shape(image)
    if len(shape) == 3 and shape[2] in (3, 4) and min(shape[0], shape[1]) > 4 * shape[2]:
        raise ValueError(f"{name} has shape {tuple(shape)}, which looks like bands last "
                         "(rows, cols, bands); rsgeo needs bands first (bands, rows, cols): "
                         f"pass np.moveaxis({name}, -1, 0)")
    return image


def check_shape(shape, name="shape"):
    """Return ``shape`` as a (rows, cols) tuple of positive ints, else raise ValueError.

    Parameters
    ----------
    shape : sequence of two numbers
        A grid size, (rows, cols); whole-valued floats are accepted.
    name : str
        Its name in the error message.

    Returns
    -------
    (int, int)

    Raises
    ------
    ValueError
        If ``shape`` is a single number, has other than two entries, or holds
        anything but positive whole numbers.

    Examples
    --------
    >>> check_shape((351.0, 369))
    (351, 369)
    >>> check_shape(351)
    Traceback (most recent call last):
    ...
    ValueError: shape must be (rows, cols), two positive integers, got 351
    """
    message = f"{name} must be (rows, cols), two positive integers, got {shape!r}"
    try:
        values = tuple(shape)
    except TypeError:
        raise ValueError(message) from None
    if len(values) != 2:
        raise ValueError(message)
    try:
        ok = all(float(n).is_integer() and n >= 1 for n in values)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ValueError(message)
    return int(values[0]), int(values[1])


def grid_positions(shape, transform=None, first_row=0):
    """Map coordinates of the centres of an output grid's cells.

    Parameters
    ----------
    shape : (rows, cols)
        Output grid size.
    transform : affine.Affine, optional
        Output geotransform (pixel corner -> map). Identity (pixel coordinates) if omitted.
    first_row : int
        Row of the grid where this block starts (for processing a grid in strips).

    Returns
    -------
    x, y : ndarray, shape ``shape``
        Map coordinates of each cell centre.

    Raises
    ------
    IndexError, TypeError
        Nothing is checked here (callers such as :func:`warp` check ``shape``
        with :func:`check_shape` first); a ``shape`` without two numbers fails
        in NumPy.

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``: output pixel centres at (j + 0.5, i + 0.5).

    Examples
    --------
    >>> x, y = grid_positions((2, 3))
    >>> x[0], y[:, 0]
    (array([0.5, 1.5, 2.5]), array([0.5, 1.5]))
    """
    a, b, c, d, e, f = (transform if transform is not None else affine.Affine.identity())[:6]
    cols = np.arange(shape[1]) + 0.5
    rows = (np.arange(first_row, first_row + shape[0]) + 0.5)[:, np.newaxis]
    return a * cols + (b * rows + c), d * cols + (e * rows + f)


def warp(image, mapping, shape, transform=None, method="nearest", nodata=0, strip_rows=256,
         num_threads=1):
    """The corrected image: every output cell filled from where ``mapping`` sends it.

    This is the lecture's "construir uma nova imagem corrigida": the output grid
    is defined in map coordinates, ``mapping`` is the model u = f(x, y),
    v = g(x, y) from map to image coordinates, and each cell takes the value
    interpolated at that source position. A callable mapping is evaluated in
    strips of ``strip_rows`` rows so that memory stays a small multiple of
    input plus output.

    Parameters
    ----------
    image : ndarray
        Source (distorted) image, 2-D or 3-D bands first.
    mapping : callable or affine.Affine
        ``mapping(points)`` with points an (n, 2) array of map (x, y) returns an
        (n, 2) array of source (col, row) - a :class:`rsgeo.gcp.PolynomialModel`
        fitted from map to image, or any function; or an ``affine.Affine``
        from map (x, y) to source (col, row), such as ``~source_transform``.
    shape : (rows, cols)
        Output grid size.
    transform : affine.Affine, optional
        Output grid geotransform; if omitted, map coordinates are the output's
        own pixel coordinates.
    method : {"nearest", "bilinear", "cubic"}
    nodata : number
        Value for cells whose source position is outside the image.
    strip_rows : int
        Rows per strip, when ``mapping`` is a callable (an affine map is
        evaluated pixel by pixel in the kernel, with no strips).
    num_threads : int
        Threads that share the output rows; 1 by default, for reproducible
        timings. The result does not depend on it.

    Returns
    -------
    ndarray
        Output image, same dtype as ``image``, shape ``shape`` (or bands first).

    Raises
    ------
    ValueError
        As :func:`interpolate`; if ``shape`` is not (rows, cols), two positive
        integers; if ``mapping`` does not return an (n, 2) array; or if no
        output cell lands inside the source image (the mapping goes the wrong
        way, image -> map, or the output grid is somewhere else): a warp
        that would return nothing but nodata.

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp`` and ``apps/gdalwarp_lib.cpp``: the warp
    kernels and ``-dstnodata``; see :func:`interpolate`.

    Examples
    --------
    >>> image = np.arange(16, dtype=np.uint8).reshape(4, 4)
    >>> shift = lambda xy: xy + [1.0, 0.0]     # output col c reads source col c + 1
    >>> warp(image, shift, (4, 4))[0]
    array([1, 2, 3, 0], dtype=uint8)
    """
    image = check_bands_first(as_image(image))
    check_choice(method, "method", METHODS)
    nodata = check_nodata(nodata, image.dtype)
    num_threads = check_num_threads(num_threads)
    out_rows, out_cols = check_shape(shape)
    height, width = image.shape[-2:]
    bands = image.shape[0] if image.ndim == 3 else 1
    out = np.empty((bands, out_rows, out_cols), dtype=image.dtype)
    to_map = transform if transform is not None else affine.Affine.identity()
    if isinstance(mapping, affine.Affine):
        # an affine map: each output pixel's source position is computed in the kernel
        to_source = np.array((mapping @ to_map)[:6], dtype=np.float64)
        flat, landed = _resample(image, method, nodata, num_threads, _NO_POSITIONS,
                                 _NO_POSITIONS, to_source, out_rows * out_cols, out_cols)
        out = flat.reshape(out.shape)
        if not landed:
            a, b, c, d, e, f = to_source
            x, y = np.array([0.5, out_cols - 0.5]), np.array([[0.5], [out_rows - 0.5]])
            corner_cols, corner_rows = a * x + (b * y + c), d * x + (e * y + f)
            spans = [(corner_cols.min(), corner_cols.max(), corner_rows.min(), corner_rows.max())]
    else:
        landed = 0
        spans = []
        for start in range(0, out_rows, strip_rows):
            stop = min(start + strip_rows, out_rows)
            x, y = grid_positions((stop - start, out_cols), to_map, first_row=start)
            source = np.asarray(mapping(np.column_stack([x.ravel(), y.ravel()])), dtype=np.float64)
            if source.shape != (x.size, 2):
                raise ValueError(f"mapping must return an (n, 2) array of (col, row), got shape {source.shape}")
            source_cols, source_rows = _check_positions(source[:, 0], source[:, 1])
            strip, inside = _resample(image, method, nodata, num_threads, source_cols,
                                      source_rows, _NO_AFFINE, x.size, out_cols)
            out[:, start:stop, :] = strip.reshape(bands, stop - start, out_cols)
            if not landed:
                spans.append((source_cols.min(), source_cols.max(),
                              source_rows.min(), source_rows.max()))
            landed += inside
    if not landed:
        raise ValueError(_nothing_lands_message(mapping, spans, width, height))
    return out if image.ndim == 3 else out[0]


def _nothing_lands_message(mapping, spans, width, height):
    """The error of a warp whose output grid falls entirely outside the source."""
    spans = np.array(spans)
    where = (f"the output cells fall at source cols {spans[:, 0].min():.6g} to "
             f"{spans[:, 1].max():.6g}, rows {spans[:, 2].min():.6g} to {spans[:, 3].max():.6g}, "
             f"outside the image's [0, {width}) x [0, {height})")
    if isinstance(mapping, affine.Affine):
        fix = ("for a raster's geotransform (pixel → map) pass its inverse, "
               "e.g. ~raster.transform")
    else:
        fix = ("fit the model from map to image, e.g. "
               "gcp.fit_polynomial(map_xy, image_xy, order), not image → map; "
               "for a raster's geotransform pass ~raster.transform")
    return ("no output cell lands inside the source image: is your mapping map → image "
            f"(u = f(x, y))? {fix}; also check that the output grid (shape, transform) "
            f"covers the source's ground ({where})")
