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

import affine
import numpy as np

from ._checks import as_image, check_choice

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

    Examples
    --------
    >>> keys_weights(0.0) + 0.0          # + 0.0 turns -0. into 0.
    array([0., 1., 0., 0.])
    >>> keys_weights(0.5)
    array([-0.0625,  0.5625,  0.5625, -0.0625])
    """
    t = np.asarray(t, dtype=np.float64)
    if a == -0.5:
        return np.stack(_gdal_cubic_weights(t))
    return np.stack([cubic_kernel(t + 1, a), cubic_kernel(t, a),
                     cubic_kernel(1 - t, a), cubic_kernel(2 - t, a)])


def _gdal_cubic_weights(t):
    """GDAL's GWKCubicComputeWeights, operation for operation, with few temporaries.

    GDAL writes w0 = ½t·(−1 + t·(2 − t)), w1 = 1 + ½t²·(−5 + 3t),
    w2 = ½t·(1 + t·(4 − 3t)), w3 = ½t²·(−1 + t); the in-place steps below
    only swap the operands of additions and products, which is exact in
    floating point, so the weights are GDAL's to the last bit.
    """
    half_t = 0.5 * t
    three_t = 3.0 * t
    half_t2 = half_t * t
    w0 = 2 - t
    w0 *= t
    w0 -= 1
    w0 *= half_t
    w1 = three_t - 5
    w1 *= half_t2
    w1 += 1
    w2 = 4 - three_t
    w2 *= t
    w2 += 1
    w2 *= half_t
    w3 = t - 1
    w3 *= half_t2
    return w0, w1, w2, w3


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
        W(s): 1 at s = 0, 0 at every other integer, 0 for |s| >= 2.

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

    Examples
    --------
    >>> bilinear_weights(0.25)
    array([0.75, 0.25])
    """
    t = np.asarray(t, dtype=np.float64)
    return np.stack([1.0 - t, t])


# Positions are processed in chunks of this many, so that the temporaries of
# the kernels stay in the processor's cache.
_CHUNK = 32768


def interpolate(image, cols, rows, method="nearest", nodata=0):
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

    Returns
    -------
    ndarray
        Same dtype as ``image``, shape ``cols.shape`` (or ``(bands,) + cols.shape``).

    Raises
    ------
    ValueError
        If the image is not 2-D or 3-D (or looks bands last, (rows, cols, 3)),
        the method is unknown, cols and rows differ in shape or hold NaN or
        infinity, or nodata does not fit the dtype.

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
    cols = np.asarray(cols, dtype=np.float64)
    rows = np.asarray(rows, dtype=np.float64)
    if cols.shape != rows.shape:
        raise ValueError(f"cols and rows must have the same shape, got {cols.shape} and {rows.shape}")
    if not (np.isfinite(cols).all() and np.isfinite(rows).all()):
        raise ValueError("cols and rows hold NaN or infinite positions; every position must be finite "
                         "(mark points you do not want with a position outside the image instead)")
    nodata = check_nodata(nodata, image.dtype)

    bands = image if image.ndim == 3 else image[np.newaxis]
    height, width = bands.shape[1:]
    flat_bands = [np.ascontiguousarray(band).ravel() for band in bands]
    kernel = {"nearest": _nearest, "bilinear": _bilinear, "cubic": _cubic}[method]
    flat_cols, flat_rows = cols.ravel(), rows.ravel()
    out = np.full((bands.shape[0], flat_cols.size), nodata, dtype=image.dtype)
    for start in range(0, flat_cols.size, _CHUNK):
        c, r = flat_cols[start:start + _CHUNK], flat_rows[start:start + _CHUNK]
        inside = _inside(c, r, width, height)
        everywhere = inside.all()
        if not everywhere:
            c, r = c[inside], r[inside]
        for band_index, flat in enumerate(flat_bands):
            exact = kernel(flat, width, height, c, r)
            values = _to_dtype(exact, image.dtype)
            if method != "nearest":
                # GDAL's nearest-neighbour path copies source values as they are.
                values = _avoid_nodata(exact, values, nodata)
            target = out[band_index, start:start + _CHUNK]
            if everywhere:
                target[:] = values
            else:
                target[inside] = values
    shape = (bands.shape[0],) + cols.shape if image.ndim == 3 else cols.shape
    return out.reshape(shape)


def check_nodata(nodata, dtype):
    """Return ``nodata`` if it is representable in ``dtype``, else raise ValueError."""
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


def _to_dtype(values, dtype):
    """GDAL's GWKClampValueT: round half up, clamp to the integer dtype's range."""
    if dtype.kind in "ui":
        info = np.iinfo(dtype)
        values = np.floor(values + 0.5)
        if dtype.itemsize < 8:
            np.clip(values, info.min, info.max, out=values)
        return values.astype(dtype)
    return values.astype(dtype)


def _avoid_nodata(exact, values, nodata):
    """GDAL's AvoidNoData: a valid pixel that comes out equal to nodata moves one step away.

    Without it a dark pixel of a valid area would read as "outside the image".
    Integers step down (nodata − 1), or up from the dtype's minimum; floats are
    compared before the cast to the output type, as GDAL does, and step to the
    next representable value.
    """
    if values.dtype.kind in "ui":
        clash = values == nodata
        if clash.any():
            values[clash] = nodata + 1 if nodata == np.iinfo(values.dtype).min else nodata - 1
    else:
        clash = exact == nodata
        if clash.any():
            values[clash] = np.nextafter(values.dtype.type(nodata), values.dtype.type(np.inf))
    return values


def _nearest(flat, width, height, c, r):
    cols = (c + _GDAL_INDEX_EPSILON).astype(np.intp)  # positive here: truncation is floor
    rows = (r + _GDAL_INDEX_EPSILON).astype(np.intp)
    return flat.take(rows * width + cols)


def _bilinear(flat, width, height, c, r):
    """GDAL's GWKBilinearResampleNoMasks4SampleT, vectorised."""
    left = np.floor(c - 0.5)
    top = np.floor(r - 0.5)
    ratio_x = 1.5 - (c - left)
    ratio_y = 1.5 - (r - top)
    left, top = left.astype(np.intp), top.astype(np.intp)
    interior = (left >= 0) & (left < width - 1) & (top >= 0) & (top < height - 1)
    if interior.all():
        return _bilinear_interior(flat, width, left, top, ratio_x, ratio_y)
    values = np.empty(c.shape, dtype=np.float64)
    values[interior] = _bilinear_interior(flat, width, left[interior], top[interior],
                                          ratio_x[interior], ratio_y[interior])
    edge = ~interior
    values[edge] = _bilinear_edge(flat, width, height, left[edge], top[edge], ratio_x[edge], ratio_y[edge])
    return values


def _bilinear_interior(flat, width, left, top, ratio_x, ratio_y):
    index = top * width + left
    other_x = 1.0 - ratio_x
    # flat[k:].take(index) reads pixel index + k without a new index array
    upper = flat.take(index) * ratio_x + flat[1:].take(index) * other_x
    lower = flat[width:].take(index) * ratio_x + flat[width + 1:].take(index) * other_x
    return upper * ratio_y + lower * (1.0 - ratio_y)


def _bilinear_edge(flat, width, height, left, top, ratio_x, ratio_y):
    """Bilinear at the image border: weights of the missing pixels dropped, the rest renormalised."""
    accumulator = np.zeros(left.shape)
    divisor = np.zeros(left.shape)
    # GDAL's order: upper left, upper right, lower right, lower left.
    for dx, dy, weight in ((0, 0, ratio_x * ratio_y),
                           (1, 0, (1.0 - ratio_x) * ratio_y),
                           (1, 1, (1.0 - ratio_x) * (1.0 - ratio_y)),
                           (0, 1, ratio_x * (1.0 - ratio_y))):
        col, row = left + dx, top + dy
        ok = (col >= 0) & (col < width) & (row >= 0) & (row < height)
        divisor[ok] += weight[ok]
        accumulator[ok] += flat.take(row[ok] * width + col[ok]) * weight[ok]
    return np.where(divisor == 1.0, accumulator, accumulator / np.where(divisor == 0, 1.0, divisor))


def _cubic(flat, width, height, c, r):
    """GDAL's cubic convolution (GWKCubicResampleNoMasks4SampleT), vectorised."""
    # GDAL truncates towards zero here; negative positions fall back to bilinear anyway.
    left = np.trunc(c - 0.5)
    top = np.trunc(r - 0.5)
    dx, dy = c - 0.5 - left, r - 0.5 - top
    left, top = left.astype(np.intp), top.astype(np.intp)
    interior = (left >= 1) & (left + 2 < width) & (top >= 1) & (top + 2 < height)
    if interior.all():
        return _cubic_interior(flat, width, left, top, dx, dy)
    values = np.empty(c.shape, dtype=np.float64)
    values[interior] = _cubic_interior(flat, width, left[interior], top[interior], dx[interior], dy[interior])
    edge = ~interior
    values[edge] = _bilinear(flat, width, height, c[edge], r[edge])
    return values


def _cubic_interior(flat, width, left, top, dx, dy):
    weights_x = _gdal_cubic_weights(dx)
    weights_y = _gdal_cubic_weights(dy)
    index = (top - 1) * width + (left - 1)
    total = np.empty(index.shape)
    along_row = np.empty(index.shape)
    term = np.empty(index.shape)
    for j in range(4):
        # Taking from a view that starts k elements later reads pixel index + k
        # without building a new index array.
        start = j * width
        # CONVOL4 along the row, in GDAL's order of additions.
        np.multiply(weights_x[0], flat[start:].take(index), out=along_row)
        for i in range(1, 4):
            np.multiply(weights_x[i], flat[start + i:].take(index), out=term)
            along_row += term
        if j == 0:
            np.multiply(weights_y[0], along_row, out=total)
        else:
            np.multiply(weights_y[j], along_row, out=term)
            total += term
    return total


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


def _inside(cols, rows, width, height):
    """GDAL's rule for a position inside a width x height image (as in :func:`interpolate`)."""
    return ((cols >= 0) & (rows >= 0)
            & (np.floor(cols + _GDAL_INDEX_EPSILON) < width)
            & (np.floor(rows + _GDAL_INDEX_EPSILON) < height))


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
    """
    a, b, c, d, e, f = (transform if transform is not None else affine.Affine.identity())[:6]
    cols = np.arange(shape[1]) + 0.5
    rows = (np.arange(first_row, first_row + shape[0]) + 0.5)[:, np.newaxis]
    return a * cols + (b * rows + c), d * cols + (e * rows + f)


def warp(image, mapping, shape, transform=None, method="nearest", nodata=0, strip_rows=256):
    """The corrected image: every output cell filled from where ``mapping`` sends it.

    This is the lecture's "construir uma nova imagem corrigida": the output grid
    is defined in map coordinates, ``mapping`` is the model u = f(x, y),
    v = g(x, y) from map to image coordinates, and each cell takes the value
    interpolated at that source position. The grid is processed in strips of
    ``strip_rows`` rows so that memory stays a small multiple of input plus output.

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
        Rows per strip.

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

    Examples
    --------
    >>> image = np.arange(16, dtype=np.uint8).reshape(4, 4)
    >>> shift = lambda xy: xy + [1.0, 0.0]     # output col c reads source col c + 1
    >>> warp(image, shift, (4, 4))[0]
    array([1, 2, 3, 0], dtype=uint8)
    """
    image = check_bands_first(as_image(image))
    check_choice(method, "method", METHODS)
    check_nodata(nodata, image.dtype)
    out_rows, out_cols = check_shape(shape)
    height, width = image.shape[-2:]
    landed = False
    spans = []
    bands = image.shape[0] if image.ndim == 3 else None
    out = np.empty(((bands,) if bands else ()) + (out_rows, out_cols), dtype=image.dtype)
    to_map = transform if transform is not None else affine.Affine.identity()
    for start in range(0, out_rows, strip_rows):
        stop = min(start + strip_rows, out_rows)
        strip = (stop - start, out_cols)
        if isinstance(mapping, affine.Affine):
            source_cols, source_rows = grid_positions(strip, mapping @ to_map, first_row=start)
        else:
            x, y = grid_positions(strip, to_map, first_row=start)
            source = np.asarray(mapping(np.column_stack([x.ravel(), y.ravel()])), dtype=np.float64)
            if source.shape != (x.size, 2):
                raise ValueError(f"mapping must return an (n, 2) array of (col, row), got shape {source.shape}")
            source_cols, source_rows = source[:, 0].reshape(x.shape), source[:, 1].reshape(x.shape)
        if not landed:
            landed = bool(_inside(source_cols, source_rows, width, height).any())
            spans.append((source_cols.min(), source_cols.max(),
                          source_rows.min(), source_rows.max()))
        out[..., start:stop, :] = interpolate(image, source_cols, source_rows, method=method, nodata=nodata)
    if not landed:
        raise ValueError(_nothing_lands_message(mapping, spans, width, height))
    return out


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
