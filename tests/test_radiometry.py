"""rsgeo.radiometry: the regression paper on synthetic pairs with a known answer and on real scenes."""

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
    assert radiometry.fit_gain_offset(pair.x_image, pair.y_image, method="rma").gain == pytest.approx(pair.gain, rel=0.05)


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
    assert radiometry.apply_gain_offset(image.astype(np.int16), 1.0, -50.0).tolist() == [-50, -49, 50, 150, 200, 205]


def test_real_seam_step_falls_below_a_fifth():
    x, y, _ = radiometry.overlap(data.load("cbers_b2_B_contraste"), data.load("cbers_b2_A"))
    fit = radiometry.fit_gain_offset(x, y, smooth=3)
    before, split = radiometry.concatenate_halves(x, y)
    after, _ = radiometry.concatenate_halves(radiometry.apply_gain_offset(x, fit.gain, fit.offset), y)
    assert radiometry.seam_step(after, split) < radiometry.seam_step(before, split) / 5


def test_overlap_of_aligned_scenes_is_an_exact_cut():
    a, b = data.load("cbers_b2_A"), data.load("cbers_b2_C")
    a_part, b_part, window = radiometry.overlap(a, b)
    assert a_part.shape == (442, 145) and window == (19, 461, 423, 568)
    np.testing.assert_array_equal(a_part, b_part)        # C was cut from the same scene as A


@pytest.mark.parametrize("call, message", [
    (lambda: radiometry.fit_gain_offset(np.zeros((3, 3)), np.arange(9.0).reshape(3, 3)), "constant"),
    (lambda: radiometry.fit_gain_offset(np.zeros((3, 3)), np.zeros((4, 3))), "same shape"),
    (lambda: radiometry.fit_gain_offset(np.ones((3, 3)), np.ones((3, 3)), method="lasso"), "unknown method"),
    (lambda: radiometry.apply_gain_offset(np.zeros(3), 1, 0), "integer dtype"),
    (lambda: radiometry.mean_filter(np.zeros((5, 5)), 4), "odd positive"),
    (lambda: radiometry.overlap(data.load("cbers_b2_A"), data.load("nat1")), "different CRSs"),
])
def test_bad_input_is_a_clear_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_scenes_that_do_not_overlap():
    a = data.load("cbers_b2_A")
    far = data.Raster(a.array, a.transform @ affine.Affine.translation(5000, 0), a.crs, None, "", "far")
    with pytest.raises(ValueError, match="do not overlap"):
        radiometry.overlap(a, far)
