"""rsgeo.synthetic.raw_scene and RawSensor: a raw pushbroom scene whose geometry is chapter 1's,
checked against chapter 1's own formulas (track angle, Earth-rotation skew, pixel growth),
chapter 4b's relief displacement, EGM96 through PROJ and the RPC fitted to it."""

import functools

import numpy as np
import pytest

from rsgeo import dem, distortion, errors, heights, relief, sensors, synthetic

pytestmark = pytest.mark.gdal          # PROJ (through rasterio) and the shipped geoid grid


@functools.cache
def scene():
    return synthetic.raw_scene(shape=(200, 180), nadir_pixel_m=30.0, simulate=False)


def unit(vector):
    return np.asarray(vector) / np.hypot(*vector)


def test_project_and_ground_invert_each_other_at_any_height():
    sensor = scene().sensor
    rng = np.random.default_rng(0)
    col, row, h = rng.uniform(0, 180, 300), rng.uniform(0, 200, 300), rng.uniform(-50, 900, 300)
    x, y = sensor.ground(col, row, h)
    back_col, back_row = sensor.project(x, y, h)
    assert np.abs(back_col - col).max() < 1e-7 and np.abs(back_row - row).max() < 1e-7


def test_the_image_centre_sees_the_dems_centre():
    s = scene()
    west, south, east, north = (s.dem_transform.c, s.dem_transform.f + s.dem.shape[0]
                                * s.dem_transform.e, s.dem_transform.c + s.dem.shape[1]
                                * s.dem_transform.a, s.dem_transform.f)
    x, y = s.sensor.ground(90.0, 100.0, 0.0)
    assert abs(x - (west + east) / 2) < 1e-6 and abs(y - (south + north) / 2) < 1e-6


def test_lines_run_across_a_track_heading_the_track_angle_west_of_south():
    s = scene()
    zeta = distortion.track_angle(s.latitude_deg, 98.5)
    assert s.sensor.heading_deg == pytest.approx(zeta)
    x, y = s.sensor.ground(np.array([60.0, 120.0]), np.array([100.0, 100.0]), 0.0)
    # along a line, columns go across the track: east and a little south
    direction = unit((x[1] - x[0], y[1] - y[0]))
    expected = (np.cos(np.radians(zeta)), -np.sin(np.radians(zeta)))
    assert direction == pytest.approx(expected, abs=1e-9)


def test_the_last_lines_ground_lies_west_by_chapter_1s_earth_rotation_skew():
    s = scene()
    rows = s.sensor.shape[0]
    x, y = s.sensor.ground(np.array([90.0, 90.0]), np.array([0.0, float(rows)]), 0.0)
    zeta = np.radians(s.sensor.heading_deg)
    across = (x[1] - x[0]) * np.cos(zeta) - (y[1] - y[0]) * np.sin(zeta)
    skew_km = distortion.earth_rotation_skew(s.latitude_deg, rows * 0.030, 778.0, 98.5)
    assert across == pytest.approx(-1000 * skew_km, rel=1e-9)
    assert s.skew_per_line == pytest.approx(distortion.skew_per_line(
        s.latitude_deg, rows, 0.030, 778.0, 98.5))


def test_pixels_grow_off_nadir_as_chapter_1s_pixel_size_says():
    s = scene()
    step = 0.01
    x, y = s.sensor.ground(np.array([90.0 - step, 90.0 + step]), np.array([100.0, 100.0]), 0.0)
    across_m = np.hypot(x[1] - x[0], y[1] - y[0]) / (2 * step)
    _along, across_km = distortion.pixel_size(s.off_nadir_deg, 778.0, 0.030)
    assert across_m == pytest.approx(1000 * float(across_km), rel=1e-6)
    assert across_m > 1.3 * 30.0                  # 30° off nadir: far wider than at nadir


def test_relief_moves_a_point_away_from_nadir_by_h_tan_z():
    s = scene()
    x, y = s.sensor.ground(90.0, 100.0, 0.0)
    col0, row0 = s.sensor.project(x, y, 0.0)
    col1, row1 = s.sensor.project(x, y, 300.0)
    _along, across_km = distortion.pixel_size(s.off_nadir_deg, 778.0, 0.030)
    moved_m = (col1 - col0) * 1000 * float(across_km)
    zenith = distortion.zenith_angle(s.off_nadir_deg, 778.0)
    assert moved_m == pytest.approx(relief.relief_displacement(300.0, zenith), rel=0.01)
    assert moved_m > 0 and abs(row1 - row0) < 1e-9         # across the track only


def test_a_roll_knowledge_error_moves_columns_by_the_angle_over_the_ifov():
    s = scene()
    x, y = s.sensor.ground(np.array([30.0, 150.0]), np.array([40.0, 160.0]), 0.0)
    known = s.sensor.with_knowledge_errors(roll_deg=0.01)
    col, row = s.sensor.project(x, y, 0.0)
    known_col, known_row = known.project(x, y, 0.0)
    assert known_col - col == pytest.approx(np.radians(0.01) / (0.030 / 778.0), rel=1e-9)
    assert np.abs(known_row - row).max() < 1e-9
    assert known.centre_xy == s.sensor.centre_xy and known.offset_km == s.sensor.offset_km
    drifting = s.sensor.with_knowledge_errors(yaw_rate_deg_per_line=1e-5)
    assert drifting.distortion.yaw_rate_deg_per_line == pytest.approx(1e-5)


def test_an_rpc_fitted_to_the_sensor_reproduces_it():
    s = scene()
    rpc = sensors.fit_rpc_to_sensor(s.sensor, s.crs, s.bounds, s.height_range)
    points = s.control_points(200, seed=1)
    col, row = rpc.project(points.lon, points.lat, points.height)
    assert np.abs(col - points.true_image_xy[:, 0]).max() < 1e-3
    assert np.abs(row - points.true_image_xy[:, 1]).max() < 1e-3


def test_control_points_lie_on_the_ellipsoidal_dem_and_carry_the_noise_asked_for():
    s = scene()
    exact = s.control_points(50, seed=2)
    col, row = s.sensor.project(exact.map_xy[:, 0], exact.map_xy[:, 1], exact.height)
    assert np.abs(col - exact.true_image_xy[:, 0]).max() < 1e-6
    assert np.abs(row - exact.true_image_xy[:, 1]).max() < 1e-6
    assert np.array_equal(exact.image_xy, exact.true_image_xy)
    dem_h = dem.dem_height(s.dem, s.dem_transform, exact.map_xy[:, 0], exact.map_xy[:, 1])
    assert np.abs(dem_h - exact.height).max() < 1e-3           # on the terrain
    noisy = s.control_points(2000, noise_px=0.5, seed=3)
    assert np.std(noisy.image_xy - noisy.true_image_xy) == pytest.approx(0.5, rel=0.05)
    placed = s.control_points([[10.0, 20.0], [100.0, 150.0]])
    assert np.array_equal(placed.true_image_xy, [[10.0, 20.0], [100.0, 150.0]])
    assert set(placed.rpc_gcps) == {"lon", "lat", "height", "col", "row"}


def test_the_dem_is_made_ellipsoidal_with_egm96():
    from rsgeo import data

    s = scene()
    orthometric = data.load("olinda_dem").array
    undulation = s.dem - orthometric
    assert np.ptp(undulation) < 0.5                       # nearly constant over 10 km
    n = heights.geoid_undulation(-34.85, -8.0)           # EGM96 at Olinda: N = -5.49 m
    assert undulation.mean() == pytest.approx(float(n), abs=0.2) and -6 < n < -5
    assert s.height_range == (pytest.approx(s.dem.min()), pytest.approx(s.dem.max()))


def test_the_simulated_image_samples_the_ground():
    small = synthetic.raw_scene(shape=(40, 36), nadir_pixel_m=100.0)
    assert small.image.shape == (40, 36) and small.image.dtype == np.uint8
    assert np.ptp(small.image) > 50                      # a landscape, not a constant


def test_refusals():
    with pytest.raises(errors.GridError, match="leaves the DEM"):
        synthetic.raw_scene(shape=(2000, 2000), simulate=False)
    with pytest.raises(errors.RsgeoError, match="off_nadir_deg"):
        synthetic.raw_scene(off_nadir_deg=60.0, simulate=False)
    with pytest.raises(errors.RsgeoError, match="shape"):
        synthetic.raw_scene(shape=(0, 10), simulate=False)
    with pytest.raises(errors.ModelError, match="view geometry"):
        sensors.RawSensor(sensors.SystematicDistortion(shape=(10, 10)), (0.0, 0.0), 8.0,
                            100.0)
    with pytest.raises(TypeError):
        sensors.RawSensor("not a model", (0.0, 0.0), 8.0, 100.0)
    with pytest.raises(errors.ModelError, match="NaN"):
        scene().sensor.project(np.nan, 0.0, 0.0)
    with pytest.raises(errors.RsgeoError, match="noise_px"):
        scene().control_points(5, noise_px=-1.0)
    with pytest.raises(errors.GridError, match="does not cover"):
        scene().sensor.ground_on_dem(-5000.0, 100.0, scene().dem, scene().dem_transform)
