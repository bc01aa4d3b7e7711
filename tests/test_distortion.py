"""rsgeo.distortion: the lecture's claims, checked against published figures."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsgeo import data, distortion, registration, sensors


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


@pytest.mark.parametrize("name, altitude, half_angle, across_limit", [
    ("SPOT HRV", 832.0, 2.06, 0.0017),        # 60 km swath: ±2.06° (pointable ±27°)
    ("CBERS CCD", 778.0, 4.2, 0.007),        # 113 km swath: ±4.2°
    ("Landsat", 705.0, 7.5, 0.021),           # 185 km swath: ±7.5°
])
def test_narrow_field_of_view_is_irrelevant(name, altitude, half_angle, across_limit):
    # Lecture, slide "Distorção - campo de visada": the narrow sensors' growth is irrelevant,
    # each at its own half-angle: at most 2 % across track (Landsat, 2.04 % on a sphere).
    along, across = distortion.pixel_size(half_angle, altitude)
    assert 0 < float(along) - 1 < across_limit / 2
    assert 0 < float(across) - 1 < across_limit
    assert float(across) - 1 > across_limit / 2     # and not much less: the limits are tight


def test_spot_pointed_off_nadir_sees_large_pixels():
    # SPOT's mirror points up to 27° off nadir: there the growth is no longer irrelevant.
    _, across = distortion.pixel_size(27.0 + 2.06, 832.0)
    assert float(across) > 1.3


def test_landsat_skew_at_the_equator():
    # Richards & Jia (2006), ch. 2: Landsat 7's 185 km frame is skewed by about 12.6 km at the
    # equator.
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
    (lambda: sensors.SystematicDistortion(scale=0), "scale must be"),
    (lambda: distortion.earth_rotation_skew(0.0, pass_direction="north"),
     "pass_direction must be"),
    (lambda: distortion.attitude_displacement(0.1, 705.0, axis="yaw"), "axis must be"),
    (lambda: distortion.attitude_displacement(1.0, 705.0, scan_angle_deg=63.5),
     "beyond the horizon"),
    (lambda: distortion.scan_footprint(10.0, 705.0, detectors=0), "detectors must be"),
    (lambda: sensors.SystematicDistortion(roll_deg=0.1), "need view_altitude_km"),
    (lambda: sensors.SystematicDistortion().with_knowledge_errors(roll_deg=0.01),
     "need view_altitude"),
])
def test_non_physical_input_is_a_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_simulate_then_correct_a_real_scene():
    truth = data.load("cbers2b_hrc").array[::4, ::4][:600, :600]
    model = sensors.SystematicDistortion(skew_per_line=0.08, scale=1.03, roll_px=6, pitch_px=-4,
                                            yaw_deg=2.0, yaw_rate_deg_per_line=0.004)
    recorded = sensors.simulate(truth, model, method="cubic")
    corrected = sensors.correct(recorded, model, method="cubic")
    inner = slice(100, 500)
    _, before = registration.measure_shifts(truth[inner, inner], recorded[inner, inner], step=50,
                                         window=64)
    points, after = registration.measure_shifts(truth[inner, inner], corrected[inner, inner],
                                                step=50,
                                             window=64)
    assert len(points) >= 40
    assert np.hypot(*before.T).mean() > 5                 # the distortion is real
    assert np.hypot(*after.T).max() < 0.5                 # and the correction removes it


def test_panoramic_model_inverts_exactly():
    model = sensors.SystematicDistortion(view_altitude_km=705.0, nadir_pixel_km=1.0,
                                            yaw_rate_deg_per_line=0.01,
                                            shape=(800, 1000))
    rng = np.random.default_rng(0)
    points = np.column_stack([rng.uniform(0, 1000, 500), rng.uniform(0, 800, 500)])
    np.testing.assert_allclose(model.inverse()(model(points)), points, atol=1e-8)
    assert model.inverse().residuals(model(points), points).max() < 1e-8
    assert model.inverse().inverse() is model


def test_roll_shifts_the_scan_angle_so_the_ground_moves_more_at_the_edge():
    # A roll turns the platform about the scan mirror's axis: scan angle θ becomes θ + roll.
    # 0.1° from 705 km: 1.23 km at nadir, ≈ 6.0 km at 55° on a sphere, 3.75 km on a flat Earth.
    nadir, edge = distortion.attitude_displacement(0.1, 705.0, scan_angle_deg=[0.0, 55.0])
    assert nadir == pytest.approx(705 * np.tan(np.radians(0.1)), rel=1e-4)
    assert edge == pytest.approx(6.0, abs=0.05)
    flat_edge = distortion.attitude_displacement(0.1, 705.0, curved_earth=False,
                                                 scan_angle_deg=55.0)
    assert flat_edge == pytest.approx(705 * (np.tan(np.radians(55.1)) - np.tan(np.radians(55))),
                                      rel=1e-9)
    assert float(flat_edge) == pytest.approx(3.75, abs=0.01)


def test_pitch_is_uniform_on_a_flat_earth_and_grows_little_on_a_sphere():
    angles = np.array([0.0, 30.0, 55.0])
    flat = distortion.attitude_displacement(0.1, 705.0, False, angles, axis="pitch")
    np.testing.assert_allclose(flat, 705 * np.tan(np.radians(0.1)), rtol=1e-5)
    curved = distortion.attitude_displacement(0.1, 705.0, True, angles, axis="pitch")
    assert curved[0] == pytest.approx(flat[0], rel=1e-4)
    assert flat[0] < curved[1] < curved[2] < 1.25 * flat[0]


def test_simulator_applies_roll_in_scan_angle_space():
    # With view geometry the same roll moves a column at 55° about 4.9 times as far as at nadir
    # (the old simulator shifted every column by the same number of pixels).
    shape = (10, 2000)
    plain = sensors.SystematicDistortion(view_altitude_km=705.0, nadir_pixel_km=1.0)
    rolled = sensors.SystematicDistortion(view_altitude_km=705.0, nadir_pixel_km=1.0,
                                             roll_px=1.0)
    cols = 1000 + np.radians([0.0, 55.0]) * 705.0
    points = np.column_stack([cols, np.full(2, 5.0)])
    difference = rolled.on_grid(shape).inverse()(points) - plain.on_grid(shape).inverse()(points)
    moved = difference[:, 0]
    expected = -distortion.attitude_displacement(-np.degrees(1 / 705.0), 705.0,
                                                 scan_angle_deg=[0.0, 55.0])
    np.testing.assert_allclose(moved, -expected, rtol=1e-9)
    assert moved[1] / moved[0] == pytest.approx(4.8, abs=0.1)
    in_degrees = sensors.SystematicDistortion(view_altitude_km=705.0, nadir_pixel_km=1.0,
                                                 roll_deg=np.degrees(1 / 705.0))
    np.testing.assert_allclose(in_degrees.on_grid(shape).inverse()(points),
                               rolled.on_grid(shape).inverse()(points))


def test_attitude_model_inverts_exactly():
    model = sensors.SystematicDistortion(skew_per_line=0.05, scale=1.02, roll_px=3, pitch_px=-2,
                                            yaw_deg=1.0, yaw_rate_deg_per_line=0.002,
                                            view_altitude_km=705.0, nadir_pixel_km=1.0,
                                            roll_deg=0.3, pitch_deg=-0.2)
    rng = np.random.default_rng(1)
    points = np.column_stack([rng.uniform(0, 2400, 500), rng.uniform(0, 100, 500)])
    model = model.on_grid((100, 2400))
    np.testing.assert_allclose(model.inverse()(model(points)), points, atol=1e-8)


def test_skew_direction_is_west_on_both_passes():
    # Lecture: "deslocamento relativo das linhas para oeste". Size unchanged by the pass direction.
    size = distortion.earth_rotation_skew(-23.5, 113.0, 778.0, 98.5)
    assert distortion.earth_rotation_skew(-23.5, 113.0, 778.0, 98.5,
                                          pass_direction="ascending") == size
    down = distortion.earth_rotation_offset(-23.5, 113.0, 778.0, 98.5, pass_direction="descending")
    up = distortion.earth_rotation_offset(-23.5, 113.0, 778.0, 98.5, pass_direction="ascending")
    for east, north in (down, up):
        assert east < 0                                     # west
        assert np.hypot(east, north) == pytest.approx(size)
    assert down[1] > 0 > up[1]      # perpendicular to a SSW (descending) or NNW (ascending) track
    zeta = np.radians(distortion.track_angle(-23.5, 98.5))
    assert np.degrees(np.arctan2(down[1], -down[0])) == pytest.approx(np.degrees(zeta))


def test_modis_bowtie_scans_overlap_by_half_at_the_edge():
    # 10 detectors of 1 km per scan: 10 km at nadir, ≈ 20 km at 55° (2.0 × the along-track pixel),
    # so successive scans (10 km apart) overlap by about half at the swath edge.
    footprint = distortion.scan_footprint(np.array([0.0, 55.0]), 705.0)
    assert footprint[0] == pytest.approx(10.0, rel=1e-3)
    along, _ = distortion.pixel_size(55.0, 705.0)
    assert footprint[1] == pytest.approx(10 * float(along), rel=0.01)
    overlap = distortion.bowtie_overlap(np.array([0.0, 30.0, 55.0]), 705.0)
    assert overlap[0] == pytest.approx(0.0, abs=1e-6)
    assert 0 < overlap[1] < overlap[2]
    assert overlap[2] == pytest.approx(0.50, abs=0.01)
    flat = distortion.bowtie_overlap(55.0, 705.0, curved_earth=False)     # 1 − cos 55°
    assert float(flat) == pytest.approx(1 - np.cos(np.radians(55.0)), abs=1e-4)
    across, first, last = distortion.scan_edges(1, np.array([-55.0, 0.0, 55.0]), 705.0)
    assert across[0] == pytest.approx(-across[2]) and across[2] > 1100
    np.testing.assert_allclose(last - first, footprint[[1, 0, 1]], rtol=0.02)


def test_correcting_with_imperfect_attitude_leaves_the_expected_shift():
    # The ground station knows the roll only to 0.01°: from 778 km that is 136 m, 13.6 px of 10 m.
    truth = data.load("cbers2b_hrc").array[::4, ::4][:400, :400]
    true_model = sensors.SystematicDistortion(view_altitude_km=778.0, nadir_pixel_km=0.01,
                                                 roll_deg=0.003, pitch_deg=-0.002, yaw_deg=1.0)
    known = true_model.with_knowledge_errors(roll_deg=0.01)
    recorded = sensors.simulate(truth, true_model, method="cubic")
    exact = sensors.correct(recorded, true_model, method="cubic")
    systematic = sensors.correct(recorded, known, method="cubic")
    inner = slice(80, 320)
    _, exact_shift = registration.measure_shifts(truth[inner, inner], exact[inner, inner], step=60,
                                              window=64)
    _, shifts = registration.measure_shifts(truth[inner, inner], systematic[inner, inner], step=60,
                                         window=64)
    assert np.hypot(*exact_shift.T).max() < 0.5
    expected = 778.0 * np.tan(np.radians(0.01)) / 0.01
    np.testing.assert_allclose(np.abs(shifts[:, 0]), expected, atol=0.5)
    assert np.abs(shifts[:, 1]).max() < 0.5


@pytest.mark.parametrize("pass_direction, sign", [("descending", -1), ("ascending", 1)])
def test_frame_outline_moves_the_last_line_west(pass_direction, sign):
    east, north = distortion.frame_outline(-23.5, 113.0, 113.0, 778.0, 98.5, pass_direction)
    east0, north0 = distortion.frame_outline(-23.5, 113.0, 113.0, 778.0, 98.5, pass_direction,
                                             earth_rotation=False)
    np.testing.assert_allclose(east[:2], east0[:2])                     # the first line stays
    moved = np.array([east[2:4] - east0[2:4], north[2:4] - north0[2:4]]).mean(axis=1)
    np.testing.assert_allclose(moved, distortion.earth_rotation_offset(-23.5, 113.0, 778.0, 98.5,
                                                                     pass_direction))
    assert moved[0] < 0
    assert np.sign(north0[2] - north0[1]) == sign           # south first on a descending pass


def test_a_folding_yaw_rate_raises_instead_of_returning_a_wrong_point():
    # 5°/line turns the lines so fast that the grid folds over itself: (10, 200) on a 300 × 300
    # grid used to come back as a point that maps to (32.4, 59.1)
    model = sensors.SystematicDistortion(yaw_rate_deg_per_line=5.0, shape=(300, 300))
    with pytest.raises(ValueError, match="no single true position"):
        model.inverse()([[10.0, 200.0]])
    # near nadir (closer than 1 / rate = 11.5 px) the inverse is still unique and exact
    near = np.array([[151.0, 148.0], [155.0, 153.0]])
    np.testing.assert_allclose(model(model.inverse()(near)), near, atol=1e-9)
    image = np.arange(300 * 300, dtype=np.float64).reshape(300, 300)
    with pytest.warns(RuntimeWarning, match="no true position"):
        recorded = sensors.simulate(image, model, nodata=-1.0)
    assert (recorded == -1.0).mean() > 0.5


def test_the_protocol_needs_the_grid_and_a_matching_image():
    model = sensors.SystematicDistortion(yaw_deg=2.0)
    with pytest.raises(ValueError, match="on_grid"):
        model([[1.0, 2.0]])
    with pytest.raises(ValueError, match="set on a"):
        sensors.correct(np.zeros((10, 12)), model.on_grid((12, 10)))
    with pytest.raises(ValueError, match="two positive integers"):
        model.on_grid((0, 5))


@settings(max_examples=60, deadline=None)
@given(col=st.floats(0, 600), row=st.floats(0, 400), yaw=st.floats(-10, 10),
       rate=st.floats(-0.01, 0.01), skew=st.floats(-0.2, 0.2), scale=st.floats(0.8, 1.25),
       roll=st.floats(-0.5, 0.5), panoramic=st.booleans())
def test_every_systematic_distortion_inverts_exactly(col, row, yaw, rate, skew, scale, roll,
                                                     panoramic):
    geometry = ({"view_altitude_km": 705.0, "nadir_pixel_km": 1.0, "roll_deg": roll}
                if panoramic else {})
    model = sensors.SystematicDistortion(skew_per_line=skew, scale=scale, yaw_deg=yaw,
                                            yaw_rate_deg_per_line=rate, shape=(400, 600),
                                            **geometry)
    point = np.array([[col, row]])
    np.testing.assert_allclose(model.inverse()(model(point)), point, atol=1e-6)
    np.testing.assert_allclose(model(model.inverse()(point)), point, atol=1e-6)
