"""IBGE's datum grids, shipped with rsgeo: read by rsgeo and by PROJ, and the transformation
PROJ applies, named ("the grid shift equals PROJ's own pipeline to < 1 mm")."""

import pickle

import affine
import numpy as np
import pyproj
import pytest
import rasterio

from rsgeo import crs, data, resample
from rsgeo._proj import GRIDS
from rsgeo.errors import CRSError, DataError, GridError

GEOD = pyproj.Geod(ellps="GRS80")
SAD69, SAD69_96, SIRGAS = "EPSG:4618", "EPSG:5527", "EPSG:4674"
FILES = {"SAD69": "br_ibge_SAD69_003.tif", "SAD69(96)": "br_ibge_SAD96_003.tif"}


def hgridshift(path):
    """PROJ's hgridshift on a grid file given by its path, degrees in and out."""
    return pyproj.Transformer.from_pipeline(
        "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
        f"+step +proj=hgridshift +grids={path} +step +proj=unitconvert +xy_in=rad +xy_out=deg")


def metres_apart(a, b):
    """Geodesic distance (m) between (n, 2) longitude, latitude arrays."""
    return GEOD.inv(a[:, 0], a[:, 1], b[:, 0], b[:, 1])[2]


def gcps_lonlat():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    return crs.transform_points(gcps.map_xy, gcps.crs, SAD69)    # same datum: no shift


def random_lonlat(grid, n=3000, seed=0):
    west, south, east, north = crs.read_shift_grid(grid).bounds
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(west, east, n), rng.uniform(south, north, n)])


# -- rsgeo's own reading of the grid equals PROJ's --------------------------------------------

@pytest.mark.parametrize("grid", list(FILES))
def test_grid_shift_equals_proj_hgridshift_to_far_below_a_millimetre(grid):
    proj = hgridshift(GRIDS / FILES[grid])
    for points in (gcps_lonlat(), random_lonlat(grid)):
        mine = crs.grid_shift(points, grid)
        theirs = np.column_stack(proj.transform(points[:, 0], points[:, 1]))
        # PROJ keeps each node's shift in radians as a float32: micrometres
        assert metres_apart(mine, theirs).max() < 1e-4
        # the shift itself is tens of metres: the comparison can fail
        assert metres_apart(mine, points).min() > 10
        back = crs.grid_shift(mine, grid, inverse=True)
        theirs_back = np.column_stack(proj.transform(mine[:, 0], mine[:, 1],
                                                     direction="INVERSE"))
        assert metres_apart(back, theirs_back).max() < 1e-4
        assert metres_apart(back, points).max() < 1e-6


def test_the_grid_shift_at_the_gcps_is_proj_s_utm_pipeline():
    # SAD69 / UTM 21S -> lon, lat -> rsgeo's grid shift -> SIRGAS 2000 / UTM 21S, against
    # transform_points (PROJ's choice, the grid) and PROJ's datum_shift result
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    moved = crs.grid_shift(gcps_lonlat(), "SAD69")
    by_rsgeo = crs.transform_points(moved, SIRGAS, "EPSG:31981")   # same datum
    by_proj = crs.transform_points(gcps.map_xy, gcps.crs, "EPSG:31981")
    assert np.hypot(*(by_rsgeo - by_proj).T).max() < 1e-3
    dx, dy, _distance = crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981")
    np.testing.assert_allclose(by_rsgeo - gcps.map_xy, np.column_stack([dx, dy]), atol=1e-3)


def test_datum_shift_across_brazil_is_the_grid_where_its_area_holds_the_points():
    # random points in EPSG:5528's area of use: PROJ's choice is the grid, rsgeo's reading agrees
    points = random_lonlat("SAD69", n=2000, seed=3)
    points = points[(points[:, 0] > -60.5) & (points[:, 0] < -35) & (points[:, 1] < 4.4)
                    & (points[:, 1] > -33.7)]
    shift = crs.datum_shift(points, SAD69, SIRGAS)
    assert shift.transformations[0].codes == ("EPSG:5528",)
    by_proj = points + np.column_stack([shift.dx, shift.dy])
    on_grid = shift.used == 0
    assert on_grid.mean() > 0.99
    assert metres_apart(by_proj[on_grid], crs.grid_shift(points[on_grid])).max() < 1e-3


def test_read_shift_grid_reads_band_order_units_and_sign_from_the_metadata():
    grid = crs.read_shift_grid("SAD69")
    assert (grid.source_crs, grid.target_crs) == (SAD69, SIRGAS)
    assert grid.bounds == pytest.approx((-63.5, -34.1666667, -33.5, 4.5))
    assert grid.dlon.shape == grid.dlat.shape == (len(grid.lat), len(grid.lon))
    with rasterio.open(GRIDS / FILES["SAD69"]) as dataset:
        # band 1 latitude, band 2 longitude, both in arc-seconds, longitude positive east
        assert dataset.descriptions[:2] == ("latitude_offset", "longitude_offset")
        assert dataset.units[:2] == ("arc-second", "arc-second")
        assert dataset.tags(2)["positive_value"] == "east"
        first_row = dataset.read(1)[0]
    # the file's first row is the north one; rsgeo's row 0 is the south
    np.testing.assert_array_equal(grid.dlat[-1], first_row.astype(np.float64))
    with pytest.raises(ValueError):
        grid.dlat[0, 0] = 0.0                                       # read-only


def write_grid(path, grid, positive="west", unit="degree", point=True):
    """The SAD69 grid rewritten in another convention: longitude positive west, degrees,
    south row first or not, nodes as pixel corners (AREA_OR_POINT=Point) or centres."""
    scale = {"degree": 1 / 3600, "arc-second": 1.0}[unit]
    sign = -1.0 if positive == "west" else 1.0
    step = grid.lon[1] - grid.lon[0]
    half = 0.0 if point else 0.5 * step
    transform = affine.Affine(step, 0, grid.lon[0] - half, 0, -step, grid.lat[-1] + half)
    profile = dict(driver="GTiff", width=len(grid.lon), height=len(grid.lat), count=2,
                   dtype="float32", crs="EPSG:4618", transform=transform)
    with rasterio.Env(GTIFF_POINT_GEO_IGNORE=True):
        with rasterio.open(path, "w", **profile) as dataset:
            dataset.update_tags(TYPE="HORIZONTAL_OFFSET", target_crs_epsg_code="4674",
                                AREA_OR_POINT="Point" if point else "Area")
            dataset.write(np.float32(grid.dlat[::-1] * scale), 1)
            dataset.write(np.float32(sign * grid.dlon[::-1] * scale), 2)
            dataset.set_band_description(1, "latitude_offset")
            dataset.set_band_description(2, "longitude_offset")
            dataset.set_band_unit(1, unit)
            dataset.set_band_unit(2, unit)
            dataset.update_tags(2, positive_value=positive)


@pytest.mark.parametrize("positive, unit, point", [("west", "degree", True),
                                                   ("east", "arc-second", False)])
def test_another_sign_unit_or_node_convention_is_read_as_proj_reads_it(tmp_path, positive,
                                                                        unit, point):
    path = tmp_path / "shift.tif"
    write_grid(path, crs.read_shift_grid("SAD69"), positive, unit, point)
    points = random_lonlat("SAD69", n=500, seed=1)
    ours = crs.grid_shift(points, path)
    theirs = np.column_stack(hgridshift(path).transform(points[:, 0], points[:, 1]))
    assert metres_apart(ours, theirs).max() < 1e-3
    # the same shifts as the shipped file's (float32 of degrees: a few micrometres)
    assert metres_apart(ours, crs.grid_shift(points, "SAD69")).max() < 1e-3


def test_a_file_that_is_not_a_shift_grid_is_refused(tmp_path):
    with pytest.raises(DataError, match="TYPE is None, not 'HORIZONTAL_OFFSET'"):
        crs.read_shift_grid(data.path("nat1"))
    with pytest.raises(DataError, match="no shift grid 'SAD70'"):
        crs.read_shift_grid("SAD70")
    with pytest.raises(TypeError, match="grid must be one of SAD69"):
        crs.read_shift_grid(3.5)


def test_points_outside_the_grid_are_refused_not_shifted_by_zero():
    # Rio Branco, Acre: west of the grid (63.5°W); PROJ's hgridshift has no number there
    with pytest.raises(GridError, match=r"1 of 2 points are outside the grid "
                                        r"br_ibge_SAD69_003.tif \(longitude -63.5 to -33.5, "
                                        r"latitude -34.1667 to 4.5; first: point 1 \(-67.8, "
                                        r"-9.97\)\)"):
        crs.grid_shift([[-47.9, -15.8], [-67.8, -9.97]], "SAD69")
    x, y = hgridshift(GRIDS / FILES["SAD69"]).transform(-67.8, -9.97)
    assert not np.isfinite([x, y]).all()
    # a point on the grid's last node is inside (PROJ's tolerance); the shift is the node's
    grid = crs.read_shift_grid("SAD69")
    corner = crs.grid_shift([[grid.lon[-1], grid.lat[-1]]], "SAD69")[0]
    assert (corner[0] - grid.lon[-1]) * 3600 == pytest.approx(grid.dlon[-1, -1])


# -- the transformation PROJ applies, named ----------------------------------------------------

def test_transformations_lists_the_grid_first_then_the_parameters():
    found = crs.transformations("EPSG:29191", "EPSG:31981")
    assert [t.codes for t in found[:2]] == [("EPSG:5528",), ("EPSG:15485",)]
    grid, three = found[:2]
    assert grid.accuracy == 1.0 and three.accuracy == 5.0
    assert grid.grids == ("br_ibge_SAD69_003.tif",) and grid.available and not three.grids
    assert str(GRIDS / "br_ibge_SAD69_003.tif") in grid.pipeline
    assert "+proj=helmert +x=-67.35 +y=3.88 +z=-38.22" in three.pipeline
    assert str(grid) == ("SAD69 to SIRGAS 2000 (2) (EPSG:5528; accuracy 1 m, grid "
                         "br_ibge_SAD69_003.tif)")
    # a grid rsgeo does not ship: listed, not available, and refused by name
    corrego = crs.transformations("EPSG:4225", SIRGAS)
    missing = [t for t in corrego if not t.available]
    assert [t.grids for t in missing] == [("br_ibge_CA7072_003.tif",)]
    with pytest.raises(CRSError, match=r"needs the grid br_ibge_CA7072_003.tif, which PROJ "
                                       r"does not find here"):
        crs.transform_points([[-47.0, -15.0]], "EPSG:4225", SIRGAS,
                                transformation=missing[0])


def test_datum_shift_names_the_grid_and_unpacks_as_three_arrays():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    shift = crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981")
    dx, dy, distance = shift
    assert len(shift) == 3 and shift[2] is distance and shift.distance is distance
    assert shift.transformation.codes == ("EPSG:5528",) and (shift.used == 0).all()
    assert "EPSG:5528" in repr(shift) and "br_ibge_SAD69_003.tif" in repr(shift)
    copy = pickle.loads(pickle.dumps(shift))
    assert copy.transformation == shift.transformation
    np.testing.assert_array_equal(copy.dx, dx)


def test_points_outside_the_grids_area_get_the_parameters_and_say_so():
    # Brasília (in EPSG:5528's area) and Rio Branco (outside it and outside the grid)
    shift = crs.datum_shift([[-47.9, -15.8], [-67.8, -9.97], [-47.0, -16.0]], SAD69, SIRGAS)
    assert [t.codes for t in shift.transformations] == [("EPSG:5528",), ("EPSG:15485",)]
    np.testing.assert_array_equal(shift.used, [0, 1, 0])
    assert "at 2 points" in repr(shift) and "at 1 points" in repr(shift)
    three = crs.transform_points([[-67.8, -9.97]], SAD69, SIRGAS, transformation="EPSG:15485")
    np.testing.assert_allclose([shift.dx[1], shift.dy[1]], three[0] - [-67.8, -9.97], atol=1e-12)


def test_a_transformation_asked_by_name_is_applied_or_refused():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    for asked in ("EPSG:15485", 15485, ["epsg:15485"]):
        shift = crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981", transformation=asked)
        assert shift.transformation.codes == ("EPSG:15485",)
    default = crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981")
    gap = np.hypot(default.dx - shift.dx, default.dy - shift.dy)
    assert np.all((gap > 5) & (gap < 10))                     # 7.8 m
    with pytest.raises(CRSError, match=r"PROJ knows no operation EPSG:1234 from EPSG:29191 "
                                       r"to EPSG:31981; it knows: EPSG:5528 SAD69 to SIRGAS "
                                       r"2000 \(2\); EPSG:15485"):
        crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981", transformation="EPSG:1234")
    with pytest.raises(CRSError, match="is not a registry code"):
        crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981", transformation="the grid")
    with pytest.raises(TypeError, match="transformation must be a code"):
        crs.datum_shift(gcps.map_xy, gcps.crs, "EPSG:31981", transformation=1.5)
    # the grid by name west of its area of use: refused, not answered by another operation
    with pytest.raises(CRSError, match=r"outside the area of use of SAD69 to SIRGAS 2000 \(2\) "
                                       r"\(EPSG:5528: longitude -60.58 to -34.74"):
        crs.transform_points([[-62.0, -9.0]], SAD69, SIRGAS, transformation="EPSG:5528")


def test_the_sad69_96_parameters_are_epsg_15485_s_and_only_the_grids_tell_them_apart():
    # EPSG:5881 applies EPSG:15485's translations to SAD69(96), on the same ellipsoid
    points = gcps_lonlat()
    classic = crs.transform_points(points, SAD69, SIRGAS, transformation="EPSG:15485")
    readjusted = crs.transform_points(points, SAD69_96, SIRGAS, transformation="EPSG:5881")
    np.testing.assert_array_equal(classic, readjusted)
    by_grids = [crs.transform_points(points, SAD69, SIRGAS),
                crs.transform_points(points, SAD69_96, SIRGAS)]
    assert metres_apart(*by_grids).min() > 0.5


def test_the_realization_change_is_the_two_grids_chained():
    points = gcps_lonlat()
    shift = crs.datum_shift(points, SAD69, SAD69_96)
    assert shift.transformation.codes == ("EPSG:5528", "EPSG:5529")
    chained = crs.grid_shift(crs.grid_shift(points, "SAD69"), "SAD69(96)", inverse=True)
    moved = points + np.column_stack([shift.dx, shift.dy])
    assert metres_apart(moved, chained).max() < 1e-3


# -- rasters and GCP sets use the same operation -------------------------------------------------

def test_reproject_samples_where_transform_points_says():
    # a raster whose values are its own northings: bilinear resampling returns, at every output
    # pixel, the source northing PROJ mapped it to (the two transformations differ by 4 m in
    # northing here, under 1 m in easting)
    transform = affine.Affine(25.0, 0, 470000.0, 0, -25.0, 7430000.0)
    rows = np.arange(120, dtype=np.float64)[:, np.newaxis] + 0.5
    northings = np.tile(transform.f + rows * transform.e, (1, 160))
    raster = data.Raster(northings, transform, crs.as_crs(29193), None, "", "northings")
    rows, cols = np.mgrid[20:100:7, 20:140:7]
    for asked, code in [(None, "EPSG:5528"), ("EPSG:15485", "EPSG:15485")]:
        out = resample.reproject(raster, "EPSG:31983", method="bilinear", nodata=None,
                               transformation=asked)
        assert code in out.description
        centres = np.column_stack(out.transform @ (cols.ravel() + 0.5, rows.ravel() + 0.5))
        source = crs.transform_points(centres, "EPSG:31983", "EPSG:29193",
                                         transformation=asked)
        np.testing.assert_allclose(out.array[rows.ravel(), cols.ravel()], source[:, 1],
                                   rtol=0, atol=1e-6)
        # the other transformation would have sampled metres away: the check can fail
        other = crs.transform_points(centres, "EPSG:31983", "EPSG:29193",
                                        transformation="EPSG:5528" if asked else "EPSG:15485")
        assert np.abs(other[:, 1] - source[:, 1]).min() > 1


def test_gcpset_to_crs_is_transform_points():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    np.testing.assert_array_equal(gcps.to_crs("EPSG:31981").map_xy,
                                  crs.transform_points(gcps.map_xy, gcps.crs, "EPSG:31981"))


# -- rsgeo's grids by path are PROJ's grids on its search path, bit for bit ------------------

PROJ_WITH_THE_GRIDS = """
import json, sys
import numpy as np
import pyproj
from rsgeo import _proj

rng = np.random.default_rng(7)
pairs = [("EPSG:29191", "EPSG:31981"), ("EPSG:4618", "EPSG:4674"), ("EPSG:5527", "EPSG:4674"),
         ("EPSG:4618", "EPSG:5527"), ("EPSG:4674", "EPSG:4618"), ("EPSG:29193", "EPSG:4326"),
         ("EPSG:4979", "EPSG:4326+5773")]
cases = []
for src, dst in pairs:
    crs = pyproj.CRS(src)
    lon, lat = rng.uniform(-78, -28, 3000), rng.uniform(-38, 8, 3000)
    x, y = pyproj.Transformer.from_crs(crs.geodetic_crs, crs, always_xy=True).transform(lon, lat)
    args = (x, y) if "5773" not in dst else (x, y, np.zeros_like(x))
    cases.append((src, dst, args))
# rsgeo's first, then PROJ's own with the grid folder on its search path (this process only)
ours = [np.array(_proj.transformer(pyproj.CRS(s).to_wkt(), pyproj.CRS(d).to_wkt()).transform(
    *a)) for s, d, a in cases]
pyproj.datadir.append_data_dir(str(_proj.GRIDS))
proj = [np.array(pyproj.Transformer.from_crs(pyproj.CRS(s).to_wkt(), pyproj.CRS(d).to_wkt(),
                                             always_xy=True).transform(*a))
        for s, d, a in cases]
print(json.dumps([[s, d, bool(np.array_equal(o, p, equal_nan=True))]
                  for (s, d, _a), o, p in zip(cases, ours, proj)]))
"""


def test_the_shipped_grids_by_path_give_what_proj_gives_with_them_on_its_path():
    # rsgeo no longer puts its grid folder on PROJ's search path (a change to every later
    # transformation of the process); its own choice between the operations, the grids read
    # by their path, gives PROJ's numbers exactly, point by point, over Brazil and beyond
    import json
    import subprocess
    import sys

    run = subprocess.run([sys.executable, "-c", PROJ_WITH_THE_GRIDS], capture_output=True,
                         text=True)
    assert run.returncode == 0, run.stderr
    results = json.loads(run.stdout)
    assert [same for _src, _dst, same in results] == [True] * len(results), results
