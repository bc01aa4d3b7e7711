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

When it downsamples (output pixels larger than 1/0.95 input pixels), GDAL
widens bilinear and cubic over 1/scale source pixels (its ``GWKResample``):
``interpolate(..., scale=(xscale, yscale))`` does the same, with GDAL's
taps, weights, order of sums and normalisation, and :func:`warp` computes the
scale from the grids as gdalwarp does (:func:`grid_scale`). Without a nodata
value (``nodata=None``) the output is gdalwarp's without ``-dstnodata``.
So "bit for bit" holds, as tested against GDAL 3.10.3 (the one in the pinned
rasterio wheel; 3.11 changes the normalisation without nodata and 3.13 keeps
the 4-sample formulas down to scale 0.5), for: integer, float32 and float64
images, in float64 arithmetic; with a destination nodata (GDAL's general
path, GWKRealCase) or without one (its no-mask kernels for Byte, Int16, UInt16
and Float32; rsgeo follows each, see ``_bilinear_masked_at``); GDAL's
exact transformer (``-et 0``), whose two geotransforms :func:`warp` applies
in GDAL's order; and the same kernel scale: the XSCALE/YSCALE given, or
gdalwarp's for the whole output grid. Two gdalwarp defaults differ: its
approximate transformer (``-et 0.125``, which ``rasterio.warp.reproject``
always uses) moves positions in their last bits, or by up to 0.125 pixel for
non-linear mappings, which rounds some exact .5 ties of an enlargement the
other way; and it computes the scale per chunk of the output, from the
bounding box of each chunk's source window, which on a rotated source falls
below 0.95 (1 / (cos θ + sin θ) for a square chunk) and widens the kernels
where rsgeo's one scale does not.

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

from ._checks import (
    as_affine,
    as_bands_first,
    as_image,
    as_integer,
    as_nodata,
    as_num_threads,
    as_number,
    as_output_shape,
    as_resolution,
    as_scale,
    as_shape,
    check_choice,
)
from ._i18n import N_, _, prose_number
from .errors import GridError, ImageError, ModelError, RsgeoError
from .transformer import ARRAYS, pack, pixel_centre, row_positions, to_source

__all__ = [
    "METHODS", "WARP_METHODS", "keys_weights", "cubic_kernel", "bilinear_weights", "interpolate",
    "grid_positions", "warp", "grid_scale", "suggested_grid",
]

METHODS = ("nearest", "bilinear", "cubic")
# warp also averages: each output cell is the area-weighted mean of the source
# pixels it covers (GDAL's "average"), which needs the cell's corners, not a point
WARP_METHODS = METHODS + ("average",)

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


def interpolate(image, cols, rows, method="nearest", nodata=0, num_threads=1, scale=1.0,
                src_nodata=None):
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
    nodata : int or float or None
        Value given to positions outside the image; must fit the dtype. None:
        gdalwarp without a destination nodata (``-dstnodata``), as for a
        source without nodata: outside is 0 and valid pixels equal to 0 stay
        0 (no AvoidNoData nudge).
    num_threads : int
        Threads that share the rows of positions (the last axis of ``cols`` is
        a row); 1 by default, for reproducible timings. The result does not
        depend on it.
    scale : float or (float, float)
        GDAL's XSCALE and YSCALE warp options: output pixels per source pixel
        along rows and columns, below 1 when downsampling. When either is
        below 0.95, bilinear and cubic are widened over 1/scale source pixels
        as GDAL's ``GWKResample`` does (bit for bit with GDAL given the same
        XSCALE/YSCALE and a destination nodata); 1 by default (the plain
        2 x 2 and 4 x 4 kernels). Nearest ignores it.
    src_nodata : int or float or None
        The source's nodata value (gdalwarp's ``-srcnodata``; NaN for NaN
        pixels of a float image): source pixels equal to it are invalid.
        As GDAL does it: nearest gives ``nodata`` where its pixel is invalid;
        bilinear renormalises its weights over the valid pixels of the 2 x 2
        window (``nodata`` if none has weight); cubic falls back to that
        bilinear wherever its 4 x 4 window holds an invalid pixel; an
        output pixel whose containing source pixel is invalid in every band
        is ``nodata`` (GDAL's unified mask, its default UNIFIED_SRC_NODATA).
        Bit for bit with GDAL 3.10.3's VRT warp with the exact transformer
        (tested for nearest, bilinear, cubic and average, uint8 and float32,
        one and two bands, with and without a destination nodata). None (the default): every pixel
        is valid, and a NaN spreads to the neighbours that weigh it, as in
        GDAL. Not with kernels widened by ``scale`` below 0.95.

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
        number from 1 to the number of threads Numba may use, or scale is not
        one or two numbers above 0; if a 64-bit integer image holds values
        beyond +-2**53 for bilinear or cubic (float64, in which they are
        computed as in GDAL, cannot hold them exactly); if src_nodata does
        not fit the dtype, or is given with a scale below 0.95.
    TypeError
        If cols or rows are not real numbers (complex, strings, booleans).

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``: its nearest-neighbour kernels, ``GWKResample``,
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
    image = as_bands_first(as_image(image))
    check_choice(method, "method", METHODS)
    num_threads = as_num_threads(num_threads)
    cols, rows = _check_positions(cols, rows)
    nodata = as_nodata(nodata, image.dtype)
    scale = as_scale(scale)
    _check_exact_in_float64(image, method)
    valid = _validity(image, src_nodata)

    shape = (image.shape[0],) + cols.shape if image.ndim == 3 else cols.shape
    # rows of positions for the threads: the last axis, or blocks of a long 1-D list
    row_length = cols.shape[-1] if cols.ndim >= 2 else min(cols.size, _BLOCK)
    out, _landed = _resample(image, method, nodata, num_threads, cols.ravel(), rows.ravel(),
                             _POSITIONS_GIVEN, cols.size, row_length, scale, valid)
    return out.reshape(shape)


# Integers above this in magnitude have no exact float64 (2**53 + 1 rounds to 2**53).
_EXACT_IN_FLOAT64 = 2 ** 53


def _check_exact_in_float64(image, method):
    """Refuse a 64-bit integer image beyond +-2**53 for a method that computes in float64.

    GDAL's kernels, and rsgeo's, weigh pixels in float64, whose 53-bit
    significand holds every integer only up to 2**53: 2**53 + 1 would come
    out as 2**53 without a word. Nearest copies values and needs no check.
    """
    if method == "nearest" or image.dtype.kind not in "ui" or image.dtype.itemsize < 8:
        return
    low, high = int(image.min()), int(image.max())
    if high > _EXACT_IN_FLOAT64 or low < -_EXACT_IN_FLOAT64:
        raise ImageError(_(
            "image ({dtype}) holds values from {low} to {high}, beyond +-2**53, which "
            "{method} cannot weigh exactly: it computes in float64 (as GDAL does), whose "
            "integers stop being exact at 2**53 = {limit}; use method='nearest' (which copies "
            "values), or subtract an offset so that the values fit").format(
                dtype=image.dtype, low=low, high=high, method=method, limit=_EXACT_IN_FLOAT64))


def _validity(image, src_nodata):
    """The source validity mask of ``src_nodata``: uint8 (bands, rows, cols), or None.

    GDAL's ``-srcnodata``: a pixel equal to it (NaN: a NaN pixel) is invalid,
    compared in the image's own type as GDAL's nodata masker does.
    """
    if src_nodata is None:
        return None
    src_nodata = as_nodata(src_nodata, image.dtype)
    bands = image if image.ndim == 3 else image[np.newaxis]
    work = _COMPUTED_AS.get(bands.dtype, bands.dtype.newbyteorder("="))
    if work.kind == "f" and np.isnan(src_nodata):
        valid = ~np.isnan(bands)
    else:
        valid = bands != np.array(src_nodata).astype(work)
    return np.ascontiguousarray(valid, dtype=np.uint8)


def _native(image):
    """``image`` in a type Numba computes in (native byte order; float16 as float32), once."""
    work = _COMPUTED_AS.get(image.dtype, image.dtype.newbyteorder("="))
    return np.ascontiguousarray(image, dtype=work)


def _check_mapping(mapping):
    """Refuse a mapping that is neither an affine.Affine nor callable, with the fix."""
    if isinstance(mapping, affine.Affine):
        as_affine(mapping, "mapping")
        return
    if isinstance(mapping, tuple) and len(mapping) in (6, 9):
        raise TypeError(_(
            "mapping must be an affine.Affine or a callable model, got a {n}-tuple {value!r}; "
            "for a GDAL geotransform (c, a, b, f, d, e) of map -> source pixel use "
            "affine.Affine.from_gdal(*t), and for a raster's own geotransform (pixel -> map) "
            "its inverse, ~affine.Affine.from_gdal(*t)").format(n=len(mapping), value=mapping))
    if not callable(mapping):
        raise TypeError(_(
            "mapping must be a callable model, map (x, y) -> source (col, row), such as one "
            "transforms.fit_transform(map_xy, image_xy, ...) returns, or an affine.Affine "
            "such as ~raster.transform; got {kind}").format(kind=type(mapping).__name__))


def _check_positions(cols, rows):
    """cols and rows as float64 arrays of one shape, finite; else ValueError (TypeError if
    they are not real numbers)."""
    arrays = []
    for name, values in (("cols", cols), ("rows", rows)):
        array = np.asarray(values)
        if array.dtype.kind not in "uif":
            raise TypeError(_("{name} must be real numbers (pixel positions), got dtype "
                              "{dtype}").format(name=name, dtype=array.dtype))
        arrays.append(array.astype(np.float64, copy=False))
    cols, rows = arrays
    if cols.shape != rows.shape:
        raise RsgeoError(_("cols and rows must have the same shape, got {cols_shape} "
                           "and {rows_shape}").format(
                cols_shape=cols.shape, rows_shape=rows.shape))
    if not (np.isfinite(cols).all() and np.isfinite(rows).all()):
        raise RsgeoError(_("cols and rows hold NaN or infinite positions; every position must "
                           "be finite (mark points you do not want with a position outside the "
                           "image instead)"))
    return cols, rows


# A 1-D list of positions is shared among threads in blocks of this many.
_BLOCK = 4096
# "No affine mapping": the positions come as arrays (see _source_position).
# the packed transformer of positions given as arrays (rsgeo.transformer's kind ARRAYS)
_POSITIONS_GIVEN = np.zeros(10)
_NO_POSITIONS = np.empty(0)
# "No source validity mask": every source pixel is valid.
_NO_MASK = np.empty((0, 0, 0), dtype=np.uint8)
# The types GDAL 3.10 warps with its no-mask kernels when there is no destination nodata
# (GWK*NoMasksOrDstDensityOnly*); every other type goes through GWKRealCase.
_NO_MASK_TYPES = ("uint8", "int16", "uint16", "float32")
# Float types Numba cannot compute in are computed in this type, then cast back.
_COMPUTED_AS = {np.dtype(np.float16): np.dtype(np.float32),
                np.dtype(np.longdouble): np.dtype(np.float64)}


def _resample(image, method, nodata, num_threads, cols, rows, packed, size, row_length,
              scale=(1.0, 1.0), valid=None):
    """Run one method's kernel over ``size`` output pixels; return (out, pixels inside).

    ``out`` is (bands, size) in ``image``'s dtype. Positions come from the
    arrays ``cols``, ``rows`` (``packed`` is ``_POSITIONS_GIVEN``) or are
    computed row by row by the packed transformer (:mod:`rsgeo.transformer`)
    for an output grid ``row_length`` pixels wide. ``valid``:
    the source validity mask (:func:`_validity`), or None for none.
    """
    bands = image if image.ndim == 3 else image[np.newaxis]
    dtype = bands.dtype
    work = _COMPUTED_AS.get(dtype, dtype.newbyteorder("="))  # Numba needs native byte order
    bands = np.ascontiguousarray(bands, dtype=work)
    out = np.empty((bands.shape[0], size), dtype=work)
    if size == 0:
        return out.astype(dtype), 0
    # no nodata (gdalwarp without -dstnodata): outside is 0 and no AvoidNoData nudge,
    # which comparing with NaN (never equal) turns off
    avoid = nodata is not None
    nodata = nodata if avoid else 0
    fill = np.array([nodata], dtype=work)
    if work.kind in "ui":
        info = np.iinfo(work)
        # the next value away from nodata, GDAL's AvoidNoData
        step = np.array([nodata + 1 if nodata == info.min else nodata - 1], dtype=work)
        # GDAL's clamp to the dtype's range; a 64-bit maximum has no float64 (2**63 - 1
        # rounds up to 2**63, which overflows the cast), so the clamp stops at the largest
        # float64 below it (64-bit images are checked to stay within +-2**53, so only the
        # bottom of uint64's range, 0, can be reached: _check_exact_in_float64)
        low = float(info.min)
        high = float(info.max) if work.itemsize < 8 else float(np.nextafter(float(info.max), 0))
    else:
        step = np.array([np.nextafter(work.type(nodata), work.type(np.inf))], dtype=work)
        low, high = -np.inf, np.inf
    n_rows = -(-size // row_length)
    kernel = {"nearest": _nearest_loop, "bilinear": _bilinear_loop, "cubic": _cubic_loop,
              "average": None}[method]
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
    previous = numba.get_num_threads()
    numba.set_num_threads(num_threads)
    try:
        if method == "average":
            margins = [2 * max(1, int(np.ceil(1.0 / value))) for value in scale]
            inside = _average_loop(bands, np.ascontiguousarray(cols), np.ascontiguousarray(rows),
                                   packed, n_rows, row_length, out, fill, step, compare,
                                   work.kind in "ui", low, high, margins[0], margins[1], valid)
        elif widened:
            inside = _widened_loop(bands, np.ascontiguousarray(cols), np.ascontiguousarray(rows),
                                   packed, n_rows, row_length, out, fill, step, compare,
                                   work.kind in "ui", low, high, _RADIUS[method],
                                   float(xscale), float(yscale))
        elif method == "nearest":
            inside = kernel(bands, np.ascontiguousarray(cols), np.ascontiguousarray(rows),
                            packed, n_rows, row_length, out, fill, step, compare,
                            work.kind in "ui", low, high, valid)
        else:
            # GDAL's general path (GWKRealCase) with a destination nodata, and for the types
            # without a specialised no-mask kernel
            # the dtype computed in (float16 in float32, as warp converts it)
            masked = avoid or work.name not in _NO_MASK_TYPES
            inside = kernel(bands, np.ascontiguousarray(cols), np.ascontiguousarray(rows),
                            packed, n_rows, row_length, out, fill, step, compare,
                            work.kind in "ui", low, high, masked, valid)
    finally:
        numba.set_num_threads(previous)
    return (out if work == dtype else out.astype(dtype)), inside


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
def _row_positions(i, row_length, size, cols, rows, packed, row_cols, row_rows, width, height):
    """Where the pixels of output row i fall in the source; returns how many pixels it has.

    Either read from the arrays of positions (kind ARRAYS), or computed by
    the packed transformer (:func:`rsgeo.transformer.row_positions`: the
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


@njit(cache=True)
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
        elif col + _GDAL_INDEX_EPSILON > width:
            again = col < width + 1.0
        elif row + _GDAL_INDEX_EPSILON > height:
            again = row < height + 1.0
        else:
            again = False
        if again:
            row_cols[j], row_rows[j] = to_source(packed, pixel_centre(packed, j),
                                                 (i + 0.5) + packed[11])


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


@njit(cache=True, parallel=True, nogil=True)
def _nearest_loop(bands, cols, rows, packed, n_rows, row_length, out, fill, step, nodata,
                  is_int, low, high, valid):
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
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
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
            landed_in_row += 1
            # positive here, so truncation is floor; GDAL adds the same tiny margin
            c = int(col + _GDAL_INDEX_EPSILON)
            r = int(row + _GDAL_INDEX_EPSILON)
            for band in range(n_bands):
                if valid.size != 0 and valid[_u(band), _u(r), _u(c)] == 0:
                    out[_u(band), _u(k)] = fill[0]
                else:
                    out[_u(band), _u(k)] = _pixel(bands, band, r, c)
        landed[i] = landed_in_row
    return landed.sum()


@njit(cache=True, inline="always")
def _bilinear_window(col, row):
    """(left, top, ratio_x, ratio_y) of the 2 x 2 window around (col, row), as GDAL computes it.

    The pixel centres are at half-integers, so the window starts at floor(col - 0.5),
    floor(row - 0.5); ratio_x and ratio_y are the weights of its left column and top row.
    """
    left_f = np.floor(col - 0.5)
    top_f = np.floor(row - 0.5)
    return int(left_f), int(top_f), 1.5 - (col - left_f), 1.5 - (row - top_f)


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
def _centre_is_invalid(valid, col, row):
    """GDAL's check of the source pixel that contains (col, row) in its unified mask.

    GDAL skips an output pixel whose containing source pixel is invalid in
    every band (its unified validity mask) before interpolating
    (GWKGeneralCaseThread); each band then interpolates over its own valid
    pixels (UNIFIED_SRC_NODATA's default).
    """
    if valid.size == 0:
        return False
    c = int(col + _GDAL_INDEX_EPSILON)
    r = int(row + _GDAL_INDEX_EPSILON)
    for band in range(valid.shape[0]):
        if valid[_u(band), _u(r), _u(c)] != 0:
            return False
    return True


@njit(cache=True, parallel=True, nogil=True)
def _bilinear_loop(bands, cols, rows, packed, n_rows, row_length, out, fill, step, nodata,
                   is_int, low, high, masked, valid):
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
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
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
            landed_in_row += 1
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
        landed[i] = landed_in_row
    return landed.sum()


@njit(cache=True, inline="always")
def _cubic_convolution(d, f0, f1, f2, f3):
    """GDAL's CubicConvolution macro: Keys (a = -0.5) at the offset d from f1.

    f1 + ½(d(f2 − f0) + d²(2f0 − 5f1 + 4f2 − f3) + d³(3(f1 − f2) + f3 − f0)),
    with d² = d·d and d³ = d²·d, evaluated left to right as GDAL does.
    """
    d2 = d * d
    d3 = d2 * d
    return f1 + 0.5 * (d * (f2 - f0) + d2 * (2.0 * f0 - 5.0 * f1 + 4.0 * f2 - f3)
                       + d3 * (3.0 * (f1 - f2) + f3 - f0))


@njit(cache=True, inline="always")
def _cubic_window_is_valid(valid, band, top, left):
    """Whether all 16 pixels of the 4 x 4 window at (top - 1, left - 1) are valid."""
    for r in range(top - 1, top + 3):
        for c in range(left - 1, left + 3):
            if valid[_u(band), _u(r), _u(c)] == 0:
                return False
    return True


@njit(cache=True, parallel=True, nogil=True)
def _cubic_loop(bands, cols, rows, packed, n_rows, row_length, out, fill, step, nodata,
                is_int, low, high, masked, valid):
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
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
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
            landed_in_row += 1
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
                continue
            wx0, wx1, wx2, wx3 = _cubic_weights(dx)
            wy0, wy1, wy2, wy3 = _cubic_weights(dy)
            c = left - 1
            for band in range(n_bands):
                if valid.size != 0 and not _cubic_window_is_valid(valid, band, top, left):
                    value, found = _bilinear_valid_at(bands, valid, band, col, row)
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
        landed[i] = landed_in_row
    return landed.sum()


# GDAL's filter radius of each method (anGWKFilterRadius), in source pixels at scale 1
_RADIUS = {"nearest": 0, "bilinear": 1, "cubic": 2}


@njit(cache=True, inline="always")
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


@njit(cache=True, parallel=True, nogil=True)
def _widened_loop(bands, cols, rows, packed, n_rows, row_length, out, fill, step, nodata,
                  is_int, low, high, radius, xscale, yscale):
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
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
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
            landed_in_row += 1
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
        landed[i] = landed_in_row
    return landed.sum()


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
def _edge_weight(index, first, stop, low, high):
    """GDAL's COMPUTE_WEIGHT along one axis: the part of pixel ``index`` inside the cell."""
    if index == first:
        return 1.0 if first + 1 == stop else 1.0 - (low - first)
    if index + 1 == stop:
        return 1.0 - (stop - high)
    return 1.0


@njit(cache=True, parallel=True, nogil=True)
def _average_loop(bands, cols, rows, packed, n_rows, row_length, out, fill, step, nodata,
                  is_int, low, high, x_margin, y_margin, valid):
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
    landed = np.zeros(n_rows, dtype=np.int64)  # per row: no shared counter
    for i in prange(n_rows):
        landed_in_row = 0
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
                landed_in_row += 1
        landed[i] = landed_in_row
    return landed.sum()


def grid_positions(shape, transform=None, first_row=0, first_col=0):
    """Map coordinates of the centres of an output grid's cells.

    Parameters
    ----------
    shape : (rows, cols)
        Output grid size.
    transform : affine.Affine, optional
        Output geotransform (pixel corner -> map). Identity (pixel coordinates) if omitted.
    first_row, first_col : int
        Row and column of the grid where this block starts (for processing a
        grid in strips or tiles).

    Returns
    -------
    x, y : ndarray, shape ``shape``
        Map coordinates of each cell centre.

    Raises
    ------
    IndexError, TypeError
        Nothing is checked here (callers such as :func:`warp` check ``shape``
        first, as rsgeo._checks.as_shape does); a ``shape`` without two numbers fails
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
    cols = np.arange(first_col, first_col + shape[1]) + 0.5
    rows = (np.arange(first_row, first_row + shape[0]) + 0.5)[:, np.newaxis]
    # GDAL's order (GDALGenImgProjTransform, GDALApplyGeoTransform): c + col * a + row * b
    return c + cols * a + rows * b, f + cols * d + rows * e


def warp(image, mapping, shape, transform=None, method="nearest", nodata=0, strip_rows=256,
         num_threads=1, scale=None, src_nodata=None, error_threshold=0.0, src_offset=None,
         dst_offset=None):
    """The corrected image: every output cell filled from where ``mapping`` sends it.

    This is the lecture's "construir uma nova imagem corrigida": the output grid
    is defined in map coordinates, ``mapping`` is the model u = f(x, y),
    v = g(x, y) from map to image coordinates, and each cell takes the value
    interpolated at that source position.

    An ``affine.Affine`` and rsgeo's polynomial, projective and thin-plate
    spline models are evaluated inside the compiled kernel, row by row, as
    GDAL's transformer is (:mod:`rsgeo.transformer`): no array of positions
    is ever made. Any other callable is evaluated in NumPy, in strips of
    ``strip_rows`` rows, so that memory stays a small multiple of input plus
    output.

    Parameters
    ----------
    image : ndarray
        Source (distorted) image, 2-D or 3-D bands first.
    mapping : callable or affine.Affine
        ``mapping(points)`` with points an (n, 2) array of map (x, y) returns an
        (n, 2) array of source (col, row) - a :class:`rsgeo.transforms.PolynomialModel`
        fitted from map to image, or any function; or an ``affine.Affine``
        from map (x, y) to source (col, row), such as ``~source_transform``.
    shape : (rows, cols)
        Output grid size.
    transform : affine.Affine, optional
        Output grid geotransform; if omitted, map coordinates are the output's
        own pixel coordinates.
    method : {"nearest", "bilinear", "cubic", "average"}
        "average" (GDAL's, the method to downsample with): each cell is the
        mean of the source pixels it covers, each weighted by the part of it
        inside the cell (the cell's corners taken to the source).
    nodata : number or None
        Value for cells whose source position is outside the image; None for
        gdalwarp's behaviour without a destination nodata (see :func:`interpolate`).
    strip_rows : int
        Rows per strip, when ``mapping`` is a callable (an affine map is
        evaluated pixel by pixel in the kernel, with no strips).
    num_threads : int
        Threads that share the output rows; 1 by default, for reproducible
        timings. The result does not depend on it.
    scale : float or (float, float), optional
        GDAL's XSCALE, YSCALE (see :func:`interpolate`). If omitted, computed
        from the grids as gdalwarp does for one chunk: output columns (rows)
        over the width (height) in source pixels of the bounding box of where
        the output grid's edges fall in the source (:func:`grid_scale`).
        gdalwarp cuts a large grid into chunks (by its warp memory, or where
        a chunk's source window is mostly empty) and gives each its own
        scale, below 0.95 on a rotated source even at the same pixel size;
        rsgeo uses one. Give both the same scale to compare them.
    src_nodata : int or float or None
        The source's nodata value (gdalwarp's ``-srcnodata``; NaN for NaN
        pixels), with GDAL's semantics (see :func:`interpolate`); also for
        "average", which leaves such pixels out.
    error_threshold : float
        GDAL's approximate transformer (``gdalwarp -et``; gdalwarp's and
        ``rasterio.warp.reproject``'s default is 0.125 source pixel): each
        output row's positions are interpolated linearly between exact ones
        wherever that stays within this many pixels (``|dcol| + |drow|``) of the
        exact position, as ``GDALApproxTransform`` does, pixel for pixel.
        0 (the default): every position exact (``-et 0``). Needs a compiled
        mapping (an ``affine.Affine`` or an rsgeo model); "average" evaluates
        its cell corners exactly.
    src_offset : (int, int), optional
        The first (col, row) of ``image`` in the full source, when ``image``
        is a window of it (GDAL's source window; :mod:`rsgeo.tiling` warps a
        scene tile by tile this way): ``mapping`` still gives positions in the
        full source. Needs ``scale``, so that tiles share one kernel.
    dst_offset : (int, int), optional
        The first (col, row) of this output in the grid of ``transform``,
        when the output is a window (a tile) of that grid: its cell (i, j)
        is the grid's (i + row, j + col), its centre at (j + 0.5) + col, as
        GDAL's warp kernel computes a chunk's cells (so that tiles equal one
        warp of the whole grid bit for bit, whatever the pixel size).

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
        that would return nothing but nodata; if ``transform`` holds NaN or
        infinity; if ``strip_rows`` is not a whole number from 1; if the
        output would not fit in this machine's memory (the message gives
        its size in GiB: choose a coarser grid or warp a window at a time);
        if ``error_threshold`` is negative or given with a mapping that is
        evaluated in NumPy; if ``src_offset`` is given without ``scale``.
    TypeError
        If ``mapping`` is neither callable nor an ``affine.Affine`` (a GDAL
        6-tuple: convert it with ``affine.Affine.from_gdal``), or
        ``transform`` is not an ``affine.Affine``.

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
    image = as_bands_first(as_image(image))
    check_choice(method, "method", WARP_METHODS)
    nodata = as_nodata(nodata, image.dtype)
    num_threads = as_num_threads(num_threads)
    bands = image.shape[0] if image.ndim == 3 else 1
    out_rows, out_cols = as_output_shape(shape, image.dtype, bands)
    to_map = as_affine(transform) if transform is not None else affine.Affine.identity()
    _check_mapping(mapping)
    strip_rows = as_integer(strip_rows, "strip_rows", low=1,
                            why=N_("rows of the output grid computed at a time"))
    _check_exact_in_float64(image, method)
    valid = _validity(image, src_nodata)
    error_threshold = as_number(error_threshold, "error_threshold", low=0.0,
                                why=N_("source pixels; 0 for exact positions"))
    src_offset = _as_src_offset(src_offset, scale)
    dst_offset = _as_offset(dst_offset, "dst_offset", "the output window's first cell")
    window_to_map = to_map @ affine.Affine.translation(*dst_offset)
    scale = (as_scale(scale) if scale is not None
             else grid_scale(mapping, (out_rows, out_cols), window_to_map, image.shape[-2:]))
    height, width = image.shape[-2:]
    dtype = image.dtype
    image = _native(image)    # float16 and big-endian converted once, not once per strip
    packed = pack(mapping, to_map, src_offset, error_threshold, dst_offset)
    if packed is not None:
        # a compiled model: each output pixel's source position (or average's cell corners)
        # is computed in the kernel, row by row, as GDAL's transformer does
        flat, landed = _resample(image, method, nodata, num_threads, _NO_POSITIONS,
                                 _NO_POSITIONS, packed, out_rows * out_cols, out_cols, scale,
                                 valid)
        out = flat.reshape((bands, out_rows, out_cols)).astype(dtype, copy=False)
        if not landed:
            # the outermost pixel centres, to say where the grid went
            centre_cols, centre_rows = np.meshgrid(np.array([0.5, out_cols - 0.5]) + dst_offset[0],
                                                   np.array([0.5, out_rows - 0.5]) + dst_offset[1])
            corners = (_call_mapping(mapping, *(to_map @ (centre_cols, centre_rows)))
                       - np.asarray(src_offset))
            spans = [(corners[:, 0].min(), corners[:, 0].max(), corners[:, 1].min(),
                      corners[:, 1].max())]
    else:
        if error_threshold > 0:
            raise RsgeoError(_(
                "error_threshold={threshold} approximates a compiled mapping's positions, but "
                "{mapping!r} is a Python function, evaluated in NumPy at every output pixel; "
                "give error_threshold=0, or a mapping rsgeo compiles (an affine.Affine or a "
                "model from rsgeo.transforms.fit_transform)").format(
                    threshold=error_threshold, mapping=type(mapping).__name__))
        out = np.empty((bands, out_rows, out_cols), dtype=dtype)
        landed = 0
        spans = []
        for start in range(0, out_rows, strip_rows):
            stop = min(start + strip_rows, out_rows)
            if method == "average":
                # the cells' corners: one more row and column than the cells
                corner_cols, corner_rows = np.meshgrid(
                    np.arange(out_cols + 1.0) + dst_offset[0],
                    np.arange(start, stop + 1.0) + dst_offset[1])
                x, y = to_map @ (corner_cols, corner_rows)
            else:
                x, y = grid_positions((stop - start, out_cols), to_map,
                                      first_row=start + int(dst_offset[1]),
                                      first_col=int(dst_offset[0]))
            source = _call_mapping(mapping, x, y)
            source_cols, source_rows = _check_positions(source[:, 0] - src_offset[0],
                                                        source[:, 1] - src_offset[1])
            strip, inside = _resample(image, method, nodata, num_threads, source_cols,
                                      source_rows, _POSITIONS_GIVEN, (stop - start) * out_cols,
                                      out_cols, scale, valid)
            out[:, start:stop, :] = strip.reshape(bands, stop - start, out_cols)
            if not landed:
                spans.append((source_cols.min(), source_cols.max(),
                              source_rows.min(), source_rows.max()))
            landed += inside
    if not landed:
        raise GridError(_nothing_lands_message(mapping, spans, width, height))
    return out if image.ndim == 3 else out[0]


def _as_offset(offset, name, why):
    """A window's (col, row) offset: two whole numbers from 0; (0.0, 0.0) for None."""
    if offset is None:
        return (0.0, 0.0)
    if np.ndim(offset) != 1 or len(offset) != 2:
        raise RsgeoError(_("{name} must be (col, row) of the window's first pixel, got "
                           "{value!r}").format(name=name, value=offset))
    return tuple(float(as_integer(value, f"{name} {axis}", low=0, why=why))
                 for value, axis in zip(offset, ("col", "row")))


def _as_src_offset(src_offset, scale):
    """The source window's (col, row) offset, two whole numbers from 0; (0, 0) for none."""
    if src_offset is None:
        return (0.0, 0.0)
    if scale is None:
        raise RsgeoError(_(
            "src_offset (a window of the source) needs scale=(xscale, yscale): the kernel's "
            "scale must be the whole warp's, so that windows join without seams; compute it "
            "once with grid_scale(mapping, shape, transform, src_shape) for the whole grid"))
    return _as_offset(src_offset, "src_offset", "the window's first pixel")


def _call_mapping(mapping, x, y):
    """A mapping at the map points (x, y): an (n, 2) array of source (col, row)."""
    points = np.column_stack([np.ravel(x), np.ravel(y)])
    if isinstance(mapping, affine.Affine):
        cols, rows = mapping @ (points[:, 0], points[:, 1])
        return np.column_stack([cols, rows])
    source = np.asarray(mapping(points), dtype=np.float64)
    if source.shape != (points.shape[0], 2):
        raise ModelError(_("mapping must return an (n, 2) array of (col, row), got "
                           "shape {source_shape}").format(source_shape=source.shape))
    return source


def _nothing_lands_message(mapping, spans, width, height):
    """The error of a warp whose output grid falls entirely outside the source."""
    spans = np.array(spans)
    if isinstance(mapping, affine.Affine):
        message = _("no output cell lands inside the source image: is your mapping map → image "
                    "(u = f(x, y))? for a raster's geotransform (pixel → map) pass its inverse, "
                    "e.g. ~raster.transform; also check that the output grid (shape, "
                    "transform) covers the source's ground (the output cells fall at source "
                    "cols {col_low:.6g} to {col_high:.6g}, rows {row_low:.6g} to "
                    "{row_high:.6g}, outside the image's [0, {width}) x [0, {height}))")
    else:
        message = _("no output cell lands inside the source image: is your mapping map → image "
                    "(u = f(x, y))? fit the model from map to image, e.g. "
                    "transforms.fit_polynomial(map_xy, image_xy, order), not image → map; for "
                    "a raster's geotransform pass ~raster.transform; also check that the "
                    "output grid (shape, transform) covers the source's ground (the output "
                    "cells fall at source cols {col_low:.6g} to {col_high:.6g}, rows "
                    "{row_low:.6g} to {row_high:.6g}, outside the image's [0, {width}) x "
                    "[0, {height}))")
    return message.format(col_low=prose_number(spans[:, 0].min()),
                          col_high=prose_number(spans[:, 1].max()),
                          row_low=prose_number(spans[:, 2].min()),
                          row_high=prose_number(spans[:, 3].max()), width=width, height=height)


def grid_scale(mapping, shape, transform=None, src_shape=None, samples=21):
    """GDAL's XSCALE, YSCALE for warping onto a grid: output pixels per source pixel.

    As ``GDALWarpOperation`` computes them for one chunk: the output grid's
    edges (``samples`` points on each side, at pixel corners) are taken to the
    source; the scale is the output's columns (rows) over the width (height)
    of their bounding box in source pixels (cut at the image's right or
    bottom edge when its shape is given, GDAL's ``dfSrcXSizeRaw``). A scale
    below 1 whose reciprocal is within 0.05 of a whole number n becomes
    exactly 1/n, as in ``GDALWarpKernel::PerformWarp``.

    Parameters
    ----------
    mapping : callable or affine.Affine
        Map (x, y) -> source (col, row), as in :func:`warp`.
    shape : (rows, cols)
        Output grid size.
    transform : affine.Affine, optional
        Output grid geotransform (identity if omitted).
    src_shape : (rows, cols), optional
        Source image size, to cut the window to; not cut if omitted.
    samples : int
        Points per edge.

    Returns
    -------
    (float, float)
        (xscale, yscale), below 1 when the output pixels are larger.

    Raises
    ------
    ValueError
        If ``shape`` is not two positive integers, or ``mapping`` does not
        return an (n, 2) array of finite positions. (A grid that covers no
        source pixel along an axis gets 1 there: nothing to widen.)

    Examples
    --------
    >>> grid_scale(affine.Affine.scale(8.0), (100, 50))
    (0.125, 0.125)
    """
    rows, cols = as_shape(shape)
    to_map = transform if transform is not None else affine.Affine.identity()
    t = np.linspace(0.0, 1.0, samples)
    px = np.concatenate([t * cols, t * cols, np.zeros(samples), np.full(samples, float(cols))])
    py = np.concatenate([np.zeros(samples), np.full(samples, float(rows)), t * rows, t * rows])
    x, y = to_map @ (px, py)
    if isinstance(mapping, affine.Affine):
        source_cols, source_rows = mapping @ (x, y)
    else:
        source = np.asarray(mapping(np.column_stack([x, y])), dtype=np.float64)
        if source.shape != (x.size, 2):
            raise ModelError(_("mapping must return an (n, 2) array of (col, row), got "
                               "shape {source_shape}").format(source_shape=source.shape))
        source_cols, source_rows = _check_positions(source[:, 0], source[:, 1])
    spans = [source_cols.max() - source_cols.min(), source_rows.max() - source_rows.min()]
    if src_shape is not None:
        # GDAL's dfSrcXSizeRaw: the span, at most from the clamped start to the image's edge
        height, width = as_shape(src_shape, "src_shape")
        for axis, (low, size) in enumerate([(source_cols.min(), width),
                                            (source_rows.min(), height)]):
            spans[axis] = max(0.0, min(float(size - int(max(0.0, low))), spans[axis]))
    scales = []
    for n_out, span in ((cols, spans[0]), (rows, spans[1])):
        if not span > 0:
            # no source pixel under the grid: GDAL's scale is infinite; nothing to widen
            scales.append(1.0)
            continue
        scale = n_out / span
        if scale < 1.0:
            reciprocal = 1.0 / scale
            whole = int(reciprocal + 0.5)
            if abs(reciprocal - whole) < 0.05:
                scale = 1.0 / whole
        scales.append(float(scale))
    return scales[0], scales[1]


def suggested_grid(src_shape, mapping, resolution=None, tap=False):
    """The output grid gdalwarp would choose: its transform and shape.

    GDAL's ``GDALSuggestedWarpOutput2``: the source's edges (at least 20
    points a side, at pixel corners) are taken to the map; their bounding box
    is the extent, and the pixel size, the same in x and y, keeps the number
    of pixels along the diagonal from the top-left to the bottom-right corner
    of the source. Columns and rows are the extent over the pixel size,
    rounded; the extent's right and bottom edges are then moved to match.
    With ``resolution`` (gdalwarp's ``-tr``) that extent is cut into pixels
    of that size, rounded to whole pixels (``int((extent + res / 2) / res)``);
    with ``tap`` (``-tap``) its edges first move outwards to multiples of
    the resolution, so that grids of several scenes line up pixel for pixel.

    Parameters
    ----------
    src_shape : (rows, cols)
        Source image size.
    mapping : affine.Affine or callable
        Source pixel (col, row) -> map (x, y): the raster's geotransform, or
        a model fitted image -> map, called with an (n, 2) array.
    resolution : float or (float, float), optional
        Output pixel size (xres, yres) in map units, both positive.
    tap : bool
        Target-aligned pixels: the grid's edges on multiples of ``resolution``.

    Returns
    -------
    transform : affine.Affine
        North-up output geotransform (pixel corner -> map).
    shape : (int, int)
        Output (rows, cols).

    Raises
    ------
    ValueError
        If ``src_shape`` is not two positive integers, ``resolution`` is not
        positive, ``tap`` is asked without a resolution (gdalwarp's rule), or
        ``mapping`` does not return an (n, 2) array of finite points or maps
        the source onto a line.

    References
    ----------
    GDAL, ``alg/gdaltransformer.cpp``: ``GDALSuggestedWarpOutput2``;
    ``apps/gdalwarp_lib.cpp``: ``-tr`` and ``-tap``.

    Examples
    --------
    >>> transform, shape = suggested_grid((2810, 2954), affine.Affine(2.5, 0, 770595, 0, -2.5,
    ...                                                                7370115))
    >>> transform.a, shape
    (2.5, (2810, 2954))
    >>> suggested_grid((2810, 2954), affine.Affine(2.5, 0, 770595, 0, -2.5, 7370115),
    ...                resolution=20, tap=True)[1]
    (352, 370)
    """
    height, width = as_shape(src_shape, "src_shape")
    if resolution is not None:
        resolution = as_resolution(resolution)
    elif tap:
        raise GridError(_("tap=True needs a resolution: target-aligned pixels are aligned on "
                          "multiples of the pixel size (gdalwarp: -tap needs -tr)"))
    steps = min(max(int(min(width, height) / 50 + 0.5), 20), 100)
    ratio = np.array([i / steps for i in range(steps)] + [1.0])
    # top, bottom, left, right: the last point is the bottom-right corner
    cols = np.concatenate([ratio * width, ratio * width, np.zeros(steps + 1),
                           np.full(steps + 1, float(width))])
    rows = np.concatenate([np.zeros(steps + 1), np.full(steps + 1, float(height)),
                           ratio * height, ratio * height])
    if isinstance(mapping, affine.Affine):
        # GDALApplyGeoTransform's order of operations: c + col * a + row * b
        a, b, c, d, e, f = mapping[:6]
        x, y = c + cols * a + rows * b, f + cols * d + rows * e
    else:
        points = np.asarray(mapping(np.column_stack([cols, rows])), dtype=np.float64)
        if points.shape != (cols.size, 2):
            raise ModelError(_("mapping must return an (n, 2) array of map (x, y), got "
                               "shape {points_shape}").format(points_shape=points.shape))
        x, y = _check_positions(points[:, 0], points[:, 1])
    min_x, max_x, min_y, max_y = x.min(), x.max(), y.min(), y.max()
    delta_x, delta_y = x[-1] - x[0], y[-1] - y[0]
    if delta_x == 0.0 or delta_y == 0.0:
        delta_x, delta_y = max_x - min_x, max_y - min_y
    size = np.sqrt(delta_x * delta_x + delta_y * delta_y) / np.sqrt(
        float(width) * width + float(height) * height)
    if not (size > 0 and max_x > min_x and max_y > min_y):
        raise ModelError(_("mapping takes the source onto a point or a line; it must go from "
                           "source pixel (col, row) to map (x, y), e.g. raster.transform"))
    n_cols = int((max_x - min_x) / size + 0.5)
    n_rows = int((max_y - min_y) / size + 0.5)
    max_x = min_x + n_cols * size
    min_y = max_y - n_rows * size
    if resolution is None:
        return affine.Affine(size, 0.0, min_x, 0.0, -size, max_y), (n_rows, n_cols)
    x_res, y_res = resolution
    if tap:
        min_x = np.floor(min_x / x_res) * x_res
        max_x = np.ceil(max_x / x_res) * x_res
        min_y = np.floor(min_y / y_res) * y_res
        max_y = np.ceil(max_y / y_res) * y_res
    n_cols = int((max_x - min_x + x_res / 2.0) / x_res)
    n_rows = int((abs(max_y - min_y) + y_res / 2.0) / y_res)
    return (affine.Affine(x_res, 0.0, float(min_x), 0.0, -y_res, float(max_y)),
            (n_rows, n_cols))
