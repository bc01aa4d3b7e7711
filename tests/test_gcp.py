"""rsgeo.gcp against GDAL's GCP transformer, plus .points files and errors."""

import affine
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
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


def test_reverse_is_the_least_squares_fit_of_the_other_direction():
    # GDAL fits image -> map separately: the reverse's residuals must satisfy the normal equations
    # of the image -> map system (orthogonal to every term), and differ from the forward's inverse
    image_xy, map_xy = utm_gcps(12, seed=3)
    model = gcp.fit_polynomial(map_xy, image_xy, 2)
    reverse = model.reverse()
    centred = (image_xy - image_xy.mean(axis=0)) / 1000
    terms = gcp.design_matrix(centred, 2)
    left_over = reverse(image_xy) - map_xy
    assert np.abs(terms.T @ left_over).max() < 1e-6 * np.abs(left_over).max() * len(terms)
    assert 5 < reverse.rms(image_xy, map_xy) < 40          # GCP noise of 15 m, not zero
    # swapping back gives the forward model again
    np.testing.assert_allclose(reverse.reverse()(map_xy), model(map_xy), atol=1e-6)


def test_inverse_undoes_the_model_where_the_reverse_fit_does_not():
    image_xy, map_xy = utm_gcps(12, seed=3)
    model = gcp.fit_polynomial(map_xy, image_xy, 2)
    inside = map_xy.mean(axis=0) + np.random.default_rng(0).uniform(-4000, 4000, (50, 2))
    np.testing.assert_allclose(model.inverse()(model(inside)), inside, atol=1e-6)
    assert model.inverse().inverse() is model
    assert model.inverse().residuals(model(inside), inside).max() < 1e-6
    assert np.abs(model.reverse()(model(inside)) - inside).max() > 0.01     # only approximate


def test_jacobian_matches_finite_differences():
    image_xy, map_xy = utm_gcps(20, seed=4)
    model = gcp.fit_polynomial(map_xy, image_xy, 3)
    point = map_xy[:3]
    step = 1e-2
    numeric = np.stack([(model(point + [step, 0]) - model(point - [step, 0])) / (2 * step),
                        (model(point + [0, step]) - model(point - [0, step])) / (2 * step)], axis=-1)
    np.testing.assert_allclose(model.jacobian(point), numeric, rtol=1e-6, atol=1e-9)


def test_inverse_refuses_points_where_the_polynomial_folds():
    src = np.array([[x, y] for x in (-1.0, 0.0, 1.0) for y in (-1.0, 0.0, 1.0)])
    u = src[:, 0] + 0.8 * src[:, 0] ** 2                   # never below -0.3125 (at x = -0.625)
    model = gcp.fit_polynomial(src, np.column_stack([u, src[:, 1]]), 2)
    with pytest.raises(ValueError, match="no inverse"):
        model.inverse()([[-1.0, 0.0]])


def test_residuals_and_rms_are_the_protocols():
    image_xy, map_xy = utm_gcps(12, seed=8)
    model = gcp.fit_polynomial(map_xy, image_xy, 1)
    dx, dy, distance = gcp.residuals(model, map_xy, image_xy)
    np.testing.assert_allclose(model.residuals(map_xy, image_xy), np.hypot(dx, dy))
    np.testing.assert_allclose(model.residuals(map_xy, image_xy), distance)
    expected = np.sqrt(np.mean(np.sum((model(map_xy) - image_xy) ** 2, axis=1)))
    assert model.rms(map_xy, image_xy) == pytest.approx(expected, rel=1e-12)
    assert model.rms(map_xy, image_xy) > 0.1
    with pytest.raises(ValueError, match="same points"):
        model.residuals(map_xy, image_xy[:-1])


@settings(max_examples=60, deadline=None)
@given(order=st.sampled_from([1, 2, 3]), seed=st.integers(0, 10_000),
       u=st.floats(0.1, 0.9), v=st.floats(0.1, 0.9), bend=st.floats(-0.15, 0.15))
def test_every_polynomial_inverse_round_trips(order, seed, u, v, bend):
    # a smooth, one-to-one map -> image mapping, sampled at enough GCPs for the order
    rng = np.random.default_rng(seed)
    image_xy = rng.uniform(0, 1000, (gcp.min_gcps(order) + 6, 2))
    c, r = image_xy[:, 0] / 1000, image_xy[:, 1] / 1000
    map_xy = np.column_stack([500_000 + 20_000 * (c + bend * r * r), 7_400_000 - 20_000 * (r + bend * c * r)])
    model = gcp.fit_polynomial(map_xy, image_xy, order)
    inside = np.array([[500_000 + 20_000 * u, 7_400_000 - 20_000 * v]])
    np.testing.assert_allclose(model.inverse()(model(inside)), inside, rtol=0, atol=1e-5)
    image_point = model(inside)
    np.testing.assert_allclose(model(model.inverse()(image_point)), image_point, rtol=0, atol=1e-6)


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


# -- Coefficient standard errors, checks against a geotransform, silent failures ----------


def test_standard_errors_follow_the_textbook_formula():
    # s² (AᵀA)⁻¹ written out on the lecture's term order, x and y measured from the GCPs' mean
    rng = np.random.default_rng(11)
    src = rng.uniform(-3000, 3000, (15, 2)) + [774_000, 7_366_000]
    dst = np.column_stack([200 + 0.05 * (src[:, 0] - 774_000), 190 - 0.05 * (src[:, 1] - 7_366_000)])
    dst = dst + rng.normal(0, 0.5, dst.shape)
    for order in (1, 2, 3):
        model = gcp.fit_polynomial(src, dst, order)
        a = gcp.design_matrix(src - src.mean(axis=0), order)
        n, m = a.shape
        s2 = np.sum((a @ model.coefficients.T - dst) ** 2, axis=0) / (n - m)
        expected = np.sqrt(np.outer(s2, np.diag(np.linalg.inv(a.T @ a))))
        np.testing.assert_allclose(model.standard_errors(), expected, rtol=1e-6)
        summary = model.coefficient_summary()
        assert list(summary.index) == list(model.coefficient_table())
        np.testing.assert_allclose(summary["standard error"], expected.ravel(), rtol=1e-6)


def test_standard_errors_match_the_spread_of_refitted_coefficients():
    # known noise σ: the coefficients' spread over many noisy GCP sets is σ sqrt(diag((AᵀA)⁻¹))
    rng = np.random.default_rng(3)
    src = rng.uniform(0, 1000, (12, 2))
    truth = np.column_stack([5 + 0.8 * src[:, 0] + 0.1 * src[:, 1], 2 - 0.2 * src[:, 0] + src[:, 1]])
    sigma = 0.5
    a = gcp.design_matrix(src - src.mean(axis=0), 1)
    theory = sigma * np.sqrt(np.diag(np.linalg.inv(a.T @ a)))
    fits = [gcp.fit_polynomial(src, truth + rng.normal(0, sigma, truth.shape), 1) for _ in range(600)]
    spread = np.std([f.coefficients for f in fits], axis=0)
    estimated = np.mean([f.standard_errors() for f in fits], axis=0)
    np.testing.assert_allclose(spread, np.vstack([theory, theory]), rtol=0.12)
    np.testing.assert_allclose(estimated, np.vstack([theory, theory]), rtol=0.12)


def test_standard_errors_need_a_redundant_gcp():
    image_xy, map_xy = utm_gcps(3, seed=1)
    with pytest.raises(ValueError, match="need more than 3 GCPs"):
        gcp.fit_polynomial(map_xy, image_xy, 1).standard_errors()


def test_geotransform_check_measures_a_known_offset():
    transform = affine.Affine(20, 0, 770_000, 0, -20, 7_370_000)
    rng = np.random.default_rng(4)
    image_xy = rng.uniform(0, 300, (10, 2))
    map_xy = np.column_stack(transform @ image_xy.T)
    exact = gcp.fit_polynomial(map_xy, image_xy, 1)
    check = gcp.compare_with_geotransform(exact, transform, (300, 320), step=7)
    assert check.rms < 1e-6 and check.max_error < 1e-6
    shifted = gcp.fit_polynomial(map_xy, image_xy + [0.3, -1.2], 1)
    check = gcp.compare_with_geotransform(shifted, transform, (300, 320))
    np.testing.assert_allclose(check.mean_offset, [0.3, -1.2], atol=1e-6)
    assert check.rms == pytest.approx(np.hypot(0.3, 1.2)) and check.centred_rms < 1e-6
    assert check.points.shape == (300 * 320, 2)
    # a scale error: zero at the centre, growing to the corners; the mean offset misses it
    scaled = gcp.fit_polynomial(map_xy, (image_xy - 150) * 1.01 + 150, 1)
    check = gcp.compare_with_geotransform(scaled, transform, (300, 300))
    assert np.abs(check.mean_offset).max() < 1e-6
    assert check.max_error == pytest.approx(0.01 * np.hypot(149.5, 149.5), rel=1e-6)


def test_geotransform_check_rejects_bad_input():
    model = gcp.fit_polynomial(*utm_gcps(6, seed=2)[::-1], 1)
    transform = affine.Affine(20, 0, 500_000, 0, -20, 7_400_000)
    with pytest.raises(ValueError, match="affine.Affine"):
        gcp.compare_with_geotransform(model, (20, 0, 0, 0, -20, 0), (10, 10))
    with pytest.raises(ValueError, match="cannot be inverted"):
        gcp.compare_with_geotransform(model, affine.Affine(0, 0, 0, 0, 0, 0), (10, 10))
    with pytest.raises(ValueError, match="shape must be"):
        gcp.compare_with_geotransform(model, transform, (10, 0))
    with pytest.raises(ValueError, match="step must be"):
        gcp.compare_with_geotransform(model, transform, (10, 10), step=0)


def _textured(shape, seed):
    from scipy.ndimage import gaussian_filter

    return gaussian_filter(np.random.default_rng(seed).normal(0, 1, shape), 12) * 400 + 100


def test_offsets_against_reference_recover_a_shifted_geotransform():
    # the coarse image is the fine one averaged 8 × 8; its declared geotransform is 10 m east and
    # 30 m north of the truth, so its content sits (+0.5, -1.5) pixels from where it says
    fine = _textured((1600, 1600), seed=8)
    fine_transform = affine.Affine(2.5, 0, 770_000, 0, -2.5, 7_370_000)
    coarse = fine.reshape(200, 8, 200, 8).mean(axis=(1, 3))
    declared = affine.Affine(20, 0, 770_000 + 10, 0, -20, 7_370_000 + 30)
    points, offsets = gcp.offsets_against_reference(coarse, declared, fine, fine_transform,
                                                    step=40, window=64)
    assert len(points) >= 9
    np.testing.assert_allclose(np.median(offsets, axis=0), [0.5, -1.5], atol=0.1)
    declared = affine.Affine(20, 0, 770_000 - 5, 0, -20, 7_370_000 - 13)   # (-0.25, +0.65) px
    _, offsets = gcp.offsets_against_reference(coarse, declared, fine, fine_transform,
                                               step=40, window=64)
    np.testing.assert_allclose(np.median(offsets, axis=0), [-0.25, 0.65], atol=0.15)
    _, none = gcp.offsets_against_reference(coarse, fine_transform @ fine_transform.scale(8),
                                            fine, fine_transform, step=40, window=64)
    np.testing.assert_allclose(np.median(none, axis=0), [0, 0], atol=0.1)
    with pytest.raises(ValueError, match="whole multiple"):
        gcp.offsets_against_reference(coarse, affine.Affine(21, 0, 770_000, 0, -21, 7_370_000),
                                      fine, fine_transform)
    with pytest.raises(ValueError, match="north-up"):
        gcp.offsets_against_reference(coarse, affine.Affine(20, 1, 770_000, 0, -20, 7_370_000),
                                      fine, fine_transform)


@pytest.mark.parametrize("call, message", [
    (lambda: gcp.rms_error(np.zeros((0, 2)), np.zeros((0, 2))), "no points"),
    (lambda: gcp.mean_error(np.ones((5, 2)), np.zeros((1, 2)), 1), "same shape"),
    (lambda: gcp.mean_error(np.ones((5, 2)), np.full((5, 2), np.nan), 1), "NaN"),
    (lambda: gcp.refine_gcps(*utm_gcps(8, seed=1), 1, 5.0, min_gcps=9), "exceeds the number"),
    (lambda: gcp.fit_with_check_points(*utm_gcps(8, seed=1), 1, [0, 0.5, 0, 0, 0, 1, 0, 0]),
     "True/False"),
    (lambda: gcp.fit_with_check_points(*utm_gcps(8, seed=1), 1, [0, np.nan, 0, 0, 0, 1, 0, 0]),
     "True/False"),
    (lambda: gcp.leave_one_out_errors(np.random.default_rng(0).random((6, 2)),
                                      np.random.default_rng(1).random((7, 2)), 1), "same GCPs"),
    (lambda: gcp.leave_one_out_errors(*utm_gcps(6, seed=1), 2), "needs at least 7 GCPs"),
    (lambda: gcp.hull_coverage(np.random.default_rng(0).random((5, 2)), 0, 100), "positive"),
    (lambda: gcp.hull_coverage(np.random.default_rng(0).random((5, 2)), np.nan, 100), "width"),
    (lambda: gcp.predicted_error_map(utm_gcps(8, seed=1)[1], 1, np.zeros(3), np.zeros(3),
                                     gcp_error=-1), "gcp_error"),
    (lambda: gcp.predicted_error_map(utm_gcps(8, seed=1)[1], 1, np.zeros(3), np.zeros(4)),
     "same shape"),
    (lambda: gcp.measure_shifts(np.ones((50, 50)), np.ones((50, 50)), window=64), "larger than"),
    (lambda: gcp.measure_shifts(np.full((80, 80), np.nan), np.ones((80, 80))), "NaN"),
    (lambda: gcp.measure_shifts(np.ones((80, 80)), np.ones((80, 80)), step=0), "step"),
    (lambda: gcp.GCPSet(np.zeros((3, 2)), np.zeros((3, 2)), enabled=[1, np.nan, 0]), "True/False"),
])
def test_silent_wrong_answers_are_value_errors(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_residual_arrows_point_down_the_image_for_positive_dy():
    # rows grow downwards: a GCP whose model position is 5 rows lower must draw downwards on screen
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from rsgeo.plot import draw_residual_arrows, figure_problems, label_points, show_image

    figure, ax = plt.subplots()
    show_image(ax, np.zeros((100, 100)), title="arrows")
    arrows = draw_residual_arrows(ax, [[50.0, 50.0]], [0.0], [5.0], exaggeration=4)
    figure.canvas.draw()
    outline = arrows.get_transform().transform(arrows.get_paths()[0].vertices)  # display units
    tail, tip = ax.transData.transform([[50.0, 50.0], [50.0, 50.0 + 5.0 * 4]])
    assert tip[1] < tail[1]                       # display y grows upwards: down the image is less
    assert outline[:, 1].min() == pytest.approx(tip[1] - tail[1], rel=0.02)   # drawn to the tip
    assert outline[:, 1].max() < 5                # nothing drawn upwards from the GCP
    labels = label_points(ax, [[10.0, 10.0]], ["G01"])
    assert labels[0].get_path_effects()           # outlined: readable on dark and bright pixels
    assert figure_problems(figure) == []
    plt.close(figure)
