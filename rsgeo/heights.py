"""Heights above the ellipsoid and above the geoid: the vertical datum of a DEM.

A DEM such as SRTM gives **orthometric** heights H, above the geoid (mean sea level, EGM96 for
SRTM). GNSS and the RPCs of every satellite give **ellipsoidal** heights h, above WGS 84's
ellipsoid. The two differ by the geoid undulation N:

    h = H + N

N is between -106 m and +85 m on Earth and between about -30 m and +20 m in Brazil; at Olinda it
is -5.5 m. IBGE's own geoid model for Brazil is MAPGEO2015 (about 0.2 m accuracy); it is not in
PROJ's grid collection, so rsgeo ships the global EGM96 (1 m or so) cut to Brazil, from Debian's
``proj-data`` (``rsgeo/data/README.md``), and uses it through PROJ.

Examples
--------
>>> from rsgeo import heights
>>> n = heights.geoid_undulation([-34.85], [-8.0])            # Olinda
>>> bool(-6.0 < n[0] < -5.0)
True
"""

import struct

import numpy as np

from ._i18n import _
from ._proj import GRIDS, transformer
from .errors import DataError, GridError

__all__ = ["GEOIDS", "VERTICAL_DATUMS", "geoid_undulation", "geoid_coverage",
           "to_ellipsoidal"]

# EGM96 height (EPSG:5773) on WGS 84: PROJ applies "WGS 84 to EGM96 height (1)" (EPSG:10084),
# the grid egm96_15.gtx, from WGS 84 3-D (EPSG:4979).
GEOIDS = {"EGM96": ("EPSG:4979", "EPSG:4326+5773", "egm96_15.gtx")}

# what a DEM's heights can be above: the ellipsoid itself or one of GEOIDS
VERTICAL_DATUMS = ("ellipsoidal", *GEOIDS)


def geoid_coverage(geoid="EGM96"):
    """The (west, south, east, north) box, in degrees, the shipped geoid grid covers.

    Parameters
    ----------
    geoid : {"EGM96"}
        The geoid model.

    Returns
    -------
    tuple of float
        West, south, east, north, from the grid file's header.

    Examples
    --------
    >>> geoid_coverage()
    (-76.0, -36.0, -28.0, 7.0)
    """
    _, _, name = _geoid(geoid)
    with open(GRIDS / name, "rb") as grid:
        south, west, dlat, dlon, rows, cols = struct.unpack(">4d2i", grid.read(40))
    return (west, south, west + (cols - 1) * dlon, south + (rows - 1) * dlat)


def _geoid(geoid):
    if geoid not in GEOIDS:
        raise GridError(_("unknown geoid {geoid!r}; rsgeo ships {known}").format(
            geoid=geoid, known=", ".join(GEOIDS)))
    return GEOIDS[geoid]


def geoid_undulation(lon, lat, geoid="EGM96"):
    """The geoid's height N above the WGS 84 ellipsoid, by PROJ with the shipped grid.

    Parameters
    ----------
    lon, lat : array_like
        WGS 84 longitude and latitude in degrees, of the same shape.
    geoid : {"EGM96"}
        The geoid model.

    Returns
    -------
    ndarray
        N in metres, the shape of ``lon``: an ellipsoidal height is h = H + N.

    Raises
    ------
    GridError
        If a point is outside the shipped grid (:func:`geoid_coverage`): PROJ would return
        N = 0 there without a word, a silent error of up to 100 m.

    Examples
    --------
    >>> round(float(geoid_undulation(-47.0, -15.0)), 2)                     # Brasília
    -15.03
    """
    src, dst, _name = _geoid(geoid)
    lon = np.asarray(lon, dtype=np.float64)
    lat = np.asarray(lat, dtype=np.float64)
    if lon.shape != lat.shape:
        raise GridError(_("lon and lat must have the same shape, got {a} and {b}").format(
            a=lon.shape, b=lat.shape))
    west, south, east, north = geoid_coverage(geoid)
    outside = ~((lon >= west) & (lon <= east) & (lat >= south) & (lat <= north))
    if outside.any():
        k = int(np.flatnonzero(outside.ravel())[0])
        raise GridError(_(
            "{n} point(s) are outside the shipped {geoid} grid (longitude {west:g} to {east:g}, "
            "latitude {south:g} to {north:g}), e.g. ({lon}, {lat}); rsgeo ships the geoid over "
            "Brazil only: give WGS 84 longitude and latitude in degrees inside it").format(
                n=int(outside.sum()), geoid=geoid, west=west, east=east, south=south,
                north=north, lon=lon.ravel()[k], lat=lat.ravel()[k]))
    if lon.size == 0:
        return np.zeros(lon.shape)
    proj = transformer(src, dst)
    _x, _y, height = proj.transform(lon.ravel(), lat.ravel(), np.zeros(lon.size))
    used = proj.get_last_used_operation()
    if geoid not in used.description:
        raise DataError(_(
            "PROJ did not apply the {geoid} grid (it used {operation!r}); is {name} in "
            "rsgeo/data/proj?").format(geoid=geoid, operation=used.description, name=_name))
    # the height above the geoid of a point on the ellipsoid (h = 0) is H = -N
    return -np.asarray(height, dtype=np.float64).reshape(lon.shape)


def to_ellipsoidal(height, lon, lat, vertical):
    """Heights above the ellipsoid from heights on a stated vertical datum (h = H + N).

    Parameters
    ----------
    height : array_like
        Heights in metres.
    lon, lat : array_like
        WGS 84 longitude and latitude of each height, degrees, the shape of ``height``.
    vertical : {"ellipsoidal", "EGM96"}
        What the heights are above: the ellipsoid already (returned unchanged) or a geoid.

    Returns
    -------
    ndarray
        Ellipsoidal heights in metres.

    Raises
    ------
    GridError
        If ``vertical`` is not one of :data:`VERTICAL_DATUMS`, or a point is outside the grid.

    Examples
    --------
    >>> h = to_ellipsoidal([10.0], [-34.85], [-8.0], "EGM96")
    >>> bool(4.0 < h[0] < 5.0)                          # 10 m above sea level, N = -5.5 m
    True
    """
    if vertical not in VERTICAL_DATUMS:
        raise GridError(_(
            "vertical must be one of {known}, got {vertical!r}: say what the heights are "
            "above (a DEM such as SRTM is above EGM96)").format(
                known=", ".join(repr(v) for v in VERTICAL_DATUMS), vertical=vertical))
    height = np.asarray(height, dtype=np.float64)
    if vertical == "ellipsoidal":
        return height.copy()
    lon = np.broadcast_to(np.asarray(lon, dtype=np.float64), height.shape)
    lat = np.broadcast_to(np.asarray(lat, dtype=np.float64), height.shape)
    return height + geoid_undulation(lon, lat, vertical)

