"""A local tangent plane: map coordinates and heights to a Cartesian east, north, up frame.

Map coordinates are not a Cartesian frame. A projection stretches distances by its scale factor
(UTM's is 0.9996 on the central meridian and about 1.0001 some 200 km from it), its grid north
turns away from true north by the meridian convergence, and heights are measured along the
ellipsoid's normal, which tilts from point to point as the Earth curves. Photogrammetry needs a
frame in which straight lines are straight (the collinearity equations, chapter 4d): a **local
tangent plane**, or topocentric frame, whose origin is a point near the scene, whose east and
north axes lie in the plane that touches the ellipsoid there, and whose up axis is the
ellipsoid's normal at the origin (EPSG's method 9837, "Geographic/topocentric conversions").

:func:`to_local_tangent_plane` takes points given as map coordinates and ellipsoidal heights in
a CRS (projected or geographic) to that frame, through PROJ: the CRS's inverse projection to
longitude and latitude on its own ellipsoid, then Earth-centred Cartesian coordinates
(``+proj=cart``), then east, north and up about the origin (``+proj=topocentric``). There is no
datum change: the frame is tied to the CRS's ellipsoid. :func:`from_local_tangent_plane` is its
inverse.

The heights must be **ellipsoidal** (above the CRS's ellipsoid, as GNSS gives them); heights
above the geoid (a DEM's, or a levelled benchmark's) are converted first
(:func:`rsgeo.heights.to_ellipsoidal`).

References
----------
IOGP (2019). Geomatics Guidance Note 7, part 2: Coordinate Conversions and Transformations
including Formulas, §4.1.2 (Geographic/topocentric conversions, EPSG method 9837), with the
worked example that tests/test_local_frame.py checks.
PROJ, the ``topocentric`` and ``cart`` operations (https://proj.org/operations/).

Examples
--------
>>> from rsgeo.local_frame import from_local_tangent_plane, to_local_tangent_plane
>>> origin = (292_500.0, 9_114_000.0, 0.0)           # SIRGAS 2000 / UTM 25S, Olinda
>>> enu = to_local_tangent_plane([[293_500.0, 9_114_000.0, 100.0]], "EPSG:31985", origin)
>>> enu.round(2).tolist()      # east, north (grid north is not north), up (the Earth curves)
[[999.87, -4.58, 99.92]]
>>> from_local_tangent_plane(enu, "EPSG:31985", origin).round(6).tolist()
[[293500.0, 9114000.0, 100.0]]
"""

import numpy as np

from .errors import CRSError, RsgeoError
from .language import N_, _
from .validation import as_crs, as_points_3d

__all__ = ["to_local_tangent_plane", "from_local_tangent_plane"]

#: what the three columns of points and origin are, for the messages
_HEIGHTS = N_("x, y, height")


def _operations(crs, origin):
    """(CRS -> its geographic CRS, geographic -> topocentric) pyproj Transformers, and the
    CRS's name."""
    from pyproj import CRS, Transformer

    checked = CRS.from_wkt(as_crs(crs).to_wkt())
    if checked.is_compound or checked.is_geocentric or checked.geodetic_crs is None:
        raise CRSError(_("crs {crs} is not a projected or geographic CRS with ellipsoidal "
                         "heights; give map coordinates in one (e.g. 'EPSG:31985', SIRGAS "
                         "2000 / UTM 25S) and heights above its ellipsoid (convert heights "
                         "above the geoid with rsgeo.heights.to_ellipsoidal)").format(
                             crs=checked.name))
    to_geographic = Transformer.from_crs(checked, checked.geodetic_crs, always_xy=True)
    origin = as_points_3d(origin, "origin", _HEIGHTS)
    if len(origin) != 1:
        raise RsgeoError(_("origin must be one (x, y, height) point, got {n}").format(
            n=len(origin)))
    lon, lat = to_geographic.transform(origin[0, 0], origin[0, 1])
    if not (np.isfinite(lon) and np.isfinite(lat) and abs(lat) <= 90):
        raise CRSError(_("origin ({x}, {y}) has no longitude and latitude in {crs}").format(
            x=origin[0, 0], y=origin[0, 1], crs=checked.name))
    ellipsoid = checked.ellipsoid
    a, rf = float(ellipsoid.semi_major_metre), float(ellipsoid.inverse_flattening)
    shape = f"+a={a!r} +rf={rf!r}" if rf else f"+R={a!r}"      # rf = 0: a sphere
    topocentric = Transformer.from_pipeline(
        f"+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
        f"+step +proj=cart {shape} +step +proj=topocentric {shape} "
        f"+lon_0={float(lon)!r} +lat_0={float(lat)!r} +h_0={float(origin[0, 2])!r}")
    return to_geographic, topocentric, checked.name


def to_local_tangent_plane(points, crs, origin):
    """Map coordinates and ellipsoidal heights -> east, north, up in a local tangent plane.

    Parameters
    ----------
    points : (n, 3) array_like
        (x, y, h): map coordinates in ``crs`` (easting and northing, or longitude and latitude
        in degrees for a geographic CRS) and heights in metres above the CRS's ellipsoid. A
        single (3,) point is taken as one row.
    crs : str, int or rasterio.crs.CRS
        A projected or geographic CRS, e.g. ``"EPSG:31985"`` (SIRGAS 2000 / UTM zone 25S).
    origin : (3,) array_like
        The tangent plane's origin, (x, y, h) in ``crs`` as ``points``: a point near the
        scene's centre, on or near the ground.

    Returns
    -------
    ndarray, shape (n, 3)
        East, north and up in metres from the origin: a right-handed Cartesian frame, north
        along the meridian through the origin, up along the ellipsoid's normal there.

    Raises
    ------
    TypeError
        If the points are not real numbers.
    rsgeo.errors.RsgeoError
        If ``points`` is not (n, 3) or not finite, or ``origin`` is not one point.
    rsgeo.errors.CRSError
        If ``crs`` is unknown, compound (orthometric heights), geocentric, or the origin or a
        point has no geographic position in it.

    See Also
    --------
    from_local_tangent_plane : The inverse.

    Notes
    -----
    In UTM the frame's axes differ from the grid's by the scale factor k (a UTM distance is k
    times the ground's on the ellipsoid), the meridian convergence (grid north against the
    frame's north), and the Earth's curvature: a point at height h a distance d from the origin
    has an up coordinate about h - d²/(2R). Over a 1.5 km photograph at Olinda k - 1 is 1.3e-4,
    0.2 m over the footprint; treating UTM and heights as Cartesian puts a frame camera's
    projection centre 0.4 m too high (chapter 4d).

    References
    ----------
    IOGP Geomatics Guidance Note 7-2, §4.1.2 (EPSG method 9837).

    Examples
    --------
    EPSG's worked example (Guidance Note 7-2): origin 55° N, 5° E, 200 m on WGS 84:

    >>> point = [[2.12955, 53.80939444, 73.0]]          # 2°07'46.38" E, 53°48'33.82" N, 73 m
    >>> to_local_tangent_plane(point, "EPSG:4979", (5.0, 55.0, 200.0)).round(3).tolist()
    [[-189013.869, -128642.04, -4220.171]]
    """
    points = as_points_3d(points, "points", _HEIGHTS)
    to_geographic, topocentric, name = _operations(crs, origin)
    lon, lat = to_geographic.transform(points[:, 0], points[:, 1])
    lon, lat = np.asarray(lon, dtype=np.float64), np.asarray(lat, dtype=np.float64)
    if not (np.isfinite(lon) & np.isfinite(lat)).all():
        rows = np.flatnonzero(~(np.isfinite(lon) & np.isfinite(lat)))[:5].tolist()
        raise CRSError(_("points (rows {rows}) have no longitude and latitude in {crs}; give "
                         "coordinates inside the CRS's area").format(rows=rows, crs=name))
    east, north, up = topocentric.transform(lon, lat, points[:, 2])
    return np.column_stack([east, north, up]).astype(np.float64)


def from_local_tangent_plane(points, crs, origin):
    """East, north, up in a local tangent plane -> map coordinates and ellipsoidal heights.

    The inverse of :func:`to_local_tangent_plane`, to PROJ's precision (a round trip returns
    the points to better than a micrometre).

    Parameters
    ----------
    points : (n, 3) array_like
        East, north and up in metres from the origin. A single (3,) point is taken as one row.
    crs : str, int or rasterio.crs.CRS
        The CRS of the map coordinates to return, projected or geographic.
    origin : (3,) array_like
        The tangent plane's origin, (x, y, h) in ``crs``.

    Returns
    -------
    ndarray, shape (n, 3)
        (x, y, h): map coordinates in ``crs`` and heights in metres above its ellipsoid.

    Raises
    ------
    TypeError
        If the points are not real numbers.
    rsgeo.errors.RsgeoError
        If ``points`` is not (n, 3) or not finite, or ``origin`` is not one point.
    rsgeo.errors.CRSError
        If ``crs`` is unknown, compound (orthometric heights) or geocentric.

    See Also
    --------
    to_local_tangent_plane : The forward conversion, and what the frame is.

    References
    ----------
    IOGP Geomatics Guidance Note 7-2, §4.1.2 (EPSG method 9837).

    Examples
    --------
    >>> from_local_tangent_plane([[0.0, 0.0, 3000.0]], "EPSG:31985",
    ...                          (292_500.0, 9_114_000.0, 0.0)).round(3).tolist()
    [[292500.0, 9114000.0, 3000.0]]
    """
    points = as_points_3d(points, "points", _HEIGHTS)
    to_geographic, topocentric, _name = _operations(crs, origin)
    lon, lat, height = topocentric.transform(points[:, 0], points[:, 1], points[:, 2],
                                             direction="INVERSE")
    x, y = to_geographic.transform(lon, lat, direction="INVERSE")
    return np.column_stack([x, y, height]).astype(np.float64)
