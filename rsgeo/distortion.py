"""Systematic distortions: Earth rotation, platform altitude and attitude, view angle.

The lecture's first half ("Remoção de erros sistemáticos"): distortions whose
cause is known, so that a mathematical model corrects them. Geometry is on a
spherical Earth of mean radius 6371 km; the Earth's rotation uses the
equatorial radius 6378.137 km and the sidereal rate 7.292115e-5 rad/s; a
circular orbit's angular rate comes from its altitude by Kepler's third law.
"""

from dataclasses import dataclass

import numpy as np

from ._checks import check_range

EARTH_RADIUS_KM = 6371.0
EQUATORIAL_RADIUS_KM = 6378.137
EARTH_ROTATION_RAD_S = 7.292115e-5
GM_KM3_S2 = 398600.4418


def orbital_rate(altitude_km):
    """Angular rate (rad/s) of a circular orbit at this altitude: sqrt(GM / (R + h)³)."""
    altitude_km = check_range(altitude_km, "altitude_km", low=1e-9, why="the satellite flies above the ground")
    return float(np.sqrt(GM_KM3_S2 / (EARTH_RADIUS_KM + altitude_km) ** 3))


def ground_track_speed(altitude_km):
    """Speed (km/s) of the sub-satellite point on the ground: orbital rate × R."""
    return orbital_rate(altitude_km) * EARTH_RADIUS_KM


def track_angle(latitude_deg, inclination_deg=98.2):
    """Angle ζ (degrees) between the ground track and the meridian: sin ζ = |cos i| / cos φ.

    Raises
    ------
    ValueError
        If the orbit never reaches this latitude.
    """
    latitude = np.radians(check_range(latitude_deg, "latitude_deg", -90, 90, "a latitude"))
    inclination = np.radians(check_range(inclination_deg, "inclination_deg", 0, 180))
    sine = abs(np.cos(inclination)) / np.cos(latitude) if np.cos(latitude) > 0 else np.inf
    if sine > 1:
        reach = 90 - abs(90 - np.degrees(inclination))
        raise ValueError(f"an orbit inclined {inclination_deg}° never passes over latitude "
                         f"{latitude_deg}° (it reaches ±{reach:.1f}°)")
    return float(np.degrees(np.arcsin(sine)))


def earth_rotation_skew(latitude_deg, frame_length_km=185.0, altitude_km=705.0, inclination_deg=98.2):
    """Eastward offset (km) of a frame's last line relative to its first.

    Lecture, slide "Distorção - rotação da Terra": while the satellite images
    a frame, the Earth turns west to east under it, so successive lines are
    shifted. The offset is Δx = ωe·Re·cos φ · t · cos ζ, with t the time to
    image the frame (frame length / ground-track speed) and ζ the angle
    between the ground track and the meridian (Richards & Jia, ch. 2).

    Parameters
    ----------
    latitude_deg : float
        Latitude of the scene, -90 to 90.
    frame_length_km : float
        Along-track length of the frame (Landsat: 185 km).
    altitude_km : float
        Orbit altitude (Landsat 7/8: 705 km).
    inclination_deg : float
        Orbit inclination (Landsat 7/8: 98.2°).

    Returns
    -------
    float
        Offset in km; zero at the poles of the orbit's reach.

    Raises
    ------
    ValueError
        For a latitude outside ±90°, a non-positive altitude or frame length,
        or a latitude the orbit never reaches.

    Examples
    --------
    >>> round(earth_rotation_skew(0.0), 2)      # Landsat frame at the equator
    12.6
    """
    check_range(frame_length_km, "frame_length_km", low=0, why="a length")
    zeta = np.radians(track_angle(latitude_deg, inclination_deg))
    imaging_time = frame_length_km / ground_track_speed(altitude_km)
    surface_speed = EARTH_ROTATION_RAD_S * EQUATORIAL_RADIUS_KM * np.cos(np.radians(latitude_deg))
    return float(surface_speed * imaging_time * np.cos(zeta))


def skew_per_line(latitude_deg, lines, pixel_size_km, altitude_km=705.0, inclination_deg=98.2):
    """Earth-rotation offset, in pixels, between successive lines of a scene of ``lines`` lines.

    The frame is ``lines × pixel_size_km`` long; its last line is offset by
    :func:`earth_rotation_skew`, spread evenly over the lines (the systematic
    correction shifts line n back by n times this value).

    Examples
    --------
    >>> round(skew_per_line(0.0, 6000, 0.030833), 4)     # Landsat: 6000 lines of 30.8 m
    0.0681
    """
    if int(lines) != lines or lines < 1:
        raise ValueError(f"lines must be a positive whole number, got {lines!r}")
    check_range(pixel_size_km, "pixel_size_km", low=1e-12, why="a size")
    offset_km = earth_rotation_skew(latitude_deg, lines * pixel_size_km, altitude_km, inclination_deg)
    return offset_km / pixel_size_km / lines


def skew_angle(latitude_deg, altitude_km=705.0, inclination_deg=98.2):
    """Angle (degrees) by which Earth rotation skews the image's columns."""
    offset = earth_rotation_skew(latitude_deg, 100.0, altitude_km, inclination_deg)
    return float(np.degrees(np.arctan2(offset, 100.0)))


def _check_scan(scan_angle_deg, altitude_km):
    theta = np.radians(np.asarray(scan_angle_deg, dtype=np.float64))
    check_range(altitude_km, "altitude_km", low=1e-9, why="the satellite flies above the ground")
    if not np.isfinite(theta).all():
        raise ValueError("scan_angle_deg must be finite")
    horizon = np.arcsin(EARTH_RADIUS_KM / (EARTH_RADIUS_KM + altitude_km))
    if np.any(np.abs(theta) >= horizon):
        raise ValueError(f"scan angle {np.degrees(np.max(np.abs(theta))):.2f}° is beyond the horizon, "
                         f"which is at {np.degrees(horizon):.2f}° from {altitude_km} km")
    return theta


def zenith_angle(scan_angle_deg, altitude_km):
    """Sensor zenith angle z (degrees) seen from the ground: sin z = ((R + h)/R)·sin θ."""
    theta = _check_scan(scan_angle_deg, altitude_km)
    return np.degrees(np.arcsin((EARTH_RADIUS_KM + altitude_km) / EARTH_RADIUS_KM * np.sin(theta)))


def ground_distance(scan_angle_deg, altitude_km, curved_earth=True):
    """Ground distance (km) from nadir of the point seen at a scan angle.

    Flat Earth: h·tan θ. Curved Earth: R·γ, with γ = z − θ the angle at the
    Earth's centre.
    """
    theta = _check_scan(scan_angle_deg, altitude_km)
    if not curved_earth:
        return altitude_km * np.tan(theta)
    z = np.radians(zenith_angle(np.degrees(theta), altitude_km))
    return EARTH_RADIUS_KM * (z - theta)


def slant_range(scan_angle_deg, altitude_km, curved_earth=True):
    """Distance (km) from the sensor to the ground point seen at a scan angle."""
    theta = _check_scan(scan_angle_deg, altitude_km)
    if not curved_earth:
        return altitude_km / np.cos(theta)
    gamma = ground_distance(np.degrees(theta), altitude_km) / EARTH_RADIUS_KM
    safe = np.where(theta == 0, 1.0, np.sin(theta))
    return np.where(theta == 0, altitude_km, EARTH_RADIUS_KM * np.sin(gamma) / safe)


def pixel_size(scan_angle_deg, altitude_km, nadir_pixel_km=1.0, curved_earth=True):
    """Along-track and across-track ground size (km) of a pixel at a scan angle.

    Lecture, slide "Distorção - campo de visada": for a wide field of view
    (MODIS, ±55°) a pixel at the edge of the swath is several times larger
    than at nadir. With β = nadir pixel / h the instantaneous field of view:

    * flat Earth: along = β·h·sec θ, across = β·h·sec² θ;
    * curved Earth: along = β·s, across = β·s / cos z, with s the slant range
      and z the sensor zenith angle.

    Returns
    -------
    along_track_km, across_track_km : float or ndarray

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle beyond the horizon.

    Examples
    --------
    >>> along, across = pixel_size(55.0, 705.0)          # MODIS at the swath edge
    >>> round(float(along), 2), round(float(across), 2)
    (2.01, 4.83)
    """
    check_range(nadir_pixel_km, "nadir_pixel_km", low=1e-12, why="a size")
    theta = _check_scan(scan_angle_deg, altitude_km)
    ifov = nadir_pixel_km / altitude_km
    if not curved_earth:
        return ifov * altitude_km / np.cos(theta), ifov * altitude_km / np.cos(theta) ** 2
    along = ifov * slant_range(np.degrees(theta), altitude_km)
    across = along / np.cos(np.radians(zenith_angle(np.degrees(theta), altitude_km)))
    return along, across


def swath_width(half_angle_deg, altitude_km, curved_earth=True):
    """Ground width (km) of a swath scanned to ±half_angle_deg.

    Examples
    --------
    >>> round(float(swath_width(55.0, 705.0)))         # MODIS
    2330
    """
    return float(2 * ground_distance(half_angle_deg, altitude_km, curved_earth))


def panoramic_displacement(scan_angle_deg, altitude_km, curved_earth=True):
    """How far (km) a point lies from where equal ground pixels would put it.

    A scanner samples equal angles, not equal ground distances: the point at
    scan angle θ is at ground distance d(θ) while the image puts it at h·θ
    (its pixel count times the nadir pixel). The difference grows towards the
    swath edge: the lecture's "deslocamento dos pixels ao longo da linha de varredura".
    """
    theta = _check_scan(scan_angle_deg, altitude_km)
    return ground_distance(np.degrees(theta), altitude_km, curved_earth) - altitude_km * theta


def attitude_displacement(angle_deg, altitude_km, curved_earth=True):
    """Ground displacement (km) of nadir for a roll (across track) or pitch (along track) angle.

    Flat Earth h·tan(angle); curved Earth the arc R·γ.
    """
    return ground_distance(angle_deg, altitude_km, curved_earth)


# --------------------------------------------------------------------------
# The forward simulator and its exact correction


@dataclass
class SystematicDistortion:
    """A combination of systematic distortions, as a mapping between pixel grids.

    Rows are along track (line by line in time), columns across track; the
    image centre is nadir. ``true_to_image`` maps a position on the true
    (corrected) grid to where the distorted image records it;
    ``image_to_true`` is its exact inverse.

    Parameters
    ----------
    skew_per_line : float
        Earth rotation: columns of offset per line (the km offset of
        :func:`earth_rotation_skew` divided by pixel size and line count).
    scale : float
        Altitude change: h / h_nominal; above 1 the sensor sees more ground
        per pixel, so the image shrinks.
    roll_px, pitch_px : float
        Attitude: shift of the whole image across and along track, in pixels
        (:func:`attitude_displacement` over the pixel size).
    yaw_deg : float
        Constant yaw: rotation of the image about nadir.
    yaw_rate_deg_per_line : float
        Varying yaw: the rotation grows line by line (the lecture's "Yaw - var.").
    view_altitude_km, nadir_pixel_km : float or None
        Wide field of view: when given, columns are scan angles of equal
        steps (nadir pixel / altitude), so pixels away from nadir cover more
        ground (the panoramic distortion on a curved Earth).
    """

    skew_per_line: float = 0.0
    scale: float = 1.0
    roll_px: float = 0.0
    pitch_px: float = 0.0
    yaw_deg: float = 0.0
    yaw_rate_deg_per_line: float = 0.0
    view_altitude_km: float = None
    nadir_pixel_km: float = None

    def __post_init__(self):
        check_range(self.scale, "scale", low=1e-6, why="a ratio of altitudes")
        if (self.view_altitude_km is None) != (self.nadir_pixel_km is None):
            raise ValueError("view_altitude_km and nadir_pixel_km go together: give both or neither")

    def _yaw(self, rows_from_centre):
        return np.radians(self.yaw_deg + self.yaw_rate_deg_per_line * rows_from_centre)

    def true_to_image(self, cols, rows, shape):
        """Distorted-image (col, row) of true-grid positions; shape = (rows, cols) of the grid."""
        centre_c, centre_r = shape[1] / 2, shape[0] / 2
        c, r = np.asarray(cols, float) - centre_c, np.asarray(rows, float) - centre_r
        angle = self._yaw(r)
        c, r = c * np.cos(angle) + r * np.sin(angle), -c * np.sin(angle) + r * np.cos(angle)
        c = c + self.skew_per_line * (r + centre_r)
        c, r = c + self.roll_px, r + self.pitch_px
        c, r = c / self.scale, r / self.scale
        if self.view_altitude_km is not None:
            # ground distance (in nadir pixels) -> scan angle (in nadir pixels)
            distance_km = c * self.nadir_pixel_km
            gamma = distance_km / EARTH_RADIUS_KM
            theta = np.arctan2(EARTH_RADIUS_KM * np.sin(gamma),
                               EARTH_RADIUS_KM + self.view_altitude_km - EARTH_RADIUS_KM * np.cos(gamma))
            c = theta * self.view_altitude_km / self.nadir_pixel_km
        return c + centre_c, r + centre_r

    def image_to_true(self, cols, rows, shape):
        """Exact inverse of :meth:`true_to_image`: the systematic correction."""
        centre_c, centre_r = shape[1] / 2, shape[0] / 2
        c, r = np.asarray(cols, float) - centre_c, np.asarray(rows, float) - centre_r
        if self.view_altitude_km is not None:
            theta = c * self.nadir_pixel_km / self.view_altitude_km
            c = ground_distance(np.degrees(theta), self.view_altitude_km) / self.nadir_pixel_km
        c, r = c * self.scale, r * self.scale
        c, r = c - self.roll_px, r - self.pitch_px
        c = c - self.skew_per_line * (r + centre_r)
        # Undo the yaw: r_true enters the angle, so iterate (converges in a few steps
        # because the rotation per line is tiny).
        c_rot, r_rot = c, r
        r_true = r_rot
        for _ in range(50):
            angle = self._yaw(r_true)
            c_true = c_rot * np.cos(angle) - r_rot * np.sin(angle)
            r_next = c_rot * np.sin(angle) + r_rot * np.cos(angle)
            if np.allclose(r_next, r_true, atol=1e-10, rtol=0):
                r_true = r_next
                break
            r_true = r_next
        return c_true + centre_c, r_true + centre_r


def simulate(image, distortion, method="bilinear", nodata=0):
    """Apply a systematic distortion to an image: what the sensor would record.

    Parameters
    ----------
    image : ndarray
        The true scene, 2-D or bands first.
    distortion : SystematicDistortion
    method : {"nearest", "bilinear", "cubic"}
        Interpolator (rsgeo.resample).

    Returns
    -------
    distorted : ndarray
        Same shape and dtype; cells that see ground outside the scene get nodata.
    """
    from .resample import grid_positions, interpolate

    shape = np.shape(image)[-2:]
    cols, rows = grid_positions(shape)
    true_c, true_r = distortion.image_to_true(cols, rows, shape)
    return interpolate(image, true_c, true_r, method, nodata)


def correct(distorted, distortion, method="bilinear", nodata=0):
    """The systematic correction: resample the distorted image back onto the true grid.

    Each true-grid cell asks the known model where the sensor recorded it
    (:meth:`SystematicDistortion.true_to_image`) and interpolates there.
    """
    from .resample import grid_positions, interpolate

    shape = np.shape(distorted)[-2:]
    cols, rows = grid_positions(shape)
    image_c, image_r = distortion.true_to_image(cols, rows, shape)
    return interpolate(distorted, image_c, image_r, method, nodata)


def distorted_grid(distortion, shape, step=32):
    """Lines of the true grid drawn where the distorted image records them (for plots).

    Returns
    -------
    list of (cols, rows) arrays, one per grid line.
    """
    lines = []
    for r in np.arange(0, shape[0] + 1, step):
        c = np.linspace(0, shape[1], 200)
        lines.append(distortion.true_to_image(c, np.full_like(c, r), shape))
    for c in np.arange(0, shape[1] + 1, step):
        r = np.linspace(0, shape[0], 200)
        lines.append(distortion.true_to_image(np.full_like(r, c), r, shape))
    return lines
