"""Coordinate reference systems, datum shifts and a complete georeferencing run.

Map coordinates only mean something with their CRS: the CBERS scenes shipped
with rsgeo are in SAD69 / UTM, Brazil's datum since 2015 is SIRGAS 2000, and the
same point has UTM coordinates tens of metres apart in the two. This module
moves points and rasters between CRSs through PROJ (via rasterio, the PROJ that
GDAL itself uses), and runs the whole correction a user makes in QGIS's
Georeferencer or with ``gdalwarp``: fit a model to the GCPs, choose an output
grid, warp, and save a GeoTIFF.

Examples
--------
>>> from rsgeo import georef
>>> x, y = georef.transform_points([[500000.0, 7400000.0]], "EPSG:29193", "EPSG:31983")[0]
>>> 30 < float(np.hypot(x - 500000.0, y - 7400000.0)) < 80     # SAD69 -> SIRGAS 2000
True
"""

import re
import warnings

import numpy as np

from . import transforms as _transforms
from ._checks import as_crs, as_output_shape, as_points, check_choice
from ._i18n import _
from .data import Raster
from .errors import CRSError, DataError, ExtrapolationWarning, GCPError
from .gcp import GCPSet

__all__ = ["as_crs", "transform_points", "datum_shift", "geocentric_translation",
           "CRSMapping", "reproject", "georeference"]

# EPSG:15485, "SAD69 to SIRGAS 2000 (1)": geocentric translations in metres (accuracy 5 m)
SAD69_TO_SIRGAS2000 = (-67.35, 3.88, -38.22)

_METHODS = ("nearest", "bilinear", "cubic")


# No position on Earth has a coordinate 25 times the Earth's circumference (1e9 m) or 25 turns
# (9,000°) from its CRS's origin; PROJ wraps longitudes by a loop whose time grows with the value
# (a point at x = 1e18 m in EPSG:3857 takes minutes), so larger coordinates never reach PROJ.
_FARTHEST_METRES = 1e9
_FARTHEST_RADIANS = 50 * np.pi


def _refuse_far_coordinates(points, crs):
    """Refuse (n, 2) finite points with a coordinate no position on Earth has in ``crs``."""
    kind, unit, factor = _kind_and_unit(crs)
    farthest = _FARTHEST_RADIANS if kind == "geographic" else _FARTHEST_METRES
    limit = farthest / factor if np.isfinite(factor) and factor > 0 else _FARTHEST_METRES
    far = (np.abs(points) > limit).any(axis=1)
    if far.any():
        first = int(np.flatnonzero(far)[0])
        raise CRSError(_(
            "{count} of {n} points have a coordinate that no position on Earth has in {crs} "
            "(first: point {first} ({x:.6g}, {y:.6g}); its coordinates stay within ±{limit:.6g} "
            "{unit}, 25 times around the Earth): PROJ is not asked, it can take minutes on such "
            "values; give points in the CRS's own coordinates and units").format(
                count=int(far.sum()), n=len(points), crs=_crs_name(crs), first=first,
                x=points[first, 0], y=points[first, 1], limit=limit, unit=unit))


def _area_of_use(crs):
    """PROJ's area of use of ``crs``: (west, south, east, north) in degrees, or None.

    Read from the CRS's WKT2 ``USAGE[... BBOX[south, west, north, east]]``, which
    PROJ fills from its database (EPSG's area of use); a CRS read from a file
    carries no usage, so its EPSG code (if PROJ identifies one) is looked up.
    """
    from rasterio.crs import CRS
    from rasterio.errors import CRSError as RasterioCRSError

    def boxes(value):
        return re.findall(r"BBOX\[([-+.\deE]+),([-+.\deE]+),([-+.\deE]+),([-+.\deE]+)\]",
                          value.to_wkt(version="WKT2_2019"))

    try:
        found = boxes(crs)
        if not found:
            code = crs.to_epsg()
            found = boxes(CRS.from_epsg(code)) if code else []
    except RasterioCRSError:
        return None
    if not found:
        return None
    south, west, north, east = (float(v) for v in found[-1])
    return west, south, east, north


def _outside_area(lon, lat, area):
    """Mask of the points (degrees) outside an area of use; NaN and inf are outside."""
    west, south, east, north = area
    inside_lon = ((lon >= west) & (lon <= east) if west <= east
                  else (lon >= west) | (lon <= east))          # an area across 180°
    return ~(inside_lon & (lat >= south) & (lat <= north))


def _check_area(points, src, dst):
    """Refuse points outside the area of use of ``src`` or of ``dst`` (PROJ's, in degrees)."""
    areas = [(crs, _area_of_use(crs)) for crs in (src, dst)]
    areas = [(crs, area) for crs, area in areas if area is not None]
    if not areas:
        return
    lon, lat = _lon_lat(points, src)
    for crs, area in areas:
        outside = _outside_area(lon, lat, area)
        if outside.any():
            first = int(np.flatnonzero(outside)[0])
            raise CRSError(_(
                "{count} of {n} points are outside the area of use of {crs} (longitude "
                "{west:g} to {east:g}, latitude {south:g} to {north:g}; first: point {first} "
                "({x:.6g}, {y:.6g}) in {src}, at longitude {lon:.4f}, latitude {lat:.4f}): "
                "PROJ's answer there is not a position; give points in src_crs's own "
                "coordinates and units (longitude and latitude typed into a projected CRS?), "
                "or CRSs whose area covers them").format(
                    count=int(outside.sum()), n=len(points), crs=_crs_name(crs),
                    west=area[0], east=area[2], south=area[1], north=area[3], first=first,
                    x=points[first, 0], y=points[first, 1], src=_crs_name(src),
                    lon=lon[first], lat=lat[first]))


def _lon_lat(points, crs):
    """Longitude, latitude (EPSG:4326) of points in ``crs``; NaN where PROJ cannot say."""
    from rasterio.warp import transform

    _refuse_far_coordinates(points, crs)
    try:
        with np.errstate(all="ignore"):
            return tuple(np.asarray(v, dtype=np.float64)
                         for v in transform(crs, "EPSG:4326", points[:, 0], points[:, 1]))
    except Exception:                  # GDAL refuses the batch: point by point, failures NaN
        lon, lat = np.full(len(points), np.nan), np.full(len(points), np.nan)
        for k, (x, y) in enumerate(points):
            try:
                with np.errstate(all="ignore"):
                    (lon[k],), (lat[k],) = transform(crs, "EPSG:4326", [x], [y])
            except Exception:
                pass
        return lon, lat


# PROJ parameters of the datum, not of the projection (a datum shift changes only these)
_DATUM_KEYS = {"ellps", "datum", "towgs84", "nadgrids", "a", "b", "rf", "f", "R", "pm",
               "no_defs", "wktext", "type", "units", "to_meter"}


def _projection(crs):
    """The projection of ``crs`` without its datum: PROJ's parameters (proj, zone, lon_0 ...)."""
    return {key: value for key, value in crs.to_dict().items() if key not in _DATUM_KEYS}


def _crs_name(crs):
    """'EPSG:31983' when PROJ identifies a code, else the CRS's name."""
    code = crs.to_epsg()
    if code:
        return f"EPSG:{code}"
    match = re.match(r'\w+\["([^"]*)"', crs.to_wkt())
    return match.group(1) if match else crs.to_string()[:60]


def _kind_and_unit(crs):
    """("geographic" or "projected" or another kind, unit name, metres or radians per unit)."""
    kind = ("geographic" if crs.is_geographic else "projected" if crs.is_projected
            else "other")
    try:
        unit, factor = crs.units_factor
    except Exception:                 # rasterio's CRSError for a CRS without one unit
        unit, factor = "unknown", float("nan")
    return kind, unit, factor


def _transform(points, src, dst):
    """PROJ's transformation of finite (n, 2) points between two checked CRSs, unchecked area."""
    from rasterio.warp import transform

    if src == dst:
        return points.copy()
    _refuse_far_coordinates(points, src)
    try:
        xs, ys = transform(src, dst, points[:, 0], points[:, 1])
    except Exception as error:        # GDAL's CPLE_AppDefinedError "Reprojection failed"
        raise CRSError(_("PROJ could not transform the points from {src} to {dst} ({error}); "
                         "give points inside both CRSs' areas of use").format(
                             src=_crs_name(src), dst=_crs_name(dst), error=error)) from None
    result = np.column_stack([xs, ys]).astype(np.float64)
    if not np.isfinite(result).all():
        raise CRSError(_("PROJ could not transform some points from {src} to {dst} "
                         "(outside the CRS's area of use?)").format(
                             src=_crs_name(src), dst=_crs_name(dst)))
    return result


def transform_points(points, src_crs, dst_crs, check_area=True):
    """Map coordinates (x, y) moved from one CRS to another by PROJ.

    PROJ picks the transformation (datum shift) it would pick for ``gdalwarp``
    with the grids it has; without network access and without the SAD69
    grid, SAD69 -> SIRGAS 2000 is EPSG:15485, three geocentric translations.

    Parameters
    ----------
    points : (n, 2) array_like
        Easting, northing (or longitude, latitude) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        See :func:`as_crs`.
    check_area : bool
        Refuse points outside the area of use (PROJ's, from the EPSG
        database) of ``src_crs`` or ``dst_crs``: there PROJ still returns
        numbers, but they are not the points' positions (longitude and
        latitude typed into a UTM CRS move 42.8 m from SAD69 to SIRGAS 2000).
        False transforms them as ``gdalwarp`` does, without a word.

    Returns
    -------
    ndarray
        (n, 2) float64 in ``dst_crs``.

    Raises
    ------
    ValueError
        For a CRS that PROJ does not know, points that are not (n, 2) finite,
        a coordinate no position on Earth has (beyond 1e9 m, or 9,000° in a
        geographic CRS: refused whatever ``check_area``, before PROJ sees it),
        or (``check_area``) points outside a CRS's area of use.

    Examples
    --------
    >>> transform_points([[0.0, 0.0]], "EPSG:4326", "EPSG:4326")
    array([[0., 0.]])
    """
    points = as_points(points, "points")
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    if check_area:
        _check_area(points, src, dst)
    return _transform(points, src, dst)


def datum_shift(points, src_crs, dst_crs):
    """How far each point's coordinates move from ``src_crs`` to ``dst_crs``.

    A shift is a difference of coordinates, so the two CRSs must be alike:
    the same projection in the same unit on two datums (SAD69 / UTM 21S and
    SIRGAS 2000 / UTM 21S), or both geographic; and the points must be inside both CRSs' areas of
    use (:func:`transform_points`).

    Parameters
    ----------
    points : (n, 2) array_like
        Map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        Two projected CRSs with the same units (e.g. SAD69 / UTM 21S and
        SIRGAS 2000 / UTM 21S), or two geographic CRSs.

    Returns
    -------
    dx, dy, distance : ndarray
        Per point, in the CRSs' units (metres for UTM).

    Raises
    ------
    ValueError
        As :func:`transform_points`; if one CRS is geographic and the other
        projected, their units differ (EPSG:4326 -> 31983 is a projection,
        not a shift), or their projections differ (UTM zones 22S and 23S,
        UTM and Web Mercator).

    Examples
    --------
    >>> dx, dy, d = datum_shift([[500000.0, 7400000.0]], "EPSG:29193", "EPSG:31983")
    >>> bool(dx[0] < 0 and dy[0] < 0)
    True
    """
    points = as_points(points, "points")
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    (src_kind, src_unit, src_factor), (dst_kind, dst_unit, dst_factor) = (
        _kind_and_unit(src), _kind_and_unit(dst))
    if src_kind != dst_kind or src_kind == "other" or not np.isclose(src_factor, dst_factor,
                                                                     rtol=1e-12, atol=0):
        raise CRSError(_(
            "a datum shift needs two CRSs of the same kind and unit, got src_crs {src} "
            "({src_kind}, {src_unit}) and dst_crs {dst} ({dst_kind}, {dst_unit}): the "
            "difference of their coordinates is not a distance; give two projected CRSs in "
            "the same unit (e.g. EPSG:29193 and EPSG:31983) or two geographic CRSs, or use "
            "transform_points to convert between kinds").format(
                src=_crs_name(src), src_kind=src_kind, src_unit=src_unit, dst=_crs_name(dst),
                dst_kind=dst_kind, dst_unit=dst_unit))
    if _projection(src) != _projection(dst):
        raise CRSError(_(
            "a datum shift compares one projection on two datums, but src_crs {src} and dst_crs "
            "{dst} are different projections ({src_projection} and {dst_projection}): the "
            "difference of their coordinates is mostly the projection's; give the same "
            "projection (e.g. UTM zone 23S: EPSG:29193 and EPSG:31983), or use transform_points "
            "to change projection").format(
                src=_crs_name(src), dst=_crs_name(dst), src_projection=_proj_text(src),
                dst_projection=_proj_text(dst)))
    moved = transform_points(points, src, dst)
    dx, dy = (moved - points).T
    return dx, dy, np.hypot(dx, dy)


def _proj_text(crs):
    """A CRS's projection as PROJ parameters, e.g. "+proj=utm +zone=23 +south"."""
    return " ".join(f"+{key}" if value is True else f"+{key}={value}"
                    for key, value in _projection(crs).items())


def _geographic(crs):
    """(geographic CRS, semi-major axis, flattening) of a CRS's datum, from its WKT1."""
    from rasterio.crs import CRS

    wkt = crs.to_wkt()
    start = wkt.find("GEOGCS[")
    depth, end = 0, start
    for end in range(start, len(wkt)):
        depth += {"[": 1, "]": -1}.get(wkt[end], 0)
        if depth == 0 and wkt[end] == "]":
            break
    geogcs = wkt[start:end + 1]
    spheroid = re.search(r'SPHEROID\["[^"]*",([-+.\deE]+),([-+.\deE]+)', geogcs)
    if start < 0 or spheroid is None:
        raise CRSError(f"cannot find the datum's ellipsoid in {crs}")
    inverse_flattening = float(spheroid.group(2))
    return (CRS.from_wkt(geogcs), float(spheroid.group(1)),
            1 / inverse_flattening if inverse_flattening else 0.0)


def _to_geocentric(lon, lat, a, f):
    """Longitude, latitude (degrees, height 0) -> Earth-centred X, Y, Z on an ellipsoid."""
    lon, lat = np.radians(lon), np.radians(lat)
    e2 = f * (2 - f)
    n = a / np.sqrt(1 - e2 * np.sin(lat) ** 2)
    return (n * np.cos(lat) * np.cos(lon), n * np.cos(lat) * np.sin(lon),
            n * (1 - e2) * np.sin(lat))


def _to_geographic(x, y, z, a, f):
    """Earth-centred X, Y, Z -> longitude, latitude in degrees (iterated, to 1e-12 rad)."""
    e2 = f * (2 - f)
    p = np.hypot(x, y)
    lat = np.arctan2(z, p * (1 - e2))
    for _iteration in range(10):
        n = a / np.sqrt(1 - e2 * np.sin(lat) ** 2)
        height = p / np.cos(lat) - n
        lat = np.arctan2(z, p * (1 - e2 * n / (n + height)))
    return np.degrees(np.arctan2(y, x)), np.degrees(lat)


def geocentric_translation(points, src_crs, dst_crs, translation=SAD69_TO_SIRGAS2000):
    """A datum shift by three geocentric translations, computed here without PROJ's choice.

    The EPSG method "Geocentric translations": geographic coordinates on the
    source ellipsoid -> Earth-centred X, Y, Z -> add (tx, ty, tz) -> back to
    geographic on the target ellipsoid (heights taken as 0). PROJ is used only
    for the projection steps (UTM <-> geographic, same datum). Comparing the
    result with :func:`transform_points` shows which transformation PROJ chose.

    Parameters
    ----------
    points : (n, 2) array_like
        Map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        Projected or geographic CRSs on two datums.
    translation : (tx, ty, tz)
        Metres; EPSG:15485's SAD69 -> SIRGAS 2000 values by default.

    Returns
    -------
    ndarray
        (n, 2) map (x, y) in ``dst_crs``.

    Raises
    ------
    ValueError
        As :func:`transform_points`; if ``translation`` is not three finite numbers.

    Examples
    --------
    >>> p = [[775445.0, 7369105.0]]
    >>> here = geocentric_translation(p, "EPSG:29191", "EPSG:31981")
    >>> bool(np.abs(here - transform_points(p, "EPSG:29191", "EPSG:31981")).max() < 0.01)
    True
    """
    shift = np.asarray(translation, dtype=np.float64)
    if shift.shape != (3,) or not np.isfinite(shift).all():
        raise CRSError(f"translation must be three finite numbers (tx, ty, tz) in metres, "
                       f"got {translation!r}")
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    (src_geo, *src_ellipsoid), (dst_geo, *dst_ellipsoid) = _geographic(src), _geographic(dst)
    lonlat = transform_points(points, src, src_geo)
    xyz = np.array(_to_geocentric(lonlat[:, 0], lonlat[:, 1], *src_ellipsoid))
    lon, lat = _to_geographic(*(xyz + shift[:, np.newaxis]), *dst_ellipsoid)
    return transform_points(np.column_stack([lon, lat]), dst_geo, dst)


class CRSMapping:
    """Output map (x, y) in ``dst_crs`` -> source (col, row), through PROJ then a model.

    Parameters
    ----------
    to_source : callable or affine.Affine
        Source map (x, y) in ``src_crs`` -> source image (col, row).
    src_crs, dst_crs : rasterio.crs.CRS
    """

    def __init__(self, to_source, src_crs, dst_crs):
        self.to_source = to_source
        self.src_crs, self.dst_crs = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")

    def __call__(self, points):
        # every output cell, as gdalwarp does: cells beyond the CRS's area of use get nodata
        moved = _transform(as_points(points, "points"), self.dst_crs, self.src_crs)
        if callable(self.to_source):
            return self.to_source(moved)
        cols, rows = self.to_source @ (moved[:, 0], moved[:, 1])
        return np.column_stack([cols, rows])


def _as_raster(raster_or_path):
    import os

    import rasterio

    if isinstance(raster_or_path, Raster):
        return raster_or_path
    if not isinstance(raster_or_path, (str, os.PathLike)):
        shape = getattr(raster_or_path, "shape", None)
        raise TypeError(_(
            "raster_or_path must be an rsgeo.data.Raster or the path of a GeoTIFF, got "
            "{kind}{shape}; wrap an array as rsgeo.data.Raster(array, transform, crs, nodata, "
            "description)").format(kind=type(raster_or_path).__name__,
                                   shape="" if shape is None else f" of shape {shape}"))
    try:
        with rasterio.open(raster_or_path) as dataset:
            array = dataset.read()
            return Raster(array[0] if dataset.count == 1 else array, dataset.transform,
                          dataset.crs, dataset.nodata, "", str(raster_or_path))
    except rasterio.errors.RasterioIOError as error:
        raise DataError(f"cannot read {raster_or_path!r} as a raster ({error}); give an "
                        "rsgeo.data.Raster or the path of a GeoTIFF") from None


def reproject(raster, dst_crs, resolution=None, method="nearest", nodata=0):
    """A raster resampled into another CRS with rsgeo's GDAL-exact warp.

    Every output pixel centre is taken to the source CRS by PROJ (exactly,
    like ``gdalwarp -et 0``) and then to the source pixel by the inverse
    geotransform. The output grid is north-up over the transformed footprint,
    with the source's pixel size unless ``resolution`` is given.

    Parameters
    ----------
    raster : rsgeo.data.Raster
        With a CRS and a geotransform.
    dst_crs : str, int or rasterio.crs.CRS
    resolution : float, optional
        Output pixel size in ``dst_crs`` units.
    method : {"nearest", "bilinear", "cubic"}
    nodata : number
        Destination nodata (``gdalwarp -dstnodata``).

    Returns
    -------
    rsgeo.data.Raster
        In ``dst_crs``, with its transform and nodata.

    Raises
    ------
    ValueError
        For a raster without a CRS, a CRS PROJ does not know, a resolution
        that is not positive, or an unknown method.

    Examples
    --------
    >>> import affine
    >>> image = np.arange(100, dtype=np.uint8).reshape(10, 10)
    >>> raster = Raster(image, affine.Affine(20, 0, 500000, 0, -20, 7400000), as_crs(29193),
    ...                 None, "", "ramp")
    >>> reproject(raster, "EPSG:31983").crs.to_epsg()
    31983
    """
    from .resample import suggested_grid, warp  # Numba, loaded only by the verbs that warp

    check_choice(method, "method", _METHODS)
    if raster.crs is None:
        raise CRSError(f"raster {raster.name!r} has no CRS; reprojecting needs to know "
                       "which CRS its coordinates are in")
    src_crs, dst = as_crs(raster.crs, "raster.crs"), as_crs(dst_crs, "dst_crs")
    size = abs(raster.transform.a) if resolution is None else resolution

    def pixel_to_dst(points):
        xs, ys = raster.transform @ (points[:, 0], points[:, 1])
        return _transform(np.column_stack([xs, ys]), src_crs, dst)

    transform, shape = suggested_grid(raster.array.shape[-2:], pixel_to_dst, resolution=size)
    as_output_shape(shape, raster.array.dtype, _bands(raster.array), "shape")
    mapping = CRSMapping(~raster.transform, src_crs, dst)
    array = warp(raster.array, mapping, shape, transform, method=method, nodata=nodata)
    return Raster(array, transform, dst, nodata, f"{raster.description} reprojected to {dst}",
                  raster.name)


def _bands(array):
    """Bands of an image: its first axis when 3-D, else 1."""
    return array.shape[0] if array.ndim == 3 else 1


def _then_transform(pixel_to_map, src_crs, dst_crs):
    """Source pixel -> map in ``src_crs`` -> map in ``dst_crs``."""
    return lambda points: _transform(as_points(pixel_to_map(points), "points"), src_crs, dst_crs)


# How far the output may reach beyond the GCPs' hull, in GCP extents (transforms.outside_hull),
# before georeference warns, and before it refuses
_REACH_WARNING = 0.1
_REACH_LIMIT = 1.0


def _edge_points(shape, per_side=21):
    """(col, row) points along the four edges of an image of ``shape``, at pixel corners."""
    height, width = shape
    ratio = np.linspace(0.0, 1.0, per_side)
    cols = np.concatenate([ratio * width, ratio * width, np.zeros(per_side),
                           np.full(per_side, float(width))])
    rows = np.concatenate([np.zeros(per_side), np.full(per_side, float(height)),
                           ratio * height, ratio * height])
    return np.column_stack([cols, rows])


def _check_extrapolation(model, reverse, image_shape):
    """Warn or refuse when the image's edges land far beyond the GCPs of an exploding model.

    A polynomial of degree 2 or 3, or a projective model, is controlled by its GCPs
    only inside them: beyond, it grows like a power of the distance (degree 3 on GCPs
    clustered in 500 m of a 10 km scene: 0.14 px RMS on the GCPs, thousands of pixels off at the
    corners, an output of 450 m pixels with 100 valid cells). The output grid is the
    footprint of the image's edges taken to the map by ``reverse``; its reach is measured
    by ``model.outside_gcps``. Order 1, linear, Helmert and TPS (affine outside its GCPs)
    extrapolate linearly and are not checked.
    """
    kind = getattr(model, "kind", None)     # the fitted kind, also for kind=2 (a polynomial)
    if kind == "polynomial" and model.order >= 2:
        what = _("a polynomial of degree {order}").format(order=model.order)
        remedy = _("use order=1, which extrapolates linearly")
    elif kind == "projective":
        what = _("a projective model")
        remedy = _("use kind='polynomial' with order=1")
    else:
        return
    edges = _edge_points(image_shape)
    footprint = np.asarray(reverse(edges), dtype=np.float64)
    reach = np.full(len(edges), np.inf)
    finite = np.isfinite(footprint).all(axis=1)
    if finite.any():
        reach[finite] = model.outside_gcps(footprint[finite])
    farthest = int(np.argmax(reach))
    if reach[farthest] <= _REACH_WARNING:
        return
    gcps_extent = float(np.ptp(model.src, axis=0).max())
    where = _(
        "the output grid reaches {reach:.3g} GCP extents ({distance:.6g} map units) beyond the "
        "GCPs' hull (image point (col, row) {edge} lands at map {point})").format(
            reach=reach[farthest], distance=reach[farthest] * gcps_extent,
            edge=edges[farthest].round(1).tolist(),
            point=footprint[farthest].round(1).tolist())
    if reach[farthest] > _REACH_LIMIT:
        raise GCPError(_(
            "{where}: {what} explodes outside its GCPs, so the output's size, pixel size "
            "and most of its cells would come from extrapolation, not from the GCPs; add GCPs "
            "near the image's edges and corners, or {remedy}").format(
                where=where, what=what, remedy=remedy))
    warnings.warn(_(
        "{where}: {what} is not controlled by its GCPs there and its error grows fast with "
        "the distance (see rsgeo.accuracy.predicted_error_map); add GCPs near the image's edges "
        "and corners, or {remedy}").format(where=where, what=what, remedy=remedy),
        ExtrapolationWarning, stacklevel=3)


def _fit(gcps, kind, order):
    """Map -> image model of the enabled GCPs."""
    if kind == "polynomial":
        return gcps.fit(1 if order is None else order)
    fit_transform = getattr(_transforms, "fit_transform", None)   # the other model kinds
    if fit_transform is None:
        raise GCPError(f"kind {kind!r} is not available; use kind='polynomial' with an order")
    image_xy, map_xy = gcps.image_xy[gcps.enabled], gcps.map_xy[gcps.enabled]
    if kind == "tps":
        # GDAL's TPS transformer: the image -> map spline, inverted point by point (its
        # GDALGenericInverse2D steps), not a second spline fitted the other way
        return fit_transform(image_xy, map_xy, kind).inverse()
    return fit_transform(map_xy, image_xy, kind, order)


def georeference(raster_or_path, gcps, kind="polynomial", order=1, resolution=None,
                 method="nearest", nodata=0, dst_crs=None):
    """The corrected image a user makes: fit the GCPs, choose the grid, warp.

    The same run as ``gdalwarp -order N -et 0 -r METHOD -dstnodata NODATA``
    on an image carrying GCPs: the model maps output map (x, y) to source
    (col, row) (through PROJ first when ``dst_crs`` differs from the GCPs'
    CRS, as GDAL chains them), and the output grid is GDAL's suggestion
    (footprint extent, diagonal-preserving pixel size) or ``resolution``.

    Parameters
    ----------
    raster_or_path : rsgeo.data.Raster or path
        The uncorrected image (its own transform and CRS are ignored).
    gcps : rsgeo.gcp.GCPSet
        With the map coordinates' CRS in ``gcps.crs`` when ``dst_crs`` is given.
    kind : str
        ``"polynomial"``, or another kind that ``rsgeo.transforms.fit_transform`` knows.
    order : {1, 2, 3} or None
        Polynomial degree (None for kinds without one, e.g. "helmert").
    resolution : float, optional
        Output pixel size in map units (``gdalwarp -tr``).
    method : {"nearest", "bilinear", "cubic"}
    nodata : number
        Destination nodata.
    dst_crs : str, int or rasterio.crs.CRS, optional
        Output CRS; the GCPs' CRS by default.

    Returns
    -------
    rsgeo.data.Raster
        With transform, CRS and nodata; save it with :func:`rsgeo.data.save`.

    Raises
    ------
    ValueError
        Too few or collinear GCPs, a GCP set without a CRS when ``dst_crs`` is
        given, a CRS PROJ does not know, a resolution that is not positive, or
        an unknown method. ``GCPError`` when a polynomial of order 2 or 3 or a
        projective model puts the image's edges more than one GCP extent (the
        larger side of the GCPs' bounding box) beyond the GCPs' convex hull
        (:meth:`rsgeo.transforms.GeometricModel.outside_gcps`): such a model
        explodes outside its GCPs, and the output grid would be its
        extrapolation.

    Warns
    -----
    UserWarning
        When such a model puts the image's edges more than 0.1 GCP extent
        beyond the GCPs' hull: the corrected image's edges are extrapolated.
        Order 1, linear, Helmert and TPS models extrapolate linearly and are
        not checked.

    Examples
    --------
    >>> from rsgeo import data
    >>> corrected = georeference(data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc"),
    ...                          order=1, resolution=20.0)
    >>> corrected.transform.a, corrected.crs.to_epsg()
    (20.0, 29191)
    """
    from .resample import suggested_grid, warp  # Numba, loaded only by the verbs that warp

    check_choice(method, "method", _METHODS)
    if not isinstance(gcps, GCPSet):
        raise TypeError(f"gcps must be an rsgeo.gcp.GCPSet, got {type(gcps).__name__}")
    raster = _as_raster(raster_or_path)
    model = _fit(gcps, kind, order)
    reverse = (model.reverse() if hasattr(model, "reverse") else model.inverse())
    _check_extrapolation(model, reverse, raster.array.shape[-2:])
    pixel_to_map = reverse
    src_crs = None if gcps.crs is None else as_crs(gcps.crs, "gcps.crs")
    mapping = model
    if dst_crs is not None:
        dst = as_crs(dst_crs, "dst_crs")
        if src_crs is None:
            raise CRSError("the GCPs have no CRS (gcps.crs is None); set it to reproject "
                           "into dst_crs")
        if dst != src_crs:
            pixel_to_map = _then_transform(reverse, src_crs, dst)
            mapping = CRSMapping(model, src_crs, dst)
        src_crs = dst
    # gdalwarp's suggested output grid (GDALSuggestedWarpOutput2; -tr when a resolution is given)
    transform, shape = suggested_grid(raster.array.shape[-2:], pixel_to_map, resolution=resolution)
    as_output_shape(shape, raster.array.dtype, _bands(raster.array), "shape")
    array = warp(raster.array, mapping, shape, transform, method=method, nodata=nodata)
    return Raster(array, transform, src_crs, nodata,
                  f"{raster.name or 'image'} georeferenced: {kind}"
                  f"{f' order {order}' if order is not None else ''}, {method}",
                  raster.name)
