"""The thin-plate spline of chapter 3b's comparison is GDAL's: the one gdalwarp -tps and QGIS's
Georeferencer use, fitted image -> map and inverted point by point (GDAL's TPS transformer,
``alg/gdal_tps.cpp``), not a spline fitted map -> image.

GDAL 3.10 through rasterio is the reference (``gdal_tps_reference``), on the course's 14 CBERS
CCD -> HRC GCPs with the blunder G10 (chapter 3b's first table) and without it.
"""

import numpy as np
import pytest

from rsgeo import accuracy, data, transforms

from gdal_tps_reference import gdal_spline_inverse

pytestmark = pytest.mark.gdal

TPS = [("tps", "tps", None)]


def course_gcps(with_g10=True):
    """Chapter 3b's GCPs: map (x, y) and image (col, row), G10 included or not."""
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    keep = np.ones(len(gcps), bool) if with_g10 else np.array(gcps.ids) != "G10"
    return gcps.map_xy[keep], gcps.image_xy[keep]


def around(map_xy, n=60, margin=0.05):
    """An n x n grid over the GCPs' bounding box and ``margin`` of it beyond (the model
    explorer's grid reaches 5 % beyond)."""
    low, high = map_xy.min(axis=0), map_xy.max(axis=0)
    pad = margin * (high - low)
    xs = np.linspace(low[0] - pad[0], high[0] + pad[0], n)
    ys = np.linspace(low[1] - pad[1], high[1] + pad[1], n)
    return np.column_stack([g.ravel() for g in np.meshgrid(xs, ys)])


def gdal_left_out(map_xy, image_xy):
    """(n, 2): GDAL's TPS fitted pixel -> map without GCP i, its map -> pixel at GCP i, minus
    GCP i's pixel."""
    out = np.empty_like(image_xy)
    for i in range(len(map_xy)):
        others = np.arange(len(map_xy)) != i
        out[i] = gdal_spline_inverse(image_xy[others], map_xy[others], map_xy[i:i + 1])[0]
    return out - image_xy


def rms(difference):
    return float(np.sqrt(np.mean(np.sum(difference**2, axis=1))))


@pytest.mark.parametrize("with_g10", [True, False])
def test_the_spline_map_to_image_is_gdals_transformer(with_g10):
    # what compare_models, the model explorer and chapter 3b's blunder map evaluate: the spline
    # fitted image -> map, inverted; GDAL's TPS transformer from map to pixel, to the last bit
    map_xy, image_xy = course_gcps(with_g10)
    points = np.vstack([map_xy, around(map_xy)])
    got = transforms.fit_transform(image_xy, map_xy, "tps").inverse()(points)
    expected = gdal_spline_inverse(image_xy, map_xy, points)
    assert np.abs(got - expected).max() < 1e-6
    assert np.array_equal(got, expected)


@pytest.mark.parametrize("with_g10", [True, False])
def test_compare_models_measures_gdals_spline(with_g10):
    map_xy, image_xy = course_gcps(with_g10)
    is_check = np.zeros(len(map_xy), bool)
    is_check[::3] = True
    table = accuracy.compare_models(map_xy, image_xy, is_check, TPS)
    fit_map, fit_image = map_xy[~is_check], image_xy[~is_check]
    # check points: GDAL's TPS fitted pixel -> map on the other GCPs, from map to pixel
    at_checks = gdal_spline_inverse(fit_image, fit_map, map_xy[is_check])
    assert abs(table.loc["tps", "check RMS (px)"] - rms(at_checks - image_xy[is_check])) < 1e-9
    # leave-one-out on the fitting GCPs, each refitted by GDAL without it
    gdal_loo = rms(gdal_left_out(fit_map, fit_image))
    assert abs(table.loc["tps", "leave-one-out RMS (px)"] - gdal_loo) < 1e-9
    # it passes through its GCPs in that direction too, and has 2 (n + 3) parameters
    assert table.loc["tps", "fitting RMS (px)"] < 1e-9
    assert table.loc["tps", "parameters"] == 2 * ((~is_check).sum() + 3)


def test_the_spline_fitted_map_to_image_is_another_model():
    # the form chapter 3b used before: fitted map -> image directly. Same GCPs, same zero
    # residuals, but on the course's GCPs with G10 it is more than half a pixel from GDAL's
    # between them (the docstring of compare_models says so), and its leave-one-out RMS is a
    # tenth of a pixel off: a compare_models that fitted it would fail the test above
    map_xy, image_xy = course_gcps(with_g10=True)
    direct = transforms.fit_transform(map_xy, image_xy, "tps")
    points = around(map_xy, margin=0.0)
    gap = np.hypot(*(direct(points) - gdal_spline_inverse(image_xy, map_xy, points)).T)
    assert gap.max() > 0.5
    np.testing.assert_allclose(direct(map_xy), image_xy, atol=1e-9)
    table = accuracy.compare_models(map_xy, image_xy, models=TPS)
    direct_loo = rms(accuracy.leave_one_out_residuals(map_xy, image_xy, "tps"))
    gdal_loo = rms(gdal_left_out(map_xy, image_xy))
    assert abs(direct_loo - gdal_loo) > 0.05
    assert abs(table.loc["tps", "leave-one-out RMS (px)"] - direct_loo) > 0.05
    # without G10 the two forms are within a few hundredths of a pixel of each other
    clean_map, clean_image = course_gcps(with_g10=False)
    points = around(clean_map, margin=0.0)
    clean_gap = np.hypot(*(transforms.fit_transform(clean_map, clean_image, "tps")(points)
                           - gdal_spline_inverse(clean_image, clean_map, points)).T)
    assert clean_gap.max() < 0.1 < gap.max()


def test_the_other_models_are_unchanged():
    # only the spline changed: every other kind is fitted map -> image, as before
    map_xy, image_xy = course_gcps()
    models = [m for m in transforms.GEOREFERENCER_MODELS if m[1] != "tps"]
    table = accuracy.compare_models(map_xy, image_xy, models=models)
    for label, kind, order in models:
        model = transforms.fit_transform(map_xy, image_xy, kind, order)
        loo = accuracy.leave_one_out_errors(map_xy, image_xy, order, kind)
        assert table.loc[label, "fitting RMS (px)"] == model.rms(map_xy, image_xy)
        assert table.loc[label, "leave-one-out RMS (px)"] == float(np.sqrt(np.mean(loo**2)))
