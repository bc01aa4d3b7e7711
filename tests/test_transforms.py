"""rsgeo.transforms: QGIS's Georeferencer models and GDAL's polynomials against GDAL and
scikit-image."""

import affine
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rasterio.control import GroundControlPoint
from rasterio.transform import GCPTransformer
from skimage.transform import PolynomialTransform, ProjectiveTransform, SimilarityTransform

from rsgeo import accuracy, data, transforms
from rsgeo.resample import grid_positions, warp

from gdal_reference import gcp_source, gdal_map_to_image, gdal_warp


def utm_gcps(n, seed, noise=15.0):
    """Random GCPs over a 1000 x 800 image with UTM-sized map coordinates."""
    rng = np.random.default_rng(seed)
    image_xy = np.column_stack([rng.uniform(0, 1000, n), rng.uniform(0, 800, n)])
    c, r = image_xy[:, 0], image_xy[:, 1]
    map_xy = np.column_stack([500_000 + 20 * c + 0.01 * r**1.5 + rng.normal(0, noise, n),
                              7_400_000 - 20 * r + 3 * c + 2e-5 * c * c + rng.normal(0, noise, n)])
    return image_xy, map_xy


def cbers():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    return gcps.image_xy, gcps.map_xy


def gdal_tps_map_to_image(image_xy, map_xy, points):
    """GDAL's TPS transformer (rasterio), map -> image (pixel, line), no rounding."""
    gcps = [GroundControlPoint(row=r, col=c, x=x, y=y) for (c, r), (x, y) in zip(image_xy, map_xy)]
    with GCPTransformer(gcps, tps=True) as transformer:
        rows, cols = transformer.rowcol(points[:, 0], points[:, 1], op=lambda v: v)
    return np.column_stack([cols, rows])


def inside_points(map_xy, n=300, seed=1):
    rng = np.random.default_rng(seed)
    low, high = map_xy.min(axis=0), map_xy.max(axis=0)
    return low + rng.random((n, 2)) * (high - low)


@pytest.mark.parametrize("gcps", [cbers(), utm_gcps(8, 1), utm_gcps(25, 2), utm_gcps(60, 3)],
                         ids=["cbers", "random8", "random25", "random60"])
def test_tps_predicts_what_gdal_tps_predicts(gcps):
    image_xy, map_xy = gcps
    model = transforms.fit_transform(map_xy, image_xy, "tps")
    points = np.vstack([map_xy, inside_points(map_xy)])
    expected = gdal_tps_map_to_image(image_xy, map_xy, points)
    assert np.abs(model(points) - expected).max() < 1e-6
    assert np.array_equal(model(points), expected)        # GDAL's spline, to the last bit
    # exact at every GCP: zero residuals
    assert model.residuals(map_xy, image_xy).max() < 1e-6
    # the reverse is GDAL's other spline (image -> map), also through every GCP
    assert model.reverse().residuals(image_xy, map_xy).max() < 1e-4


def test_tps_warp_matches_gdalwarp_tps_bit_for_bit():
    rng = np.random.default_rng(3)
    image = rng.integers(0, 256, (320, 320), dtype=np.uint8)
    image_xy = rng.uniform(0, 320, (12, 2))
    u, v = image_xy[:, 0] - 160, image_xy[:, 1] - 160
    map_xy = np.column_stack([600_000 + 10 * image_xy[:, 0] + 0.4 * image_xy[:, 1] + 0.002 * u * v,
                              7_300_000 - 10 * image_xy[:, 1] + 0.5 * image_xy[:, 0]
                              + 0.003 * u * u])
    dst_transform = affine.Affine(7.0, 0, 600_400, 0, -7.0, 7_299_600)
    shape = (400, 400)
    source = (gcp_source(image_xy, map_xy, 1)
              .replace("<SrcGCPTransformer><GCPTransformer><Order>1</Order>",
                       "<SrcTPSTransformer><TPSTransformer>")
              .replace("</GCPTransformer></SrcGCPTransformer>",
                       "</TPSTransformer></SrcTPSTransformer>"))
    # gdalwarp fits the spline image -> map and inverts it at every output cell, starting from
    # the spline map -> image (GDALTPSTransform, GDALGenericInverse2D); rsgeo's inverse() takes
    # the same steps with the same spline (rsgeo._kernels.thin_plate), so every pixel is GDAL's
    model = transforms.fit_transform(image_xy, map_xy, "tps").inverse()
    for method in ("nearest", "bilinear", "cubic"):
        expected = gdal_warp(image, source, dst_transform, shape, method, 0)
        got = warp(image, model, shape, dst_transform, method=method, dst_nodata=0)
        assert np.count_nonzero(expected) > shape[0] * shape[1] // 4
        assert np.array_equal(got, expected)
    # the reverse spline (what rasterio's GCPTransformer gives map -> image) is NOT what
    # gdalwarp uses: it is off by up to a tenth of a pixel between the GCPs
    reverse = transforms.fit_transform(map_xy, image_xy, "tps")
    assert np.count_nonzero(warp(image, reverse, shape, dst_transform, dst_nodata=0)
                            != gdal_warp(image, source, dst_transform, shape, "nearest", 0)) > 100


def noisy_similarity(seed, reflect):
    rng = np.random.default_rng(seed)
    src = rng.uniform(-1000, 1000, (20, 2)) + [500_000, 7_400_000]
    angle, scale = 0.3, 0.05
    rotation = scale * np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    dst = (src - src.mean(axis=0)) @ rotation.T + [400, 300] + rng.normal(0, 2, (20, 2))
    if reflect:
        dst[:, 1] = 600 - dst[:, 1]
    return src, dst


@pytest.mark.parametrize("reflect", [False, True])
def test_helmert_is_scikit_image_similarity_estimate(reflect):
    src, dst = noisy_similarity(4, reflect)
    model = transforms.fit_transform(src, dst, "helmert")
    flip = np.diag([1.0, -1.0, 1.0]) if reflect else np.eye(3)
    # scikit-image keeps a proper rotation: give it the rows flipped back (image y up)
    reference = SimilarityTransform.from_estimate(src, dst @ flip[:2, :2])
    expected = flip @ reference.params
    expected[1, 2] += 0.0
    if reflect:
        expected = np.diag([1.0, -1.0, 1.0]) @ reference.params
    assert np.abs(model.matrix - expected).max() <= 1e-9 * np.abs(expected).max()
    assert model.kind == "helmert" and model.n_parameters == 4
    # a similarity: one scale, perpendicular axes
    linear = model.matrix[:2, :2]
    assert np.allclose(linear.T @ linear, np.eye(2) * abs(np.linalg.det(linear)))


@pytest.mark.parametrize("gcps", [cbers(), utm_gcps(30, 5)], ids=["cbers", "random30"])
def test_projective_is_scikit_image_projective_estimate(gcps):
    image_xy, map_xy = gcps
    model = transforms.fit_transform(map_xy, image_xy, "projective")
    reference = ProjectiveTransform.from_estimate(map_xy, image_xy).params
    reference = reference / reference[2, 2]
    assert np.abs(model.matrix - reference).max() <= 1e-9 * np.abs(reference).max()
    assert model.n_parameters == 8


def test_projective_from_four_points_is_exact_and_inverts():
    src = np.array([[0.0, 0], [100, 0], [100, 100], [0, 100]])
    dst = np.array([[10.0, 5], [90, 12], [80, 95], [5, 80]])
    model = transforms.fit_transform(src, dst, "projective")
    assert model.residuals(src, dst).max() < 1e-9
    back = model.inverse()
    assert back.kind == "projective"
    assert np.abs(back(dst) - src).max() < 1e-9


def test_linear_is_scale_and_offset_per_axis():
    rng = np.random.default_rng(6)
    src = rng.uniform(0, 1000, (15, 2))
    dst = src * [0.05, -0.04] + [10, 900] + rng.normal(0, 0.5, (15, 2))
    model = transforms.fit_transform(src, dst, "linear")
    assert model.matrix[0, 1] == 0 and model.matrix[1, 0] == 0
    for axis in range(2):
        slope, intercept = np.polyfit(src[:, axis], dst[:, axis], 1)
        assert np.isclose(model.matrix[axis, axis], slope, rtol=1e-12)
        assert np.isclose(model.matrix[axis, 2], intercept, rtol=1e-9, atol=1e-9)
    assert np.abs(model.inverse()(model(src)) - src).max() < 1e-9


def test_polynomial_kind_is_fit_polynomial_and_differs_from_scikit_image_tls():
    image_xy, map_xy = utm_gcps(20, 7, noise=40.0)
    model = transforms.fit_transform(map_xy, image_xy, "polynomial", order=2)
    reference = transforms.fit_polynomial(map_xy, image_xy, 2)
    assert np.array_equal(model.coefficients, reference.coefficients)
    assert model.kind == "polynomial" and model.n_parameters == 12
    # ordinary least squares: the residuals are orthogonal to every term
    residual = model(map_xy) - image_xy
    terms = transforms.design_matrix(map_xy - map_xy.mean(axis=0), 2)
    assert np.abs(terms.T @ residual).max() < 1e-6 * np.abs(terms).max() * np.abs(residual).max()
    # scikit-image's total least squares is another estimate: off by far more than rounding
    # even on centred coordinates, and by pixels on raw UTM coordinates
    image_xy, map_xy = cbers()
    model = transforms.fit_transform(map_xy, image_xy, "polynomial", order=2)
    centred = map_xy - map_xy.mean(axis=0)
    tls = PolynomialTransform.from_estimate(centred, image_xy, order=2)
    assert np.abs(tls(centred) - model(map_xy)).max() > 1e-3
    raw = PolynomialTransform.from_estimate(map_xy, image_xy, order=2)
    assert np.abs(raw(map_xy) - model(map_xy)).max() > 1.0


@pytest.mark.parametrize("kind, order, expected", [
    ("helmert", None, 2), ("projective", None, 4), ("linear", None, 2), ("tps", None, 3),
    ("polynomial", 1, 3), ("polynomial", 2, 6), ("polynomial", 3, 10)])
def test_min_gcps_of_every_kind(kind, order, expected):
    assert transforms.min_gcps(kind, order) == expected
    if order is not None:
        assert transforms.min_gcps(order) == expected


@pytest.mark.parametrize("kind, order", [
    ("linear", None), ("helmert", None), ("polynomial", 1), ("polynomial", 3),
    ("projective", None), ("tps", None)])
def test_every_kind_follows_the_protocol(kind, order):
    image_xy, map_xy = cbers()
    model = transforms.fit_transform(map_xy, image_xy, kind, order)
    assert model.kind == kind
    assert model(map_xy).shape == map_xy.shape
    assert model.residuals(map_xy, image_xy).shape == (len(map_xy),)
    assert np.isclose(model.rms(map_xy, image_xy),
                      np.sqrt(np.mean(model.residuals(map_xy, image_xy) ** 2)))
    back = model.inverse()
    assert np.abs(back(model(map_xy)) - map_xy).max() < (1.0 if kind == "tps" else 1e-6)


@pytest.mark.parametrize("kind, order, message", [
    ("affine", None, "unknown transformation kind"),
    ("helmert", 2, "has no order"),
    ("polynomial", None, "needs an order"),
    ("polynomial", 4, "must be 1, 2 or 3"),
])
def test_bad_kind_or_order_is_a_value_error(kind, order, message):
    image_xy, map_xy = cbers()
    with pytest.raises(ValueError, match=message):
        transforms.fit_transform(map_xy, image_xy, kind, order)
    with pytest.raises(ValueError, match=message):
        transforms.min_gcps(kind, order)


@pytest.mark.parametrize("kind, n", [("helmert", 1), ("projective", 3), ("tps", 2),
                                     ("linear", 1)])
def test_too_few_points_is_a_value_error(kind, n):
    image_xy, map_xy = cbers()
    needed = transforms.min_gcps(kind)
    with pytest.raises(ValueError, match=f"needs at least {needed} GCPs, got {n}"):
        transforms.fit_transform(map_xy[:n], image_xy[:n], kind)


def test_collinear_points_for_projective_and_tps_are_value_errors():
    line = np.column_stack([np.arange(6.0), 2 * np.arange(6.0) + 1])
    target = line * 3 + [[0, 0], [1, 0], [0, 1], [2, 2], [0, 0], [1, 1]]
    with pytest.raises(ValueError, match="collinear"):
        transforms.fit_transform(line, target, "projective")
    with pytest.raises(ValueError, match="collinear"):
        transforms.fit_transform(line, target, "tps")
    three_on_a_line = np.array([[0.0, 0], [1, 1], [2, 2], [0, 5]])
    with pytest.raises(ValueError, match="collinear"):
        transforms.fit_transform(three_on_a_line, three_on_a_line * 2, "projective")


def test_duplicate_points_for_tps_are_a_value_error():
    image_xy, map_xy = cbers()
    map_xy = np.vstack([map_xy, map_xy[3]])
    image_xy = np.vstack([image_xy, image_xy[3] + 2])
    with pytest.raises(ValueError, match="same src point and different dst"):
        transforms.fit_transform(map_xy, image_xy, "tps")


def test_model_explorer_switches_models_in_place():
    import matplotlib

    matplotlib.use("Agg")
    from rsgeo import widgets

    from figure_audit import figure_problems

    gcps = data.load_gcps("cbers2b_ccd_hrc")
    box = widgets.model_explorer(gcps, model="polynomial 1")
    choice, factor = box.children[0].children
    line = box.figure.axes[0].lines[0]
    straight = np.array(line.get_xydata())
    choice.value = "tps"
    bent = np.array(line.get_xydata())
    assert len(box.figure.axes) == 1 and line is box.figure.axes[0].lines[0]
    assert np.nanmax(np.abs(bent - straight)) > 1.0
    assert "tps (34 parameters)" in box.figure.axes[0].get_title()
    assert figure_problems(box.figure) == []
    with pytest.raises(ValueError, match="unknown model"):
        widgets.model_explorer(gcps, model="affine")


# -- exercise checks of chapter 3b ----------------------------------------------------------

def helmert_task():
    rng = np.random.default_rng(7)
    dst = rng.uniform(0, 500, (8, 2))
    angle = np.radians(3.0)
    rotation = 0.2 * np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    src = (dst - [20, 35]) @ np.linalg.inv(rotation).T
    return src, dst + rng.normal(0, 0.3, dst.shape)


def test_check_helmert_recognises_the_answer_and_the_mistakes():
    from rsgeo_course.exercises import ExerciseNotSolved, check_helmert

    src, dst = helmert_task()
    m = transforms.fit_transform(src, dst, "helmert").matrix
    right = [m[0, 0], m[1, 0], m[0, 2], m[1, 2]]
    assert check_helmert(right, src, dst).ok
    with pytest.raises(ExerciseNotSolved):
        check_helmert(..., src, dst)
    sign = check_helmert([right[0], -right[1], right[2], right[3]], src, dst)
    assert not sign.ok and "wrong sign" in sign.hint and "`b`" in sign.message
    exact = transforms.fit_transform(src[:2], dst[:2], "helmert").matrix
    two = check_helmert([exact[0, 0], exact[1, 0], exact[0, 2], exact[1, 2]], src, dst)
    assert not two.ok and "every point" in two.hint
    assert "four" in check_helmert([1, 2, 3], src, dst).message
    assert "text" in check_helmert("abcd", src, dst).message
    for verdict in (sign, two):
        assert f"{right[1]:.3g}" not in repr(verdict) and f"{right[0]:.4g}" not in repr(verdict)


def test_check_projective_matrix_recognises_the_answer_and_the_mistakes():
    from rsgeo_course.exercises import check_projective_matrix

    ground = np.array([[0.0, 0.0], [105.0, 0.0], [105.0, 68.0], [0.0, 68.0]])
    photo = np.array([[112.0, 590.0], [905.0, 610.0], [760.0, 210.0], [250.0, 200.0]])
    right = transforms.fit_transform(ground, photo, "projective").matrix
    assert check_projective_matrix(right, ground, photo).ok
    assert check_projective_matrix(3 * right, ground, photo).ok
    assert "transposed" in check_projective_matrix(right.T, ground, photo).hint
    assert "dst to src" in check_projective_matrix(np.linalg.inv(right), ground, photo).hint
    affine = transforms.fit_transform(ground, photo, "polynomial", 1)
    a = np.vstack([affine.coefficients[:, [1, 2, 0]], [0, 0, 1]])
    a[:, 2] -= a[:, :2] @ affine.origin
    verdict = check_projective_matrix(a, ground, photo)
    assert not verdict.ok and "affine" in verdict.hint
    assert "3 × 3" in check_projective_matrix(np.zeros(8), ground, photo).message


def test_check_model_choice_judges_on_check_points():
    from rsgeo import synthetic
    from rsgeo_course.exercises import check_model_choice

    gcps = synthetic.distorted_pair(seed=2).gcps
    is_check = np.arange(len(gcps)) % 3 == 0
    table = accuracy.compare_models(gcps.map_xy, gcps.image_xy, is_check,
                               [m for m in transforms.GEOREFERENCER_MODELS
                                if m[0] != "polynomial 3"])
    best = table["check RMS (px)"].idxmin()
    assert check_model_choice(best, gcps.map_xy, gcps.image_xy, is_check).ok
    tps = check_model_choice("tps", gcps.map_xy, gcps.image_xy, is_check)
    assert not tps.ok and "used in the fit" in tps.hint
    assert f"{table['check RMS (px)'][best]:.2f}" not in repr(tps)
    assert "one of" in check_model_choice("affine", gcps.map_xy, gcps.image_xy, is_check).message
    assert "as text" in check_model_choice(2, gcps.map_xy, gcps.image_xy, is_check).message


# --- Polynomials: GDAL's GCP transformer, the lecture's terms, Newton's inverse ---


@pytest.mark.parametrize("order, n", [(1, 8), (2, 12), (3, 20), (3, 10)])
def test_map_to_image_agrees_with_gdal(order, n):
    # GDAL's own reference: a warped VRT with <Order>, no approximate transformer
    # (Reference: gdal_crs.cpp)
    image_xy, map_xy = utm_gcps(n, seed=order * 100 + n)
    dst_transform = affine.Affine(20, 0, map_xy[:, 0].min() + 2000, 0, -20,
                                  map_xy[:, 1].max() - 2000)
    gdal_cols, gdal_rows = gdal_map_to_image(image_xy, map_xy, order, dst_transform, (150, 150))
    x, y = grid_positions((150, 150), dst_transform)
    predicted = transforms.fit_polynomial(map_xy, image_xy, order)(
        np.column_stack([x.ravel(), y.ravel()]))
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
    predicted = transforms.fit_polynomial(image_xy, map_xy, order)(np.column_stack([cols, rows]))
    # 1e-6 pixel = 2e-5 m at 20 m pixels
    np.testing.assert_allclose(predicted, np.column_stack([xs, ys]), rtol=0, atol=2e-5)


def test_exact_with_the_minimum_number_of_gcps():
    for order in (1, 2, 3):
        image_xy, map_xy = utm_gcps(transforms.min_gcps(order), seed=order)
        model = transforms.fit_polynomial(map_xy, image_xy, order)
        np.testing.assert_allclose(model(map_xy), image_xy, atol=1e-6)


def test_reverse_is_the_least_squares_fit_of_the_other_direction():
    # GDAL fits image -> map separately: the reverse's residuals must satisfy the normal equations
    # of the image -> map system (orthogonal to every term), and differ from the forward's inverse
    image_xy, map_xy = utm_gcps(12, seed=3)
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    reverse = model.reverse()
    centred = (image_xy - image_xy.mean(axis=0)) / 1000
    terms = transforms.design_matrix(centred, 2)
    left_over = reverse(image_xy) - map_xy
    assert np.abs(terms.T @ left_over).max() < 1e-6 * np.abs(left_over).max() * len(terms)
    assert 5 < reverse.rms(image_xy, map_xy) < 40          # GCP noise of 15 m, not zero
    # swapping back gives the forward model again
    np.testing.assert_allclose(reverse.reverse()(map_xy), model(map_xy), atol=1e-6)


def test_inverse_undoes_the_model_where_the_reverse_fit_does_not():
    image_xy, map_xy = utm_gcps(12, seed=3)
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    inside = map_xy.mean(axis=0) + np.random.default_rng(0).uniform(-4000, 4000, (50, 2))
    np.testing.assert_allclose(model.inverse()(model(inside)), inside, atol=1e-6)
    assert model.inverse().inverse() is model
    assert model.inverse().residuals(model(inside), inside).max() < 1e-6
    assert np.abs(model.reverse()(model(inside)) - inside).max() > 0.01     # only approximate


def test_jacobian_matches_finite_differences():
    image_xy, map_xy = utm_gcps(20, seed=4)
    model = transforms.fit_polynomial(map_xy, image_xy, 3)
    point = map_xy[:3]
    step = 1e-2
    numeric = np.stack([(model(point + [step, 0]) - model(point - [step, 0])) / (2 * step),
                        (model(point + [0, step]) - model(point - [0, step])) / (2 * step)],
                       axis=-1)
    np.testing.assert_allclose(model.jacobian(point), numeric, rtol=1e-6, atol=1e-9)


def test_inverse_refuses_points_where_the_polynomial_folds():
    src = np.array([[x, y] for x in (-1.0, 0.0, 1.0) for y in (-1.0, 0.0, 1.0)])
    u = src[:, 0] + 0.8 * src[:, 0] ** 2                   # never below -0.3125 (at x = -0.625)
    model = transforms.fit_polynomial(src, np.column_stack([u, src[:, 1]]), 2)
    with pytest.raises(ValueError, match="no inverse"):
        model.inverse()([[-1.0, 0.0]])


@settings(max_examples=60, deadline=None)
@given(order=st.sampled_from([1, 2, 3]), seed=st.integers(0, 10_000),
       u=st.floats(0.1, 0.9), v=st.floats(0.1, 0.9), bend=st.floats(-0.15, 0.15))
def test_every_polynomial_inverse_round_trips(order, seed, u, v, bend):
    # a smooth, one-to-one map -> image mapping, sampled at enough GCPs for the order
    rng = np.random.default_rng(seed)
    image_xy = rng.uniform(0, 1000, (transforms.min_gcps(order) + 6, 2))
    c, r = image_xy[:, 0] / 1000, image_xy[:, 1] / 1000
    map_xy = np.column_stack([500_000 + 20_000 * (c + bend * r * r),
                              7_400_000 - 20_000 * (r + bend * c * r)])
    model = transforms.fit_polynomial(map_xy, image_xy, order)
    inside = np.array([[500_000 + 20_000 * u, 7_400_000 - 20_000 * v]])
    # Newton stops within 1e-9 of the dst extent (1,000 px): 1e-6 px, up to ~2e-5 m at 20 m/px
    np.testing.assert_allclose(model.inverse()(model(inside)), inside, rtol=0, atol=1e-4)
    image_point = model(inside)
    np.testing.assert_allclose(model(model.inverse()(image_point)), image_point, rtol=0, atol=1e-6)


@pytest.mark.parametrize("src, dst, order, message", [
    (np.zeros((4, 2)) + np.arange(4)[:, None] * [1, 2], np.random.default_rng(0).random((4, 2)), 2,
     "order 2 needs at least 6 GCPs, got 4"),
    (np.column_stack([np.arange(5.0), 2 * np.arange(5.0)]),
     np.random.default_rng(0).random((5, 2)), 1,
     "collinear, repeated"),
    (np.array([[0, 0], [1, 0], [0, 1], [1, 1.0]]).repeat(2, axis=0),
     np.random.default_rng(0).random((8, 2)), 2,
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
        transforms.fit_polynomial(src, dst, order)


def test_coefficients_in_the_lecture_order():
    src = np.random.default_rng(2).random((10, 2)) * 100
    dst = np.column_stack([1 + 2 * src[:, 0] + 3 * src[:, 1] + 4 * src[:, 0] * src[:, 1],
                           5 + 6 * src[:, 0] ** 2 + 7 * src[:, 1] ** 2])
    model = transforms.fit_polynomial(src - src.mean(axis=0), dst, 2)
    table = model.coefficient_table()
    assert list(table)[:6] == ["a0 (1)", "a1 (x)", "a2 (y)", "a3 (xy)", "a4 (x²)", "a5 (y²)"]
    assert table["a3 (xy)"] == pytest.approx(4) and table["b5 (y²)"] == pytest.approx(7)


# --- One registry, one Newton inverse ---


def test_the_registry_is_the_one_list_of_kinds():
    image_xy, map_xy = cbers()
    assert transforms.GEOREFERENCER_MODELS == tuple(
        (entry.label, entry.kind, entry.order) for entry in transforms.REGISTRY)
    assert transforms.KINDS == ("linear", "helmert", "polynomial", "projective", "tps")
    for entry in transforms.REGISTRY:
        model = transforms.fit_transform(map_xy, image_xy, entry.kind, entry.order)
        assert model.n_parameters == transforms.n_parameters(entry.kind, entry.order,
                                                             n_gcps=len(map_xy))
        assert transforms.min_gcps(entry.kind, entry.order) == entry.min_gcps
    with pytest.raises(ValueError, match="give n_gcps"):
        transforms.n_parameters("tps")


def test_polynomial_and_spline_share_one_newton_inverse():
    from rsgeo.errors import ModelError

    src = np.array([[x, y] for x in (-1.0, 0.0, 1.0) for y in (-1.0, 0.0, 1.0)])
    u = src[:, 0] + 0.8 * src[:, 0] ** 2                   # folds: no inverse below -0.3125
    folded = np.column_stack([u, src[:, 1]])
    for model in (transforms.fit_polynomial(src, folded, 2),
                  transforms.fit_transform(src, folded, "tps")):
        with pytest.raises(ModelError, match="no inverse"):
            model.inverse(max_iterations=0)([[0.5, 0.5]])      # no step: nothing converges
        inside = model(np.array([[0.2, 0.3]]))
        np.testing.assert_allclose(model(model.inverse()(inside)), inside, atol=1e-8)
    with pytest.raises(ModelError, match="no inverse"):
        transforms.fit_polynomial(src, folded, 2).inverse()([[-1.0, 0.0]])


# --- bad and extreme GCPs ---


def test_tps_skips_exact_duplicates_as_gdal_does():
    # GDAL's GDALCreateTPSTransformerInt skips a GCP that repeats an earlier one exactly
    image_xy, map_xy = cbers()
    twice_map, twice_image = np.vstack([map_xy, map_xy[[3, 5]]]), np.vstack([image_xy,
                                                                             image_xy[[3, 5]]])
    model = transforms.fit_transform(twice_map, twice_image, "tps")
    assert model.skipped == (len(map_xy), len(map_xy) + 1)
    points = inside_points(map_xy)
    expected = gdal_tps_map_to_image(twice_image, twice_map, points)
    assert np.abs(model(points) - expected).max() < 1e-6


def test_tps_refuses_near_duplicates_with_different_targets():
    image_xy, map_xy = cbers()
    map_xy = np.vstack([map_xy, map_xy[4] + [0.01, 0]])          # 1 cm from GCP 4
    image_xy = np.vstack([image_xy, image_xy[4] + [30, 0]])       # but 30 px elsewhere
    with pytest.raises(transforms.GCPError, match=r"rows 4 and 14"):
        transforms.fit_transform(map_xy, image_xy, "tps")


@pytest.mark.slow
def test_tps_inverse_converges_on_two_thousand_noisy_gcps():
    # GDAL autotest transformer.py, test_transformer_tps_precision (2,115 GCPs), made synthetic:
    # the spline through 2,000 noisy GCPs cannot be evaluated to 1e-10 of its extent
    rng = np.random.default_rng(0)
    image_xy = rng.uniform(0, 5000, (2000, 2))
    c, r = image_xy[:, 0] / 5000, image_xy[:, 1] / 5000
    map_xy = (np.column_stack([500_000 + 100_000 * c + 2000 * r * r,
                               7_400_000 - 100_000 * r + 500 * c])
              + rng.normal(0, 200, (2000, 2)))
    model = transforms.fit_transform(image_xy, map_xy, "tps")
    assert model.evaluation_floor() > 1e-10 * np.ptp(map_xy, axis=0).max() / 2
    back = model.inverse()(map_xy)
    np.testing.assert_allclose(back, image_xy, atol=1e-6)


@pytest.mark.parametrize("src, dst, order", [
    (np.ones((6, 2), complex), np.ones((6, 2)), 1),
    (np.ones((6, 2), bool), np.ones((6, 2)), 1),
    (np.random.default_rng(0).random((6, 2)), np.random.default_rng(1).random((6, 2)), True),
    (np.random.default_rng(0).random((6, 2)), np.random.default_rng(1).random((6, 2)), "1"),
])
def test_complex_bool_and_boolean_orders_are_type_errors(src, dst, order):
    with pytest.raises(TypeError):
        transforms.fit_polynomial(src, dst, order)
    with pytest.raises(TypeError):
        transforms.fit_transform(src, dst, "polynomial", order)
    with pytest.raises(TypeError):
        transforms.min_gcps(True)


def test_nearly_collinear_gcps_are_refused():
    rng = np.random.default_rng(0)
    x = np.linspace(0, 1000, 12)
    src = np.column_stack([x, 2 * x + rng.normal(0, 0.01, 12)])     # 1e-5 off one line
    for order in (1, 2):
        with pytest.raises(transforms.GCPError, match=r"\(nearly\) collinear"):
            transforms.fit_polynomial(src, rng.random((12, 2)), order)
    # an elongated but genuine strip (QGIS's test GCPs, 1.5 km x 62 km) is accepted
    transforms.fit_polynomial(QGIS_MAP_10, QGIS_PIXEL_10, 3)


def test_models_copy_their_gcps():
    image_xy, map_xy = cbers()
    src, dst = map_xy.copy(), image_xy.copy()
    for kind, order in (("polynomial", 2), ("helmert", None), ("tps", None)):
        model = transforms.fit_transform(src, dst, kind, order)
        before = model.reverse()(dst[:3]) if hasattr(model, "reverse") else model.inverse()(
            dst[:3])
        src += 100.0
        dst *= 1.5
        after = model.reverse()(image_xy[:3]) if hasattr(model, "reverse") else \
            model.inverse()(image_xy[:3])
        np.testing.assert_allclose(after, before)
        np.testing.assert_array_equal(model.src, map_xy)
        src, dst = map_xy.copy(), image_xy.copy()


def test_outside_gcps_rates_extrapolation_and_inverse_refuses_far_preimages():
    from rsgeo.errors import ModelError

    rng = np.random.default_rng(3)
    src = rng.uniform(0, 500, (20, 2)) + [500_000, 7_400_000]      # clustered in 500 m
    c, r = (src[:, 0] - 500_000) / 20, (7_400_000 - src[:, 1]) / 20
    dst = np.column_stack([c + 1e-3 * c * c, r - 1e-3 * c * r])
    model = transforms.fit_polynomial(src, dst, 2)
    assert model.outside_gcps(src).max() == 0
    far = np.array([[600_000.0, 7_400_000.0]])                      # 100 km away
    assert model.outside_gcps(far)[0] > 100
    with pytest.raises(ModelError, match="far outside its GCPs"):
        model.inverse()(model(far))
    inside = src.mean(axis=0, keepdims=True)
    np.testing.assert_allclose(model.inverse()(model(inside)), inside, atol=1e-6)
    # order 1 has one preimage everywhere: nothing refused
    linear = transforms.fit_polynomial(src, dst, 1)
    np.testing.assert_allclose(linear.inverse()(linear(far)), far, atol=1e-4)


# --- QGIS tests/src/analysis/testqgsgcptransformer.cpp, ported ---
# QGIS's updateParametersFromGcps(source=pixel, destination=map): transform() maps pixel ->
# map; transform(..., true) is the exact inverse for linear, Helmert and projective and GDAL's
# separately fitted reverse for the polynomials and the spline (rsgeo's .reverse()).
# QGSCOMPARENEAR(value, expected, 1): within 1.

QGIS_PIXEL_4 = np.array([(288, 1126), (2352, 716), (2067, 2398), (1102, 2209)], float)
QGIS_MAP_4 = np.array([(321210, 130280), (322698, 129979), (322501, 192061),
                       (321803, 192198)], float)
QGIS_PIXEL_6 = np.vstack([QGIS_PIXEL_4[:3], [(2100, 1500)], QGIS_PIXEL_4[3:], [(300, 1550)]])
QGIS_MAP_6 = np.vstack([QGIS_MAP_4[:3], [(322550, 149979)], QGIS_MAP_4[3:], [(321310, 145979)]])
QGIS_PIXEL_10 = np.vstack([QGIS_PIXEL_6, [(300, 850), (1000, 830), (900, 1450), (700, 1550)]])
QGIS_MAP_10 = np.vstack([QGIS_MAP_6, [(321310, 131979), (321703, 131579), (321603, 145979),
                                      (321003, 146179)]])
QGIS_POINTS = np.array([(288, 1000), (2352, 1150), (2067, 2500), (1102, 2300)], float)
QGIS_IDENTITY_10 = np.array([(321210, 130280), (322698, 129979), (322501, 192061),
                             (322501, 152061), (321803, 192198), (321210, 152061),
                             (322010, 182061), (322010, 132061), (321050, 162061),
                             (321050, 172061)], float)
QGIS_IDENTITY_POINTS = np.array([(321212, 123003), (322702, 140444), (322496, 194554),
                                 (321800, 186514)], float)

QGIS_CASES = {
    # name: (kind, order, pixel GCPs, map GCPs, expected forward, expected back)
    "testLinear": ("linear", None, QGIS_PIXEL_4, QGIS_MAP_4,
                   [(321212, 135047), (322702, 141437), (322496, 198947), (321800, 190427)],
                   QGIS_POINTS),
    "testHelmert": ("helmert", None, QGIS_PIXEL_4, QGIS_MAP_4,
                    [(302325, 145676), (340495, 155540), (330540, 179867), (313138, 172822)],
                    QGIS_POINTS),
    "testPolyOrder1": ("polynomial", 1, QGIS_PIXEL_4, QGIS_MAP_4,
                       [(321209, 128732), (322700, 146403), (322501, 202230), (321803, 188448)],
                       [(288, 1017), (2352, 1164), (2067, 2474), (1102, 2279)]),
    "testPolyOrder2": ("polynomial", 2, QGIS_PIXEL_6, QGIS_MAP_6,
                       [(321175, 126837), (322763, 135026), (322489, 198409), (321803, 197778)],
                       [(265, 1025), (2336, 936), (2097, 2445), (1123, 2225)]),
    "testPolyOrder3": ("polynomial", 3, QGIS_PIXEL_10, QGIS_MAP_10,
                       [(321202, 129364), (318595, 101765), (321488, 185766), (320879, 189391)],
                       [(237, 1319), (138412, 15444), (-1237, 5315), (-4000, 2621)]),
    "testTPSReports": ("tps", None, QGIS_PIXEL_4, QGIS_MAP_4,
                       [(321209, 124248), (322700, 146609), (322501, 196160), (321803, 195999)],
                       [(290, 680), (2347, 1636), (2068, 2273), (1103, 2177)]),
    "testProjective": ("projective", None, QGIS_PIXEL_4, QGIS_MAP_4,
                       [(321256, 123764), (322687, 142908), (322494, 197069), (321781, 198051)],
                       QGIS_POINTS),
}


def _qgis_back(model, points):
    """QGIS's transform(..., true): the reverse fit (GDAL) or the exact inverse (matrices)."""
    return (model.reverse() if hasattr(model, "reverse") else model.inverse())(points)


@pytest.mark.parametrize("name", list(QGIS_CASES))
def test_qgis_gcp_transformer(name):
    kind, order, pixel, map_xy, forward, back = QGIS_CASES[name]
    model = transforms.fit_transform(pixel, map_xy, kind, order)
    there = model(QGIS_POINTS)
    np.testing.assert_allclose(there, forward, rtol=0, atol=1)
    np.testing.assert_allclose(_qgis_back(model, there), back, rtol=0, atol=1)


@pytest.mark.parametrize("kind, order, n", [
    ("linear", None, 4), ("helmert", None, 4), ("polynomial", 1, 4), ("polynomial", 2, 6),
    ("polynomial", 3, 10), ("tps", None, 4), ("projective", None, 4)])
def test_qgis_gcp_transformer_exact(kind, order, n):
    # QGIS's test...Exact cases: the identity, fitted on map points, reproduces any point
    gcps = QGIS_IDENTITY_10[:n] if n != 4 else QGIS_MAP_4
    model = transforms.fit_transform(gcps, gcps, kind, order)
    there = model(QGIS_IDENTITY_POINTS)
    np.testing.assert_allclose(there, QGIS_IDENTITY_POINTS, rtol=0, atol=1)
    np.testing.assert_allclose(_qgis_back(model, there), QGIS_IDENTITY_POINTS, rtol=0, atol=1)


QGIS_RASTER_Y = {
    # QGIS's ...RasterYAxis cases for the GDAL-based models and the projective one: the pixel
    # GCPs are given with y = -line and flipped before fitting, but the points transformed are
    # passed as given (y = -line, i.e. outside the image): a QGIS convention, reproduced here by
    # fitting on (x, -y) and evaluating at (x, y).
    "testPolyOrder1RasterYAxis": ("polynomial", 1, [(288, -716), (2352, -1126), (2067, -2398),
                                                    (1102, -2209)], QGIS_MAP_4,
                                  [(321201, 63463), (322686, 24965), (322474, -31687),
                                   (321780, -13813)]),
    "testPolyOrder2RasterYAxis": ("polynomial", 2, QGIS_PIXEL_6 * [1, -1], QGIS_MAP_6,
                                  [(320404, 131061), (322022, 176342), (320831, 273376),
                                   (319958, 243375)]),
    "testTPSRasterYAxis": ("tps", None, [(288, -716), (2352, -1126), (2067, -2398),
                                         (1102, -2209)], QGIS_MAP_4,
                           [(321202, 63505), (322686, 24959), (322474, -31676),
                            (321780, -13787)]),
    "testProjectiveRasterYAxis": ("projective", None, [(288, -716), (2352, -1126),
                                                       (2067, -2398), (1102, -2209)], QGIS_MAP_4,
                                  [(321203, 63965), (322681, 25366), (322467, -30635),
                                   (321777, -12647)]),
}
QGIS_RASTER_Y_POINTS = np.array([(288, -716), (2352, -1126), (2067, -2398), (1102, -2209)],
                                float)


@pytest.mark.parametrize("name", list(QGIS_RASTER_Y))
def test_qgis_gcp_transformer_raster_y_axis(name):
    kind, order, pixel, map_xy, forward = QGIS_RASTER_Y[name]
    model = transforms.fit_transform(np.asarray(pixel, float) * [1, -1], map_xy, kind, order)
    points = QGIS_RASTER_Y_POINTS if "Order2" not in name else QGIS_RASTER_Y_POINTS[
        [0, 1, 2, 3]]
    np.testing.assert_allclose(model(points), forward, rtol=0, atol=1)
