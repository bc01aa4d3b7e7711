"""rsgeo.sensors: a frame camera's collinearity equations and space resection, against a synthetic
camera with a known truth.

Outside references: the collinearity equations as Wolf, Dewitt & Wilkes (Elements of
Photogrammetry, appendix C) write them, with their M matrix element by element (written out
below, not taken from rsgeo); scikit-image's ``ProjectiveTransform`` for the flat-terrain case;
the relief-displacement formula d = r·h/H (``relief.relief_displacement_photo``) for relief.
"""

import numpy as np
import pytest
from skimage.transform import ProjectiveTransform

from rsgeo import errors, relief, transforms
from rsgeo.sensors import (
    PARAMETERS,
    ExteriorOrientation,
    FrameCamera,
    InteriorOrientation,
    angles_from_rotation,
    resect,
    rotation_matrix,
)

# a 48 × 36 mm sensor of 6 µm pixels behind a 100 mm lens, 3 km up: 18 cm pixels
INTERIOR = InteriorOrientation(100.0, 0.006, (8000, 6000), principal_point_mm=(0.012, -0.008))
TRUTH = ExteriorOrientation(5000.0, 8000.0, 3000.0, 2.0, -1.5, 30.0)
NOISE_PX = 0.5


def gcps(camera, n, seed=0, relief=(0.0, 150.0)):
    """n GCPs seen by ``camera``: positions spread over the image, heights drawn in ``relief``,
    the ground point on each ray at its height (exact image positions)."""
    rng = np.random.default_rng(seed)
    cols, rows = camera.interior.size
    image = rng.uniform([0.04 * cols, 0.04 * rows], [0.96 * cols, 0.96 * rows], (n, 2))
    ground = camera.ground_at_height(image, rng.uniform(*relief, n))
    return ground, image


def wolf_project(ground, interior, exterior):
    """The collinearity equations as Wolf et al. write them (M element by element, f, x0, y0)."""
    o, p, k = np.radians([exterior.omega, exterior.phi, exterior.kappa])
    so, co, sp, cp, sk, ck = np.sin(o), np.cos(o), np.sin(p), np.cos(p), np.sin(k), np.cos(k)
    m = np.array([[cp * ck, so * sp * ck + co * sk, -co * sp * ck + so * sk],
                  [-cp * sk, -so * sp * sk + co * ck, co * sp * sk + so * ck],
                  [sp, -so * cp, co * cp]])
    d = np.asarray(ground) - [exterior.x0, exterior.y0, exterior.z0]
    r, s, q = m @ d.T
    xa = interior.principal_point_mm[0] - interior.focal_mm * r / q
    ya = interior.principal_point_mm[1] - interior.focal_mm * s / q
    cols, rows = interior.size
    return np.column_stack([cols / 2 + xa / interior.pixel_mm, rows / 2 - ya / interior.pixel_mm])


# --- the camera ------------------------------------------------------------------------------


@pytest.mark.parametrize("angles", [(0, 0, 0), (2.0, -1.5, 30.0), (-25.0, 40.0, -170.0)])
def test_rotation_is_the_transpose_of_the_asprs_orientation_matrix(angles):
    exterior = ExteriorOrientation(0, 0, 0, *angles)
    ground = np.array([[1.0, 2.0, -3.0]])
    rotation = rotation_matrix(*angles)
    np.testing.assert_allclose(rotation @ rotation.T, np.eye(3), atol=1e-15)
    assert np.linalg.det(rotation) == pytest.approx(1.0)
    np.testing.assert_allclose(angles_from_rotation(rotation), angles, atol=1e-12)
    # Wolf's M applied to a vector is Rᵀ applied to it
    interior = InteriorOrientation(1.0, 1.0, (2, 2))
    ours = (ground - 0) @ rotation                      # Rᵀ d
    xa = -ours[0, 0] / ours[0, 2] + 1
    assert wolf_project(ground, interior, exterior)[0, 0] == pytest.approx(xa)


def test_project_is_the_textbook_collinearity():
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, _ = gcps(camera, 30, seed=4)
    np.testing.assert_allclose(camera.project(ground), wolf_project(ground, INTERIOR, TRUTH),
                               atol=1e-9)


def test_a_vertical_photo_is_a_map_at_scale_c_over_h():
    interior = InteriorOrientation(100.0, 0.01, (2000, 1500))
    camera = FrameCamera(interior, ExteriorOrientation(1000.0, 2000.0, 1500.0, 0, 0, 0))
    image = camera.project([[1000.0, 2000.0, 0.0], [1150.0, 2000.0, 0.0], [1000.0, 2100, 500]])
    # the nadir at the image centre (a pixel corner: GDAL's convention); 15 m = 1000 pixels of
    # 1.5 m; north is up (rows decrease); at 500 m the scale is c / (H - h) = 1:10,000
    np.testing.assert_allclose(image, [[1000, 750], [2000, 750], [1000, 750 - 1000]],
                               atol=1e-9)


def test_principal_point_and_kappa_move_the_image_as_stated():
    interior = InteriorOrientation(100.0, 0.01, (2000, 1500), principal_point_mm=(0.5, 0.2))
    camera = FrameCamera(interior, ExteriorOrientation(0, 0, 1000.0, 0, 0, 90.0))
    # the nadir images at the principal point: 50 px right, 20 px up of the centre
    np.testing.assert_allclose(camera.project([[0, 0, 0]]), [[1050, 730]], atol=1e-9)
    # κ = 90°: the photo's x axis points north, so a point to the north is to the right
    east, north = camera.project([[100.0, 0, 0], [0, 100.0, 0]]) - [[1050, 730]]
    np.testing.assert_allclose(north, [1000, 0], atol=1e-9)
    np.testing.assert_allclose(east, [0, 1000], atol=1e-9)


@pytest.mark.parametrize("k1", [0.0, -2e-6, 3e-6])
def test_ground_at_height_inverts_project(k1):
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000), (0.012, -0.008), k1=k1)
    camera = FrameCamera(interior, TRUTH)
    ground, image = gcps(camera, 50, seed=1, relief=(-50, 400))
    np.testing.assert_allclose(camera.project(ground), image, atol=1e-9)


def test_radial_distortion_moves_points_radially_by_k1_rho_cubed():
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000), k1=-1e-6)
    plain = InteriorOrientation(100.0, 0.006, (8000, 6000))
    exterior = ExteriorOrientation(0, 0, 3000.0, 0, 0, 0)
    ground = np.array([[300.0, 200.0, 0.0], [-500.0, 400.0, 0.0]])
    distorted = interior.to_photo(FrameCamera(interior, exterior).project(ground))
    ideal = plain.to_photo(FrameCamera(plain, exterior).project(ground))
    rho = np.hypot(*ideal.T)
    np.testing.assert_allclose(np.hypot(*distorted.T) - rho, -1e-6 * rho**3, atol=1e-12)
    cross = distorted[:, 0] * ideal[:, 1] - distorted[:, 1] * ideal[:, 0]
    np.testing.assert_allclose(cross, 0, atol=1e-12)                # radial: parallel


@pytest.mark.parametrize("k1", [0.0, -1e-6])
def test_the_analytic_jacobian_matches_central_differences(k1):
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000), (0.012, -0.008), k1=k1)
    camera = FrameCamera(interior, TRUTH)
    ground, _ = gcps(camera, 12, seed=2)
    analytic = camera.jacobian(ground)
    numeric = np.empty_like(analytic)
    for k, step in enumerate([1e-3] * 3 + [1e-6] * 3):
        moved = []
        for sign in (1, -1):
            values = TRUTH.as_array()
            values[k] += sign * step
            moved.append(FrameCamera(interior, ExteriorOrientation.from_array(values))
                         .project(ground))
        numeric[:, :, k] = (moved[0] - moved[1]) / (2 * step)
    scale = np.abs(analytic).max(axis=(0, 1))
    assert (np.abs(analytic - numeric).max(axis=(0, 1)) < 1e-6 * scale).all()


# --- space resection -----------------------------------------------------------------------


@pytest.mark.parametrize("n, relief, method", [
    (3, (0, 150), "vertical"), (4, (20, 20), "projective"), (8, (20, 20), "projective"),
    (8, (0, 150), "dlt"), (12, (0, 600), "dlt")])
def test_noise_free_gcps_recover_the_orientation(n, relief, method):
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, image = gcps(camera, n, seed=5, relief=relief)
    fit = resect(ground, image, INTERIOR)
    assert fit.initial_method == method
    error = fit.exterior.as_array() - TRUTH.as_array()
    assert np.abs(error[:3]).max() < 1e-9 * 3000 and np.abs(error[3:]).max() < 1e-9
    assert fit.redundancy == 2 * n - 6 and np.abs(fit.residuals).max() < 1e-8
    if n == 3:
        assert np.isnan(fit.sigma0_px) and np.isnan(fit.covariance).all()
    else:
        assert fit.sigma0_px < 1e-8


def test_resection_with_distortion_and_utm_sized_coordinates():
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000), (0.012, -0.008), k1=-1e-6)
    truth = ExteriorOrientation(292500.0, 9114000.0, 3000.0, 2.0, -1.5, 30.0)
    ground, image = gcps(FrameCamera(interior, truth), 10, seed=1, relief=(0, 200))
    given = ground.copy(), image.copy()
    fit = resect(ground, image, interior)
    error = fit.exterior.as_array() - truth.as_array()
    # 9e6 m coordinates hold 2e-9 m in float64: metres to 1e-7, angles to 1e-9 degrees
    assert np.abs(error[:3]).max() < 1e-7 and np.abs(error[3:]).max() < 1e-9
    np.testing.assert_array_equal(ground, given[0])          # inputs untouched
    np.testing.assert_array_equal(image, given[1])


def test_utm_is_not_cartesian_but_a_local_tangent_plane_is():
    # The truth in a true 3-D frame: a camera 3,000 m above a local tangent plane at Olinda.
    # Its GCPs given as SIRGAS 2000 / UTM 25S and ellipsoidal heights, resected as if UTM were
    # Cartesian, put the camera too high by about H (k - 1), UTM's scale factor k stretching
    # the footprint; resected in the tangent plane, they give the truth back.
    from pyproj import CRS, Proj, Transformer

    from rsgeo.local_frame import from_local_tangent_plane, to_local_tangent_plane

    crs, origin = "EPSG:31985", (292_500.0, 9_114_000.0, 0.0)
    truth = ExteriorOrientation(0.0, 0.0, 3000.0, 2.0, -1.5, 30.0)
    ground, image = gcps(FrameCamera(INTERIOR, truth), 12, seed=2)
    surveyed = from_local_tangent_plane(ground, crs, origin)           # UTM + h
    centre = from_local_tangent_plane(truth.as_array()[:3], crs, origin)[0]
    lon, lat = Transformer.from_crs(crs, "EPSG:4674", always_xy=True).transform(*origin[:2])
    k = Proj(CRS(crs)).get_factors(lon, lat).meridional_scale
    as_cartesian = resect(surveyed, image, INTERIOR).exterior.as_array()[:3]
    in_plane = resect(to_local_tangent_plane(surveyed, crs, origin), image, INTERIOR)
    back = from_local_tangent_plane(in_plane.exterior.as_array()[:3], crs, origin)[0]
    bias = as_cartesian[2] - centre[2]
    assert 0.8 * 3000 * (k - 1) < bias < 1.05 * 3000 * (k - 1)       # 0.32 to 0.42 m high
    assert np.abs(back - centre).max() < 1e-5


def test_a_given_initial_orientation_is_used():
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, image = gcps(camera, 6, seed=3)
    start = ExteriorOrientation(5100.0, 7900.0, 2800.0, 0, 0, 25.0)
    fit = resect(ground, image, INTERIOR, initial=start)
    assert fit.initial_method == "given" and fit.initial == start
    np.testing.assert_allclose(fit.exterior.as_array(), TRUTH.as_array(), atol=1e-6)


def test_a_degenerate_linear_start_is_skipped_and_angles_are_wrapped():
    # three of the four GCPs on one line: no projective start; κ = 200° comes back as -160°
    truth = ExteriorOrientation(5000.0, 8000.0, 3000.0, 3.0, -2.0, 200.0)
    ground = np.array([[4800, 7900, 0], [5000, 8000, 0], [5200, 8100, 0], [5100, 7800, 30.0]])
    fit = resect(ground, FrameCamera(INTERIOR, truth).project(ground), INTERIOR)
    assert fit.initial_method == "vertical"
    np.testing.assert_allclose(fit.exterior.as_array(), [5000, 8000, 3000, 3, -2, -160],
                               atol=1e-8)


def test_noisy_gcps_give_an_estimate_within_its_standard_deviations():
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, image = gcps(camera, 10, seed=6)
    noisy = image + np.random.default_rng(7).normal(0, NOISE_PX, image.shape)
    fit = resect(ground, noisy, INTERIOR)
    table = fit.table(TRUTH)
    assert list(table.index) == list(PARAMETERS)
    assert (table["error / std"].abs() < 4).all()
    assert 0.5 * NOISE_PX < fit.sigma0_px < 1.5 * NOISE_PX
    np.testing.assert_allclose(fit.rms_px, np.sqrt(np.mean(np.sum(fit.residuals**2, 1))))
    np.testing.assert_allclose(fit.residuals, camera.__class__(INTERIOR, fit.exterior)
                               .project(ground) - noisy, atol=1e-9)
    np.testing.assert_allclose(np.diag(fit.correlation), 1.0)


def test_the_covariance_matches_the_spread_of_estimates_over_seeds():
    # Monte Carlo: 300 noise draws on the same GCPs; the covariance predicted from one
    # noise-free adjustment (cofactor × σ²) must be the spread of the 300 estimates
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, image = gcps(camera, 8, seed=8)
    predicted = resect(ground, image, INTERIOR).cofactor * NOISE_PX**2
    estimates, sigma0_squared = [], []
    for seed in range(300):
        noise = np.random.default_rng(seed).normal(0, NOISE_PX, image.shape)
        fit = resect(ground, image + noise, INTERIOR)
        estimates.append(fit.exterior.as_array())
        sigma0_squared.append(fit.sigma0_px**2)
    estimates = np.array(estimates)
    error = estimates - TRUTH.as_array()
    ratio = estimates.std(axis=0, ddof=1) / np.sqrt(np.diag(predicted))
    assert (np.abs(ratio - 1) < 0.15).all(), ratio              # sample std: ±4 % (1 SE)
    standard_error = np.sqrt(np.diag(predicted) / len(estimates))
    assert (np.abs(error.mean(axis=0)) < 4 * standard_error).all()        # unbiased
    mahalanobis = np.einsum("ij,jk,ik->i", error, np.linalg.inv(predicted), error)
    assert 5.2 < mahalanobis.mean() < 6.8                       # χ² with 6 degrees of freedom
    assert abs(np.mean(sigma0_squared) / NOISE_PX**2 - 1) < 0.1   # E[σ0²] = σ²


# --- the projective model is the flat-terrain case ---------------------------------------------


def test_on_flat_ground_the_camera_is_a_homography_rsgeo_and_scikit_image_fit():
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000), (0.012, -0.008))
    camera = FrameCamera(interior, ExteriorOrientation(5000.0, 8000.0, 3000.0, 12.0, -8.0, 30))
    ground, image = gcps(camera, 12, seed=9, relief=(35.0, 35.0))
    checks, check_image = gcps(camera, 200, seed=10, relief=(35.0, 35.0))
    ours = transforms.fit_transform(ground[:, :2], image, "projective")
    theirs = ProjectiveTransform.from_estimate(ground[:, :2], image)
    exact = camera.homography(35.0)
    for model in (ours, theirs, exact):
        np.testing.assert_allclose(model(checks[:, :2]), check_image, atol=1e-8)
    np.testing.assert_allclose(ours.matrix, exact.matrix, rtol=1e-9, atol=1e-9 * np.abs(
        exact.matrix).max())


def test_relief_leaves_the_projective_model_the_relief_displacement_r_h_over_h():
    # a vertical photo, the projective model fitted on GCPs on the datum (Z = 0): points at
    # height h image d = r·h/H farther from the centre, r their (displaced) radial distance
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000))
    camera = FrameCamera(interior, ExteriorOrientation(5000.0, 8000.0, 3000.0, 0, 0, 25.0))
    ground, image = gcps(camera, 8, seed=11, relief=(0, 0))
    model = transforms.fit_transform(ground[:, :2], image, "projective")
    checks, check_image = gcps(camera, 200, seed=12, relief=(0, 500))
    residual_mm = (model(checks[:, :2]) - check_image) * [1, -1] * interior.pixel_mm
    photo = interior.to_photo(check_image)
    radius = np.hypot(*photo.T)
    expected = relief.relief_displacement_photo(checks[:, 2], radius, 3000.0)
    np.testing.assert_allclose(np.hypot(*residual_mm.T), expected, atol=1e-9)
    inward = -np.einsum("ij,ij->i", residual_mm, photo) / radius       # the model misses inwards
    np.testing.assert_allclose(inward, expected, atol=1e-9)


def test_with_relief_the_projective_check_error_grows_and_resection_does_not():
    camera = FrameCamera(INTERIOR, TRUTH)
    projective, resection = [], []
    for top in (0.0, 100.0, 300.0):
        ground, image = gcps(camera, 10, seed=13, relief=(0, top))
        checks, check_image = gcps(camera, 100, seed=14, relief=(0, top))
        model = transforms.fit_transform(ground[:, :2], image, "projective")
        projective.append(model.rms(checks[:, :2], check_image))
        fitted = resect(ground, image, INTERIOR).camera
        resection.append(np.sqrt(np.mean(np.sum((fitted.project(checks) - check_image)**2, 1))))
    assert projective[0] < 1e-6 and projective[0] < projective[1] < projective[2]
    assert projective[2] > 10 and max(resection) < 1e-6


def test_a_camera_with_distortion_is_no_homography():
    camera = FrameCamera(InteriorOrientation(100.0, 0.006, (8000, 6000), k1=-1e-6), TRUTH)
    with pytest.raises(errors.ModelError, match="remove the distortion"):
        camera.homography(0.0)


# --- errors ----------------------------------------------------------------------------------


def test_too_few_gcps():
    ground, image = gcps(FrameCamera(INTERIOR, TRUTH), 2)
    with pytest.raises(errors.GCPError, match="at least 3 GCPs.*got 2"):
        resect(ground, image, INTERIOR)


def test_mismatched_gcps():
    ground, image = gcps(FrameCamera(INTERIOR, TRUTH), 5)
    with pytest.raises(errors.GCPError, match="same GCPs, got 5 and 4"):
        resect(ground, image[:4], INTERIOR)


def test_collinear_gcps_are_refused():
    camera = FrameCamera(INTERIOR, TRUTH)
    line = np.column_stack([np.linspace(4800, 5200, 5), np.linspace(7900, 8100, 5), np.zeros(5)])
    with pytest.raises(errors.GCPError, match="ground points all lie on one line"):
        resect(line, camera.project(line), INTERIOR)
    ground, image = gcps(camera, 5)
    image[:, 1] = 2 * image[:, 0] + 3                       # measured along one image line
    with pytest.raises(errors.GCPError, match="image points all lie on one line"):
        resect(ground, image, INTERIOR)


def test_the_critical_cylinder_is_detected():
    # three GCPs on a circle, the projection centre on the vertical cylinder through them
    interior = InteriorOrientation(50.0, 0.01, (8000, 8000))
    angles = np.radians([10, 130, 250])
    ground = np.column_stack([300 * np.cos(angles), 300 * np.sin(angles), np.zeros(3)])
    on_cylinder = FrameCamera(interior, ExteriorOrientation(300.0, 0, 1000.0, 0, 0, 0))
    with pytest.raises(errors.GCPError, match="critical cylinder"):
        resect(ground, on_cylinder.project(ground), interior)
    inside = FrameCamera(interior, ExteriorOrientation(150.0, 0, 1000.0, 0, 0, 0))
    fit = resect(ground, inside.project(ground), interior)
    np.testing.assert_allclose(fit.exterior.as_array(), [150, 0, 1000, 0, 0, 0], atol=1e-6)


def test_no_convergence_is_an_error():
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, image = gcps(camera, 6)
    start = ExteriorOrientation(4000.0, 9000.0, 2000.0, 0, 0, 0)
    with pytest.raises(errors.ModelError, match="did not converge in 2 iterations"):
        resect(ground, image, INTERIOR, initial=start, max_iterations=2)


def test_a_start_below_the_ground_is_an_error():
    camera = FrameCamera(INTERIOR, TRUTH)
    ground, image = gcps(camera, 6)
    with pytest.raises(errors.ModelError, match="behind the camera"):
        resect(ground, image, INTERIOR, initial=ExteriorOrientation(5000, 8000, -500, 0, 0, 0))


def test_points_behind_the_camera_have_no_image():
    camera = FrameCamera(INTERIOR, TRUTH)
    with pytest.raises(errors.ModelError, match="behind the camera"):
        camera.project([[5000.0, 8000.0, 3500.0]])
    with pytest.raises(errors.ModelError, match="do not reach their height"):
        camera.ground_at_height([[4000.0, 3000.0]], 3500.0)


@pytest.mark.parametrize("call, error, match", [
    (lambda: resect(np.zeros((5, 2)), np.zeros((5, 2)), INTERIOR), errors.GCPError, r"\(n, 3\)"),
    (lambda: resect([[0, 0, np.nan]] * 4, np.zeros((4, 2)), INTERIOR), errors.GCPError, "NaN"),
    (lambda: resect(np.zeros((4, 3)), np.zeros((4, 2)), "camera"), TypeError, "Interior"),
    (lambda: InteriorOrientation(-100.0, 0.006, (10, 10)), ValueError, "focal_mm"),
    (lambda: InteriorOrientation(100.0, 0.006, (10,)), errors.GCPError, "cols, rows"),
    (lambda: InteriorOrientation(100.0, 0.006, (10.5, 10)), ValueError, "size"),
    (lambda: ExteriorOrientation(0, 0, "1000", 0, 0, 0), TypeError, "z0"),
    (lambda: FrameCamera(INTERIOR, (0, 0, 1000, 0, 0, 0)), TypeError, "Exterior"),
    (lambda: angles_from_rotation(np.ones((3, 3))), errors.GCPError, "rotation"),
])
def test_bad_inputs_are_refused_with_a_message(call, error, match):
    with pytest.raises(error, match=match):
        call()
