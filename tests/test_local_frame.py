"""rsgeo.local_frame: map coordinates and ellipsoidal heights to a local tangent plane and back.

Outside references: EPSG's worked example of the geographic/topocentric conversion (IOGP
Geomatics Guidance Note 7-2, §4.1.2, method 9837: origin 55° N, 5° E, 200 m on WGS 84; the
point 53°48'33.820" N, 2°07'46.380" E, 73 m is at E = -189,013.869 m, N = -128,642.040 m,
U = -4,220.171 m), and the textbook formulas (geodetic to Earth-centred Cartesian, then the
rotation to east, north, up) written out below with NumPy, not taken from rsgeo or PROJ.
"""

import numpy as np
import pytest

from rsgeo import errors
from rsgeo.local_frame import from_local_tangent_plane, to_local_tangent_plane

UTM = "EPSG:31985"                               # SIRGAS 2000 / UTM zone 25S (Olinda)
ORIGIN = (292_500.0, 9_114_000.0, 0.0)
GRS80 = (6378137.0, 298.257222101)


def textbook_enu(lon, lat, h, origin, ellipsoid):
    """East, north, up of geodetic points about a geodetic origin (degrees, metres)."""
    a, rf = ellipsoid
    e2 = (2 - 1 / rf) / rf

    def ecef(lon, lat, h):
        lon, lat = np.radians(lon), np.radians(lat)
        n = a / np.sqrt(1 - e2 * np.sin(lat) ** 2)
        return np.stack([(n + h) * np.cos(lat) * np.cos(lon),
                         (n + h) * np.cos(lat) * np.sin(lon),
                         (n * (1 - e2) + h) * np.sin(lat)], axis=-1)

    lon0, lat0, h0 = origin
    sl, cl = np.sin(np.radians(lon0)), np.cos(np.radians(lon0))
    sp, cp = np.sin(np.radians(lat0)), np.cos(np.radians(lat0))
    rotation = np.array([[-sl, cl, 0.0], [-sp * cl, -sp * sl, cp], [cp * cl, cp * sl, sp]])
    return (ecef(lon, lat, h) - ecef(lon0, lat0, h0)) @ rotation.T


def utm_points(n=200, seed=0):
    """Points over a 20 km square around the origin, heights from -50 to 3,500 m."""
    rng = np.random.default_rng(seed)
    xy = np.array(ORIGIN[:2]) + rng.uniform(-10_000, 10_000, (n, 2))
    return np.column_stack([xy, rng.uniform(-50.0, 3500.0, n)])


def test_the_epsg_guidance_note_example():
    lon = 2 + 7 / 60 + 46.380 / 3600
    lat = 53 + 48 / 60 + 33.820 / 3600
    expected = [-189013.869, -128642.040, -4220.171]
    for crs in ("EPSG:4979", "EPSG:4326"):              # WGS 84 3-D, and 2-D with heights
        got = to_local_tangent_plane([lon, lat, 73.0], crs, (5.0, 55.0, 200.0))
        np.testing.assert_allclose(got[0], expected, atol=0.001)
        back = from_local_tangent_plane(expected, crs, (5.0, 55.0, 200.0))[0]
        np.testing.assert_allclose(back[:2], [lon, lat], atol=1e-8)      # 1 mm in degrees
        assert abs(back[2] - 73.0) < 0.001


def test_utm_points_agree_with_the_textbook_formulas():
    from pyproj import Transformer

    points = utm_points()
    lon, lat = Transformer.from_crs(UTM, "EPSG:4674", always_xy=True).transform(
        points[:, 0], points[:, 1])
    lon0, lat0 = Transformer.from_crs(UTM, "EPSG:4674", always_xy=True).transform(*ORIGIN[:2])
    expected = textbook_enu(np.asarray(lon), np.asarray(lat), points[:, 2],
                            (lon0, lat0, ORIGIN[2]), GRS80)
    got = to_local_tangent_plane(points, UTM, ORIGIN)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-6)
    # the same points given in SIRGAS 2000 geographic coordinates land on the same frame
    geographic = to_local_tangent_plane(np.column_stack([lon, lat, points[:, 2]]),
                                        "EPSG:4674", (lon0, lat0, ORIGIN[2]))
    np.testing.assert_allclose(geographic, got, rtol=0, atol=1e-6)


def test_round_trip_and_origin():
    points = utm_points(seed=1)
    enu = to_local_tangent_plane(points, UTM, ORIGIN)
    np.testing.assert_allclose(from_local_tangent_plane(enu, UTM, ORIGIN), points,
                               rtol=0, atol=1e-6)
    np.testing.assert_allclose(to_local_tangent_plane(ORIGIN, UTM, ORIGIN), [[0, 0, 0]],
                               atol=1e-6)
    # straight up from the origin is the up axis
    above = from_local_tangent_plane([0.0, 0.0, 3000.0], UTM, ORIGIN)[0]
    np.testing.assert_allclose(above, [*ORIGIN[:2], 3000.0], atol=1e-6)


def test_utm_is_not_the_tangent_plane():
    # UTM's scale factor, its grid convergence and the Earth's curvature, each seen alone
    from pyproj import CRS, Proj, Transformer

    lon0, lat0 = Transformer.from_crs(UTM, "EPSG:4674", always_xy=True).transform(*ORIGIN[:2])
    factors = Proj(CRS(UTM)).get_factors(lon0, lat0)
    k, convergence = factors.meridional_scale, np.radians(factors.meridian_convergence)
    d = 1000.0
    east, north, up = to_local_tangent_plane([ORIGIN[0], ORIGIN[1] + d, 0.0], UTM, ORIGIN)[0]
    assert abs(np.hypot(east, north) - d / k) < 0.01           # 1 km of grid: 1/k km
    assert abs(np.arctan2(east, north) - convergence) < 1e-5   # grid north turned by γ
    assert abs(up + d**2 / (2 * 6_378_000.0)) < 0.002          # d²/2R below the plane


def test_refusals():
    with pytest.raises(errors.CRSError, match="ellipsoidal"):
        to_local_tangent_plane(ORIGIN, "EPSG:4326+5773", (-34.9, -8.0, 0.0))   # + EGM96 height
    with pytest.raises(errors.CRSError, match="ellipsoidal"):
        to_local_tangent_plane(ORIGIN, "EPSG:4978", ORIGIN)                    # geocentric
    with pytest.raises(errors.CRSError):
        to_local_tangent_plane(ORIGIN, "EPSG:999999", ORIGIN)
    with pytest.raises(errors.RsgeoError, match=r"\(n, 3\)"):
        to_local_tangent_plane([[1.0, 2.0]], UTM, ORIGIN)
    with pytest.raises(errors.RsgeoError, match="NaN"):
        from_local_tangent_plane([[np.nan, 0.0, 0.0]], UTM, ORIGIN)
    with pytest.raises(errors.RsgeoError, match="one"):
        to_local_tangent_plane(ORIGIN, UTM, [ORIGIN, ORIGIN])
    with pytest.raises(TypeError):
        to_local_tangent_plane([["a", "b", "c"]], UTM, ORIGIN)
    with pytest.raises(errors.CRSError, match="no longitude and latitude"):
        to_local_tangent_plane([[1e12, 1e12, 0.0]], UTM, ORIGIN)       # off the Earth
    with pytest.raises(errors.CRSError, match="no longitude and latitude"):
        to_local_tangent_plane(ORIGIN, UTM, (1e12, 1e12, 0.0))
    points = np.array([ORIGIN])
    to_local_tangent_plane(points, UTM, ORIGIN)
    assert points.tolist() == [list(ORIGIN)]                   # the input is not modified
