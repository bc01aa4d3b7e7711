"""rsgeo.radiometry: the regression paper on synthetic pairs (known answer) and on real scenes."""

import affine
import numpy as np
import pytest

from rsgeo import data, radiometry, synthetic


def test_filtered_fit_recovers_a_known_gain_and_offset_raw_ols_does_not():
    pair = synthetic.contrast_pair()
    raw = radiometry.fit_gain_offset(pair.x_image, pair.y_image)
    assert raw.r == pytest.approx(0.45, abs=0.05)                   # the paper's raw r
    assert raw.gain < 0.7 * pair.gain                               # measurably biased (dilution)
    # a window large enough for the noise, which varies pixel to pixel, to average out
    filtered = radiometry.fit_gain_offset(pair.x_image, pair.y_image, smooth=15)
    assert filtered.gain == pytest.approx(pair.gain, rel=0.05)
    assert filtered.offset == pytest.approx(pair.offset, rel=0.05)


def test_rma_is_unbiased_by_symmetric_noise():
    pair = synthetic.contrast_pair()
    assert radiometry.fit_gain_offset(pair.x_image, pair.y_image,
                                      method="rma").gain == pytest.approx(pair.gain, rel=0.05)


@pytest.mark.parametrize("size", [3, 5, 7])
def test_mean_filter_raises_r(size):
    pair = synthetic.contrast_pair()
    assert (radiometry.fit_gain_offset(pair.x_image, pair.y_image, smooth=size).r
            > radiometry.fit_gain_offset(pair.x_image, pair.y_image).r + 0.3)


def test_apply_truncates_like_the_paper_and_never_wraps():
    image = np.array([0, 1, 100, 200, 250, 255], dtype=np.uint8)
    out = radiometry.apply_gain_offset(image, 0.885, 27.107)
    np.testing.assert_array_equal(out, np.trunc(0.885 * image + 27.107).astype(np.uint8))
    assert radiometry.apply_gain_offset(image, 2.0, 10.0).tolist() == [10, 12, 210, 255, 255, 255]
    assert radiometry.apply_gain_offset(image, 1.0, -50.0).tolist() == [0, 0, 50, 150, 200, 205]
    signed = radiometry.apply_gain_offset(image.astype(np.int16), 1.0, -50.0)
    assert signed.tolist() == [-50, -49, 50, 150, 200, 205]


def test_real_seam_step_falls_below_a_fifth():
    x, y, _ = radiometry.overlap(data.load("cbers_b2_B_contraste"), data.load("cbers_b2_A"))
    fit = radiometry.fit_gain_offset(x, y, smooth=3)
    before, split = radiometry.concatenate_halves(x, y)
    after, _ = radiometry.concatenate_halves(radiometry.apply_gain_offset(x, fit.gain, fit.offset),
                                             y)
    assert radiometry.seam_step(after, split) < radiometry.seam_step(before, split) / 5


def test_overlap_of_aligned_scenes_is_an_exact_cut():
    a, b = data.load("cbers_b2_A"), data.load("cbers_b2_C")
    a_part, b_part, window = radiometry.overlap(a, b)
    assert a_part.shape == (442, 145) and window == (19, 461, 423, 568)
    np.testing.assert_array_equal(a_part, b_part)        # C was cut from the same scene as A


@pytest.mark.parametrize("call, message", [
    (lambda: radiometry.fit_gain_offset(np.zeros((3, 3)), np.arange(9.0).reshape(3, 3)),
     "constant"),
    (lambda: radiometry.fit_gain_offset(np.zeros((3, 3)), np.zeros((4, 3))), "same shape"),
    (lambda: radiometry.fit_gain_offset(np.ones((3, 3)), np.ones((3, 3)), method="lasso"),
     "unknown method"),
    (lambda: radiometry.apply_gain_offset(np.zeros(3), 1, 0), "integer dtype"),
    (lambda: radiometry.mean_filter(np.zeros((5, 5)), 4), "odd positive"),
    (lambda: radiometry.apply_gain_offset(np.zeros(3, np.uint8), 1, 0, rounding="up"),
     "unknown rounding"),
    (lambda: radiometry.seam_metrics(np.arange(9.0), np.ones(9)), "reference is constant"),
    (lambda: radiometry.overlap(data.load("cbers_b2_A"), data.load("nat1")), "different CRSs"),
])
def test_bad_input_is_a_clear_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_scenes_that_do_not_overlap():
    a = data.load("cbers_b2_A")
    far = data.Raster(a.array, a.transform @ affine.Affine.translation(5000, 0), a.crs, None, "",
                      "far")
    with pytest.raises(ValueError, match="do not overlap"):
        radiometry.overlap(a, far)


@pytest.mark.parametrize("smooth", [None, 3])
@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_nan_is_a_clear_error_not_a_nan_gain(smooth, bad):
    pair = synthetic.contrast_pair()
    x = pair.x_image.astype(np.float64)
    x[10, 20] = bad
    with pytest.raises(ValueError, match=r"x_image holds 1 NaN or infinite.*np\.isfinite"):
        radiometry.fit_gain_offset(x, pair.y_image, smooth=smooth)
    y = pair.y_image.astype(np.float64)
    y[0, 0] = bad
    with pytest.raises(ValueError, match="y_image holds 1 NaN"):
        radiometry.fit_gain_offset(pair.x_image, y, smooth=smooth)
    # the way out the message gives: fit the finite pairs only
    keep = np.isfinite(x)
    masked = radiometry.fit_gain_offset(x[keep], pair.y_image[keep])
    whole = radiometry.fit_gain_offset(pair.x_image, pair.y_image)
    assert masked.gain == pytest.approx(whole.gain, abs=0.005)


def test_seam_metrics_signs_and_ratio_on_a_known_stretch():
    reference = np.arange(100.0).reshape(10, 10)
    metrics = radiometry.seam_metrics(0.5 * reference + 10, reference)
    assert metrics["mean_difference"] == pytest.approx(0.5 * 49.5 + 10 - 49.5)
    assert metrics["std_difference"] == pytest.approx(-0.5 * reference.std())  # less contrast
    assert metrics["std_ratio"] == pytest.approx(0.5)
    assert radiometry.seam_metrics(reference, reference) == {
        "mean_difference": 0.0, "std_difference": 0.0, "std_ratio": 1.0, "histogram_distance": 0.0}


def test_paper_ols_matches_the_mean_but_flips_the_contrast_rma_does_not():
    """Chapter 5's claim, on several noise draws: seam_metrics over the whole overlap."""
    for seed in range(3):
        pair = synthetic.contrast_pair(seed=seed)
        x, y = pair.x_image, pair.y_image
        before = radiometry.seam_metrics(x, y)
        ols = radiometry.fit_gain_offset(x, y, smooth=3)
        rma = radiometry.fit_gain_offset(x, y, method="rma")
        after_ols = radiometry.seam_metrics(radiometry.apply_gain_offset(x, ols.gain, ols.offset),
                                            y)
        after_rma = radiometry.seam_metrics(radiometry.apply_gain_offset(x, rma.gain, rma.offset),
                                            y)
        assert before["mean_difference"] < -10 and before["std_difference"] > 4
        assert abs(after_ols["mean_difference"]) < 1                  # the mean is matched ...
        assert after_ols["std_difference"] < -4                      # ... the contrast overshoots
        assert ols.gain < 0.93 * pair.gain                            # because the gain is diluted
        assert rma.gain == pytest.approx(pair.gain, rel=0.05)
        assert abs(after_rma["std_difference"]) < 1


def test_truncation_lowers_the_mean_by_half_a_dn_rounding_does_not():
    pair = synthetic.contrast_pair()
    fit = radiometry.fit_gain_offset(pair.x_image, pair.y_image, smooth=3)
    exact = fit.predict(pair.x_image).mean()          # in range: no clipping involved
    truncated = radiometry.apply_gain_offset(pair.x_image, fit.gain, fit.offset)
    rounded = radiometry.apply_gain_offset(pair.x_image, fit.gain, fit.offset, rounding="nearest")
    assert truncated.mean() - exact == pytest.approx(-0.5, abs=0.05)
    assert rounded.mean() - exact == pytest.approx(0.0, abs=0.05)
    values = np.array([0, 1, 2, 3], dtype=np.uint8)
    up = radiometry.apply_gain_offset(values, 1.0, 0.5, rounding="nearest")
    down = radiometry.apply_gain_offset(values, 1.0, 0.49, rounding="nearest")
    assert up.tolist() == [1, 2, 3, 4] and down.tolist() == [0, 1, 2, 3]


def test_stretch_frame_titles_state_the_seam_metrics():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rsgeo.plot import draw_stretch_frame

    from figure_audit import figure_problems

    pair = synthetic.contrast_pair()
    fit = radiometry.fit_gain_offset(pair.x_image, pair.y_image, smooth=3)
    fig, axes = plt.subplots(1, 3)
    try:
        for t in (0.0, 1.0):
            shown = draw_stretch_frame(axes, pair.x_image, pair.y_image, fit.gain, fit.offset, t)
            gain_t, offset_t = 1 + t * (fit.gain - 1), t * fit.offset
            stretched = radiometry.apply_gain_offset(pair.x_image, gain_t, offset_t)
            expected = radiometry.seam_metrics(stretched, pair.y_image)
            assert shown == expected
            title = axes[0].get_title()
            assert f"mean Δ {expected['mean_difference']:+.1f} DN" in title
            assert f"spread Δ {expected['std_difference']:+.1f} DN" in title
            assert figure_problems(fig) == []
    finally:
        plt.close(fig)


def test_regression_widget_reaches_the_chosen_fit():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rsgeo.widgets import regression_stretch

    from figure_audit import figure_problems

    pair = synthetic.contrast_pair()
    plt.close("all")
    box = regression_stretch(pair.x_image, pair.y_image)
    play_row, menu_row, _ = box.children
    step, (size, method) = play_row.children[1], menu_row.children
    try:
        for chosen_size, chosen_method in ((3, "ols"), (7, "ols"), (1, "rma")):
            size.value, method.value = chosen_size, chosen_method
            step.value = 10
            fit = radiometry.fit_gain_offset(pair.x_image, pair.y_image, method=chosen_method,
                                             smooth=chosen_size if chosen_size > 1 else None)
            figure = plt.gcf()
            assert figure.axes[2].get_title().startswith(f"Y = {fit.gain:.3f} X + "
                                                         f"{fit.offset:.2f}")
            assert figure_problems(figure) == []
    finally:
        plt.close("all")
    with pytest.raises(ValueError, match="offered sizes"):
        regression_stretch(pair.x_image, pair.y_image, size=4)


def test_match_histograms_works_on_floats_and_refuses_nan():
    # it used to fail inside np.iinfo on a float image
    rng = np.random.default_rng(0)
    reference = rng.normal(100.0, 20.0, (50, 50))
    image = rng.normal(0.0, 1.0, (40, 40)).astype(np.float32)
    matched = radiometry.match_histograms(image, reference)
    assert matched.dtype == np.float32 and matched.shape == image.shape
    assert matched.mean() == pytest.approx(reference.mean(), abs=2.0)
    assert matched.std() == pytest.approx(reference.std(), rel=0.1)
    assert np.array_equal(np.argsort(matched.ravel(), kind="stable"),
                          np.argsort(image.ravel(), kind="stable"))
    integers = radiometry.match_histograms(rng.integers(0, 50, (40, 40)).astype(np.uint8),
                                           reference)
    assert integers.dtype == np.uint8 and integers.mean() == pytest.approx(reference.mean(),
                                                                           abs=3.0)
    with pytest.raises(ValueError, match="image holds NaN"):
        radiometry.match_histograms(np.where(image > 1, np.nan, image), reference)
    with pytest.raises(ValueError, match="integers or floats"):
        radiometry.match_histograms(image, np.array([["a"]]))


def test_fit_gain_offset_refuses_complex_images():
    # complex input was silently made real
    x = np.arange(100.0).reshape(10, 10)
    with pytest.raises(TypeError, match="x_image must hold real numbers.*complex128"):
        radiometry.fit_gain_offset(x + 1j, x)
    with pytest.raises(TypeError, match="y_image must hold real numbers"):
        radiometry.fit_gain_offset(x, (x + 1j).astype(np.complex64))


def test_fit_gain_offset_refuses_a_mask():
    # found by tests/test_fuzz.py: a bool array (a mask) was regressed as 0 and 1, where every
    # other image check of rsgeo refuses bool
    x = np.arange(100.0).reshape(10, 10)
    with pytest.raises(TypeError, match="x_image must hold real numbers.*bool.*is a mask"):
        radiometry.fit_gain_offset(x > 50, x)
    with pytest.raises(TypeError, match="y_image must hold real numbers.*bool"):
        radiometry.fit_gain_offset(x, x > 50)


def test_fit_gain_offset_refuses_what_cannot_be_regressed():
    # a constant image, no covariance or an overflowing spread gave gain NaN
    x = np.arange(100.0).reshape(10, 10)
    with pytest.raises(ValueError, match="x_image is constant.*cannot be regressed"):
        radiometry.fit_gain_offset(np.full((10, 10), 7, np.uint8), x)
    symmetric = np.tile(np.array([-1.0, 0.0, 1.0]), (3, 1))
    for method in ("ols", "orthogonal", "rma"):
        with pytest.raises(ValueError, match="do not vary together"):
            radiometry.fit_gain_offset(symmetric, symmetric.T * 0 + symmetric ** 2, method=method)
    with pytest.raises(ValueError, match="too large to regress"):
        radiometry.fit_gain_offset(x * 1e300, x)


def test_fit_gain_offset_on_64_bit_integers_matches_numpy_in_float64():
    x = (np.arange(10000, dtype=np.uint64).reshape(100, 100) * 1000 + 2**40)
    y = (x.astype(np.int64) * 3 - 5)
    fit = radiometry.fit_gain_offset(x, y)
    # the exact line, and NumPy's float64 fit agrees on the gain (its offset loses ~0.3 DN)
    np.testing.assert_allclose([fit.gain, fit.offset], [3.0, -5.0], rtol=1e-12, atol=1e-3)
    gain = np.polyfit(x.ravel().astype(np.float64), y.ravel().astype(np.float64), 1)[0]
    np.testing.assert_allclose(fit.gain, gain, rtol=1e-12)
    assert np.isfinite([fit.gain, fit.offset, fit.r]).all()


def test_fit_gain_offset_refuses_smooth_on_a_band_stack():
    # smooth filtered across bands; a band stack is fitted band by band
    stack = np.stack([np.arange(100.0).reshape(10, 10)] * 2)
    with pytest.raises(ValueError, match="smooth filters one band.*\\(2, 10, 10\\)"):
        radiometry.fit_gain_offset(stack, 2 * stack, smooth=3)
    fit = radiometry.fit_gain_offset(stack, 2 * stack)           # without smooth: all pixels
    assert round(fit.gain, 9) == 2.0


# -- 64-bit images -------------------------------------------------

@pytest.mark.parametrize("dtype", ["int64", "uint64"])
def test_apply_gain_offset_clips_64_bit_results_to_the_dtype_exactly(dtype):
    # 2**53 * 4096 is beyond both maxima: it clipped in float64 to 2**63 (2**64), whose cast
    # wrapped around to -2**63 (0)
    info = np.iinfo(dtype)
    image = np.array([2**53, 3, 0], dtype)
    np.testing.assert_array_equal(radiometry.apply_gain_offset(image, 4096.0, 0.0),
                                  np.array([info.max, 12288, 0], dtype))
    low = radiometry.apply_gain_offset(image, -4096.0, 0.0)
    assert low[0] == info.min and low.dtype == np.dtype(dtype)


@pytest.mark.parametrize("value, dtype", [(2**62, "int64"), (2**53 + 1, "int64"),
                                          (2**64 - 1, "uint64"), (-(2**53) - 1, "int64")])
def test_apply_gain_offset_refuses_64_bit_values_float64_cannot_hold(value, dtype):
    # 2**62 * 4 gave -2**63 and uint64's maximum gave 0; 2**53 + 1 lost its last bit
    with pytest.raises(ValueError, match=r"beyond \+-2\*\*53"):
        radiometry.apply_gain_offset(np.array([value, 1], dtype), 4.0, 0.0)


@pytest.mark.parametrize("smooth, error, message", [
    (True, TypeError, "smooth must be a number"),
    (2.5, ValueError, "smooth must be a whole number"),
    (np.nan, ValueError, "smooth must be a finite number"),
    (4, ValueError, "odd positive integer"),
])
def test_fit_gain_offset_smooth_is_an_odd_whole_number(smooth, error, message):
    x = np.arange(100.0).reshape(10, 10)
    with pytest.raises(error, match=message):
        radiometry.fit_gain_offset(x, 2 * x, smooth=smooth)
