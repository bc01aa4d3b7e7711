"""CRSs, datum shifts and a complete georeferencing run, checked against GDAL/PROJ."""

from xml.sax.saxutils import escape

import affine
import numpy as np
import pytest
import rasterio
from rasterio.control import GroundControlPoint
from rasterio.warp import calculate_default_transform

from rsgeo import data, georef, radiometry
from rsgeo.gcp import GCPSet

from gdal_reference import affine_source, gcp_source, gdal_warp

SAD69_UTM21S, SIRGAS_UTM21S = "EPSG:29191", "EPSG:31981"
SAD69_UTM23S, SIRGAS_UTM23S = "EPSG:29193", "EPSG:31983"


def reprojection_xml(src_crs, dst_crs):
    """GDAL's exact reprojection step (no approximate transformer: gdalwarp -et 0)."""
    return (f"<ReprojectTransformer><ReprojectionTransformer>"
            f"<SourceSRS>{escape(georef.as_crs(src_crs).to_wkt())}</SourceSRS>"
            f"<TargetSRS>{escape(georef.as_crs(dst_crs).to_wkt())}</TargetSRS>"
            f"</ReprojectionTransformer></ReprojectTransformer>")


@pytest.fixture(scope="module")
def nat1_crop():
    raster = data.load("nat1")
    # a crop keeps the test quick
    window = raster.array[300:560, 200:470]
    transform = raster.transform @ affine.Affine.translation(200, 300)
    return data.Raster(window, transform, raster.crs, None, raster.description, "nat1")


@pytest.mark.parametrize("method", ["nearest", "bilinear", "cubic"])
def test_sad69_to_sirgas_warp_equals_gdalwarp(nat1_crop, method):
    out = georef.reproject(nat1_crop, SIRGAS_UTM23S, method=method, nodata=0)
    assert out.crs.to_epsg() == 31983
    xml = affine_source(nat1_crop.transform) + reprojection_xml(nat1_crop.crs, SIRGAS_UTM23S)
    reference = gdal_warp(nat1_crop.array, xml, out.transform, out.array.shape, method, 0)
    assert (out.array != 0).mean() > 0.9
    np.testing.assert_array_equal(out.array, reference)


def test_transform_points_matches_proj_and_the_helmert_shift():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    moved = georef.transform_points(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    xs, ys = rasterio.warp.transform(SAD69_UTM21S, SIRGAS_UTM21S, gcps.map_xy[:, 0],
                                     gcps.map_xy[:, 1])
    np.testing.assert_array_equal(moved, np.column_stack([xs, ys]))
    dx, dy, distance = georef.datum_shift(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    # EPSG:15485 translates by (-67.35, 3.88, -38.22) m: about 68 m horizontally, to the SW here
    assert np.all((distance > 60) & (distance < 75))
    assert np.all(dx < 0) and np.all(dy < 0)
    back = georef.transform_points(moved, SIRGAS_UTM21S, gcps.crs)
    np.testing.assert_allclose(back, gcps.map_xy, atol=1e-6)


@pytest.mark.parametrize("bad", ["EPSG:999999", "not a crs", 12345678])
def test_a_crs_proj_does_not_know_is_a_value_error(bad):
    with pytest.raises(ValueError, match="not a CRS that PROJ knows"):
        georef.transform_points([[500000.0, 7400000.0]], bad, SIRGAS_UTM23S)
    with pytest.raises(ValueError, match="not a CRS that PROJ knows"):
        data.load_gcps("cbers2b_ccd_hrc").to_crs(bad)
    with pytest.raises(ValueError, match="not a CRS that PROJ knows"):
        georef.georeference(data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc"),
                            dst_crs=bad)


def test_gcpset_to_crs_moves_map_coordinates_only():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    moved = gcps.to_crs(SIRGAS_UTM21S)
    assert georef.as_crs(moved.crs).to_epsg() == 31981
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


@pytest.mark.parametrize("order", [1, 2, 3])
def test_output_grid_is_gdals_suggestion(order):
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    height, width = raster.array.shape[-2:]
    points = [GroundControlPoint(row=r, col=c, x=x, y=y, z=0.0)
              for (c, r), (x, y) in zip(gcps.image_xy, gcps.map_xy)]
    transform, cols, rows = calculate_default_transform(
        gcps.crs, gcps.crs, width, height, gcps=points, MAX_GCP_ORDER=order)
    out = georef.georeference(raster, gcps, order=order)
    assert out.array.shape[-2:] == (rows, cols)
    np.testing.assert_allclose(tuple(out.transform)[:6], tuple(transform)[:6], rtol=0, atol=1e-6)


@pytest.mark.parametrize("order, method, dst_crs", [(1, "nearest", None),
                                                    (2, "bilinear", None),
                                                    (2, "cubic", SIRGAS_UTM21S)])
def test_georeference_saved_geotiff_equals_gdalwarp(tmp_path, order, method, dst_crs):
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    out = georef.georeference(raster, gcps, order=order, resolution=20.0, method=method,
                              nodata=0, dst_crs=dst_crs)
    written = data.save(tmp_path / "corrected.tif", out)
    with rasterio.open(written) as dataset:
        back = dataset.read()
        assert dataset.crs == georef.as_crs(dst_crs or gcps.crs)
        assert dataset.transform == out.transform and dataset.nodata == 0
        assert dataset.transform.a == 20.0
    np.testing.assert_array_equal(back, out.array)
    xml = gcp_source(gcps.image_xy, gcps.map_xy, order)
    if dst_crs is not None:
        xml += reprojection_xml(gcps.crs, dst_crs)
    reference = gdal_warp(raster.array, xml, out.transform, back.shape[-2:], method, 0)
    np.testing.assert_array_equal(back, reference)


def test_georeference_reads_a_path_and_checks_its_input(tmp_path):
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    from_path = georef.georeference(data.path("cbers2b_rgb342"), gcps, order=1)
    from_raster = georef.georeference(data.load("cbers2b_rgb342"), gcps, order=1)
    np.testing.assert_array_equal(from_path.array, from_raster.array)
    with pytest.raises(ValueError, match="resolution must be .* above 0"):
        georef.georeference(data.load("cbers2b_rgb342"), gcps, resolution=0.0)
    with pytest.raises(ValueError, match="resolution must be .* above 0"):
        georef.reproject(data.load("nat1"), SIRGAS_UTM23S, resolution=-25.0)
    with pytest.raises(ValueError, match="cannot read"):
        georef.georeference(tmp_path / "missing.tif", gcps)
    with pytest.raises(ValueError, match="no CRS"):
        georef.georeference(data.load("cbers2b_rgb342"), GCPSet(gcps.map_xy, gcps.image_xy),
                            dst_crs=SIRGAS_UTM21S)
    with pytest.raises(ValueError, match="unknown method"):
        georef.georeference(data.load("cbers2b_rgb342"), gcps, method="lanczos")


def test_overlap_refuses_rasters_in_different_crss():
    a = data.load("cbers_b2_A")
    b = data.load("cbers_b2_C")
    moved = data.Raster(b.array, b.transform, georef.as_crs(31982), None, "", "C in SIRGAS")
    with pytest.raises(ValueError, match=r"different CRSs.*georef\.reproject"):
        radiometry.overlap(a, moved)
    unplaced = data.Raster(b.array, b.transform, None, None, "", "C without CRS")
    with pytest.raises(ValueError, match="EPSG:29192 and no CRS"):
        radiometry.overlap(a, unplaced)
    assert radiometry.overlap(a, b)[0].size > 0


def test_proj_uses_epsg_15485_offline_the_three_translations():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    by_proj = georef.transform_points(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    by_hand = georef.geocentric_translation(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
    assert np.abs(by_hand - by_proj).max() < 1e-3
    # the ellipsoid change alone (no translation) is tens of metres away: the check can fail
    ellipsoid_only = georef.geocentric_translation(gcps.map_xy, gcps.crs, SIRGAS_UTM21S, (0, 0, 0))
    assert np.abs(ellipsoid_only - by_proj).max() > 10
    with pytest.raises(ValueError, match="three finite numbers"):
        georef.geocentric_translation(gcps.map_xy, gcps.crs, SIRGAS_UTM21S, (1.0, 2.0))


def test_check_datum_shift_pixels_judges_form_then_value_without_telling_it():
    from rsgeo.exercises import ExerciseNotSolved, check_datum_shift_pixels

    gcps = data.load_gcps("cbers2b_ccd_hrc")
    dx, dy, distance = georef.datum_shift(gcps.map_xy, gcps.crs, SIRGAS_UTM21S)
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
    linear = georef.georeference(raster, gcps, order=1, resolution=20.0)
    helmert = georef.georeference(raster, gcps, kind="helmert", order=None, resolution=20.0)
    assert "helmert" in helmert.description and "None" not in helmert.description
    # a similarity and an affine model of the same GCPs place the scene within a few pixels
    assert abs(helmert.transform.c - linear.transform.c) < 5 * 20.0
    assert abs(helmert.array.shape[-1] - linear.array.shape[-1]) < 5
