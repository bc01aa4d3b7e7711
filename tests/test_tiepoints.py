"""rsgeo.registration: automatic tie points by correlation and by features."""

import affine
import numpy as np
import pytest

from rsgeo import accuracy, data, gcp, registration, resample, synthetic
from rsgeo.registration import _bands
from rsgeo.registration import _tiepoints as tiepoints


@pytest.fixture(scope="module")
def land():
    return synthetic.two_date_landscape()


def perturbed(transform, shift, degrees, centre):
    """``transform`` moved by ``shift`` (map units) and turned by ``degrees`` about ``centre``."""
    return (affine.Affine.translation(*shift) @ affine.Affine.translation(*centre)
            @ affine.Affine.rotation(degrees) @ affine.Affine.translation(-centre[0], -centre[1])
            @ transform)


@pytest.fixture(scope="module")
def ccd_hrc():
    ccd, hrc = data.load("cbers2b_rgb342"), data.load("cbers2b_hrc")
    rows, cols = (n // 8 * 8 for n in hrc.shape)
    blocks = hrc.array[:rows, :cols].astype(float).reshape(rows // 8, 8, cols // 8, 8).mean(
        axis=(1, 3))
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    hand, kept = accuracy.refine_gcps(gcps.map_xy, gcps.image_xy, 1, 2.5)
    loo = accuracy.leave_one_out_errors(gcps.map_xy[kept], gcps.image_xy[kept], 1)
    loo_rms = float(np.sqrt(np.mean(loo**2)))
    return ccd, blocks, hrc.transform @ affine.Affine.scale(8), hand, loo_rms


def test_robust_fit_drops_a_blunder_with_any_rsgeo_model():
    rng = np.random.default_rng(0)
    src = rng.uniform(0, 100, (30, 2))
    dst = src * [1.5, -1.5] + [3, 400] + rng.normal(0, 0.05, src.shape)
    dst[[4, 17]] += [25, -40]
    for kind, order in (("polynomial", 1), ("helmert", None), ("projective", None)):
        model, inliers = registration.robust_fit(src, dst, kind, order, threshold=0.5)
        assert inliers.sum() == 28 and not inliers[[4, 17]].any()
        assert model.rms(src[inliers], dst[inliers]) < 0.1


def test_correlation_recovers_a_pure_translation_with_the_right_sign(land):
    image = land.reference.astype(float)
    shift = np.array([2.3, -1.7])                     # moving(c, r) = image(c - 2.3, r + 1.7)
    moving = resample.warp(image, affine.Affine.translation(*-shift), image.shape,
                           method="cubic", dst_nodata=0)
    valid = np.zeros(image.shape, bool)
    valid[20:-20, 20:-20] = True
    medians = {}
    for passes in (1, 6):
        gcps = registration.correlation_tiepoints(image, moving, 48, 64, iterations=passes,
                                               valid=valid)
        offsets = gcps.image_xy[gcps.enabled] - gcps.map_xy[gcps.enabled]
        medians[passes] = np.median(offsets, axis=0)
        assert gcps.enabled.sum() >= 30
    # one pass is pulled towards whole pixels ("pixel locking"); passes on the resampled
    # image measure ever smaller shifts, where that pull is ever smaller
    assert np.abs(medians[1] - shift).max() > 0.1
    np.testing.assert_allclose(medians[6], shift, atol=0.05)


def test_correlation_iterations_remove_the_single_pass_bias(land):
    truth = ~land.adjustment_transform
    centre = land.adjustment_transform @ (106.5, 106.5)
    initial = ~perturbed(land.adjustment_transform, (60, -45), 1.0, centre)
    errors = {}
    for passes in (1, 4):
        gcps = registration.correlation_tiepoints(land.reference, land.adjustment, 32, 64,
                                               land.reference_transform, initial=initial,
                                               iterations=passes)
        model = registration.register(gcps).model
        errors[passes] = registration.grid_error(model, truth, land.adjustment_transform,
                                              land.adjustment.shape)
    # with the landscape centred (no 5 m offset in the reference): 0.15 px after 4 passes,
    # 0.18 px after one, which keeps fewer windows under the 1 degree rotation
    assert errors[4] < min(0.2, errors[1])
    assert set(gcps.notes) <= {"reliable", "invalid", "outlier", "weak peak", "low contrast"}
    assert gcps.reliability["reliability"][gcps.enabled].min() >= 8.0


def test_features_and_correlation_reproduce_the_hand_made_gcps_on_the_real_pair(ccd_hrc):
    ccd, blocks, transform, hand, loo = ccd_hrc
    green = ccd.array[2].astype(float)
    by_features = registration.feature_tiepoints(blocks, green, "sift", transform)
    by_correlation = registration.correlation_tiepoints(blocks, ccd.array[0], 32, 64, transform,
                                                     initial=~ccd.transform)
    for gcps in (by_features, by_correlation):
        model = registration.register(gcps).model
        assert registration.grid_error(model, hand, transform, blocks.shape) < loo
    assert len(by_features) >= 50 and by_features.n_matches >= len(by_features)


def test_feature_tiepoints_map_coordinates_follow_the_reference_transform(land):
    # the same image twice, with a known transform: every inlier obeys it to a fraction of a pixel
    reference = land.reference.astype(float)
    gcps = registration.feature_tiepoints(reference, reference, "orb", land.reference_transform,
                                       threshold=0.5)
    expected = np.column_stack((~land.reference_transform) @ tuple(gcps.map_xy.T))
    np.testing.assert_allclose(gcps.image_xy, expected, atol=0.5)
    assert len(gcps) > 50


def test_register_refines_other_kinds_like_gdal():
    map_xy = np.array([[0, 0], [100, 0], [0, 100], [100, 100], [50, 50], [20, 70]], float)
    image_xy = map_xy[:, ::-1] / 10 + 5
    image_xy[4] += [2, 2]
    result = registration.register(gcp.GCPSet(map_xy, image_xy), "projective", tolerance=0.5)
    assert result.kept.tolist() == [True, True, True, True, False, True]
    assert result.rms_kept < 1e-9 < result.rms_all
    # disabled GCPs are left out of the fit
    disabled = gcp.GCPSet(map_xy, image_xy, enabled=[True, True, True, True, False, True])
    assert registration.register(disabled, tolerance=0.5).rms_all < 1e-9


def test_register_by_regions_runs_the_shared_pipeline(land):
    reference = registration.forest_segments(land.reference, threshold=185)
    adjustment = registration.forest_segments(land.adjustment, threshold=185)
    paper = registration.register_by_regions(reference, adjustment, land.reference_transform, 20,
                                             30,
                                         seed=1)
    shared = registration.register(gcp.GCPSet(paper.map_xy, paper.image_xy), tolerance=1.0,
                                min_gcps=4)
    np.testing.assert_array_equal(paper.kept, shared.kept)
    assert paper.rms_kept == shared.rms_kept and paper.rms_all == shared.rms_all


def test_measure_shifts_details_report_every_window():
    rng = np.random.default_rng(1)
    image = rng.normal(100, 20, (128, 128))
    image[:64, :64] = 50.0                                # a constant quarter
    valid = np.ones(image.shape, bool)
    valid[100:, 100:] = False
    points, shifts = registration.measure_shifts(image, image, step=64, window=64)
    all_points, all_shifts, table = registration.measure_shifts(image, image, step=64, window=64,
                                                       valid=valid, details=True)
    assert len(points) == 3 and len(all_points) == 4
    assert table["skipped"].tolist() == ["constant", "", "", "invalid"]
    assert np.isnan(all_shifts[[0, 3]]).all() and np.allclose(all_shifts[1:3], 0)
    assert (table["peak"][1:3] > 0.99).all()


@pytest.mark.parametrize("call, message", [
    (lambda land: registration.correlation_tiepoints(
        land.reference, land.adjustment, 32, 64, land.reference_transform,
        initial=~affine.Affine(30, 0, 90_000, 0, -30, 90_000)), "do not overlap"),
    (lambda land: registration.correlation_tiepoints(np.full((128, 128), 7.0),
                                                  np.full((128, 128), 7.0), 32, 64),
     "0 reliable tie points of 9 windows \\(9 constant\\)"),
    (lambda land: registration.correlation_tiepoints(land.reference, land.reference, 32, 64,
                                                  min_contrast=1e6), "low contrast"),
    (lambda land: registration.correlation_tiepoints(land.reference, land.reference[None], 32, 64),
     "2-D"),
    (lambda land: registration.feature_tiepoints(land.reference, np.zeros((50, 50))), "constant"),
    (lambda land: registration.feature_tiepoints(land.reference, land.adjustment, "surf"),
     "unknown detector"),
    (lambda land: registration.robust_fit([[0, 0], [1, 1]], [[0, 0], [1, 1]]), "at least 3"),
    (lambda land: registration.grid_error(affine.Affine.identity(), affine.Affine.identity(),
                                       affine.Affine.identity(), (5, 5), step=0), "step"),
])
def test_bad_input_says_what_was_found_and_what_is_needed(land, call, message):
    with pytest.raises(ValueError, match=message):
        call(land)


def test_register_refuses_what_is_not_a_gcp_set():
    with pytest.raises(TypeError, match="GCPSet"):
        registration.register("not gcps")


def test_register_and_register_by_regions_return_one_registration_type(land):
    reference = registration.forest_segments(land.reference, threshold=185)
    adjustment = registration.forest_segments(land.adjustment, threshold=185)
    by_regions = registration.register_by_regions(reference, adjustment, land.reference_transform,
                                              20, 30, seed=0)
    shared = registration.register(gcp.GCPSet(by_regions.map_xy, by_regions.image_xy),
                                tolerance=1.0, min_gcps=4)
    assert type(by_regions) is type(shared) is registration.Registration
    assert by_regions.match is not None and shared.match is None
    np.testing.assert_array_equal(shared.map_xy, by_regions.map_xy)


# -- the exercise checks of chapter 6c (rsgeo_course.exercises) ---------------------

def test_keypoint_check_recognises_the_convention_mistakes():
    from rsgeo_course import exercises

    assert exercises.check_keypoint_position((20.5, 10.5), (10, 20))
    for answer, hint in (((20, 10), "Half a pixel is missing"), ((10, 20), "swapped"),
                         ((10.5, 20.5), "swapped"), ((19.5, 9.5), "other way")):
        verdict = exercises.check_keypoint_position(answer, (10, 20))
        assert not verdict and hint in verdict.hint
    with pytest.raises(exercises.ExerciseNotSolved):
        exercises.check_keypoint_position(..., (10, 20))
    assert "two numbers" in exercises.check_keypoint_position("20.5, 10.5", (10, 20)).message


def test_composed_tiepoint_check_recognises_sign_order_and_missing_steps():
    from rsgeo_course import exercises

    to_map = affine.Affine(20, 0, 1000, 0, -20, 5000)
    estimate = ~(to_map @ affine.Affine.scale(1.5) @ affine.Affine.rotation(3))
    centre, shift = np.array([40.0, 30.0]), (1.5, -2.5)           # (drow, dcol)
    right = estimate @ (to_map @ tuple(centre - [-2.5, 1.5]))
    assert exercises.check_composed_tiepoint(right, centre, shift, estimate, to_map)
    wrong = {"not plus": estimate @ (to_map @ tuple(centre + [-2.5, 1.5])),
             "rows first": estimate @ (to_map @ tuple(centre - [1.5, -2.5])),
             "reference grid": tuple(centre - [-2.5, 1.5]),
             "map first": estimate @ tuple(centre - [-2.5, 1.5])}
    for hint, answer in wrong.items():
        verdict = exercises.check_composed_tiepoint(answer, centre, shift, estimate, to_map)
        assert not verdict and hint in verdict.hint, (hint, verdict)


def test_check_point_error_check_knows_the_mean_the_2n_and_metres(land):
    from rsgeo_course import exercises

    truth = ~land.adjustment_transform
    model = affine.Affine.translation(0.3, -0.2) @ affine.Affine.rotation(0.2) @ truth
    args = (model, truth, land.adjustment_transform, land.adjustment.shape)
    expected = registration.grid_error(*args)
    assert exercises.check_check_point_error(expected, *args, pixel_size=30)
    for answer, hint in ((expected / np.sqrt(2), "2n"), (30 * expected, "map units")):
        verdict = exercises.check_check_point_error(answer, *args, pixel_size=30)
        assert not verdict and hint in verdict.hint
        assert f"{expected:.3g}" not in verdict.message          # never the expected value


def test_blas_threads_are_restored_after_correlation():
    import ctypes

    paths = sorted({line.split()[-1] for line in open("/proc/self/maps") if "openblas" in line})
    if not paths:
        pytest.skip("NumPy is not linked to OpenBLAS here")
    library = ctypes.CDLL(paths[0])
    get = getattr(library, "scipy_openblas_get_num_threads64_", None)
    if get is None:
        pytest.skip("not scipy-openblas")
    before = get()
    with tiepoints.one_blas_thread():
        assert get() == 1
    assert get() == before


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
    points, offsets = registration.offsets_against_reference(coarse, declared, fine,
                                                             fine_transform,
                                                    step=40, window=64)
    assert len(points) >= 9
    np.testing.assert_allclose(np.median(offsets, axis=0), [0.5, -1.5], atol=0.1)
    declared = affine.Affine(20, 0, 770_000 - 5, 0, -20, 7_370_000 - 13)   # (-0.25, +0.65) px
    _, offsets = registration.offsets_against_reference(coarse, declared, fine, fine_transform,
                                               step=40, window=64)
    np.testing.assert_allclose(np.median(offsets, axis=0), [-0.25, 0.65], atol=0.15)
    _, none = registration.offsets_against_reference(coarse,
                                                     fine_transform @ fine_transform.scale(8),
                                            fine, fine_transform, step=40, window=64)
    np.testing.assert_allclose(np.median(none, axis=0), [0, 0], atol=0.1)
    with pytest.raises(ValueError, match="whole multiple"):
        registration.offsets_against_reference(
            coarse, affine.Affine(21, 0, 770_000, 0, -21, 7_370_000), fine, fine_transform)
    with pytest.raises(ValueError, match="north-up"):
        registration.offsets_against_reference(
            coarse, affine.Affine(20, 1, 770_000, 0, -20, 7_370_000), fine, fine_transform)


@pytest.mark.parametrize("call, message", [
    (lambda: registration.measure_shifts(np.ones((50, 50)), np.ones((50, 50)), window=64),
     "larger than"),
    (lambda: registration.measure_shifts(np.full((80, 80), np.nan), np.ones((80, 80))), "NaN"),
    (lambda: registration.measure_shifts(np.ones((80, 80)), np.ones((80, 80)), step=0), "step"),
])
def test_measure_shifts_refuses_what_it_cannot_measure(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def _smooth_scene(sigma, size=200, seed=0):
    from scipy.ndimage import gaussian_filter

    image = gaussian_filter(np.random.default_rng(seed).normal(0, 1, (size, size)), sigma)
    return 100 + 50 * image / image.std()


@pytest.mark.parametrize("sigma", [2, 4, 8])
def test_smooth_windows_are_rejected_not_called_reliable_while_pixels_off(sigma):
    # plain phase correlation on a smooth scene is pulled towards zero shift by the
    # windows' cut edges; 16 of 16 windows were "reliable" while up to 2.3 px off
    image, shift = _smooth_scene(sigma), np.array([2.3, -1.7])
    moving = resample.warp(image, affine.Affine.translation(*-shift), image.shape,
                           method="cubic", dst_nodata=0)
    valid = np.zeros(image.shape, bool)
    valid[10:-10, 10:-10] = True
    with pytest.raises(ValueError, match=r"\d+ smooth\).*use taper=True"):
        registration.correlation_tiepoints(image, moving, 40, 48, valid=valid)
    # without the filter the old silent answer: windows called reliable, pixels off
    gcps = registration.correlation_tiepoints(image, moving, 40, 48, valid=valid, max_edge_share=1)
    offsets = gcps.image_xy[gcps.enabled] - gcps.map_xy[gcps.enabled]
    assert np.abs(offsets - shift).max() > 1.0
    # the tapered correlation measures them
    gcps = registration.correlation_tiepoints(image, moving, 40, 48, valid=valid, taper=True)
    offsets = gcps.image_xy[gcps.enabled] - gcps.map_xy[gcps.enabled]
    assert gcps.enabled.sum() == 9 and np.abs(offsets - shift).max() < (0.3 if sigma == 8 else 0.1)


def test_edge_share_separates_textured_from_smooth_windows(ccd_hrc):
    rng = np.random.default_rng(0)
    assert registration.edge_share(rng.normal(size=(64, 64))) < 0.05
    assert registration.edge_share(_smooth_scene(8, 64)) > 0.9
    ccd, blocks, _, _, _ = ccd_hrc
    band = ccd.array[0][:64, :64].astype(float)
    assert registration.edge_share(band, band) < registration.MAX_EDGE_SHARE
    with pytest.raises(ValueError, match="window must be a finite 2-D array"):
        registration.edge_share(np.ones(5))
    with pytest.raises(ValueError, match="same shape"):
        registration.edge_share(np.ones((8, 8)), np.ones((8, 9)))


@pytest.mark.parametrize("kwargs, error, message", [
    ({"iterations": 2.5}, ValueError, "iterations must be a whole number, got 2.5"),
    ({"iterations": True}, TypeError, "iterations must be a number"),
    ({"min_contrast": np.nan}, ValueError, "min_contrast must be a finite number"),
    ({"min_contrast": "2"}, TypeError, "min_contrast must be a number"),
    ({"min_reliability": np.nan}, ValueError, "min_reliability must be a finite number"),
    # a negative threshold was accepted (it keeps every window, like 0, unsaid)
    ({"min_reliability": -1}, ValueError,
     r"min_reliability must be >= 0 \(a peak height in standard deviations; 0 keeps every "
     r"window\), got -1"),
    ({"min_reliability": True}, TypeError, "min_reliability must be a number, got bool"),
    # bool is an int subclass: True is not taken for 1
    ({"spacing": True}, TypeError, "spacing must be a number, got bool True"),
    ({"upsample": True}, TypeError, "upsample must be a number, got bool True"),
    ({"seed": True}, TypeError, "seed must be a number, got bool True"),
    ({"upsample": np.True_}, TypeError, "upsample must be a number, got bool"),
    ({"upsample": 2.5}, ValueError, "upsample must be a whole number, got 2.5"),
    ({"tolerance": -1}, ValueError, "tolerance must be"),
    ({"max_edge_share": 1.5}, ValueError, "max_edge_share must be"),
    ({"window": 1}, ValueError, "window must be >= 8"),
    ({"window": 7.5}, ValueError, "window must be a whole number"),
])
def test_correlation_tiepoints_checks_its_numbers(kwargs, error, message):
    image = _smooth_scene(0.5, 64)
    arguments = {"spacing": 16, "window": 16, **kwargs}
    with pytest.raises(error, match=message):
        registration.correlation_tiepoints(image, image, **arguments)


def test_measure_shifts_refuses_a_window_below_the_minimum():
    image = _smooth_scene(0.5, 64)
    with pytest.raises(ValueError, match=f"window must be >= {registration.MIN_WINDOW}"):
        registration.measure_shifts(image, image, step=4, window=1)


@pytest.mark.parametrize("kwargs, message", [
    ({"seed": 2.5}, "seed must be a whole number"),
    ({"spacing": np.nan}, "spacing must be a finite number"),
    ({"upsample": 0}, "upsample must be"),
])
def test_correlation_tiepoints_seed_spacing_and_upsample_are_whole_numbers(kwargs, message):
    image = _smooth_scene(0.5, 64)
    arguments = {"spacing": 16, "window": 16, **kwargs}
    with pytest.raises(ValueError, match=message):
        registration.correlation_tiepoints(image, image, **arguments)


# Band-to-band registration: bands of one scene with known sub-pixel shifts.
BAND_SHIFTS = [(0.0, 0.0), (0.3, -0.2), (-0.45, 0.15), (0.12, 0.37)]    # (dx, dy) px per band
BAND_GAINS = [1.0, -1.0, "partial", 1.4]           # kept, inverted, partly inverted, stretched
BAND_PAIRS = [(i, j) for i in range(4) for j in range(i + 1, 4)]


def _analytic_bands(offsets, gains, size=256, seed=0, noise=0.5, n_waves=300):
    """Bands of one continuous scene, each seen shifted by its (dx, dy): a feature at (x, y) is
    at (x + dx, y + dy) in the band. The scene is a sum of plane waves with a 1/f-like spectrum,
    each averaged exactly over a pixel's square (a sinc factor), so no interpolation makes the
    truth. A "partial" gain multiplies the scene by a smooth field of +1 and -1 regions, as a
    near-infrared band is inverted against a red one over vegetation and not over soil."""
    rng = np.random.default_rng(seed)
    wavelength = np.exp(rng.uniform(np.log(2.5), np.log(200), n_waves))     # px
    angle = rng.uniform(0, np.pi, n_waves)
    kx, ky = 2 * np.pi / wavelength * np.cos(angle), 2 * np.pi / wavelength * np.sin(angle)
    amplitude = wavelength**0.8 * 40 / np.sqrt(0.5 * np.sum(wavelength**1.6))
    amplitude *= np.sinc(kx / (2 * np.pi)) * np.sinc(ky / (2 * np.pi))   # pixel average
    phase = rng.uniform(0, 2 * np.pi, n_waves)
    sign_k = 2 * np.pi / rng.uniform(60, 150, (4, 2)) * rng.choice([-1, 1], (4, 2))
    sign_phase = rng.uniform(0, 2 * np.pi, 4)
    rows, cols = np.mgrid[0:size, 0:size] + 0.5
    bands = []
    for (dx, dy), gain in zip(offsets, gains):
        x, y = cols - dx, rows - dy
        scene = sum(a * np.sin(u * x + v * y + p) for a, u, v, p in zip(amplitude, kx, ky, phase))
        if gain == "partial":
            gain = np.tanh(3 * sum(np.sin(u * x + v * y + p)
                                   for (u, v), p in zip(sign_k, sign_phase)))
        bands.append(128 + gain * scene + rng.normal(0, noise, scene.shape))
    return np.array(bands)


@pytest.fixture(scope="module")
def shifted_bands():
    return _analytic_bands(BAND_SHIFTS, BAND_GAINS)


@pytest.fixture(scope="module")
def band_table(shifted_bands):
    names = ["kept", "inverted", "partly inverted", "stretched"]
    return registration.band_misregistration(shifted_bands, names=names)


def _band_errors(table, bands=(0, 1, 2, 3)):
    pairs = [(i, j) for i, j in BAND_PAIRS if i in bands and j in bands]
    truth = np.array([np.subtract(BAND_SHIFTS[j], BAND_SHIFTS[i]) for i, j in pairs])
    return np.abs(table[["dx (px)", "dy (px)"]].to_numpy() - truth).max(axis=1)


def test_band_misregistration_recovers_known_subpixel_shifts(band_table):
    names = ["kept", "inverted", "partly inverted", "stretched"]
    assert band_table.index.tolist() == [f"{names[i]} → {names[j]}" for i, j in BAND_PAIRS]
    # every pair, the inverted and the partly inverted band too, to 0.02 px of the truth
    assert _band_errors(band_table).max() < 0.02
    assert (band_table["tie points"] == band_table["windows"]).all()
    assert (band_table["windows"] == 16).all()
    se = band_table[["se dx (px)", "se dy (px)"]].to_numpy()
    assert (se < 0.01).all() and np.allclose(
        band_table["shift (px)"], np.hypot(band_table["dx (px)"], band_table["dy (px)"]))


def test_band_misregistration_needs_the_gradient_where_contrast_is_partly_inverted(
        shifted_bands, band_table):
    # brightness correlation: the partly inverted band's inverted and kept edges pull the
    # correlation peak apart, and it is tenths of a pixel off; the gradient magnitude does not
    # care which side of an edge is bright
    kept_and_partly = (0, 2)
    by_brightness = registration.band_misregistration(shifted_bands[list(kept_and_partly)],
                                                   feature="intensity")
    assert _band_errors(by_brightness, kept_and_partly).min() > 0.1
    assert _band_errors(band_table).max() < 0.02


def test_band_misregistration_moves_bands_exactly_not_by_cubic_convolution(shifted_bands,
                                                                           monkeypatch):
    # what the docstring says: the iterations' Fourier shift is what makes 0.02 px; moving the
    # band by GDAL's cubic convolution (correlation_tiepoints' resampling) leaves 0.03-0.04 px
    kept_and_inverted = (0, 1)
    bands = shifted_bands[list(kept_and_inverted)]
    exact = _band_errors(registration.band_misregistration(bands), kept_and_inverted).max()

    def cubic(image, dx, dy, pad):
        return resample.warp(image, affine.Affine.translation(-dx, -dy), image.shape,
                             method="cubic", dst_nodata=None)

    monkeypatch.setattr(_bands, "_fourier_shift", cubic)
    convolved = _band_errors(registration.band_misregistration(bands), kept_and_inverted).max()
    assert exact < 0.01 and convolved > 0.02


def test_band_misregistration_agrees_with_scikit_image_on_the_same_windows(shifted_bands):
    # cross-check: move the moving band back by the measured shift with SciPy's spline
    # interpolation (not rsgeo's Fourier shift) and let scikit-image's phase_cross_correlation
    # measure what is left in each window rsgeo used: nothing, to a hundredth of a pixel
    from scipy.ndimage import shift as spline_shift
    from scipy.ndimage import sobel
    from skimage.registration import phase_cross_correlation

    def gradient(band):
        return np.hypot(sobel(band, axis=0), sobel(band, axis=1))

    reference, moving = shifted_bands[0], shifted_bands[2]      # kept against partly inverted
    table, windows = registration.band_misregistration([reference, moving], details=True)
    dx, dy = table[["dx (px)", "dy (px)"]].to_numpy()[0]
    back = gradient(spline_shift(moving, (-dy, -dx), order=3, mode="mirror"))
    ref = gradient(reference)
    used = windows[windows["reason"] == "reliable"]
    left = []
    for col, row in used[["col", "row"]].to_numpy(dtype=int):
        box = np.s_[row - 32:row + 32, col - 32:col + 32]
        shift, _, _ = phase_cross_correlation(ref[box], back[box], upsample_factor=100)
        left.append(-shift[::-1])                      # (dcol, drow), moving minus reference
    assert len(left) == 16
    assert np.abs(np.mean(left, axis=0)).max() < 0.01
    # and the per-window shifts rsgeo reports are those windows' own, not the mean copied
    assert len(np.unique(used["dx (px)"].round(6))) > 1


@pytest.mark.parametrize("call, error, message", [
    (lambda b: registration.band_misregistration(b[0]), ValueError, "at least two bands"),
    (lambda b: registration.band_misregistration(b[:1]), ValueError, "at least two bands"),
    (lambda b: registration.band_misregistration(b, names=["a", "b"]), ValueError,
     "one name per band \\(4\\), got 2"),
    (lambda b: registration.band_misregistration(b, feature="phase"), ValueError,
     "unknown feature 'phase'"),
    (lambda b: registration.band_misregistration(b, window=300), ValueError, "window must be"),
    (lambda b: registration.band_misregistration(b, tolerance=0), ValueError, "more than 0"),
    (lambda b: registration.band_misregistration(b, valid=np.ones((10, 10), bool)), ValueError,
     "boolean mask of the bands' shape"),
    (lambda b: registration.band_misregistration(np.where(np.arange(256) < 5, np.nan, b)),
     ValueError, "NaN"),
    (lambda b: registration.band_misregistration(b, min_reliability="8"), TypeError,
     "must be a number"),
    (lambda b: registration.band_misregistration(b, valid=np.zeros((256, 256), bool)),
     ValueError, "0 usable windows of 16 \\(16 invalid\\)"),
])
def test_band_misregistration_says_what_was_wrong(shifted_bands, call, error, message):
    with pytest.raises(error, match=message):
        call(shifted_bands)
