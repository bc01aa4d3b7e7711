"""Heights above the ellipsoid and above the geoid: the vertical datum of a DEM.

A DEM such as SRTM gives **orthometric** heights H, above the geoid (mean sea level, EGM96 for
SRTM). GNSS and the RPCs of every satellite give **ellipsoidal** heights h, above WGS 84's
ellipsoid. The two differ by the geoid undulation N:

    h = H + N

N is tens of metres: over the box rsgeo's grid covers (Brazil and its neighbours,
:func:`geoid_coverage`) EGM96 goes from about -40 m to +50 m, and at Olinda it is -5.5 m.
rsgeo ships the global EGM96 (the geoid SRTM's heights are given on) cut to that box, from
Debian's ``proj-data`` (``rsgeo/data/README.md``), and uses it through PROJ. It ships no other
model. EGM2008, the geoid of the Copernicus DEM's heights, is not in Debian's ``proj-data``,
nor in any PyPI package we found. IBGE's model for Brazil, hgeoHNOR2020 (2021, which replaced
MAPGEO2015), converts h to the **normal** heights that Brazil's levelling network has published
since its REALT-2018 readjustment: H_N = h - eta, with eta IBGE's conversion factor, which plays
the part of the height anomaly (the quasigeoid's height above the ellipsoid). PROJ's database
(PROJ 9.5) lists no grid of it, and its terms of use were not checked, so EGM96 stands in for
it; how far the two differ was not measured here.

Examples
--------
>>> from rsgeo import heights
>>> n = heights.geoid_undulation([-34.85], [-8.0])            # Olinda
>>> bool(-6.0 < n[0] < -5.0)
True
"""

import struct
from functools import cache

import numpy as np

from ._proj import GRIDS, transformer
from .errors import CRSError, DataError, GridError
from .language import _, prose_number

__all__ = ["GEOIDS", "VERTICAL_DATUMS", "geoid_undulation", "geoid_coverage",
           "geoid_on_grid", "add_geoid", "to_ellipsoidal", "check_vertical"]

#: The geoids rsgeo ships: name -> (source CRS, target CRS, grid file) of PROJ's operation.
#: EGM96 height (EPSG:5773) on WGS 84: PROJ applies "WGS 84 to EGM96 height (1)"
#: (EPSG:10084), the grid egm96_15.gtx, from WGS 84 3-D (EPSG:4979).
GEOIDS = {"EGM96": ("EPSG:4979", "EPSG:4326+5773", "egm96_15.gtx")}

#: What a DEM's heights can be above: the ellipsoid itself or one of :data:`GEOIDS`.
VERTICAL_DATUMS = ("ellipsoidal", *GEOIDS)

# The most cells geoid_on_grid computes (2**30: 8 GiB of float64 N); a larger grid is refused
# with its size rather than left to fail in NumPy's allocation (a MemoryError of terabytes)
_MAX_GRID_CELLS = 2 ** 30


def _numbers(value, name):
    """``value`` as a float64 array; strings and booleans are refused, not read as numbers."""
    array = np.asarray(value)
    if array.dtype.kind not in "iuf":
        kind = (_("text") if array.dtype.kind in "US" else _("booleans")
                if array.dtype.kind == "b" else type(value).__name__)
        raise TypeError(_("{name} must be numbers (degrees or metres), got {kind} {value!r}; "
                          "give int or float values, not text or True/False").format(
                              name=name, kind=kind, value=value))
    return array.astype(np.float64)


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
    south, west, dlat, dlon, values = _grid(geoid)
    rows, cols = values.shape
    return (west, south, west + (cols - 1) * dlon, south + (rows - 1) * dlat)


@cache
def _grid(geoid):
    """(south, west, dlat, dlon, N) of a shipped GTX grid; N (rows, cols), south row first.

    GTX (NOAA's vertical grid format, which PROJ reads): a 40-byte big-endian header, south
    and west edges and the latitude and longitude steps (degrees, 4 doubles), rows and columns
    (2 int32), then rows x cols big-endian float32 heights, the southernmost row first.
    """
    _, _, name = _geoid(geoid)
    raw = (GRIDS / name).read_bytes()
    south, west, dlat, dlon, rows, cols = struct.unpack(">4d2i", raw[:40])
    if len(raw) != 40 + 4 * rows * cols:
        raise DataError(_("{name} holds {size} bytes, not the 40 + 4 x {rows} x {cols} its "
                          "header says: the shipped grid is damaged; reinstall rsgeo").format(
                              name=name, size=len(raw), rows=rows, cols=cols))
    values = np.frombuffer(raw, dtype=">f4", count=rows * cols, offset=40)
    values = values.astype(np.float64).reshape(rows, cols)
    values.flags.writeable = False
    return south, west, dlat, dlon, values


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
    TypeError
        If ``lon`` or ``lat`` is text or a boolean, not numbers.

    Examples
    --------
    >>> round(float(geoid_undulation(-47.0, -15.0)), 2)                     # Brasília
    -15.03
    """
    src, dst, _name = _geoid(geoid)
    lon, lat = _inside(_numbers(lon, "lon"), _numbers(lat, "lat"), geoid)
    if lon.size == 0:
        return np.zeros(lon.shape)
    proj = transformer(src, dst)
    _x, _y, height = proj.transform(lon.ravel(), lat.ravel(), np.zeros(lon.size))
    used = proj.get_last_used_operation()
    # PROJ's ballpark (N = 0 everywhere) names EGM96 too: the grid must be what was applied
    if geoid not in used.description or "ballpark" in used.description.lower():
        raise DataError(_(
            "PROJ did not apply the {geoid} grid (it used {operation!r}); is {name} in "
            "rsgeo/data/proj?").format(geoid=geoid, operation=used.description, name=_name))
    height = np.asarray(height, dtype=np.float64)
    if not np.isfinite(height).all():
        raise CRSError(_(
            "PROJ gave no geoid height (inf or nan) at {count} of {n} points with the {geoid} "
            "grid {name}: the grid could not be read; reinstall rsgeo, whose "
            "rsgeo/data/proj holds it").format(count=int((~np.isfinite(height)).sum()),
                                                n=height.size, geoid=geoid, name=_name))
    # the height above the geoid of a point on the ellipsoid (h = 0) is H = -N
    return -height.reshape(lon.shape)


def _inside(lon, lat, geoid):
    """lon and lat as float64 arrays of one shape, refused if a point is outside the grid."""
    lon = _numbers(lon, "lon")
    lat = _numbers(lat, "lat")
    if lon.shape != lat.shape:
        raise GridError(_("lon and lat must have the same shape, got {a} and {b}").format(
            a=lon.shape, b=lat.shape))
    west, south, east, north = geoid_coverage(geoid)
    # written so that NaN is outside too
    outside = ~((lon >= west) & (lon <= east) & (lat >= south) & (lat <= north))
    if outside.any():
        k = int(np.flatnonzero(outside.ravel())[0])
        raise GridError(_(
            "{n} point(s) are outside the shipped {geoid} grid (longitude {west:g} to {east:g}, "
            "latitude {south:g} to {north:g}), e.g. ({lon}, {lat}); rsgeo ships the geoid over "
            "Brazil only: give WGS 84 longitude and latitude in degrees inside it").format(
                n=int(outside.sum()), geoid=geoid, west=west, east=east, south=south,
                north=north, lon=lon.ravel()[k], lat=lat.ravel()[k]))
    return lon, lat


def _bilinear(lon, lat, geoid):
    """N read from the GTX grid by rsgeo itself: bilinear between the four nodes around each
    point, as PROJ's vertical grid shift does (tests/test_heights.py: the two agree to far
    below a millimetre). No coverage check: the caller has made it (:func:`_inside`)."""
    south, west, dlat, dlon, values = _grid(geoid)
    rows, cols = values.shape
    x = (lon - west) / dlon
    y = (lat - south) / dlat
    # the node to the south-west; on the east or north edge, the last cell (weight 1 there)
    i = np.clip(np.floor(x).astype(np.intp), 0, cols - 2)
    j = np.clip(np.floor(y).astype(np.intp), 0, rows - 2)
    fx, fy = x - i, y - j
    south_row = values[j, i] * (1 - fx) + values[j, i + 1] * fx
    north_row = values[j + 1, i] * (1 - fx) + values[j + 1, i + 1] * fx
    return south_row * (1 - fy) + north_row * fy


# cells of the grid whose longitude and latitude are computed at a time in geoid_on_grid
_STRIP_CELLS = 2 ** 18


def geoid_on_grid(transform, shape, crs=None, geoid="EGM96"):
    """The geoid undulation N at the centre of every cell of a grid, e.g. of a DEM.

    Each cell centre's longitude and latitude (by PROJ when ``crs`` is projected), then N by
    bilinear interpolation in the shipped grid, read by rsgeo (the same numbers as PROJ's
    :func:`geoid_undulation`, to far below a millimetre, without PROJ's cost per point).
    ``dem + geoid_on_grid(...)`` turns a DEM above the geoid into one above the ellipsoid.

    Parameters
    ----------
    transform : affine.Affine or sequence of 6 numbers
        The grid's geotransform (pixel corner -> map), an affine.Affine or GDAL's 6 numbers.
    shape : (rows, cols)
        The grid's size.
    crs : str, int or rasterio CRS, optional
        The grid's CRS; None is EPSG:4326 (longitude, latitude in degrees).
    geoid : {"EGM96"}
        The geoid model.

    Returns
    -------
    ndarray
        N in metres, float64, ``shape``.

    Raises
    ------
    GridError
        If a cell centre is outside the shipped grid (:func:`geoid_coverage`), or the grid
        has more than 2**30 cells (8 GiB of N).
    TypeError, ValueError
        If the transform, shape or CRS is not one (as :func:`rsgeo.data.save` reads them).

    Examples
    --------
    >>> import affine
    >>> n = geoid_on_grid(affine.Affine(0.01, 0, -34.9, 0, -0.01, -7.95), (3, 4))
    >>> n.shape, bool((-5.5 < n).all() and (n < -5.3).all())
    ((3, 4), True)
    """
    from .validation import as_shape

    if transform is None:
        raise GridError(_("transform is None; give the grid's affine.Affine (pixel corner -> "
                          "map)"))
    rows, cols = as_shape(shape, "shape")
    if rows * cols > _MAX_GRID_CELLS:
        raise GridError(_(
            "shape {shape} is {cells:,} cells, more than the {limit:,} geoid_on_grid computes "
            "(8 GiB of float64): give a smaller grid, or add N strip by strip of rows").format(
                shape=(rows, cols), cells=prose_number(rows * cols),
                limit=prose_number(_MAX_GRID_CELLS)))
    return add_geoid(np.zeros((rows, cols)), transform, crs, geoid)


def add_geoid(heights, transform, crs, geoid):
    """Add the geoid undulation N at each cell centre of a grid to ``heights``, in place.

    Strip by strip of rows, so that a DEM becomes H + N without a second array of its size
    (:func:`geoid_on_grid` is the same on zeros).

    Parameters
    ----------
    heights : ndarray
        float64, (rows, cols): orthometric heights H, made ellipsoidal h = H + N.
    transform : affine.Affine
        The grid's geotransform (pixel corner -> map).
    crs : str, rasterio.crs.CRS or None
        The grid's CRS; None is EPSG:4326.
    geoid : str
        The geoid model (``"EGM96"``, ...), as :func:`check_vertical` accepts it.

    Returns
    -------
    ndarray
        ``heights``, changed.
    """
    from .crs import as_crs
    from .validation import as_affine

    _geoid(geoid)
    gt = as_affine(transform, "transform", gdal_tuple=True)
    crs = as_crs("EPSG:4326" if crs is None else crs, "crs")
    to_lon_lat = None if crs.to_epsg() == 4326 else transformer(crs.to_wkt(), "EPSG:4326")
    rows, cols = heights.shape
    strip = max(1, _STRIP_CELLS // max(cols, 1))
    centre_cols = np.arange(cols) + 0.5
    for start in range(0, rows, strip):
        centre_rows = (np.arange(start, min(start + strip, rows)) + 0.5)[:, None]
        x = gt.c + centre_cols * gt.a + centre_rows * gt.b
        y = gt.f + centre_cols * gt.d + centre_rows * gt.e
        if to_lon_lat is not None:
            x, y = (np.reshape(v, x.shape) for v in to_lon_lat.transform(x.ravel(), y.ravel()))
        lon, lat = _inside(*np.broadcast_arrays(x, y), geoid)
        heights[start:start + len(centre_rows)] += _bilinear(lon, lat, geoid)
    return heights


def _stated_vertical(crs):
    """What a CRS says its heights are above: a geoid of :data:`GEOIDS`, "ellipsoidal" (a 3-D
    geographic CRS), another vertical datum's name, or None when it says nothing (2-D)."""
    from pyproj import CRS

    try:
        crs = CRS.from_wkt(crs.to_wkt()) if hasattr(crs, "to_wkt") else CRS.from_user_input(crs)
    except Exception:                 # pyproj's CRSError: nothing it can say
        return None
    if crs.is_compound:
        vertical = crs.sub_crs_list[-1]
        names = f"{vertical.name} {vertical.datum.name if vertical.datum else ''}"
        return next((geoid for geoid in GEOIDS if geoid in names), vertical.name)
    if crs.is_geographic and len(crs.axis_info) == 3:
        return "ellipsoidal"
    return None


def check_vertical(vertical, name="vertical", crs=None, crs_name="crs"):
    """``vertical`` if it is one of :data:`VERTICAL_DATUMS`, else a GridError that asks.

    Parameters
    ----------
    vertical : str or None
        What heights are above: "ellipsoidal" or a geoid ("EGM96").
    name : str
        The argument's name, for the message.
    crs : rasterio.crs.CRS or str, optional
        The heights' CRS: when it states a vertical datum (a compound CRS such as
        ``"EPSG:4326+5773"``, WGS 84 + EGM96 height, or a 3-D geographic CRS), it must be
        ``vertical``'s.
    crs_name : str
        The CRS argument's name, for the message.

    Returns
    -------
    str

    Raises
    ------
    GridError
        If ``vertical`` is None or not one of :data:`VERTICAL_DATUMS`.
    CRSError
        If ``crs`` states another vertical datum than ``vertical``.

    Examples
    --------
    >>> check_vertical("EGM96")
    'EGM96'
    >>> check_vertical("EGM96", crs="EPSG:4326+5773")
    'EGM96'
    """
    if not isinstance(vertical, str) or vertical not in VERTICAL_DATUMS:
        raise GridError(_(
            "{name} must be one of {known}, got {vertical!r}: RPCs and GNSS take heights above "
            "the WGS 84 ellipsoid; say what the heights are above (SRTM and Copernicus DEMs "
            "are above a geoid, EGM96 and EGM2008 respectively, not the ellipsoid; rsgeo ships "
            "EGM96 over Brazil, not EGM2008)").format(
                name=name, known=", ".join(repr(v) for v in VERTICAL_DATUMS), vertical=vertical))
    stated = None if crs is None else _stated_vertical(crs)
    if stated is not None and stated != vertical:
        raise CRSError(_(
            "{name} is {vertical!r} but {crs_name} says the heights are above {stated!r}: "
            "the two contradict each other; give {crs_name} without a vertical part (e.g. "
            "'EPSG:4326') and say in {name} what the heights are above, or give the {name} "
            "that {crs_name} states").format(name=name, vertical=vertical, crs_name=crs_name,
                                             stated=stated))
    return vertical


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
        If ``vertical`` is not one of :data:`VERTICAL_DATUMS`, a point is outside the grid,
        or ``lon`` and ``lat`` are not of ``height``'s shape.
    TypeError
        If a value is text or a boolean, not a number.

    Examples
    --------
    >>> h = to_ellipsoidal([10.0], [-34.85], [-8.0], "EGM96")
    >>> bool(4.0 < h[0] < 5.0)                          # 10 m above sea level, N = -5.5 m
    True
    """
    check_vertical(vertical)
    height = _numbers(height, "height")
    lon, lat = _numbers(lon, "lon"), _numbers(lat, "lat")
    if vertical == "ellipsoidal":
        return height.copy()
    try:
        lon = np.broadcast_to(lon, height.shape)
        lat = np.broadcast_to(lat, height.shape)
    except ValueError:
        raise GridError(_(
            "height, lon and lat must have one shape (a height per point), got height "
            "{height}, lon {lon} and lat {lat}").format(
                height=height.shape, lon=lon.shape, lat=lat.shape)) from None
    return height + geoid_undulation(lon, lat, vertical)

