"""rsgeo.gcp.fit_transform: QGIS's Georeferencer models against GDAL and scikit-image."""

import affine
import numpy as np
import pytest
from rasterio.control import GroundControlPoint
from rasterio.transform import GCPTransformer
from skimage.transform import PolynomialTransform, ProjectiveTransform, SimilarityTransform

from gdal_reference import gcp_source, gdal_warp
from rsgeo import data, gcp
from rsgeo.resample import warp


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
    model = gcp.fit_transform(map_xy, image_xy, "tps")
    points = np.vstack([map_xy, inside_points(map_xy)])
    expected = gdal_tps_map_to_image(image_xy, map_xy, points)
    assert np.abs(model(points) - expected).max() < 1e-6
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
    # gdalwarp fits the spline image -> map and inverts it exactly at every output cell
    model = gcp.fit_transform(image_xy, map_xy, "tps").inverse()
    # GDAL stops its inversion within about 1e-6 px of the root, rsgeo goes to 1e-8 px:
    # nearest is bit-exact, and bilinear/cubic may round a handful of pixels (of 160 000)
    # the other way, by one DN.
    for method, allowed in (("nearest", 0), ("bilinear", 3), ("cubic", 3)):
        expected = gdal_warp(image, source, dst_transform, shape, method, 0)
        got = warp(image, model, shape, dst_transform, method=method, nodata=0)
        assert np.count_nonzero(expected) > shape[0] * shape[1] // 4
        assert np.count_nonzero(got != expected) <= allowed
        assert np.abs(got.astype(int) - expected).max() <= (1 if allowed else 0)
    # the reverse spline (what rasterio's GCPTransformer gives map -> image) is NOT what
    # gdalwarp uses: it is off by up to a tenth of a pixel between the GCPs
    reverse = gcp.fit_transform(map_xy, image_xy, "tps")
    assert np.count_nonzero(warp(image, reverse, shape, dst_transform, nodata=0)
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
    model = gcp.fit_transform(src, dst, "helmert")
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
    model = gcp.fit_transform(map_xy, image_xy, "projective")
    reference = ProjectiveTransform.from_estimate(map_xy, image_xy).params
    reference = reference / reference[2, 2]
    assert np.abs(model.matrix - reference).max() <= 1e-9 * np.abs(reference).max()
    assert model.n_parameters == 8


def test_projective_from_four_points_is_exact_and_inverts():
    src = np.array([[0.0, 0], [100, 0], [100, 100], [0, 100]])
    dst = np.array([[10.0, 5], [90, 12], [80, 95], [5, 80]])
    model = gcp.fit_transform(src, dst, "projective")
    assert model.residuals(src, dst).max() < 1e-9
    back = model.inverse()
    assert back.kind == "projective"
    assert np.abs(back(dst) - src).max() < 1e-9


def test_linear_is_scale_and_offset_per_axis():
    rng = np.random.default_rng(6)
    src = rng.uniform(0, 1000, (15, 2))
    dst = src * [0.05, -0.04] + [10, 900] + rng.normal(0, 0.5, (15, 2))
    model = gcp.fit_transform(src, dst, "linear")
    assert model.matrix[0, 1] == 0 and model.matrix[1, 0] == 0
    for axis in range(2):
        slope, intercept = np.polyfit(src[:, axis], dst[:, axis], 1)
        assert np.isclose(model.matrix[axis, axis], slope, rtol=1e-12)
        assert np.isclose(model.matrix[axis, 2], intercept, rtol=1e-9, atol=1e-9)
    assert np.abs(model.inverse()(model(src)) - src).max() < 1e-9


def test_polynomial_kind_is_fit_polynomial_and_differs_from_scikit_image_tls():
    image_xy, map_xy = utm_gcps(20, 7, noise=40.0)
    model = gcp.fit_transform(map_xy, image_xy, "polynomial", order=2)
    reference = gcp.fit_polynomial(map_xy, image_xy, 2)
    assert np.array_equal(model.coefficients, reference.coefficients)
    assert model.kind == "polynomial" and model.n_parameters == 12
    # ordinary least squares: the residuals are orthogonal to every term
    residual = model(map_xy) - image_xy
    terms = gcp.design_matrix(map_xy - map_xy.mean(axis=0), 2)
    assert np.abs(terms.T @ residual).max() < 1e-6 * np.abs(terms).max() * np.abs(residual).max()
    # scikit-image's total least squares is another estimate: off by far more than rounding
    # even on centred coordinates, and by pixels on raw UTM coordinates
    image_xy, map_xy = cbers()
    model = gcp.fit_transform(map_xy, image_xy, "polynomial", order=2)
    centred = map_xy - map_xy.mean(axis=0)
    tls = PolynomialTransform.from_estimate(centred, image_xy, order=2)
    assert np.abs(tls(centred) - model(map_xy)).max() > 1e-3
    raw = PolynomialTransform.from_estimate(map_xy, image_xy, order=2)
    assert np.abs(raw(map_xy) - model(map_xy)).max() > 1.0


@pytest.mark.parametrize("kind, order, expected", [
    ("helmert", None, 2), ("projective", None, 4), ("linear", None, 2), ("tps", None, 3),
    ("polynomial", 1, 3), ("polynomial", 2, 6), ("polynomial", 3, 10)])
def test_min_gcps_of_every_kind(kind, order, expected):
    assert gcp.min_gcps(kind, order) == expected
    if order is not None:
        assert gcp.min_gcps(order) == expected


@pytest.mark.parametrize("kind, order", [
    ("linear", None), ("helmert", None), ("polynomial", 1), ("polynomial", 3),
    ("projective", None), ("tps", None)])
def test_every_kind_follows_the_protocol(kind, order):
    image_xy, map_xy = cbers()
    model = gcp.fit_transform(map_xy, image_xy, kind, order)
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
        gcp.fit_transform(map_xy, image_xy, kind, order)
    with pytest.raises(ValueError, match=message):
        gcp.min_gcps(kind, order)


@pytest.mark.parametrize("kind, n", [("helmert", 1), ("projective", 3), ("tps", 2),
                                     ("linear", 1)])
def test_too_few_points_is_a_value_error(kind, n):
    image_xy, map_xy = cbers()
    with pytest.raises(ValueError, match=f"needs at least {gcp.min_gcps(kind)} GCPs, got {n}"):
        gcp.fit_transform(map_xy[:n], image_xy[:n], kind)


def test_collinear_points_for_projective_and_tps_are_value_errors():
    line = np.column_stack([np.arange(6.0), 2 * np.arange(6.0) + 1])
    target = line * 3 + [[0, 0], [1, 0], [0, 1], [2, 2], [0, 0], [1, 1]]
    with pytest.raises(ValueError, match="collinear"):
        gcp.fit_transform(line, target, "projective")
    with pytest.raises(ValueError, match="collinear"):
        gcp.fit_transform(line, target, "tps")
    three_on_a_line = np.array([[0.0, 0], [1, 1], [2, 2], [0, 5]])
    with pytest.raises(ValueError, match="collinear"):
        gcp.fit_transform(three_on_a_line, three_on_a_line * 2, "projective")


def test_duplicate_points_for_tps_are_a_value_error():
    image_xy, map_xy = cbers()
    map_xy = np.vstack([map_xy, map_xy[3]])
    image_xy = np.vstack([image_xy, image_xy[3] + 2])
    with pytest.raises(ValueError, match="repeat"):
        gcp.fit_transform(map_xy, image_xy, "tps")


def test_leave_one_out_matches_fitting_without_the_point():
    image_xy, map_xy = cbers()
    for kind, order in (("projective", None), ("tps", None), ("polynomial", 2)):
        errors = gcp.transform_leave_one_out(map_xy, image_xy, kind, order)
        keep = np.arange(len(map_xy)) != 9
        alone = gcp.fit_transform(map_xy[keep], image_xy[keep], kind, order)
        assert np.isclose(errors[9], alone.residuals(map_xy[9:10], image_xy[9:10])[0])
        if kind == "polynomial":
            assert np.allclose(errors, gcp.leave_one_out_errors(map_xy, image_xy, order))
    with pytest.raises(ValueError, match="one more than its minimum"):
        gcp.transform_leave_one_out(map_xy[:4], image_xy[:4], "projective")


def test_compare_models_fits_on_gcps_and_measures_check_points():
    image_xy, map_xy = cbers()
    is_check = np.zeros(len(map_xy), bool)
    is_check[[1, 6, 12]] = True
    table = gcp.compare_models(map_xy, image_xy, is_check)
    assert list(table.index) == [label for label, _, _ in gcp.GEOREFERENCER_MODELS]
    tps = gcp.fit_transform(map_xy[~is_check], image_xy[~is_check], "tps")
    assert np.isclose(table.loc["tps", "check RMS (px)"],
                      tps.rms(map_xy[is_check], image_xy[is_check]))
    assert table.loc["tps", "fitting RMS (px)"] < 1e-6
    assert table.loc["polynomial 3", "parameters"] == 20
    with pytest.raises(ValueError, match="one flag per point"):
        gcp.compare_models(map_xy, image_xy, is_check[:5])


def test_model_explorer_switches_models_in_place():
    import matplotlib

    matplotlib.use("Agg")
    from rsgeo import widgets
    from rsgeo.plot import figure_problems

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
    from rsgeo.exercises import ExerciseNotSolved, check_helmert

    src, dst = helmert_task()
    m = gcp.fit_transform(src, dst, "helmert").matrix
    right = [m[0, 0], m[1, 0], m[0, 2], m[1, 2]]
    assert check_helmert(right, src, dst).ok
    with pytest.raises(ExerciseNotSolved):
        check_helmert(..., src, dst)
    sign = check_helmert([right[0], -right[1], right[2], right[3]], src, dst)
    assert not sign.ok and "wrong sign" in sign.hint and "`b`" in sign.message
    exact = gcp.fit_transform(src[:2], dst[:2], "helmert").matrix
    two = check_helmert([exact[0, 0], exact[1, 0], exact[0, 2], exact[1, 2]], src, dst)
    assert not two.ok and "every point" in two.hint
    assert "four" in check_helmert([1, 2, 3], src, dst).message
    assert "text" in check_helmert("abcd", src, dst).message
    for verdict in (sign, two):
        assert f"{right[1]:.3g}" not in repr(verdict) and f"{right[0]:.4g}" not in repr(verdict)


def test_check_projective_matrix_recognises_the_answer_and_the_mistakes():
    from rsgeo.exercises import check_projective_matrix

    ground = np.array([[0.0, 0.0], [105.0, 0.0], [105.0, 68.0], [0.0, 68.0]])
    photo = np.array([[112.0, 590.0], [905.0, 610.0], [760.0, 210.0], [250.0, 200.0]])
    right = gcp.fit_transform(ground, photo, "projective").matrix
    assert check_projective_matrix(right, ground, photo).ok
    assert check_projective_matrix(3 * right, ground, photo).ok
    assert "transposed" in check_projective_matrix(right.T, ground, photo).hint
    assert "dst to src" in check_projective_matrix(np.linalg.inv(right), ground, photo).hint
    affine = gcp.fit_transform(ground, photo, "polynomial", 1)
    a = np.vstack([affine.coefficients[:, [1, 2, 0]], [0, 0, 1]])
    a[:, 2] -= a[:, :2] @ affine.origin
    verdict = check_projective_matrix(a, ground, photo)
    assert not verdict.ok and "affine" in verdict.hint
    assert "3 × 3" in check_projective_matrix(np.zeros(8), ground, photo).message


def test_check_model_choice_judges_on_check_points():
    from rsgeo import synthetic
    from rsgeo.exercises import check_model_choice

    gcps = synthetic.distorted_pair(seed=2).gcps
    is_check = np.arange(len(gcps)) % 3 == 0
    table = gcp.compare_models(gcps.map_xy, gcps.image_xy, is_check,
                               [m for m in gcp.GEOREFERENCER_MODELS if m[0] != "polynomial 3"])
    best = table["check RMS (px)"].idxmin()
    assert check_model_choice(best, gcps.map_xy, gcps.image_xy, is_check).ok
    tps = check_model_choice("tps", gcps.map_xy, gcps.image_xy, is_check)
    assert not tps.ok and "used in the fit" in tps.hint
    assert f"{table['check RMS (px)'][best]:.2f}" not in repr(tps)
    assert "one of" in check_model_choice("affine", gcps.map_xy, gcps.image_xy, is_check).message
    assert "as text" in check_model_choice(2, gcps.map_xy, gcps.image_xy, is_check).message
