"""rsgeo.accuracy: residuals, RMS, refinement like gdalwarp -refine_gcps, leave-one-out, check
points, standard errors and comparisons with a geotransform."""

import affine
import numpy as np
import pytest

from rsgeo import accuracy, data, gcp, registration, transforms
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
    # GDAL's and QGIS's spline: fitted image -> map, inverted (map -> image)
    tps = transforms.fit_transform(image_xy[~is_check], map_xy[~is_check], "tps").inverse()
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
    result = registration.register(gcp.GCPSet(map_xy, image_xy), "helmert", tolerance=2.5)
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
    from rsgeo.accuracy._residuals import _propagated_deviation

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


# --- Leave-one-out per axis ----------------------------------------------------------------------

def test_leave_one_out_residuals_are_the_fit_without_the_point():
    image_xy, map_xy = cbers()
    residuals = accuracy.leave_one_out_residuals(image_xy, map_xy, 1)
    np.testing.assert_allclose(np.hypot(*residuals.T),
                               accuracy.leave_one_out_errors(image_xy, map_xy, 1))
    for index in (0, 6, 13):
        others = np.arange(len(map_xy)) != index
        model = transforms.fit_polynomial(image_xy[others], map_xy[others], 1)
        np.testing.assert_allclose(residuals[index], model(image_xy[index])[0] - map_xy[index])
    with pytest.raises(GCPError, match="needs at least 4 GCPs"):
        accuracy.leave_one_out_residuals(image_xy[:3], map_xy[:3], 1)


# --- Accuracy standards -------------------------------------------------------------------------

# ET-CQDG's planimetric PEC-PCD in metres per scale (PEC, EP), as the standard tabulates it and
# as two independent implementations copy it (LFTools, Qualy_Accuracy_Horizontal.py; UFV's
# PEC-Avalia, biblioteca/normas.py): typed from the table, not computed from the millimetres.
PEC_PCD_METRES = {
    1_000: {"A": (0.28, 0.17), "B": (0.5, 0.3), "C": (0.8, 0.5), "D": (1.0, 0.6)},
    25_000: {"A": (7.0, 4.25), "B": (12.5, 7.5), "C": (20.0, 12.5), "D": (25.0, 15.0)},
    50_000: {"A": (14.0, 8.5), "B": (25.0, 15.0), "C": (40.0, 25.0), "D": (50.0, 30.0)},
    250_000: {"A": (70.0, 42.5), "B": (125.0, 75.0), "C": (200.0, 125.0), "D": (250.0, 150.0)},
}


@pytest.mark.parametrize("scale", PEC_PCD_METRES)
def test_pec_pcd_thresholds_are_the_standards_table(scale):
    assert accuracy.pec_thresholds(scale) == PEC_PCD_METRES[scale]


def test_the_pec_pcd_renames_the_decrees_classes_and_adds_a_stricter_a():
    pcd, decree = accuracy.PEC_CLASSES["PEC-PCD"], accuracy.PEC_CLASSES["Decreto 89.817"]
    assert [pcd[name] for name in "BCD"] == [decree[name] for name in "ABC"]
    assert pcd["A"][0] < pcd["B"][0] and pcd["A"][1] < pcd["B"][1]
    # art. 8 §2: PEC = 1.6449 EP, to the rounding of the printed millimetres
    for pec, ep in [*pcd.values(), *decree.values()]:
        assert pec / ep == pytest.approx(accuracy.LE90_FACTOR, rel=0.03)
    rng = np.random.default_rng(4)
    for _ in range(30):
        errors = rng.normal(0, rng.uniform(2, 30), (rng.integers(5, 40), 2))
        for scale in (10_000, 25_000, 50_000):
            new = accuracy.classify(errors, scale).meets
            old = accuracy.classify(errors, scale, "Decreto 89.817").meets
            assert [new[name] for name in "BCD"] == [old[name] for name in "ABC"]


@pytest.mark.parametrize("n", [1, 5, 10, 13, 20, 30, 70, 101])
def test_the_90_percent_test_counts_and_its_error_is_the_order_statistic(n):
    # at 1:25,000 class D's PEC is 25 m: exactly ceil(0.9 n) errors within it pass (90 % is
    # "at least", so exactly 9 of 10 passes), one fewer fails
    needed = -(-9 * n // 10)
    for within in (needed, needed - 1):
        if within < 0:
            continue
        distances = np.r_[np.full(within, 25.0), np.full(n - within, 25.01)]
        result = accuracy.classify(distances, 25_000)
        assert result.pec_test["D"] == (within == needed)
        assert (result.percentile_90 <= 25.0) == result.pec_test["D"]
        assert result.within["D"] == pytest.approx(within / n)


def test_thresholds_are_inclusive_and_the_best_class_is_the_strictest_met():
    result = accuracy.classify(np.full(20, 15.0), 25_000)   # RMS = class D's EP exactly
    assert result.best == "D" and result.ep_test["D"] and not result.ep_test["C"]
    assert accuracy.classify(np.full(20, 4.25), 25_000).best == "A"
    rng = np.random.default_rng(7)
    for _ in range(200):
        distances = np.abs(rng.standard_cauchy(rng.integers(3, 30))) * rng.uniform(1, 20)
        result = accuracy.classify(distances, 50_000)
        met = [result.meets[name] for name in "ABCD"]
        assert met == sorted(met)                   # meeting a class means meeting the looser
        assert result.best == next((name for name in "ABCD" if result.meets[name]), None)
        assert result.rms == pytest.approx(np.sqrt(np.mean(distances**2)))


def test_vectors_and_distances_classify_alike():
    rng = np.random.default_rng(2)
    vectors = rng.normal(0, 8, (25, 2))
    by_vector = accuracy.classify(vectors, 25_000)
    by_distance = accuracy.classify(np.hypot(*vectors.T), 25_000)
    assert by_vector == by_distance and accuracy.classify(-vectors, 25_000) == by_vector
    table = by_vector.table()
    assert list(table.index) == list("ABCD") and table["meets"].tolist() == [
        by_vector.meets[name] for name in "ABCD"]


def test_largest_scale_is_where_classify_first_says_yes():
    rng = np.random.default_rng(3)
    for _ in range(20):
        errors = rng.normal(0, rng.uniform(1, 60), (rng.integers(8, 30), 2))
        found = accuracy.largest_scale(errors)
        for name, denominator in found.items():
            met = [s for s in accuracy.MAP_SCALES if accuracy.classify(errors, s).meets[name]]
            assert denominator == (met[0] if met else None)
            if met:       # the thresholds grow with the denominator: met from there on
                assert met == [s for s in accuracy.MAP_SCALES if s >= denominator]


@pytest.mark.parametrize("call, error, message", [
    (lambda: accuracy.classify([], 25_000), GCPError, "no check point"),
    (lambda: accuracy.classify([1.0, np.nan], 25_000), GCPError, "finite"),
    (lambda: accuracy.classify([1.0, -2.0], 25_000), GCPError, "not negative"),
    (lambda: accuracy.classify(np.ones((4, 3)), 25_000), GCPError, r"\(n, 2\)"),
    (lambda: accuracy.classify(["1", "2"], 25_000), TypeError, "real numbers"),
    (lambda: accuracy.classify([1.0, 2.0], "1:25000"), TypeError, "scale must be a number"),
    (lambda: accuracy.classify([1.0, 2.0], 0.00004), ValueError, "denominator"),
    (lambda: accuracy.classify([1.0, 2.0], 25_000, "ASPRS"), ValueError, "PEC-PCD"),
    (lambda: accuracy.largest_scale([1.0, 2.0], scales=()), GCPError, "scales is empty"),
    (lambda: accuracy.asprs_horizontal([1.0, 2.0, 3.0]), GCPError, "both components"),
    (lambda: accuracy.asprs_vertical(np.ones((3, 2))), GCPError, r"\(n,\)"),
])
def test_standards_refuse_what_they_cannot_judge(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_the_standards_constants_are_the_normal_and_rayleigh_quantiles():
    # scipy's quantiles, not our arithmetic: CE90 and the NSSDA's 95 % radius are the Rayleigh
    # distribution's (σ = 1), LE90 and 1.96 the normal distribution's two-sided 90 % and 95 %
    from scipy import stats

    assert accuracy.CE90_FACTOR == round(stats.rayleigh.ppf(0.90), 4)
    assert accuracy.NSSDA_95_FACTOR == round(stats.rayleigh.ppf(0.95), 4)
    # the standards print 1.5175, the rounded 2.1460 over sqrt(2); the exact ratio rounds to 1.5174
    assert accuracy.CE90_RADIAL_FACTOR == round(accuracy.CE90_FACTOR / np.sqrt(2), 4)
    assert abs(accuracy.CE90_RADIAL_FACTOR - stats.rayleigh.ppf(0.90) / np.sqrt(2)) < 1e-4
    assert accuracy.NSSDA_95_RADIAL_FACTOR == round(stats.rayleigh.ppf(0.95) / np.sqrt(2), 4)
    assert accuracy.LE90_FACTOR == round(stats.norm.ppf(0.95), 4)
    assert accuracy.VERTICAL_95_FACTOR == round(stats.norm.ppf(0.975), 4)


def test_ce90_and_the_95_percent_radius_match_simulated_circular_errors():
    # 200,000 circular normal errors of σ = 3 m: their 90th and 95th percentile radii are CE90
    # and the 95 % accuracy to the sampling error of a quantile, sqrt(p(1-p)/n) / density
    n, sigma = 200_000, 3.0
    errors = np.random.default_rng(12).normal(0, sigma, (n, 2))
    radial = np.hypot(*errors.T)
    result = accuracy.asprs_horizontal(errors)
    for p, value in ((0.90, result.ce90), (0.95, result.accuracy_95)):
        quantile = np.quantile(radial, p)
        density = quantile / sigma**2 * np.exp(-quantile**2 / (2 * sigma**2))
        sampling = np.sqrt(p * (1 - p) / n) / density
        assert abs(value - quantile) < 5 * sampling, (p, value, quantile, sampling)
    # the one-dimensional factor applied to RMSE_r, a common slip, is far outside that error
    assert abs(accuracy.LE90_FACTOR * result.rmse_r - np.quantile(radial, 0.9)) > 0.5
    assert result.rmse_r == pytest.approx(np.sqrt(2) * sigma, rel=0.01)
    assert result.ce90 == pytest.approx(accuracy.CE90_FACTOR * result.rmse_x, rel=0.01)


def test_le90_matches_simulated_height_errors():
    n, sigma = 200_000, 2.0
    dz = np.random.default_rng(13).normal(0, sigma, n)
    result = accuracy.asprs_vertical(dz)
    for p, value in ((0.90, result.le90), (0.95, result.accuracy_95)):
        quantile = np.quantile(np.abs(dz), p)
        density = 2 * np.exp(-quantile**2 / (2 * sigma**2)) / (sigma * np.sqrt(2 * np.pi))
        assert abs(value - quantile) < 5 * np.sqrt(p * (1 - p) / n) / density


def test_elongated_errors_get_the_nssda_approximation_or_none():
    rng = np.random.default_rng(14)
    elongated = rng.normal(0, 1, (100_000, 2)) * [4.0, 3.2]       # RMSE ratio 0.8
    result = accuracy.asprs_horizontal(elongated)
    assert result.axis_ratio == pytest.approx(0.8, abs=0.01)
    assert result.accuracy_95 == pytest.approx(2.4477 * (result.rmse_x + result.rmse_y) / 2)
    assert 0.94 < np.mean(np.hypot(*elongated.T) <= result.accuracy_95) < 0.955
    flat = accuracy.asprs_horizontal(rng.normal(0, 1, (1000, 2)) * [4.0, 1.0])
    assert np.isnan(flat.accuracy_95) and np.isnan(flat.ce90) and flat.axis_ratio < 0.6


# -- ASPRS Edition 2 (2023) -----------------------------------------------------------------------

# Edition 2's worked table of vertical product accuracy (its Table 7.4, "computing vertical product
# accuracy"): the RMSE_V1 measured against checkpoints surveyed to RMSE_V2 = 2.0 cm, and the
# product's RMSE_V it prints, in cm. The standard itself could not be read on this machine (no
# internet); the rows are those of a public transcription, and each is sqrt(RMSE_V1² + 2.0²) to
# the table's 0.01 cm, which this test would catch if rsgeo combined them any other way (a plain
# sum gives 3.00 for the first row, Edition 1's 95 % figure 1.96 RMSE_V1 gives 1.96).
TABLE_7_4 = [(1.00, 2.24), (1.50, 2.50), (2.00, 2.83), (2.50, 3.20), (3.00, 3.61), (3.50, 4.03),
             (4.00, 4.47), (4.50, 4.92), (5.00, 5.39), (5.50, 5.85), (6.00, 6.32), (6.50, 6.80),
             (7.00, 7.28), (7.50, 7.76), (8.00, 8.25), (8.50, 8.73), (9.00, 9.22), (9.50, 9.71),
             (10.00, 10.20)]


@pytest.mark.parametrize("fit, product", TABLE_7_4)
def test_edition2_vertical_accuracy_is_its_worked_table(fit, product):
    dz = np.tile([fit, -fit], 15)                  # 30 checkpoints whose RMSE is `fit` exactly
    result = accuracy.asprs_vertical_2023(dz, checkpoint_rmse_v=2.0)
    assert result.rmse_v1 == pytest.approx(fit, rel=1e-12) and result.checkpoint_rmse_v == 2.0
    assert abs(result.rmse_v - product) <= 0.005, (fit, result.rmse_v, product)
    assert result.n_points == 30 and result.enough_checkpoints


def test_edition2_horizontal_adds_the_checkpoints_survey_in_quadrature():
    # by hand: errors of (±3, ±4) m give RMSE_x 3, RMSE_y 4 and RMSE_H1 5; checkpoints surveyed
    # to RMSE_H2 12 m make the product's RMSE_H sqrt(5² + 12²) = 13 m
    errors = np.array([[3, 4], [-3, -4], [3, -4], [-3, 4]] * 8, dtype=float)[:30]
    exact = accuracy.asprs_horizontal_2023(errors)
    assert (exact.rmse_x, exact.rmse_y, exact.rmse_h1, exact.rmse_h) == (3.0, 4.0, 5.0, 5.0)
    assert exact.checkpoint_rmse_h == 0.0          # the default: checkpoints taken as exact
    surveyed = accuracy.asprs_horizontal_2023(errors, checkpoint_rmse_h=12.0)
    assert surveyed.rmse_h1 == 5.0 and surveyed.rmse_h == 13.0
    # Edition 1's RMSE_r is what Edition 2 calls RMSE_H1; the 95 % figures are gone
    assert exact.rmse_h1 == accuracy.asprs_horizontal(errors).rmse_r
    assert not hasattr(exact, "accuracy_95") and not hasattr(exact, "ce90")
    assert accuracy.asprs_vertical_2023(errors[:, 1]).rmse_v == 4.0


def test_edition2_never_states_a_product_better_than_its_checkpoints():
    rng = np.random.default_rng(21)
    for _ in range(50):
        errors = rng.normal(0, rng.uniform(0.1, 30), (int(rng.integers(1, 60)), 2))
        survey = float(rng.uniform(0, 20))
        result = accuracy.asprs_horizontal_2023(errors, checkpoint_rmse_h=survey)
        assert result.rmse_h >= max(result.rmse_h1, survey)
        assert result.rmse_h == pytest.approx(np.sqrt(np.mean(np.sum(errors**2, axis=1))
                                                      + survey**2), rel=1e-12)
        assert result.enough_checkpoints == (len(errors) >= 30)


def test_edition2_classes_need_30_checkpoints_twice_as_accurate_as_the_class():
    errors = np.array([[3, 4], [-3, -4], [3, -4], [-3, 4]] * 8, dtype=float)[:30]
    result = accuracy.asprs_horizontal_2023(errors, checkpoint_rmse_h=2.0)   # RMSE_H sqrt(29)
    assert accuracy.ASPRS_MIN_CHECKPOINTS == 30 and accuracy.ASPRS_CHECKPOINT_RATIO == 2
    assert result.meets(np.sqrt(29.0)) and result.meets(5.4) and not result.meets(5.3)
    assert result.meets(4.0) is False              # 2 m checkpoints may test a 4 m class
    with pytest.raises(GCPError, match=r"at least 2 times more accurate .*at most 1\.5\)"):
        result.meets(3.0)                          # ... not a 3 m one
    # with 29 checkpoints the figure is given, flagged, and no class is stated
    few = accuracy.asprs_horizontal_2023(errors[:29])
    assert few.rmse_h == 5.0 and not few.enough_checkpoints
    with pytest.raises(GCPError, match="needs at least 30 checkpoints, got 29: test on 1 more"):
        few.meets(100.0)
    heights = accuracy.asprs_vertical_2023(errors[:13, 0], checkpoint_rmse_v=1.0)
    assert heights.rmse_v == pytest.approx(np.sqrt(10.0)) and not heights.enough_checkpoints
    with pytest.raises(GCPError, match="got 13: test on 17 more, or report RMSE_V"):
        heights.meets(10.0)
    assert accuracy.asprs_vertical_2023(np.tile(errors[:, 0], 2)).meets(3.0)


@pytest.mark.parametrize("call, error, message", [
    (lambda: accuracy.asprs_horizontal_2023(np.zeros((0, 2))), GCPError,
     "no check point.*Edition 2 asks for 30"),
    (lambda: accuracy.asprs_horizontal_2023([3.0, 4.0]), GCPError, "flat pair"),
    (lambda: accuracy.asprs_horizontal_2023([1.0, 2.0, 3.0]), GCPError, "both components"),
    (lambda: accuracy.asprs_horizontal_2023([["1", "2"]]), TypeError, "real numbers"),
    (lambda: accuracy.asprs_horizontal_2023([[1.0, 2.0]], checkpoint_rmse_h=-1.0), ValueError,
     "checkpoint_rmse_h must be >= 0"),
    (lambda: accuracy.asprs_horizontal_2023([[1.0, 2.0]], checkpoint_rmse_h="1"), TypeError,
     "checkpoint_rmse_h must be a number"),
    (lambda: accuracy.asprs_horizontal_2023([[1.0, 2.0]], 1.0), TypeError, "positional"),
    (lambda: accuracy.asprs_vertical_2023([]), GCPError, "non-empty"),
    (lambda: accuracy.asprs_vertical_2023([1.0, np.nan]), GCPError, "finite"),
    (lambda: accuracy.asprs_vertical_2023([True, False]), TypeError, "number"),
    (lambda: accuracy.asprs_vertical_2023([1.0], checkpoint_rmse_v=np.inf), ValueError,
     "finite"),
    (lambda: accuracy.asprs_vertical_2023([1.0] * 30).meets(0.0), ValueError, "positive"),
    (lambda: accuracy.asprs_vertical_2023([1.0] * 30).meets("5 cm"), TypeError, "number"),
    # Edition 1's function refuses an empty set too, instead of answering NaN
    (lambda: accuracy.asprs_horizontal(np.zeros((0, 2))), GCPError, "no check point"),
])
def test_edition2_refuses_what_it_cannot_judge(call, error, message):
    with pytest.raises(error, match=message):
        call()
