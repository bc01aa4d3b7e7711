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
approximate transformer (``-et 0.125``, which ``rasterio.warp.reproject`` uses
between two grids; rasterio 1.4 has no ``tolerance`` argument; with RPCs and
``RPC_DEM`` GDAL's transformer is exact) moves positions in their last bits,
or by up to 0.125 pixel for non-linear mappings, which rounds some exact .5
ties of an enlargement the other way; and it computes the scale per chunk of
the output, from the bounding box of each chunk's source window, which on a
rotated source falls below 0.95 (1 / (cos θ + sin θ) for a square chunk) and
widens the kernels where rsgeo's one scale does not.

:func:`warp` refuses the two classic silent mistakes: a mapping in the wrong
direction (image -> map, e.g. a raster's own geotransform instead of its
inverse), which would give an image of nothing but nodata, and a bands-last
(rows, cols, 3) array.
"""




import affine  # noqa: E402
import numpy as np  # noqa: E402

from .._deprecated import renamed_arguments
from .._kernels.resampling import (
    BLOCK,
    COMPUTED_AS,
    METHODS,
    NO_POSITIONS,
    POSITIONS_GIVEN,
    WARP_METHODS,
    resample_pixels,
)
from .._kernels.transformer import pack
from ..errors import GridError, ImageError, ModelError, RsgeoError
from ..language import N_, _, prose_number
from ..validation import (
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

__all__ = ["interpolate", "grid_positions", "warp", "grid_scale", "suggested_grid",
           "check_mapping", "call_mapping", "nothing_lands_message"]


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
    row_length = cols.shape[-1] if cols.ndim >= 2 else min(cols.size, BLOCK)
    out, _landed = resample_pixels(image, method, nodata, num_threads, cols.ravel(), rows.ravel(),
                             POSITIONS_GIVEN, cols.size, row_length, scale, valid)
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
    work = COMPUTED_AS.get(bands.dtype, bands.dtype.newbyteorder("="))
    if work.kind == "f" and np.isnan(src_nodata):
        valid = ~np.isnan(bands)
    else:
        valid = bands != np.array(src_nodata).astype(work)
    return np.ascontiguousarray(valid, dtype=np.uint8)


def _native(image):
    """``image`` in a type Numba computes in (native byte order; float16 as float32), once."""
    work = COMPUTED_AS.get(image.dtype, image.dtype.newbyteorder("="))
    return np.ascontiguousarray(image, dtype=work)


def check_mapping(mapping):
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
        first, as rsgeo.validation.as_shape does); a ``shape`` without two numbers fails
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


@renamed_arguments(
    ("image", "mapping", "shape", "transform", "method", "nodata", "strip_rows",
     "num_threads", "scale", "src_nodata", "error_threshold", "src_offset", "dst_offset"),
    {"shape": "dst_shape", "transform": "dst_transform", "nodata": "dst_nodata"})
def warp(image, mapping, dst_shape, dst_transform=None, *, method="nearest", dst_nodata=0,
         strip_rows=256, num_threads=1, scale=None, src_nodata=None, error_threshold=0.0,
         src_offset=None, dst_offset=None):
    """The corrected image: every output cell filled from where ``mapping`` sends it.

    This is the lecture's "construir uma nova imagem corrigida": the output grid
    is defined in map coordinates, ``mapping`` is the model u = f(x, y),
    v = g(x, y) from map to image coordinates, and each cell takes the value
    interpolated at that source position.

    An ``affine.Affine`` and rsgeo's polynomial, projective and thin-plate
    spline models are evaluated inside the compiled kernel, row by row, as
    GDAL's transformer is (``rsgeo._kernels.transformer``): no array of positions
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
    dst_shape : (rows, cols)
        Output grid size.
    dst_transform : affine.Affine, optional
        Output grid geotransform; if omitted, map coordinates are the output's
        own pixel coordinates.
    method : {"nearest", "bilinear", "cubic", "average"}
        "average" (GDAL's, the method to downsample with): each cell is the
        mean of the source pixels it covers, each weighted by the part of it
        inside the cell (the cell's corners taken to the source).
    dst_nodata : number or None
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
        is a window of it (GDAL's source window; :mod:`rsgeo.resample` warps a
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
    shape, transform, nodata = dst_shape, dst_transform, dst_nodata
    image = as_bands_first(as_image(image))
    check_choice(method, "method", WARP_METHODS)
    nodata = as_nodata(nodata, image.dtype)
    num_threads = as_num_threads(num_threads)
    bands = image.shape[0] if image.ndim == 3 else 1
    out_rows, out_cols = as_output_shape(shape, image.dtype, bands)
    to_map = as_affine(transform) if transform is not None else affine.Affine.identity()
    check_mapping(mapping)
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
        flat, landed = resample_pixels(image, method, nodata, num_threads, NO_POSITIONS,
                                 NO_POSITIONS, packed, out_rows * out_cols, out_cols, scale,
                                 valid)
        out = flat.reshape((bands, out_rows, out_cols)).astype(dtype, copy=False)
        if not landed:
            # the outermost pixel centres, to say where the grid went
            centre_cols, centre_rows = np.meshgrid(np.array([0.5, out_cols - 0.5]) + dst_offset[0],
                                                   np.array([0.5, out_rows - 0.5]) + dst_offset[1])
            corners = (call_mapping(mapping, *(to_map @ (centre_cols, centre_rows)))
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
            source = call_mapping(mapping, x, y)
            source_cols, source_rows = _check_positions(source[:, 0] - src_offset[0],
                                                        source[:, 1] - src_offset[1])
            strip, inside = resample_pixels(image, method, nodata, num_threads, source_cols,
                                      source_rows, POSITIONS_GIVEN, (stop - start) * out_cols,
                                      out_cols, scale, valid)
            out[:, start:stop, :] = strip.reshape(bands, stop - start, out_cols)
            if not landed:
                spans.append((source_cols.min(), source_cols.max(),
                              source_rows.min(), source_rows.max()))
            landed += inside
    if not landed:
        raise GridError(nothing_lands_message(mapping, spans, width, height))
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


def call_mapping(mapping, x, y):
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


def nothing_lands_message(mapping, spans, width, height):
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


def grid_scale(mapping, shape, transform=None, src_shape=None, samples=21,
               skip_failed=False):
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
    skip_failed : bool
        Leave out the edge points that ``mapping`` gives NaN for (points a
        transformer could not take to the source, such as a point off its
        DEM), as GDAL leaves out the points its transformer fails on; by
        default a NaN is an error.

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
        if skip_failed:
            source = source[np.isfinite(source).all(axis=1)]
            if not len(source):
                return 1.0, 1.0               # no point reaches the source: nothing to widen
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
