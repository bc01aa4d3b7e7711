"""CRSs, datum shifts and a complete georeferencing run, checked against GDAL/PROJ."""

import contextlib
from xml.sax.saxutils import escape

import affine
import numpy as np
import pyproj
import pytest
import rasterio
from rasterio.control import GroundControlPoint
from rasterio.warp import calculate_default_transform

from rsgeo import crs, data, radiometry, resample
from rsgeo.errors import ExtrapolationWarning
from rsgeo.gcp import GCPSet

from gdal_reference import affine_source, gcp_source, gdal_warp

SAD69_UTM21S, SIRGAS_UTM21S = "EPSG:29191", "EPSG:31981"
SAD69_UTM23S, SIRGAS_UTM23S = "EPSG:29193", "EPSG:31983"


def reprojection_xml(src_crs, dst_crs, operation=None):
    """GDAL's exact reprojection step (no approximate transformer: gdalwarp -et 0).

    ``operation``: a PROJ pipeline GDAL must apply (its COORDINATE_OPERATION option, as
    ``gdalwarp -ct``): rasterio's GDAL does not find rsgeo's grids by name, so it is given
    the operation rsgeo applies, its grids by their absolute paths.
    """
    options = (f'<Options><Option key="COORDINATE_OPERATION">{escape(operation)}</Option>'
               f"</Options>" if operation else "")
    return (f"<ReprojectTransformer><ReprojectionTransformer>"
            f"<SourceSRS>{escape(crs.as_crs(src_crs).to_wkt())}</SourceSRS>"
            f"<TargetSRS>{escape(crs.as_crs(dst_crs).to_wkt())}</TargetSRS>"
            f"{options}</ReprojectionTransformer></ReprojectTransformer>")


def operation_at(points, src_crs, dst_crs):
    """The PROJ pipeline rsgeo applies at these points (one for all of them)."""
    shift = crs.datum_shift(points, src_crs, dst_crs)
    assert len(shift.transformations) == 1, shift
    return shift.transformation.pipeline


def proj_pipeline(src_zone_sad69_to_sirgas, grid="br_ibge_SAD69_003.tif"):
    """SAD69 / UTM zone N south -> SIRGAS 2000 / UTM N south by IBGE's grid, written here."""
    from rsgeo._proj import GRIDS

    zone = src_zone_sad69_to_sirgas
    return pyproj.Transformer.from_pipeline(
        f"+proj=pipeline +step +inv +proj=utm +zone={zone} +south +ellps=aust_SA "
        f"+step +proj=hgridshift +grids={GRIDS / grid} "
        f"+step +proj=utm +zone={zone} +south +ellps=GRS80")


@pytest.fixture(scope="module")
def nat1_crop():
    raster = data.load("nat1")
    # a crop keeps the test quick
    window = raster.array[300:560, 200:470]
    transform = raster.transform @ affine.Affine.translation(200, 300)
    return data.Raster(window, transform, raster.crs, None, raster.description, "nat1")


@pytest.mark.parametrize("method", ["nearest", "bilinear", "cubic"])
def test_sad69_to_sirgas_warp_equals_gdalwarp(nat1_crop, method):
    out = resample.reproject(nat1_crop, SIRGAS_UTM23S, method=method, nodata=0)
    assert out.crs.to_epsg() == 31983 and "EPSG:5528" in out.description
    corner = [[nat1_crop.transform.c, nat1_crop.transform.f]]
    xml = affine_source(nat1_crop.transform) + reprojection_xml(
        nat1_crop.crs, SIRGAS_UTM23S, operation_at(corner, nat1_crop.crs, SIRGAS_UTM23S))
    reference = gdal_warp(nat1_crop.array, xml, out.transform, out.array.shape, method, 0)
    assert (out.array != 0).mean() > 0.9
    np.testing.assert_array_equal(out.array, reference)


def test_transform_points_matches_proj_and_the_helmert_shift():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    moved = crs.transform_points(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    # IBGE's grid through a PROJ pipeline written here, the grid by its path
    xs, ys = proj_pipeline(21).transform(gcps.map_xy[:, 0], gcps.map_xy[:, 1])
    np.testing.assert_allclose(moved, np.column_stack([xs, ys]), rtol=0, atol=1e-6)
    dx, dy, distance = crs.datum_shift(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    # the grid moves them about 63 m to the south-west here
    assert np.all((distance > 60) & (distance < 75))
    assert np.all(dx < 0) and np.all(dy < 0)
    back = crs.transform_points(moved, SIRGAS_UTM21S, gcps.crs)
    np.testing.assert_allclose(back, gcps.map_xy, atol=1e-6)
    # EPSG:15485 asked by name is what rasterio's GDAL applies (it has no grid)
    three = crs.transform_points(gcps.map_xy, gcps.crs, SIRGAS_UTM21S,
                                    transformation="EPSG:15485")
    xs, ys = rasterio.warp.transform(SAD69_UTM21S, SIRGAS_UTM21S, gcps.map_xy[:, 0],
                                     gcps.map_xy[:, 1])
    np.testing.assert_allclose(three, np.column_stack([xs, ys]), rtol=0, atol=1e-6)


@pytest.mark.parametrize("bad", ["EPSG:999999", "not a crs", 12345678])
def test_a_crs_proj_does_not_know_is_a_value_error(bad):
    with pytest.raises(ValueError, match="not a CRS that PROJ knows"):
        crs.transform_points([[500000.0, 7400000.0]], bad, SIRGAS_UTM23S)
    with pytest.raises(ValueError, match="not a CRS that PROJ knows"):
        data.load_gcps("cbers2b_ccd_hrc").to_crs(bad)
    with pytest.raises(ValueError, match="not a CRS that PROJ knows"):
        resample.georeference(data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc"),
                            dst_crs=bad)


def test_gcpset_to_crs_moves_map_coordinates_only():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    moved = gcps.to_crs(SIRGAS_UTM21S)
    assert crs.as_crs(moved.crs).to_epsg() == 31981
    np.testing.assert_array_equal(moved.image_xy, gcps.image_xy)
    assert moved.ids == gcps.ids and moved.notes == gcps.notes
    assert np.all(np.hypot(*(moved.map_xy - gcps.map_xy).T) > 60)
    with pytest.raises(ValueError, match="no CRS"):
        GCPSet(gcps.map_xy, gcps.image_xy).to_crs(SIRGAS_UTM21S)


def test_gcpset_refuses_to_mix_crss():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    assert len(gcps.combine(gcps)) == 2 * len(gcps)
    with pytest.raises(ValueError, match="cannot mix GCPs in EPSG:29191 with GCPs in EPSG:31981"):
        gcps.combine(gcps.to_crs(SIRGAS_UTM21S))
    with pytest.raises(ValueError, match="no CRS"):
        gcps.combine(GCPSet(gcps.map_xy, gcps.image_xy))
    assert len(gcps.to_crs(SIRGAS_UTM21S).combine(gcps.to_crs(31981))) == 28


def extrapolation_warning(order):
    """The shipped GCPs leave the scene's corners outside their hull: degree 2 and 3 warn."""
    if order == 1:
        return contextlib.nullcontext()
    return pytest.warns(ExtrapolationWarning, match=r"GCP extents \(.*\) beyond the GCPs' hull")


@pytest.mark.parametrize("order", [1, 2, 3])
def test_output_grid_is_gdals_suggestion(order):
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    height, width = raster.array.shape[-2:]
    points = [GroundControlPoint(row=r, col=c, x=x, y=y, z=0.0)
              for (c, r), (x, y) in zip(gcps.image_xy, gcps.map_xy)]
    transform, cols, rows = calculate_default_transform(
        gcps.crs, gcps.crs, width, height, gcps=points, MAX_GCP_ORDER=order)
    with extrapolation_warning(order):
        out = resample.georeference(raster, gcps, order=order)
    assert out.array.shape[-2:] == (rows, cols)
    np.testing.assert_allclose(tuple(out.transform)[:6], tuple(transform)[:6], rtol=0, atol=1e-6)


@pytest.mark.parametrize("order, method, dst_crs", [(1, "nearest", None),
                                                    (2, "bilinear", None),
                                                    (2, "cubic", SIRGAS_UTM21S)])
def test_georeference_saved_geotiff_equals_gdalwarp(tmp_path, order, method, dst_crs):
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    with extrapolation_warning(order):
        out = resample.georeference(raster, gcps, order=order, resolution=20.0, method=method,
                                  nodata=0, dst_crs=dst_crs)
    written = data.save(tmp_path / "corrected.tif", out)
    with rasterio.open(written) as dataset:
        back = dataset.read()
        assert dataset.crs == crs.as_crs(dst_crs or gcps.crs)
        assert dataset.transform == out.transform and dataset.nodata == 0
        assert dataset.transform.a == 20.0
    np.testing.assert_array_equal(back, out.array)
    xml = gcp_source(gcps.image_xy, gcps.map_xy, order)
    if dst_crs is not None:
        xml += reprojection_xml(gcps.crs, dst_crs, operation_at(gcps.map_xy, gcps.crs, dst_crs))
    reference = gdal_warp(raster.array, xml, out.transform, back.shape[-2:], method, 0)
    np.testing.assert_array_equal(back, reference)


def test_georeference_reads_a_path_and_checks_its_input(tmp_path):
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    from_path = resample.georeference(data.path("cbers2b_rgb342"), gcps, order=1)
    from_raster = resample.georeference(data.load("cbers2b_rgb342"), gcps, order=1)
    np.testing.assert_array_equal(from_path.array, from_raster.array)
    with pytest.raises(ValueError, match="resolution must be .* above 0"):
        resample.georeference(data.load("cbers2b_rgb342"), gcps, resolution=0.0)
    with pytest.raises(ValueError, match="resolution must be .* above 0"):
        resample.reproject(data.load("nat1"), SIRGAS_UTM23S, resolution=-25.0)
    with pytest.raises(ValueError, match="cannot read"):
        resample.georeference(tmp_path / "missing.tif", gcps)
    with pytest.raises(ValueError, match="no CRS"):
        resample.georeference(data.load("cbers2b_rgb342"), GCPSet(gcps.map_xy, gcps.image_xy),
                            dst_crs=SIRGAS_UTM21S)
    with pytest.raises(ValueError, match="unknown method"):
        resample.georeference(data.load("cbers2b_rgb342"), gcps, method="lanczos")


def test_overlap_refuses_rasters_in_different_crss():
    a = data.load("cbers_b2_A")
    b = data.load("cbers_b2_C")
    moved = data.Raster(b.array, b.transform, crs.as_crs(31982), None, "", "C in SIRGAS")
    with pytest.raises(ValueError, match=r"different CRSs.*resample\.reproject"):
        radiometry.overlap(a, moved)
    unplaced = data.Raster(b.array, b.transform, None, None, "", "C without CRS")
    with pytest.raises(ValueError, match="EPSG:29192 and no CRS"):
        radiometry.overlap(a, unplaced)
    assert radiometry.overlap(a, b)[0].size > 0


def test_epsg_15485_by_name_is_the_three_translations_by_hand():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    by_proj = crs.transform_points(gcps.map_xy, gcps.crs, SIRGAS_UTM21S,
                                      transformation="EPSG:15485")
    by_hand = crs.geocentric_translation(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    assert np.abs(by_hand - by_proj).max() < 1e-3
    # the ellipsoid change alone (no translation) is tens of metres away: the check can fail
    ellipsoid_only = crs.geocentric_translation(gcps.map_xy, gcps.crs, SIRGAS_UTM21S, (0, 0, 0))
    assert np.abs(ellipsoid_only - by_proj).max() > 10
    # PROJ's own choice here is IBGE's grid, metres away from the translations
    by_grid = crs.transform_points(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    assert np.hypot(*(by_hand - by_grid).T).min() > 5
    with pytest.raises(ValueError, match="three finite numbers"):
        crs.geocentric_translation(gcps.map_xy, gcps.crs, SIRGAS_UTM21S, (1.0, 2.0))


def test_check_datum_shift_pixels_judges_form_then_value_without_telling_it():
    from rsgeo_course.exercises import ExerciseNotSolved, check_datum_shift_pixels

    gcps = data.load_gcps("cbers2b_ccd_hrc")
    dx, dy, distance = crs.datum_shift(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    right = distance.mean() / 20.0

    def check(answer):
        return check_datum_shift_pixels(answer, gcps.map_xy, gcps.crs, SIRGAS_UTM21S, 20.0)

    assert check(right).ok and check(right * 1.005).ok
    with pytest.raises(ExerciseNotSolved):
        check(...)
    assert "not a string" in check(str(right)).message
    assert "None" in check(None).message
    for wrong, hint in [(distance.mean(), "in metres"), (np.abs(dx).mean() / 20, "easting"),
                        (np.abs(dy).mean() / 20, "northing"),
                        ((np.abs(dx) + np.abs(dy)).mean() / 20, "|dx| + |dy|")]:
        verdict = check(wrong)
        assert not verdict.ok and hint in verdict.hint
        assert f"{right:.3g}" not in verdict.message + verdict.hint
    assert "transform_points" in check(right * 1.3).hint
    with pytest.raises(ValueError, match="pixel_size"):
        check_datum_shift_pixels(right, gcps.map_xy, gcps.crs, SIRGAS_UTM21S, 0.0)


def test_georeference_accepts_the_other_model_kinds():
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    linear = resample.georeference(raster, gcps, order=1, resolution=20.0)
    helmert = resample.georeference(raster, gcps, kind="helmert", order=None, resolution=20.0)
    assert "helmert" in helmert.description and "None" not in helmert.description
    # a similarity and an affine model of the same GCPs place the scene within a few pixels
    assert abs(helmert.transform.c - linear.transform.c) < 5 * 20.0
    assert abs(helmert.array.shape[-1] - linear.array.shape[-1]) < 5


@pytest.mark.parametrize("kind", ["helmert", "linear", "projective", "tps"])
def test_kinds_without_an_order_ignore_the_default_order(kind):
    # the default order=1 is the polynomial's: not given, for a kind that has none
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    out = resample.georeference(raster, gcps, kind=kind, resolution=20.0)
    assert out.description.endswith(f"georeferenced: {kind}, nearest")
    with pytest.raises(ValueError, match=f"kind {kind!r} has no order"):
        resample.georeference(raster, gcps, kind=kind, order=2, resolution=20.0)
    # a polynomial's order given as the kind keeps it, and says "polynomial"
    assert resample.georeference(raster, gcps, kind=2, resolution=20.0).description.endswith(
        "georeferenced: polynomial order 2, nearest")


# -- datum shifts between unlike CRSs, points outside a CRS's area of use ------------

@pytest.mark.parametrize("src, dst, kinds", [
    ("EPSG:4326", SIRGAS_UTM23S,
     r"EPSG:4326 \(geographic, degree\).*EPSG:31983 \(projected, metre"),
    (SIRGAS_UTM23S, "EPSG:4674", r"EPSG:31983 \(projected, metre\).*EPSG:4674 \(geographic"),
    ("EPSG:2263", "EPSG:32618",
     r"EPSG:2263 \(projected, US survey foot\).*EPSG:32618 \(projected, metre"),
])
def test_datum_shift_refuses_crss_of_different_kinds_or_units(src, dst, kinds):
    # EPSG:4326 -> 31983 was a "shift" of 7,473 km: a projection, not a datum shift
    with pytest.raises(ValueError, match="a datum shift needs two CRSs of the same kind and "
                                         f"unit, got src_crs {kinds}.*transform_points"):
        crs.datum_shift([[-45.0, -23.0]], src, dst)


@pytest.mark.parametrize("dst, projection", [("EPSG:29192", r"\+proj=utm \+zone=22 \+south\)"),
                                             ("EPSG:3857", r"\+proj=merc")])
def test_datum_shift_refuses_two_projections(dst, projection):
    # UTM 23S -> 22S or Web Mercator, both in metres: hundreds of km of "shift"
    with pytest.raises(ValueError, match=r"src_crs EPSG:29193 and dst_crs .* are different "
                                         rf"projections \(\+proj=utm \+zone=23 \+south and "
                                         rf"{projection}.*transform_points"):
        crs.datum_shift([[500000.0, 7400000.0]], SAD69_UTM23S, dst)


def test_datum_shift_between_two_geographic_crss_is_proj_in_degrees():
    lonlat = [[-54.3, -23.78], [-45.2, -23.3]]
    shift = crs.datum_shift(lonlat, "EPSG:4618", "EPSG:4674")   # SAD69 -> SIRGAS
    dx, dy, distance = shift
    moved = crs.grid_shift(lonlat, "SAD69")                     # the grid, read by rsgeo
    np.testing.assert_allclose(dx, moved[:, 0] - [-54.3, -45.2], rtol=0, atol=1e-10)
    np.testing.assert_allclose(dy, moved[:, 1] - [-23.78, -23.3], rtol=0, atol=1e-10)
    assert np.all((distance > 1e-4) & (distance < 1e-3))     # tens of metres, in degrees
    assert shift.transformation.codes == ("EPSG:5528",)
    three = crs.datum_shift(lonlat, "EPSG:4618", "EPSG:4674", transformation=15485)
    xs, ys = rasterio.warp.transform("EPSG:4618", "EPSG:4674", [-54.3, -45.2], [-23.78, -23.3])
    np.testing.assert_allclose(three.dx, np.array(xs) - [-54.3, -45.2], rtol=0, atol=1e-12)
    np.testing.assert_allclose(three.dy, np.array(ys) - [-23.78, -23.3], rtol=0, atol=1e-12)


def test_points_outside_a_crss_area_of_use_are_refused():
    # lon/lat typed into two UTM CRSs "moved" 42.8 m; PROJ's area of use of EPSG:29193 is
    # 48°W to 42°W, 33.5°S to 5.13°N (EPSG's, in the CRS's WKT2 usage)
    typed = [[500000.0, 7400000.0], [-45.0, -23.0]]
    message = (r"1 of 2 points are outside the area of use of EPSG:29193 \(longitude -48 to -42, "
               r"latitude -33.5 to 5.13; first: point 1 \(-45, -23\) in EPSG:29193.*longitude "
               r"and latitude typed into a projected CRS")
    with pytest.raises(ValueError, match=message):
        crs.datum_shift(typed, SAD69_UTM23S, SIRGAS_UTM23S)
    with pytest.raises(ValueError, match=message):
        crs.transform_points(typed, SAD69_UTM23S, SIRGAS_UTM23S)
    # inside the source's area, outside the target's (UTM 23S is 48°W to 42°W)
    with pytest.raises(ValueError, match="outside the area of use of EPSG:31983 .*point 0 "
                                         r"\(-60, -20\) in EPSG:4326"):
        crs.transform_points([[-60.0, -20.0]], "EPSG:4326", SIRGAS_UTM23S)
    # check_area=False: what PROJ gives with rsgeo's grids, without a word (rsgeo's
    # transformer, the grids by path, which is PROJ's with the grid folder on its search path
    # bit for bit: test_datum_grids.py, in a process of its own)
    from rsgeo import _proj

    moved = crs.transform_points(typed, SAD69_UTM23S, SIRGAS_UTM23S, check_area=False)
    xs, ys = _proj.transformer(SAD69_UTM23S, SIRGAS_UTM23S).transform(
        [500000.0, -45.0], [7400000.0, -23.0])
    np.testing.assert_allclose(moved, np.column_stack([xs, ys]), rtol=0, atol=1e-6)
    # a CRS read from a file (no usage in its WKT) is looked up by its EPSG code
    nat1 = data.load("nat1")
    with pytest.raises(ValueError, match="outside the area of use of EPSG:29193"):
        crs.datum_shift([[-45.0, -23.0]], nat1.crs, SIRGAS_UTM23S)
    # a CRS without an area of use (a PROJ string PROJ does not identify) is not checked
    local = "+proj=tmerc +lon_0=-45.3 +lat_0=-23 +k=1 +x_0=1000 +y_0=1000 +ellps=GRS80"
    assert np.isfinite(crs.transform_points([[-45.0, -23.0]], local, "EPSG:4326")).all()


def test_datum_shift_inside_the_areas_is_unchanged():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    dx, dy, distance = crs.datum_shift(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    xs, ys = proj_pipeline(21).transform(gcps.map_xy[:, 0], gcps.map_xy[:, 1])
    np.testing.assert_allclose(dx, np.array(xs) - gcps.map_xy[:, 0], rtol=0, atol=1e-6)
    np.testing.assert_array_equal(distance, np.hypot(dx, dy))


# -- georeference's input and its output's size ---------------------------------------

def test_georeference_given_a_bare_array_says_its_type_and_shape():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    array = data.load("cbers2b_rgb342").array
    with pytest.raises(TypeError, match=r"raster_or_path must be an rsgeo.data.Raster or the "
                                        r"path of a GeoTIFF, got ndarray of shape \(3, 351, 369\)"
                                        r"; wrap an array as rsgeo.data.Raster") as error:
        resample.georeference(array, gcps)
    assert len(str(error.value)) < 250          # not the whole array
    with pytest.raises(TypeError, match="got list"):
        resample.georeference([[1, 2], [3, 4]], gcps)


def test_georeference_refuses_an_output_too_big_before_allocating_it():
    # resolution=0.01 on a 20 m image: about 706,865 x 736,902 cells x 3 bands, 1,455 GiB
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    with pytest.raises(ValueError, match=r"3 band\(s\) of uint8\) would take 14\d\d\.\d GiB.*"
                                         "coarser resolution"):
        resample.georeference(raster, gcps, resolution=0.01)
    with pytest.raises(ValueError, match=r"GiB.*coarser resolution"):
        resample.reproject(data.load("nat1"), SIRGAS_UTM23S, resolution=0.01)


# -- a polynomial of degree 2 or 3 extrapolated far beyond its GCPs -------------------

SCENE_ORIGIN = (500000.0, 7400000.0)


def scene_and_gcps(cols, rows, seed=0):
    """A 10 km scene (500 x 500 pixels of 20 m) and GCPs at (cols, rows), map to 3 m."""
    rng = np.random.default_rng(seed)
    x0, y0 = SCENE_ORIGIN
    image = rng.integers(1, 255, (500, 500), dtype=np.uint8)
    raster = data.Raster(image, affine.Affine(20, 0, x0, 0, -20, y0), crs.as_crs(31983),
                         None, "", "scene")
    map_xy = np.column_stack([x0 + 20 * cols, y0 - 20 * rows]) + rng.normal(0, 3, (len(cols), 2))
    return raster, GCPSet(map_xy, np.column_stack([cols, rows]), crs="EPSG:31983")


@pytest.fixture(scope="module")
def clustered():
    # the case: 15 GCPs in a 500 m patch (25 x 25 pixels) of a 10 km scene
    rng = np.random.default_rng(0)
    return scene_and_gcps(rng.uniform(240, 265, 15), rng.uniform(240, 265, 15))


@pytest.mark.parametrize("kind, order, what", [
    ("polynomial", 3, "a polynomial of degree 3"), ("polynomial", 2, "a polynomial of degree 2"),
    ("projective", None, "a projective model"),
    (3, None, "a polynomial of degree 3")])          # the order given as the kind
def test_georeference_refuses_a_model_extrapolated_far_beyond_clustered_gcps(clustered, kind,
                                                                             order, what):
    # degree 3 fitted the GCPs to 0.14 px and gave a 592 x 491 grid of 446 m pixels with 100
    # valid cells, without a word
    raster, gcps = clustered
    assert gcps.fit(3).rms(gcps.map_xy, gcps.image_xy) < 0.5
    message = (r"the output grid reaches [\d.]+ GCP extents \([\d.e+]+ map units\) beyond the "
               rf"GCPs' hull \(image point \(col, row\) .* lands at map .*\): {what} explodes "
               r"outside its GCPs.*add GCPs near the image's edges and corners, or use")
    with pytest.raises(ValueError, match=message):
        resample.georeference(raster, gcps, kind=kind, order=order)
    with pytest.raises(ValueError, match="explodes outside its GCPs"):   # before any PROJ step
        resample.georeference(raster, gcps, kind=kind, order=order, dst_crs="EPSG:29193")


@pytest.mark.parametrize("kind", ["polynomial", "linear", "helmert", "tps"])
def test_models_that_extrapolate_linearly_are_not_checked(clustered, recwarn, kind):
    # order 1, linear, Helmert and TPS (affine outside its GCPs) keep the scene's 20 m pixels
    raster, gcps = clustered
    out = resample.georeference(raster, gcps, kind=kind, order=1 if kind == "polynomial" else None)
    assert abs(out.transform.a - 20.0) < 1.0 and (out.array != 0).mean() > 0.9
    assert not [w for w in recwarn if "GCP extents" in str(w.message)]


def test_degree_3_on_gcps_spread_to_the_corners_is_neither_warned_nor_refused(recwarn):
    grid = np.linspace(0, 500, 5)
    cols, rows = (a.ravel() for a in np.meshgrid(grid, grid))
    raster, gcps = scene_and_gcps(cols, rows)
    out = resample.georeference(raster, gcps, order=3)
    assert abs(out.transform.a - 20.0) < 0.1
    assert not [w for w in recwarn if "GCP extents" in str(w.message)]


@pytest.mark.parametrize("kind, order", [("polynomial", 2), ("polynomial", 3),
                                         ("projective", None)])
def test_the_shipped_gcps_warn_that_degree_2_and_3_extrapolate_at_the_corners(kind, order):
    # the hand-made GCPs' hull leaves the scene's corners 0.29 to 0.39 GCP extents out; there
    # degree 3 and degree 1 differ by 53 px
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    with pytest.warns(ExtrapolationWarning,
                      match=r"the output grid reaches 0\.[23]\d+ GCP extents .*"
                            r"not controlled by its GCPs there.*predicted_error_map"):
        resample.georeference(raster, gcps, kind=kind, order=order, resolution=20.0)


# -- coordinates no position on Earth has never reach PROJ -----------------------------

HUGE_CASES = """
import time
from rsgeo import crs
calls = [
    lambda: crs.datum_shift([[1e30, 1e30]], "EPSG:29193", "EPSG:31983"),
    lambda: crs.transform_points([[1e30, 1e30]], "EPSG:29193", "EPSG:31983"),
    lambda: crs.transform_points([[1e30, 1e30]], "EPSG:29193", "EPSG:31983", check_area=False),
    lambda: crs.transform_points([[1e30, 1e30]], "EPSG:4326", "EPSG:31983"),
    lambda: crs.transform_points([[1e30, 1e30]], "EPSG:4326", "EPSG:31983", check_area=False),
    lambda: crs.datum_shift([[1e30, 1e30]], "EPSG:4326", "EPSG:31983"),
    # PROJ wraps a Web Mercator longitude by a loop: x = 1e18 m took minutes
    lambda: crs.transform_points([[1e18, 0.0]], "EPSG:3857", "EPSG:4326"),
    lambda: crs.transform_points([[1e30, 1e30]], "EPSG:3857", "EPSG:4326", check_area=False),
    lambda: crs.transform_points([[0.0, 0.0], [1e30, 0.0]], "EPSG:3857", "EPSG:29193",
                                    check_area=False),
]
for call in calls:
    try:
        call()
        print("answered")
    except ValueError as error:
        print(type(error).__name__, str(error)[:90])
"""


def test_huge_coordinates_are_refused_before_proj_promptly():
    import resource
    import subprocess
    import sys

    def cpu_limit():
        # in a subprocess with a CPU-time limit (a wide margin over the second it needs, which
        # a loaded machine does not stretch as it stretches the clock): a regression that
        # spins fails here instead of hanging the suite
        resource.setrlimit(resource.RLIMIT_CPU, (120, 120))

    run = subprocess.run([sys.executable, "-c", HUGE_CASES], capture_output=True, text=True,
                         preexec_fn=cpu_limit, timeout=3600)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert len(lines) == 9 and all(line.startswith("CRSError") for line in lines), lines
    # all but datum_shift 4326 -> 31983, refused first for its unlike CRSs
    assert sum("no position on Earth has" in line for line in lines) == 8, lines


def test_far_but_physical_coordinates_still_reach_proj():
    # Web Mercator at 1e8 m (2.5 times around the Earth) wraps, as PROJ does; beyond 1e9 m not
    moved = crs.transform_points([[1e8, 0.0]], "EPSG:3857", "EPSG:4326", check_area=False)
    xs, ys = rasterio.warp.transform("EPSG:3857", "EPSG:4326", [1e8], [0.0])
    np.testing.assert_array_equal(moved, np.column_stack([xs, ys]))
    with pytest.raises(ValueError, match=r"1 of 1 points have a coordinate that no position on "
                                         r"Earth has in EPSG:3857 \(first: point 0 \(2e\+09, 0\); "
                                         r"its coordinates stay within ±1e\+09 metre"):
        crs.transform_points([[2e9, 0.0]], "EPSG:3857", "EPSG:4326", check_area=False)
    with pytest.raises(ValueError, match=r"in EPSG:4326 .*stay within ±9000 degree"):
        crs.transform_points([[1e5, 0.0]], "EPSG:4326", "EPSG:4618", check_area=False)
    # the geographic limit is in turns, not metres: 720° still reaches PROJ
    moved = crs.transform_points([[720.0, 0.0]], "EPSG:4326", "EPSG:4618", check_area=False)
    assert np.isfinite(moved).all()


def test_georeference_blames_a_wrong_order_not_the_kind():
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    with pytest.raises(TypeError, match="order must be a number, got str '2'"):
        resample.georeference(raster, gcps, "polynomial", order="2")
