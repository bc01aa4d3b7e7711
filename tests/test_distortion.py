"""rsgeo.distortion: the lecture's claims, checked against published figures."""

import numpy as np
import pytest

from rsgeo import data, distortion, gcp


def test_modis_edge_pixel_and_swath():
    # MODIS ATBD (Wolfe et al., 2002): 1 km at nadir grows to ~2.0 km along track and
    # ~4.8 km across track at the edge of the ±55°, 2330 km swath from 705 km.
    along, across = distortion.pixel_size(55.0, 705.0)
    assert float(along) == pytest.approx(2.0, abs=0.05)
    assert float(across) == pytest.approx(4.8, abs=0.1)
    assert distortion.swath_width(55.0, 705.0) == pytest.approx(2330, abs=10)


def test_flat_earth_underestimates_the_edge_pixel():
    flat_along, flat_across = distortion.pixel_size(55.0, 705.0, curved_earth=False)
    assert float(flat_along) == pytest.approx(1 / np.cos(np.radians(55)))
    assert float(flat_across) == pytest.approx(1 / np.cos(np.radians(55)) ** 2)


@pytest.mark.parametrize("altitude", [705.0, 778.0, 832.0])   # Landsat, CBERS, SPOT
def test_narrow_field_of_view_is_irrelevant(altitude):
    # Lecture, slide "Distorção - campo de visada": ±7.5° (SPOT, Landsat, CBERS) is irrelevant.
    # Along track the pixel grows by ~1 %, across track by ~2 % at the very edge (2.04 % on a sphere).
    along, across = distortion.pixel_size(7.5, altitude)
    assert float(along) - 1 < 0.02
    assert float(across) - 1 < 0.021


def test_landsat_skew_at_the_equator():
    # Richards & Jia (2006), ch. 2: Landsat 7's 185 km frame is skewed by about 12.6 km at the equator.
    assert distortion.earth_rotation_skew(0.0, 185.0, 705.0, 98.2) == pytest.approx(12.6, rel=0.03)


def test_skew_falls_with_latitude_and_vanishes_at_the_orbit_limit():
    skews = [distortion.earth_rotation_skew(lat) for lat in (0, 30, 60, 80)]
    assert skews == sorted(skews, reverse=True)
    assert distortion.earth_rotation_skew(81.79) < 0.5


@pytest.mark.parametrize("call, message", [
    (lambda: distortion.earth_rotation_skew(95.0), "latitude_deg must be"),
    (lambda: distortion.earth_rotation_skew(-91.0), "latitude_deg must be"),
    (lambda: distortion.earth_rotation_skew(85.0), "never passes over latitude"),
    (lambda: distortion.pixel_size(10.0, -5.0), "altitude_km must be"),
    (lambda: distortion.pixel_size(70.0, 705.0), "beyond the horizon"),
    (lambda: distortion.swath_width(np.nan, 705.0), "finite"),
    (lambda: distortion.SystematicDistortion(scale=0), "scale must be"),
])
def test_non_physical_input_is_a_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_simulate_then_correct_a_real_scene():
    truth = data.load("cbers2b_hrc").array[::4, ::4][:600, :600]
    model = distortion.SystematicDistortion(skew_per_line=0.08, scale=1.03, roll_px=6, pitch_px=-4,
                                            yaw_deg=2.0, yaw_rate_deg_per_line=0.004)
    recorded = distortion.simulate(truth, model, method="cubic")
    corrected = distortion.correct(recorded, model, method="cubic")
    inner = slice(100, 500)
    _, before = gcp.measure_shifts(truth[inner, inner], recorded[inner, inner], step=50, window=64)
    points, after = gcp.measure_shifts(truth[inner, inner], corrected[inner, inner], step=50, window=64)
    assert len(points) >= 40
    assert np.hypot(*before.T).mean() > 5                 # the distortion is real
    assert np.hypot(*after.T).max() < 0.5                 # and the correction removes it


def test_panoramic_model_inverts_exactly():
    model = distortion.SystematicDistortion(view_altitude_km=705.0, nadir_pixel_km=1.0, yaw_rate_deg_per_line=0.01)
    rng = np.random.default_rng(0)
    cols, rows = rng.uniform(0, 1000, 500), rng.uniform(0, 800, 500)
    back = model.image_to_true(*model.true_to_image(cols, rows, (800, 1000)), (800, 1000))
    np.testing.assert_allclose(back, (cols, rows), atol=1e-8)
