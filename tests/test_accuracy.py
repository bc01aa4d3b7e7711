"""rsgeo.accuracy: residuals, RMS, refinement like gdalwarp -refine_gcps, leave-one-out, check
points, standard errors and comparisons with a geotransform."""

import affine
import numpy as np
import pytest

from rsgeo import accuracy, data, gcp, transforms
from rsgeo.errors import GCPError
from rsgeo.resample import grid_positions

from gcp_samples import utm_gcps
from gdal_reference import gdal_map_to_image


def cbers():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    return gcps.image_xy, gcps.map_xy


def test_refinement_removes_the_same_gcps_as_gdal():
    image_xy, map_xy = utm_gcps(14, seed=5, blunders=2)
    tolerance, minimum = 40.0, 6      # metres: GDAL's residuals are pixel -> map
    _, kept = accuracy.refine_gcps(image_xy, map_xy, 1, tolerance, minimum)
    assert (~kept).sum() == 2 and not kept[1] and not kept[4]
    dst_transform = affine.Affine(20, 0, map_xy[:, 0].min() + 2000, 0, -20,
                                  map_xy[:, 1].max() - 2000)
    gdal_cols, gdal_rows = gdal_map_to_image(image_xy, map_xy, 1, dst_transform, (100, 100),
                                             refine=(tolerance, minimum))
    x, y = grid_positions((100, 100), dst_transform)
    refitted = transforms.fit_polynomial(map_xy[kept], image_xy[kept], 1)(
        np.column_stack([x.ravel(), y.ravel()]))
    inside = np.isfinite(gdal_cols.ravel())
    assert np.abs(refitted[inside, 0] - gdal_cols.ravel()[inside]).max() < 1e-6
    assert np.abs(refitted[inside, 1] - gdal_rows.ravel()[inside]).max() < 1e-6


def test_residuals_and_rms_are_the_protocols():
    image_xy, map_xy = utm_gcps(12, seed=8)
    model = transforms.fit_polynomial(map_xy, image_xy, 1)
    dx, dy, distance = accuracy.residuals(model, map_xy, image_xy)
    np.testing.assert_allclose(model.residuals(map_xy, image_xy), np.hypot(dx, dy))
    np.testing.assert_allclose(model.residuals(map_xy, image_xy), distance)
    expected = np.sqrt(np.mean(np.sum((model(map_xy) - image_xy) ** 2, axis=1)))
    assert model.rms(map_xy, image_xy) == pytest.approx(expected, rel=1e-12)
    assert model.rms(map_xy, image_xy) > 0.1
    with pytest.raises(ValueError, match="same points"):
        model.residuals(map_xy, image_xy[:-1])


def test_rms_and_mean_error_by_hand():
    predicted = np.array([[0.0, 0.0], [3.0, 4.0], [0.0, 1.0], [1.0, 0.0]])
    observed = np.zeros((4, 2))
    assert accuracy.rms_error(predicted, observed) == pytest.approx(np.sqrt((0 + 25 + 1 + 1) / 4))
    assert accuracy.mean_error(predicted, observed, order=1) == pytest.approx(np.sqrt(27 / 1))


def test_standard_errors_follow_the_textbook_formula():
    # s² (AᵀA)⁻¹ written out on the lecture's term order, x and y measured from the GCPs' mean
    rng = np.random.default_rng(11)
    src = rng.uniform(-3000, 3000, (15, 2)) + [774_000, 7_366_000]
    dst = np.column_stack([200 + 0.05 * (src[:, 0] - 774_000),
                           190 - 0.05 * (src[:, 1] - 7_366_000)])
    dst = dst + rng.normal(0, 0.5, dst.shape)
    for order in (1, 2, 3):
        model = transforms.fit_polynomial(src, dst, order)
        a = transforms.design_matrix(src - src.mean(axis=0), order)
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
    truth = np.column_stack([5 + 0.8 * src[:, 0] + 0.1 * src[:, 1],
                             2 - 0.2 * src[:, 0] + src[:, 1]])
    sigma = 0.5
    a = transforms.design_matrix(src - src.mean(axis=0), 1)
    theory = sigma * np.sqrt(np.diag(np.linalg.inv(a.T @ a)))
    fits = [transforms.fit_polynomial(src, truth + rng.normal(0, sigma, truth.shape), 1)
            for _ in range(600)]
    spread = np.std([f.coefficients for f in fits], axis=0)
    estimated = np.mean([f.standard_errors() for f in fits], axis=0)
    np.testing.assert_allclose(spread, np.vstack([theory, theory]), rtol=0.12)
    np.testing.assert_allclose(estimated, np.vstack([theory, theory]), rtol=0.12)


def test_standard_errors_need_a_redundant_gcp():
    image_xy, map_xy = utm_gcps(3, seed=1)
    with pytest.raises(ValueError, match="need more than 3 GCPs"):
        transforms.fit_polynomial(map_xy, image_xy, 1).standard_errors()


def test_geotransform_check_measures_a_known_offset():
    transform = affine.Affine(20, 0, 770_000, 0, -20, 7_370_000)
    rng = np.random.default_rng(4)
    image_xy = rng.uniform(0, 300, (10, 2))
    map_xy = np.column_stack(transform @ image_xy.T)
    exact = transforms.fit_polynomial(map_xy, image_xy, 1)
    check = accuracy.compare_with_geotransform(exact, transform, (300, 320), step=7)
    assert check.rms < 1e-6 and check.max_error < 1e-6
    shifted = transforms.fit_polynomial(map_xy, image_xy + [0.3, -1.2], 1)
    check = accuracy.compare_with_geotransform(shifted, transform, (300, 320))
    np.testing.assert_allclose(check.mean_offset, [0.3, -1.2], atol=1e-6)
    assert check.rms == pytest.approx(np.hypot(0.3, 1.2)) and check.centred_rms < 1e-6
    assert check.points.shape == (300 * 320, 2)
    # a scale error: zero at the centre, growing to the corners; the mean offset misses it
    scaled = transforms.fit_polynomial(map_xy, (image_xy - 150) * 1.01 + 150, 1)
    check = accuracy.compare_with_geotransform(scaled, transform, (300, 300))
    assert np.abs(check.mean_offset).max() < 1e-6
    assert check.max_error == pytest.approx(0.01 * np.hypot(149.5, 149.5), rel=1e-6)


def test_geotransform_check_rejects_bad_input():
    model = transforms.fit_polynomial(*utm_gcps(6, seed=2)[::-1], 1)
    transform = affine.Affine(20, 0, 500_000, 0, -20, 7_400_000)
    with pytest.raises(ValueError, match="affine.Affine"):
        accuracy.compare_with_geotransform(model, (20, 0, 0, 0, -20, 0), (10, 10))
    with pytest.raises(ValueError, match="cannot be inverted"):
        accuracy.compare_with_geotransform(model, affine.Affine(0, 0, 0, 0, 0, 0), (10, 10))
    with pytest.raises(ValueError, match="shape must be"):
        accuracy.compare_with_geotransform(model, transform, (10, 0))
    with pytest.raises(ValueError, match="step must be"):
        accuracy.compare_with_geotransform(model, transform, (10, 10), step=0)


def test_leave_one_out_matches_fitting_without_the_point():
    image_xy, map_xy = cbers()
    for kind, order in (("projective", None), ("tps", None), ("polynomial", 2)):
        errors = accuracy.leave_one_out_errors(map_xy, image_xy, order, kind)
        keep = np.arange(len(map_xy)) != 9
        alone = transforms.fit_transform(map_xy[keep], image_xy[keep], kind, order)
        assert np.isclose(errors[9], alone.residuals(map_xy[9:10], image_xy[9:10])[0])
        if kind == "polynomial":
            assert np.allclose(errors, accuracy.leave_one_out_errors(map_xy, image_xy, order))
    with pytest.raises(ValueError, match="one more than its minimum"):
        accuracy.leave_one_out_errors(map_xy[:4], image_xy[:4], "projective")


def test_compare_models_fits_on_gcps_and_measures_check_points():
    image_xy, map_xy = cbers()
    is_check = np.zeros(len(map_xy), bool)
    is_check[[1, 6, 12]] = True
    table = accuracy.compare_models(map_xy, image_xy, is_check)
    assert list(table.index) == [label for label, _, _ in transforms.GEOREFERENCER_MODELS]
    tps = transforms.fit_transform(map_xy[~is_check], image_xy[~is_check], "tps")
    assert np.isclose(table.loc["tps", "check RMS (px)"],
                      tps.rms(map_xy[is_check], image_xy[is_check]))
    assert table.loc["tps", "fitting RMS (px)"] < 1e-6
    assert table.loc["polynomial 3", "parameters"] == 20
    with pytest.raises(ValueError, match="one flag per point"):
        accuracy.compare_models(map_xy, image_xy, is_check[:5])


@pytest.mark.parametrize("call, message", [
    (lambda: accuracy.rms_error(np.zeros((0, 2)), np.zeros((0, 2))), "no points"),
    (lambda: accuracy.mean_error(np.ones((5, 2)), np.zeros((1, 2)), 1), "same shape"),
    (lambda: accuracy.mean_error(np.ones((5, 2)), np.full((5, 2), np.nan), 1), "NaN"),
    (lambda: accuracy.refine_gcps(*utm_gcps(8, seed=1), 1, 5.0, min_gcps=9), "exceeds the number"),
    (lambda: accuracy.fit_with_check_points(*utm_gcps(8, seed=1), 1, [0, 0.5, 0, 0, 0, 1, 0, 0]),
     "True/False"),
    (lambda: accuracy.fit_with_check_points(*utm_gcps(8, seed=1), 1,
                                            [0, np.nan, 0, 0, 0, 1, 0, 0]),
     "True/False"),
    (lambda: accuracy.leave_one_out_errors(np.random.default_rng(0).random((6, 2)),
                                      np.random.default_rng(1).random((7, 2)), 1), "same GCPs"),
    (lambda: accuracy.leave_one_out_errors(*utm_gcps(6, seed=1), 2), "needs at least 7 GCPs"),
    (lambda: accuracy.hull_coverage(np.random.default_rng(0).random((5, 2)), 0, 100), "positive"),
    (lambda: accuracy.hull_coverage(np.random.default_rng(0).random((5, 2)), np.nan, 100),
     "width"),
    (lambda: accuracy.predicted_error_map(utm_gcps(8, seed=1)[1], 1, np.zeros(3), np.zeros(3),
                                     gcp_error=-1), "gcp_error"),
    (lambda: accuracy.predicted_error_map(utm_gcps(8, seed=1)[1], 1, np.zeros(3), np.zeros(4)),
     "same shape"),
])
def test_silent_wrong_answers_are_value_errors(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_refine_gcps_takes_any_kind_and_register_calls_it():
    image_xy, map_xy = cbers()
    for kind, order in (("helmert", None), ("projective", None), ("polynomial", 2)):
        model, kept = accuracy.refine_gcps(map_xy, image_xy, order, 2.5, kind=kind)
        assert model.kind == kind and kept.sum() >= transforms.min_gcps(kind, order)
        assert model.residuals(map_xy[kept], image_xy[kept]).max() < 2.5
        same = transforms.fit_transform(map_xy[kept], image_xy[kept], kind, order)
        np.testing.assert_allclose(same(map_xy), model(map_xy))
    # a kind's name in the order's place, as min_gcps takes it
    _, by_name = accuracy.refine_gcps(map_xy, image_xy, "helmert", 2.5)
    _, by_kind = accuracy.refine_gcps(map_xy, image_xy, None, 2.5, kind="helmert")
    assert (by_name == by_kind).all()
    from rsgeo import tiepoints
    result = tiepoints.register(gcp.GCPSet(map_xy, image_xy), "helmert", tolerance=2.5)
    assert (result.kept == by_name).all()
    with pytest.raises(ValueError, match="min_gcps must be at least 2 for 'helmert'"):
        accuracy.refine_gcps(map_xy, image_xy, "helmert", 2.5, min_gcps=1)


def test_mean_error_of_other_kinds_divides_by_their_degrees_of_freedom():
    predicted = np.array([[0.0, 0.0], [3.0, 4.0], [0.0, 1.0], [1.0, 0.0]])
    observed = np.zeros((4, 2))
    assert accuracy.mean_error(predicted, observed, "helmert") == pytest.approx(np.sqrt(27 / 2))
    assert accuracy.mean_error(predicted, observed, 1) == accuracy.mean_error(
        predicted, observed, 1, kind="polynomial")
    with pytest.raises(ValueError, match="needs more than 4 GCPs"):
        accuracy.mean_error(predicted, observed, "projective")


def test_predicted_error_of_any_kind_is_the_polynomials_formula_for_polynomials():
    # the propagation every other kind uses gives the analytic σ²a(AᵀA)⁻¹a for polynomials
    from rsgeo.accuracy import _propagated_deviation

    rng = np.random.default_rng(0)
    src = rng.uniform(0, 1000, (12, 2)) + [5e5, 7e6]
    x, y = np.meshgrid(np.linspace(5e5 - 500, 5e5 + 1500, 7),
                       np.linspace(7e6 - 500, 7e6 + 1500, 5))
    grid = np.column_stack([x.ravel(), y.ravel()])
    for order in (1, 2, 3):
        analytic = accuracy.predicted_error_map(src, order, x, y).ravel()
        propagated = _propagated_deviation(transforms.registered(order).fit, src, grid)
        np.testing.assert_allclose(propagated, analytic, rtol=1e-9)


@pytest.mark.parametrize("kind", ["linear", "helmert", "projective", "tps"])
def test_predicted_error_of_any_kind_matches_simulated_gcp_errors(kind):
    # an independent check: fit the model to many sets of GCPs with errors of σ and measure the
    # spread of its predictions; the map must say the same (to the sampling error of 2,000 fits)
    rng = np.random.default_rng(1)
    src = rng.uniform(0, 1000, (10, 2))
    dst = src * [0.05, -0.05] + [10, 80] + np.where(kind == "projective", 1e-5, 0) * src**2
    points = np.array([[500.0, 500.0], [100.0, 900.0], [1400.0, -300.0]])
    sigma = 0.01 if kind == "projective" else 0.5
    fit = transforms.registered(kind).fit
    predictions = np.array([fit(src, dst + rng.normal(0, sigma, dst.shape))(points)
                            for _ in range(2000)])
    simulated = np.sqrt(predictions.var(axis=0).mean(axis=1))      # per axis, both averaged
    predicted = accuracy.predicted_error_map(src, kind, points[:, 0], points[:, 1], sigma,
                                             dst=dst)
    np.testing.assert_allclose(predicted, simulated, rtol=0.06)


def test_a_projective_error_map_needs_the_dst_points():
    src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 2]], dtype=float)
    with pytest.raises(GCPError, match="pass dst"):
        accuracy.predicted_error_map(src, "projective", np.zeros(2), np.zeros(2))


def test_refine_gcps_checks_its_numbers():
    src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    with pytest.raises(TypeError, match="tolerance must be a number"):
        accuracy.refine_gcps(src, src / 2, 1, "1.0")
    with pytest.raises(ValueError, match="tolerance must be"):
        accuracy.refine_gcps(src, src / 2, 1, float("nan"))
    with pytest.raises(TypeError, match="min_gcps"):
        accuracy.refine_gcps(src, src / 2, 1, 1.0, min_gcps=True)
