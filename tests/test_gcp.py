"""rsgeo.gcp against GDAL's GCP transformer, plus .points files and errors."""

import affine
import numpy as np
import pytest
from rasterio.control import GroundControlPoint
from rasterio.transform import GCPTransformer

from gdal_reference import gdal_map_to_image
from rsgeo import data, gcp
from rsgeo.resample import grid_positions


def utm_gcps(n, seed, blunders=0):
    """Random GCPs over a 1000 x 800 image with UTM-sized map coordinates and a gentle curvature."""
    rng = np.random.default_rng(seed)
    image_xy = np.column_stack([rng.uniform(0, 1000, n), rng.uniform(0, 800, n)])
    c, r = image_xy[:, 0], image_xy[:, 1]
    map_xy = np.column_stack([500_000 + 20 * c + 0.01 * r**1.5 + rng.normal(0, 15, n),
                              7_400_000 - 20 * r + 3 * c + 2e-5 * c * c + rng.normal(0, 15, n)])
    for k in range(blunders):
        image_xy[3 * k + 1] += (25 + 10 * k, -30)
    return image_xy, map_xy


@pytest.mark.parametrize("order, n", [(1, 8), (2, 12), (3, 20), (3, 10)])
def test_map_to_image_agrees_with_gdal(order, n):
    # GDAL's own reference: a warped VRT with <Order>, no approximate transformer (Reference: gdal_crs.cpp)
    image_xy, map_xy = utm_gcps(n, seed=order * 100 + n)
    dst_transform = affine.Affine(20, 0, map_xy[:, 0].min() + 2000, 0, -20, map_xy[:, 1].max() - 2000)
    gdal_cols, gdal_rows = gdal_map_to_image(image_xy, map_xy, order, dst_transform, (150, 150))
    x, y = grid_positions((150, 150), dst_transform)
    predicted = gcp.fit_polynomial(map_xy, image_xy, order)(np.column_stack([x.ravel(), y.ravel()]))
    inside = np.isfinite(gdal_cols.ravel())
    assert inside.sum() > 5000
    assert np.abs(predicted[inside, 0] - gdal_cols.ravel()[inside]).max() < 1e-6
    assert np.abs(predicted[inside, 1] - gdal_rows.ravel()[inside]).max() < 1e-6


@pytest.mark.parametrize("order, n", [(1, 5), (2, 9)])
def test_image_to_map_agrees_with_rasterio_gcp_transformer(order, n):
    # rasterio's GCPTransformer picks GDAL's order from the count: 1 below 6 GCPs, else 2.
    image_xy, map_xy = utm_gcps(n, seed=7 + n)
    gcps = [GroundControlPoint(row=r, col=c, x=x, y=y) for (c, r), (x, y) in zip(image_xy, map_xy)]
    rng = np.random.default_rng(1)
    cols, rows = rng.uniform(0, 1000, 300), rng.uniform(0, 800, 300)
    with GCPTransformer(gcps) as transformer:
        xs, ys = transformer.xy(rows, cols, offset="ul")
    predicted = gcp.fit_polynomial(image_xy, map_xy, order)(np.column_stack([cols, rows]))
    # 1e-6 pixel = 2e-5 m at 20 m pixels
    np.testing.assert_allclose(predicted, np.column_stack([xs, ys]), rtol=0, atol=2e-5)


def test_refinement_removes_the_same_gcps_as_gdal():
    image_xy, map_xy = utm_gcps(14, seed=5, blunders=2)
    tolerance, minimum = 40.0, 6      # metres: GDAL's residuals are pixel -> map
    _, kept = gcp.refine_gcps(image_xy, map_xy, 1, tolerance, minimum)
    assert (~kept).sum() == 2 and not kept[1] and not kept[4]
    dst_transform = affine.Affine(20, 0, map_xy[:, 0].min() + 2000, 0, -20, map_xy[:, 1].max() - 2000)
    gdal_cols, gdal_rows = gdal_map_to_image(image_xy, map_xy, 1, dst_transform, (100, 100),
                                             refine=(tolerance, minimum))
    x, y = grid_positions((100, 100), dst_transform)
    refitted = gcp.fit_polynomial(map_xy[kept], image_xy[kept], 1)(np.column_stack([x.ravel(), y.ravel()]))
    inside = np.isfinite(gdal_cols.ravel())
    assert np.abs(refitted[inside, 0] - gdal_cols.ravel()[inside]).max() < 1e-6
    assert np.abs(refitted[inside, 1] - gdal_rows.ravel()[inside]).max() < 1e-6


def test_exact_with_the_minimum_number_of_gcps():
    for order in (1, 2, 3):
        image_xy, map_xy = utm_gcps(gcp.min_gcps(order), seed=order)
        model = gcp.fit_polynomial(map_xy, image_xy, order)
        np.testing.assert_allclose(model(map_xy), image_xy, atol=1e-6)


def test_reverse_is_fitted_separately():
    image_xy, map_xy = utm_gcps(12, seed=3)
    model = gcp.fit_polynomial(map_xy, image_xy, 2)
    reverse = model.reverse()
    np.testing.assert_allclose(reverse.src, image_xy)
    assert gcp.rms_error(reverse(image_xy), map_xy) < 40


def test_rms_and_mean_error_by_hand():
    predicted = np.array([[0.0, 0.0], [3.0, 4.0], [0.0, 1.0], [1.0, 0.0]])
    observed = np.zeros((4, 2))
    assert gcp.rms_error(predicted, observed) == pytest.approx(np.sqrt((0 + 25 + 1 + 1) / 4))
    assert gcp.mean_error(predicted, observed, order=1) == pytest.approx(np.sqrt(27 / 1))


def test_points_file_round_trip(tmp_path):
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    gcps.enabled[3] = False
    model = gcps.fit(1)
    path = tmp_path / "ccd.points"
    gcp.write_points(path, gcps, model)
    again = gcp.read_points(path)
    np.testing.assert_array_equal(again.map_xy, gcps.map_xy)
    np.testing.assert_array_equal(again.image_xy, gcps.image_xy)
    np.testing.assert_array_equal(again.enabled, gcps.enabled)
    assert again.crs == gcps.crs
    header = path.read_text().splitlines()[1]
    assert header == "mapX,mapY,sourceX,sourceY,enable,dX,dY,residual"


def test_reads_qgis_files_new_and_old(tmp_path):
    # Written by hand after QGIS Georeferencer's format: sourceY is minus the line number.
    new = tmp_path / "new.points"
    new.write_text("#CRS: EPSG:31983\n"
                   "mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n"
                   "330000.5,7390000.25,10.5,-20.25,1,0.1,-0.2,0.22\n"
                   "331000,7389000,110,-120,0,0,0,0\n"
                   "332000,7391000,210,-20,1,0,0,0\n")
    gcps = gcp.read_points(new)
    assert gcps.crs == "EPSG:31983"
    np.testing.assert_array_equal(gcps.image_xy[0], [10.5, 20.25])
    np.testing.assert_array_equal(gcps.map_xy[0], [330000.5, 7390000.25])
    assert gcps.enabled.tolist() == [True, False, True]
    old = tmp_path / "old.points"
    old.write_text("mapX\tmapY\tpixelX\tpixelY\tenable\n330000\t7390000\t10\t-20\t1\n"
                   "331000\t7389000\t110\t-120\t1\n332000\t7391000\t210\t-20\t1\n")
    assert gcp.read_points(old).image_xy[1].tolist() == [110.0, 120.0]


@pytest.mark.parametrize("src, dst, order, message", [
    (np.zeros((4, 2)) + np.arange(4)[:, None] * [1, 2], np.random.default_rng(0).random((4, 2)), 2,
     "order 2 needs at least 6 GCPs, got 4"),
    (np.column_stack([np.arange(5.0), 2 * np.arange(5.0)]), np.random.default_rng(0).random((5, 2)), 1,
     "collinear, repeated"),
    (np.array([[0, 0], [1, 0], [0, 1], [1, 1.0]]).repeat(2, axis=0), np.random.default_rng(0).random((8, 2)), 2,
     "collinear, repeated"),
    (np.array([[0, 0], [1, np.nan], [0, 1.0]]), np.zeros((3, 2)), 1, "NaN or infinite"),
    (np.array([[0, 0], [1, np.inf], [0, 1.0]]), np.zeros((3, 2)), 1, "NaN or infinite"),
    (np.zeros((5, 3)), np.zeros((5, 2)), 1, r"\(n, 2\)"),
    (np.random.default_rng(0).random((5, 2)), np.zeros((4, 2)), 1, "same GCPs"),
    (np.random.default_rng(0).random((12, 2)), np.zeros((12, 2)), 4, "must be 1, 2 or 3"),
    (np.random.default_rng(0).random((12, 2)), np.zeros((12, 2)), 0, "must be 1, 2 or 3"),
])
def test_bad_gcps_are_clear_value_errors(src, dst, order, message):
    with pytest.raises(ValueError, match=message):
        gcp.fit_polynomial(src, dst, order)


def test_coefficients_in_the_lecture_order():
    src = np.random.default_rng(2).random((10, 2)) * 100
    dst = np.column_stack([1 + 2 * src[:, 0] + 3 * src[:, 1] + 4 * src[:, 0] * src[:, 1],
                           5 + 6 * src[:, 0] ** 2 + 7 * src[:, 1] ** 2])
    model = gcp.fit_polynomial(src - src.mean(axis=0), dst, 2)
    table = model.coefficient_table()
    assert list(table)[:6] == ["a0 (1)", "a1 (x)", "a2 (y)", "a3 (xy)", "a4 (x²)", "a5 (y²)"]
    assert table["a3 (xy)"] == pytest.approx(4) and table["b5 (y²)"] == pytest.approx(7)
