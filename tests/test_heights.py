"""rsgeo.heights: the geoid undulation N, with PROJ and GDAL as the oracles.

PROJ (pyproj, the shipped ``egm96_15.gtx`` read by its path) gives N through "WGS 84 to
EGM96 height (1)"; GDAL's GTX driver (rasterio) reads the same grid file independently of
rsgeo's own reader, which :func:`rsgeo.heights.geoid_on_grid` uses for speed.
"""

import affine
import numpy as np
import pytest
import rasterio

from rsgeo import heights
from rsgeo._proj import GRIDS
from rsgeo.errors import GridError


def random_points(seed, n, margin=0.0):
    """``n`` random (lon, lat) inside the shipped grid, ``margin`` degrees from its edges."""
    west, south, east, north = heights.geoid_coverage()
    rng = np.random.default_rng(seed)
    return (rng.uniform(west + margin, east - margin, n),
            rng.uniform(south + margin, north - margin, n))


def test_rsgeo_reads_the_gtx_as_gdal_does():
    # GDAL's GTX driver: pixel-is-area, so its first pixel's corner is half a step west and
    # north of the grid's first node; rows north first
    south, west, dlat, dlon, values = heights._grid("EGM96")
    with rasterio.open(GRIDS / "egm96_15.gtx") as grid:
        gdal_values = grid.read(1).astype(np.float64)
        transform = grid.transform
    np.testing.assert_array_equal(values, gdal_values[::-1])
    assert transform.almost_equals(affine.Affine(dlon, 0, west - dlon / 2, 0, -dlat,
                                                 south + (values.shape[0] - 0.5) * dlat))
    assert heights.geoid_coverage() == (-76.0, -36.0, -28.0, 7.0)
    assert not values.flags.writeable


def test_rsgeo_bilinear_agrees_with_proj_to_far_below_a_millimetre():
    lon, lat = random_points(0, 20_000)
    west, south, east, north = heights.geoid_coverage()
    # the grid's nodes, its edges and corners, where an off-by-one would show
    nodes_lon = np.concatenate([lon, [west, east, west, east, -50.0, -50.125, east, -40.0]])
    nodes_lat = np.concatenate([lat, [south, south, north, north, -20.0, -20.25, -10.0, north]])
    by_proj = heights.geoid_undulation(nodes_lon, nodes_lat)
    by_rsgeo = heights._bilinear(nodes_lon, nodes_lat, "EGM96")
    assert np.abs(by_proj - by_rsgeo).max() < 1e-6            # measured: 3e-13 m
    assert by_proj.min() < -30 and by_proj.max() > 15         # Brazil's range of N


def test_geoid_on_a_grid_is_proj_at_each_cell_centre():
    from pyproj import Transformer

    lonlat = affine.Affine(0.0123, 0, -35.2, 0, -0.0117, -7.6)
    np.testing.assert_allclose(
        heights.geoid_on_grid(lonlat, (30, 40)),
        heights.geoid_undulation(*np.meshgrid(-35.2 + (np.arange(40) + 0.5) * 0.0123,
                                              -7.6 - (np.arange(30) + 0.5) * 0.0117)),
        rtol=0, atol=1e-6)
    # a UTM grid (SIRGAS 2000 / UTM 25S), its centres to lon, lat by PROJ independently
    utm = affine.Affine(90.0, 0, 288776.25, 0, -90.0, 9120760.75)
    n = heights.geoid_on_grid(utm.to_gdal(), (111, 111), "EPSG:31985")
    cols, rows = np.meshgrid(np.arange(111) + 0.5, np.arange(111) + 0.5)
    x, y = utm.c + cols * utm.a, utm.f + rows * utm.e
    lon, lat = Transformer.from_crs(31985, 4326, always_xy=True).transform(x, y)
    np.testing.assert_allclose(n, heights.geoid_undulation(lon, lat), rtol=0, atol=1e-6)
    # Olinda: the N = -5.49 m
    assert -5.50 < n.mean() < -5.48


def test_geoid_on_a_grid_in_strips_is_the_same(monkeypatch):
    grid = affine.Affine(0.01, 0, -40.0, 0, -0.01, -10.0)
    whole = heights.geoid_on_grid(grid, (37, 23))
    monkeypatch.setattr(heights, "_STRIP_CELLS", 50)            # two rows at a time
    np.testing.assert_array_equal(heights.geoid_on_grid(grid, (37, 23)), whole)


def test_to_ellipsoidal_adds_n():
    h = heights.to_ellipsoidal([10.0, 20.0], [-34.85, -47.0], [-8.0, -15.0], "EGM96")
    np.testing.assert_allclose(h - [10.0, 20.0],
                               heights.geoid_undulation([-34.85, -47.0], [-8.0, -15.0]))
    np.testing.assert_array_equal(heights.to_ellipsoidal([3.0], [0.0], [0.0], "ellipsoidal"),
                                  [3.0])


@pytest.mark.parametrize("call, match", [
    (lambda: heights.geoid_undulation([-80.0], [-10.0]), "outside the shipped EGM96 grid"),
    (lambda: heights.geoid_undulation([-40.0], [np.nan]), "outside the shipped EGM96 grid"),
    (lambda: heights.geoid_undulation([-40.0, -41.0], [-10.0]), "same shape"),
    (lambda: heights.geoid_undulation([-40.0], [-10.0], "EGM2008"), "unknown geoid"),
    (lambda: heights.geoid_on_grid(affine.Affine(1, 0, -30, 0, -1, 0), (3, 3)),
     "outside the shipped EGM96 grid"),
    (lambda: heights.to_ellipsoidal([1.0], [-40.0], [-10.0], "orthometric"),
     "SRTM and Copernicus DEMs are above a geoid, EGM96 and EGM2008 respectively.*"
     "rsgeo ships EGM96 over Brazil, not EGM2008"),
    (lambda: heights.check_vertical(None, "dem_vertical"), "dem_vertical must be one of"),
])
def test_refusals_say_what_is_needed(call, match):
    with pytest.raises(GridError, match=match):
        call()


def test_the_module_docstring_states_the_grid_range():
    """heights' docstring says EGM96 over the shipped box goes from about -40 m to +50 m."""
    undulation = heights._grid("EGM96")[-1]
    assert -42 < undulation.min() < -38 and 48 < undulation.max() < 52


# -- arguments refused with rsgeo's errors, naming them --------------------------------------

def test_geoid_on_grid_refuses_a_missing_transform_and_a_huge_grid():
    with pytest.raises(GridError, match="transform is None"):
        heights.geoid_on_grid(None, (3, 4))
    # 10**14 cells (728 TiB of N) are refused with their count, not left to NumPy's allocation
    with pytest.raises(GridError, match=r"shape \(10000000, 10000000\) is "
                                        r"100,000,000,000,000 cells, more than the "
                                        r"1,073,741,824"):
        heights.geoid_on_grid(affine.Affine(0.01, 0, -34.9, 0, -0.01, -7.95),
                              (10 ** 7, 10 ** 7))


def test_to_ellipsoidal_refuses_lengths_that_do_not_match_and_text():
    with pytest.raises(GridError, match=r"height, lon and lat must have one shape.*height "
                                        r"\(3,\), lon \(2,\)"):
        heights.to_ellipsoidal([1.0, 2.0, 3.0], [-34.85, -34.8], [-8.0, -8.0], "EGM96")
    with pytest.raises(TypeError, match="height must be numbers.*text '10'"):
        heights.to_ellipsoidal("10", [-34.85], [-8.0], "EGM96")
    with pytest.raises(TypeError, match="lon must be numbers.*booleans"):
        heights.to_ellipsoidal([10.0], [True], [-8.0], "EGM96")
    with pytest.raises(TypeError, match="lat must be numbers"):
        heights.geoid_undulation([-34.85], ["-8"])


def test_a_compound_crs_must_agree_with_the_vertical_datum_stated():
    from rsgeo.errors import CRSError

    assert heights.check_vertical("EGM96", crs="EPSG:4326+5773") == "EGM96"
    assert heights.check_vertical("ellipsoidal", crs="EPSG:4326") == "ellipsoidal"
    with pytest.raises(CRSError, match="dem_vertical is 'ellipsoidal' but dem_crs says the "
                                       "heights are above 'EGM96'"):
        heights.check_vertical("ellipsoidal", "dem_vertical", "EPSG:4326+5773", "dem_crs")
    with pytest.raises(CRSError, match="above 'EGM2008 height'"):
        heights.check_vertical("EGM96", crs="EPSG:4326+3855")
    with pytest.raises(CRSError, match="above 'ellipsoidal'"):
        heights.check_vertical("EGM96", crs="EPSG:4979")
