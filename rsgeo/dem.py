"""Heights from a DEM, sampled as GDAL's RPC transformer samples them, and where lines of sight
meet the ground.

The DEM is sampled as GDAL 3.10's GDALRPCGetDEMHeight does it with bilinear interpolation
(``alg/gdal_interpolateatpoint.cpp``): at (x - 0.5, y - 0.5) in DEM pixels, the 2 x 2 window's
indices clamped to the DEM, so that within its outer half cell the height is interpolated along
the edge; a point is on the DEM for 0 <= x <= columns and 0 <= y <= rows (DEM pixels). GDAL 3.9
and earlier truncated the index toward zero and took the nearest cell at the edge.
"""

import numpy as np

from ._grids import as_gdal, gdal_inverse, grid_bounds, outside_mask
from ._kernels.dem import dem_heights
from .errors import GridError, ImageError, RsgeoError
from .language import _, prose_number

__all__ = [
    "dem_height", "line_of_sight_on_dem", "prepare_dem", "sample_dem", "raise_dem_problems",
]


def line_of_sight_on_dem(ground, shape, dem, dem_transform, iterations):
    """Where lines of sight meet a DEM, by the fixed-point iteration h -> (x, y) -> h.

    One idea for every sensor model of the course (:class:`~rsgeo.sensors.PushbroomSensor`,
    :class:`rsgeo.sensors.RawSensor`): start on the datum (h = 0), find where each line of
    sight is at that height, read the DEM there, repeat. Each step shrinks the error by the
    terrain's slope times tan θ, so a few steps suffice on gentle terrain.

    Parameters
    ----------
    ground : callable
        ``ground(h) -> (x, y)``: where the lines of sight are at heights ``h`` (an array of
        ``shape``), in the DEM's map coordinates.
    shape : tuple of int
        The shape of the lines of sight's array.
    dem : 2-D array
        Heights (m) on the sensor model's datum.
    dem_transform : affine.Affine
        The DEM's geotransform.
    iterations : int
        How many steps.

    Returns
    -------
    x, y, h : ndarray
        The ground points, of ``shape``.

    Raises
    ------
    ValueError
        If a line of sight leaves the DEM (:func:`dem_height`).

    Examples
    --------
    >>> import affine
    >>> dem = np.full((10, 10), 50.0)
    >>> x, y, h = line_of_sight_on_dem(lambda h: (2.0 + 0.1 * h, 5.0 - 0 * h), (1,), dem,
    ...                                affine.Affine(1, 0, 0, 0, -1, 10), 3)
    >>> float(x[0]), float(h[0])                        # 50 m up, 0.1 m east per metre
    (7.0, 50.0)
    """
    h = np.zeros(shape)
    for _iteration in range(iterations):
        x, y = ground(h)
        h = dem_height(dem, dem_transform, x, y)
    x, y = ground(h)
    return x, y, h


def dem_height(dem, dem_transform, x, y, dem_nodata=None):
    """DEM heights at map points, bilinear, exactly as GDAL's RPC transformer samples its DEM.

    Parameters
    ----------
    dem : (rows, cols) array_like
        Heights (m). NaN (or ``dem_nodata``) marks a hole.
    dem_transform : affine.Affine
        The DEM's geotransform (pixel corner -> map).
    x, y : array_like
        Points in the DEM's coordinates, same shape.
    dem_nodata : float, optional
        Value marking holes, besides NaN.

    Returns
    -------
    ndarray
        Heights, shape of ``x``.

    Raises
    ------
    ValueError
        If the DEM is not 2-D, a point falls outside the DEM, or a point
        needs a DEM cell that is a hole; the message says how many and the
        first such point.

    References
    ----------
    GDAL, ``alg/gdal_rpc.cpp``: ``GDALRPCGetDEMHeight``.

    Examples
    --------
    >>> import affine
    >>> dem = np.array([[0.0, 10.0], [20.0, 30.0]])
    >>> float(dem_height(dem, affine.Affine(1, 0, 0, 0, -1, 2), 1.0, 1.0))
    15.0
    """
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if x.shape != y.shape:
        raise RsgeoError(_("x and y must have the same shape, got {x_shape} and "
                           "{y_shape}").format(x_shape=x.shape, y_shape=y.shape))
    prepared = prepare_dem(dem, dem_transform, dem_nodata)
    heights, outside, holed = sample_dem(prepared, x, y)
    raise_dem_problems(prepared, outside, holed, x.size)
    return heights


def prepare_dem(dem, dem_transform, dem_nodata):
    """A DEM made ready for :func:`sample_dem`: checked, float64, its holes NaN.

    Parameters
    ----------
    dem : 2-D ndarray
        Heights in metres.
    dem_transform : affine.Affine
        The DEM's geotransform (pixel corner -> map).
    dem_nodata : number or None
        The DEM's nodata value; NaN and infinity are holes too.

    Returns
    -------
    tuple
        ``(heights with NaN holes, GDAL's inverse geotransform, holes mask, dem_transform)``.

    Raises
    ------
    rsgeo.errors.ImageError
        If the DEM is not a 2-D array of real heights.
    """
    kind = np.asarray(dem).dtype.kind
    if kind not in "uif":
        raise ImageError(_(
            "dem must hold real heights in metres (integers or floats), got dtype {dtype}; a "
            "complex DEM has no height: give its real part (dem.real) if that is one").format(
                dtype=np.asarray(dem).dtype))
    dem = np.asarray(dem, dtype=np.float64)
    if dem.ndim != 2 or min(dem.shape) < 1:
        raise ImageError(_("dem must be a 2-D (rows, cols) array of heights, got shape "
                           "{dem_shape}").format(dem_shape=dem.shape))
    inverse = gdal_inverse(as_gdal(dem_transform, "dem_transform"))
    holes = ~np.isfinite(dem)
    if dem_nodata is not None:
        holes |= dem == dem_nodata
    work = np.ascontiguousarray(np.where(holes, np.nan, dem))
    return work, inverse, holes, dem_transform


def sample_dem(prepared, x, y):
    """Heights at points, GDAL's bilinear sampling, and which points it could not sample.

    Parameters
    ----------
    prepared : tuple
        :func:`prepare_dem`'s DEM.
    x, y : array_like
        Map coordinates in the DEM's CRS.

    Returns
    -------
    tuple
        ``(heights (shape of x), outside, holed)``: ``outside`` and ``holed`` are
        (count, first x, first y) of the points outside the DEM and over a hole (count 0:
        none).
    """
    work, inverse, _holes, _transform = prepared
    flat_x, flat_y = np.ravel(x), np.ravel(y)
    out = np.empty(flat_x.size)
    outside = dem_heights(work, inverse, flat_x, flat_y, out)
    outside_first = holed_first = (0, 0.0, 0.0)
    if outside:
        first = int(np.flatnonzero(np.isnan(out) & outside_mask(work.shape, inverse, flat_x,
                                                                     flat_y))[0])
        outside_first = (outside, flat_x[first], flat_y[first])
    else:
        missing = np.isnan(out)
        if missing.any():
            first = int(np.flatnonzero(missing)[0])
            holed_first = (int(missing.sum()), flat_x[first], flat_y[first])
    return out.reshape(np.shape(x)), outside_first, holed_first


def raise_dem_problems(prepared, outside, holed, n):
    """Raise the error of points outside the DEM or over its holes, if there are any.

    Parameters
    ----------
    prepared : tuple
        :func:`prepare_dem`'s DEM.
    outside, holed : tuple
        :func:`sample_dem`'s (count, first x, first y) of each.
    n : int
        How many points were sampled.

    Raises
    ------
    rsgeo.errors.GridError
        If points are outside the DEM.
    rsgeo.errors.ImageError
        If points are over its holes.
    """
    work, _inverse, holes, dem_transform = prepared
    if outside[0]:
        raise GridError(_("the DEM does not cover {value} of {n} points (first at "
                          "x={value2:.6f}, y={value3:.6f}; DEM bounds {bounds}); give a "
                          "DEM that covers the output grid").format(
                value=outside[0], n=n, value2=prose_number(outside[1]),
                value3=prose_number(outside[2]), bounds=grid_bounds(work.shape, dem_transform)))
    if holed[0]:
        rows, cols = np.nonzero(holes)
        raise ImageError(_("the DEM has nodata holes ({sum} cells, e.g. row {value}, "
                           "col {value2}) under {value3} points (first at "
                           "x={value4:.6f}, y={value5:.6f}); fill them first").format(
                sum=holes.sum(), value=rows[0], value2=cols[0], value3=holed[0],
                value4=prose_number(holed[1]), value5=prose_number(holed[2])))


