"""Systematic distortions: Earth rotation, platform altitude and attitude, view angle.

The lecture's first half ("Remoção de erros sistemáticos"): distortions whose
cause is known, so that a mathematical model corrects them. Geometry is on a
spherical Earth of mean radius 6371 km; the Earth's rotation uses the
equatorial radius 6378.137 km and the sidereal rate 7.292115e-5 rad/s; a
circular orbit's angular rate comes from its altitude by Kepler's third law.
"""


import numpy as np

from ._deprecated import moved_names
from .errors import ModelError, RsgeoError
from .language import N_, _, prose_number
from .validation import as_number

__all__ = [
    "EARTH_RADIUS_KM", "EQUATORIAL_RADIUS_KM", "EARTH_ROTATION_RAD_S", "GM_KM3_S2",
    "orbital_rate", "ground_track_speed", "track_angle", "PASS_DIRECTIONS",
    "earth_rotation_skew", "earth_rotation_offset", "frame_outline", "skew_per_line",
    "skew_angle", "zenith_angle", "ground_distance", "slant_range", "pixel_size", "swath_width",
    "panoramic_displacement", "attitude_displacement", "scan_footprint", "bowtie_overlap",
    "scan_edges", "ground_point", "orbit_coordinates",
]

# moved to rsgeo.sensors: importable from here for one release, with a warning (the module
# keeps its own dir(): autodoc and help() list what it defines)
__getattr__ = moved_names(__name__, {
    name: "rsgeo.sensors" for name in ("SystematicDistortion", "simulate", "correct",
                                       "distorted_grid")})[0]

EARTH_RADIUS_KM = 6371.0
EQUATORIAL_RADIUS_KM = 6378.137
EARTH_ROTATION_RAD_S = 7.292115e-5
GM_KM3_S2 = 398600.4418


def orbital_rate(altitude_km):
    """Angular rate (rad/s) of a circular orbit at this altitude: sqrt(GM / (R + h)³).

    Parameters
    ----------
    altitude_km : float
        Orbit altitude above the ground, km.

    Returns
    -------
    float
        rad/s.

    Raises
    ------
    ValueError
        If the altitude is not a positive finite number.

    References
    ----------
    Kepler's third law for a circular orbit, GM = 398600.4418 km³/s².
    """
    altitude_km = as_number(altitude_km, "altitude_km", low=1e-9,
                              why=N_("the satellite flies above the ground"))
    return float(np.sqrt(GM_KM3_S2 / (EARTH_RADIUS_KM + altitude_km) ** 3))


def ground_track_speed(altitude_km):
    """Speed (km/s) of the sub-satellite point on the ground: orbital rate × R.

    Parameters
    ----------
    altitude_km : float
        Orbit altitude above the ground, km.

    Returns
    -------
    float
        km/s.

    Raises
    ------
    ValueError
        If the altitude is not a positive finite number.
    """
    return orbital_rate(altitude_km) * EARTH_RADIUS_KM


def track_angle(latitude_deg, inclination_deg=98.2):
    """Angle ζ (degrees) between the ground track and the meridian: ``sin ζ = |cos i| / cos φ``.

    Parameters
    ----------
    latitude_deg : float
        Latitude, -90 to 90.
    inclination_deg : float
        Orbit inclination, 0 to 180.

    Returns
    -------
    float
        ζ, 0 to 90 degrees.

    Raises
    ------
    ValueError
        If the orbit never reaches this latitude.

    References
    ----------
    Richards, J. A. and Jia, X. (2006), *Remote Sensing Digital Image
    Analysis*, 4th ed., Springer, ch. 2 (geometric distortion).
    """
    latitude = np.radians(as_number(latitude_deg, "latitude_deg", -90, 90, N_("a latitude")))
    inclination = np.radians(as_number(inclination_deg, "inclination_deg", 0, 180))
    sine = abs(np.cos(inclination)) / np.cos(latitude) if np.cos(latitude) > 0 else np.inf
    if sine > 1:
        reach = 90 - abs(90 - np.degrees(inclination))
        raise RsgeoError(_("an orbit inclined {inclination_deg}° never passes over "
                           "latitude {latitude_deg}° (it reaches ±{reach:.1f}°)").format(
                inclination_deg=inclination_deg, latitude_deg=latitude_deg,
                reach=prose_number(reach)))
    return float(np.degrees(np.arcsin(sine)))


PASS_DIRECTIONS = ("descending", "ascending")


def _check_pass(pass_direction):
    if pass_direction not in PASS_DIRECTIONS:
        raise RsgeoError(_("pass_direction must be 'descending' (north to south, the "
                           "daytime pass of Landsat and CBERS) or 'ascending' (south to "
                           "north), got {pass_direction!r}").format(
                pass_direction=pass_direction))
    return pass_direction


def earth_rotation_skew(latitude_deg, frame_length_km=185.0, altitude_km=705.0,
                        inclination_deg=98.2,
                        pass_direction="descending"):
    """Size (km) of the across-track offset between a frame's last line and its first.

    Lecture, slide "Distorção - rotação da Terra": the Earth turns west to
    east while the satellite images a frame, so each line's ground lies
    further **west** than the previous line's ("deslocamento relativo das
    linhas para oeste"). The size of the offset is
    Δx = ωe·Re·cos φ · t · cos ζ, with t the time to image the frame (frame
    length / ground-track speed) and ζ the angle between the ground track and
    the meridian (Richards & Jia, ch. 2).

    Direction: the ground under the last line lies WEST of the first line's
    (across the track), on either pass; :func:`earth_rotation_offset` gives it
    as an (east, north) vector.

    * ``"descending"`` (north to south; Landsat's and CBERS's daytime passes):
      the last line is the southern one, so the frame's southern end lies west
      of its northern end; the offset points west and slightly north
      (perpendicular to the south-south-west track).
    * ``"ascending"`` (south to north): the last line is the northern one, so
      the northern end lies west; the offset points west and slightly south.

    The returned value is the size only, the same on both passes.

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
    pass_direction : {"descending", "ascending"}
        Which way the satellite crosses the scene (see above for the direction).

    Returns
    -------
    float
        Size of the westward offset in km (≥ 0); zero at the orbit's highest latitude.

    Raises
    ------
    ValueError
        For a latitude outside ±90°, a non-positive altitude or frame length,
        a latitude the orbit never reaches, or an unknown pass direction.

    References
    ----------
    Richards, J. A. and Jia, X. (2006), *Remote Sensing Digital Image
    Analysis*, 4th ed., Springer, ch. 2 (geometric distortion).

    Examples
    --------
    >>> round(earth_rotation_skew(0.0), 2)      # Landsat frame at the equator: 12.6 km west
    12.6
    >>> earth_rotation_skew(0.0, pass_direction="ascending") == earth_rotation_skew(0.0)
    True
    """
    _check_pass(pass_direction)
    as_number(frame_length_km, "frame_length_km", low=0, why=N_("a length"))
    zeta = np.radians(track_angle(latitude_deg, inclination_deg))
    imaging_time = frame_length_km / ground_track_speed(altitude_km)
    surface_speed = EARTH_ROTATION_RAD_S * EQUATORIAL_RADIUS_KM * np.cos(np.radians(latitude_deg))
    return float(surface_speed * imaging_time * np.cos(zeta))


def earth_rotation_offset(latitude_deg, frame_length_km=185.0, altitude_km=705.0,
                          inclination_deg=98.2,
                          pass_direction="descending"):
    """Where the ground under a frame's last line lies from the first line's: (east, north) km.

    The offset is across the ground track, of size :func:`earth_rotation_skew`,
    on the track's west side. A retrograde sun-synchronous orbit (inclination
    over 90°) heads south-south-west on its descending pass, at the angle ζ of
    :func:`track_angle` west of south, and north-north-west on its ascending
    pass; the offset is perpendicular to that heading.

    Parameters
    ----------
    latitude_deg, frame_length_km, altitude_km, inclination_deg, pass_direction
        As in :func:`earth_rotation_skew`.

    Returns
    -------
    east_km, north_km : float
        East component always negative (the last line's ground is west of the
        first's); north component positive on a descending pass, negative on an
        ascending one.

    Raises
    ------
    ValueError
        As :func:`earth_rotation_skew`.

    Examples
    --------
    >>> east, north = earth_rotation_offset(-23.5, 113.0, 778.0, 98.5)    # CBERS over São Paulo
    >>> round(east, 2), round(north, 2)
    (-7.05, 1.15)
    """
    size = earth_rotation_skew(latitude_deg, frame_length_km, altitude_km, inclination_deg,
                               pass_direction)
    zeta = np.radians(track_angle(latitude_deg, inclination_deg))
    north = np.sin(zeta) if pass_direction == "descending" else -np.sin(zeta)
    if np.cos(np.radians(inclination_deg)) > 0:        # prograde orbit: the track leans east
        north = -north
    return float(-size * np.cos(zeta)), float(size * north)


def frame_outline(latitude_deg, frame_length_km, width_km, altitude_km=705.0, inclination_deg=98.2,
                  pass_direction="descending", earth_rotation=True):
    """Corners (east, north) in km of a frame on the ground, first line centred at (0, 0).

    The frame runs ``frame_length_km`` along the ground track's heading
    (south-south-west on a descending pass of a retrograde orbit, north-north-
    west on an ascending one) and ``width_km`` across it. With
    ``earth_rotation`` the last line is moved by :func:`earth_rotation_offset`
    (west), the first line stays: the rectangle becomes the parallelogram the
    scene really covers.

    Parameters
    ----------
    latitude_deg, frame_length_km : float
        As in :func:`earth_rotation_skew`.
    width_km : float
        Across-track width of the frame.
    altitude_km, inclination_deg, pass_direction
        As in :func:`earth_rotation_skew`.
    earth_rotation : bool
        Move the last line by the Earth's rotation (True) or not.

    Returns
    -------
    east_km, north_km : ndarray, shape (5,)
        Closed outline: first line's two ends, last line's two ends, back to the start.

    Raises
    ------
    ValueError
        As :func:`earth_rotation_skew`, or for a negative width.

    Examples
    --------
    >>> east, north = frame_outline(0.0, 185.0, 185.0, earth_rotation=False)
    >>> round(float(np.hypot(east[2] - east[1], north[2] - north[1])), 1)   # along-track side
    185.0
    """
    as_number(width_km, "width_km", low=0, why=N_("a width"))
    offset = np.array(earth_rotation_offset(latitude_deg, frame_length_km, altitude_km,
                                            inclination_deg,
                                            pass_direction))
    zeta = np.radians(track_angle(latitude_deg, inclination_deg))
    retrograde = np.cos(np.radians(inclination_deg)) < 0      # heads west of the meridian
    north = -np.cos(zeta) if pass_direction == "descending" else np.cos(zeta)
    heading = np.array([-np.sin(zeta) if retrograde else np.sin(zeta), north])
    right = np.array([heading[1], -heading[0]]) * width_km / 2
    last = frame_length_km * heading + (offset if earth_rotation else 0.0)
    corners = np.array([-right, right, last + right, last - right, -right])
    return corners[:, 0], corners[:, 1]


def skew_per_line(latitude_deg, lines, pixel_size_km, altitude_km=705.0, inclination_deg=98.2,
                  pass_direction="descending"):
    """Earth-rotation offset, in pixels, between successive lines of a scene of ``lines`` lines.

    The frame is ``lines × pixel_size_km`` long; its last line's ground lies
    :func:`earth_rotation_skew` west of its first line's, spread evenly over
    the lines (each line's ground is this many pixels west of the previous
    line's; the systematic correction shifts line n back east by n times this
    value). Positive on both passes: the size, as in :func:`earth_rotation_skew`.

    Parameters
    ----------
    latitude_deg : float
        Latitude of the scene.
    lines : int
        Lines in the scene.
    pixel_size_km : float
        Along-track size of a line.
    altitude_km, inclination_deg, pass_direction
        As in :func:`earth_rotation_skew`.

    Returns
    -------
    float
        Pixels of westward offset per line (≥ 0).

    Raises
    ------
    ValueError
        If ``lines`` is not a positive whole number, the pixel size is not
        positive, or as :func:`earth_rotation_skew`.

    Examples
    --------
    >>> round(skew_per_line(0.0, 6000, 0.030833), 4)     # Landsat: 6000 lines of 30.8 m
    0.0681
    """
    if int(lines) != lines or lines < 1:
        raise RsgeoError(_("lines must be a positive whole number, got {lines!r}").format(
                lines=lines))
    as_number(pixel_size_km, "pixel_size_km", low=1e-12, why=N_("a size"))
    offset_km = earth_rotation_skew(latitude_deg, lines * pixel_size_km, altitude_km,
                                    inclination_deg,
                                    pass_direction)
    return offset_km / pixel_size_km / lines


def skew_angle(latitude_deg, altitude_km=705.0, inclination_deg=98.2):
    """Angle (degrees) by which Earth rotation skews the image's columns.

    Parameters
    ----------
    latitude_deg : float
        Latitude of the scene.
    altitude_km, inclination_deg
        As in :func:`earth_rotation_skew`.

    Returns
    -------
    float
        Degrees, ≥ 0: the across-track offset per along-track distance, as an angle.

    Raises
    ------
    ValueError
        As :func:`earth_rotation_skew`.

    References
    ----------
    Richards, J. A. and Jia, X. (2006), *Remote Sensing Digital Image
    Analysis*, 4th ed., Springer, ch. 2 (geometric distortion).
    """
    offset = earth_rotation_skew(latitude_deg, 100.0, altitude_km, inclination_deg)
    return float(np.degrees(np.arctan2(offset, 100.0)))


def _check_scan(scan_angle_deg, altitude_km):
    theta = np.radians(np.asarray(scan_angle_deg, dtype=np.float64))
    as_number(altitude_km, "altitude_km", low=1e-9, why=N_("the satellite flies above the ground"))
    if not np.isfinite(theta).all():
        raise RsgeoError(_("scan_angle_deg must be finite"))
    horizon = np.arcsin(EARTH_RADIUS_KM / (EARTH_RADIUS_KM + altitude_km))
    if np.any(np.abs(theta) >= horizon):
        raise ModelError(_("scan angle {degrees:.2f}° is beyond the horizon, which is "
                           "at {degrees2:.2f}° from {altitude_km:g} km").format(
                degrees=prose_number(np.degrees(np.max(np.abs(theta)))),
                degrees2=prose_number(np.degrees(horizon)),
                altitude_km=prose_number(altitude_km)))
    return theta


def zenith_angle(scan_angle_deg, altitude_km):
    """Sensor zenith angle z (degrees) seen from the ground: sin z = ((R + h)/R)·sin θ.

    Parameters
    ----------
    scan_angle_deg : float or array_like
        Scan angle from nadir, degrees.
    altitude_km : float
        Orbit altitude above the ground, km.

    Returns
    -------
    float or ndarray
        Degrees, larger than the scan angle on a curved Earth.

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle that is not finite or is
        beyond the horizon.

    References
    ----------
    Richards, J. A. and Jia, X. (2006), *Remote Sensing Digital Image
    Analysis*, 4th ed., Springer, ch. 2 (geometric distortion).
    """
    theta = _check_scan(scan_angle_deg, altitude_km)
    return np.degrees(np.arcsin((EARTH_RADIUS_KM + altitude_km) / EARTH_RADIUS_KM * np.sin(theta)))


def ground_distance(scan_angle_deg, altitude_km, curved_earth=True):
    """Ground distance (km) from nadir of the point seen at a scan angle.

    Flat Earth: h·tan θ. Curved Earth: R·γ, with γ = z − θ the angle at the
    Earth's centre.

    Parameters
    ----------
    scan_angle_deg : float or array_like
        Scan angle from nadir, degrees.
    altitude_km : float
        Orbit altitude above the ground, km.
    curved_earth : bool
        A sphere of radius 6371 km (True) or a flat Earth.

    Returns
    -------
    float or ndarray
        km, signed like the scan angle.

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle that is not finite or is
        beyond the horizon.

    References
    ----------
    Richards, J. A. and Jia, X. (2006), *Remote Sensing Digital Image
    Analysis*, 4th ed., Springer, ch. 2 (geometric distortion).
    """
    theta = _check_scan(scan_angle_deg, altitude_km)
    if not curved_earth:
        return altitude_km * np.tan(theta)
    z = np.radians(zenith_angle(np.degrees(theta), altitude_km))
    return EARTH_RADIUS_KM * (z - theta)


def slant_range(scan_angle_deg, altitude_km, curved_earth=True):
    """Distance (km) from the sensor to the ground point seen at a scan angle.

    Parameters
    ----------
    scan_angle_deg : float or array_like
        Scan angle from nadir, degrees.
    altitude_km : float
        Orbit altitude above the ground, km.
    curved_earth : bool
        A sphere of radius 6371 km (True) or a flat Earth.

    Returns
    -------
    float or ndarray
        km.

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle that is not finite or is
        beyond the horizon.
    """
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

    Parameters
    ----------
    scan_angle_deg : float or array_like
        Scan angle from nadir, degrees.
    altitude_km : float
        Orbit altitude above the ground, km.
    nadir_pixel_km : float
        The pixel's size at nadir, km.
    curved_earth : bool
        A sphere of radius 6371 km (True) or a flat Earth.

    Returns
    -------
    along_track_km, across_track_km : float or ndarray

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle beyond the horizon.

    References
    ----------
    Wolfe, R. E., Nishihama, M., Fleig, A. J. et al. (2002), "Achieving
    sub-pixel geolocation accuracy in support of MODIS land science",
    Remote Sensing of Environment 83, 31-49.

    Examples
    --------
    >>> along, across = pixel_size(55.0, 705.0)          # MODIS at the swath edge
    >>> round(float(along), 2), round(float(across), 2)
    (2.01, 4.83)
    """
    as_number(nadir_pixel_km, "nadir_pixel_km", low=1e-12, why=N_("a size"))
    theta = _check_scan(scan_angle_deg, altitude_km)
    ifov = nadir_pixel_km / altitude_km
    if not curved_earth:
        return ifov * altitude_km / np.cos(theta), ifov * altitude_km / np.cos(theta) ** 2
    along = ifov * slant_range(np.degrees(theta), altitude_km)
    across = along / np.cos(np.radians(zenith_angle(np.degrees(theta), altitude_km)))
    return along, across


def swath_width(half_angle_deg, altitude_km, curved_earth=True):
    """Ground width (km) of a swath scanned to ±half_angle_deg.

    Parameters
    ----------
    half_angle_deg : float
        Largest scan angle, degrees.
    altitude_km : float
        Orbit altitude above the ground, km.
    curved_earth : bool
        A sphere of radius 6371 km (True) or a flat Earth.

    Returns
    -------
    float
        km.

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle that is not finite or is
        beyond the horizon.

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

    Parameters
    ----------
    scan_angle_deg : float or array_like
        Scan angle from nadir, degrees.
    altitude_km : float
        Orbit altitude above the ground, km.
    curved_earth : bool
        A sphere of radius 6371 km (True) or a flat Earth.

    Returns
    -------
    float or ndarray
        km, positive away from nadir (the ground point is further out).

    Raises
    ------
    ValueError
        For a non-positive altitude or a scan angle that is not finite or is
        beyond the horizon.

    References
    ----------
    Negri, R. G., *Pré-processamento: correções geométricas*, lecture
    slides (after Meneses and Almeida, 2012).
    """
    theta = _check_scan(scan_angle_deg, altitude_km)
    return ground_distance(np.degrees(theta), altitude_km, curved_earth) - altitude_km * theta


def _look_vector(theta, psi=0.0, epsilon=0.0):
    """Unit look vector (across, along, up) of a scanner on a platform pitched by psi.

    The scan mirror turns about the along-track axis (scan angle theta, to
    which a roll adds); a detector sits epsilon along track in the focal plane;
    platform pitch psi turns everything about the across-track axis.
    """
    theta, psi, epsilon = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64)
                                                for a in (theta, psi, epsilon)))
    x = np.cos(epsilon) * np.sin(theta)
    y = np.sin(epsilon)
    z = -np.cos(epsilon) * np.cos(theta)
    return x, y * np.cos(psi) - z * np.sin(psi), y * np.sin(psi) + z * np.cos(psi)


def ground_point(altitude_km, theta, psi=0.0, epsilon=0.0, curved_earth=True):
    """The 3-D ground point (km) a look ray hits.

    Parameters
    ----------
    altitude_km : float
        The platform's altitude.
    theta : float or ndarray
        Scan angle (radians), across track.
    psi : float, optional
        Pitch (radians), along track.
    epsilon : float or ndarray, optional
        A further turn about the along-track axis (radians), e.g. the scan's own spread.
    curved_earth : bool, optional
        A sphere of radius ``EARTH_RADIUS_KM`` centred at the origin (default), or the flat
        ground z = 0.

    Returns
    -------
    tuple of ndarray
        ``(x, y, z)`` km: across, along, up.

    Raises
    ------
    ModelError
        If the ray points at or above the horizon (flat) or misses the Earth (curved).
    """
    ux, uy, uz = _look_vector(theta, psi, epsilon)
    if not curved_earth:
        if np.any(uz >= 0):
            raise ModelError(_("the look direction does not reach a flat ground (it points at "
                               "or above the horizon)"))
        t = altitude_km / -uz
        return t * ux, t * uy, np.zeros_like(t)
    height = EARTH_RADIUS_KM + altitude_km
    b = height * -uz
    disc = b ** 2 - (height ** 2 - EARTH_RADIUS_KM ** 2)
    if np.any(disc < 0) or np.any(b <= 0):
        raise ModelError(_("the look direction misses the Earth: scan plus roll angle "
                           "is beyond the horizon ({degrees:.2f}° from {altitude_km:g} "
                           "km)").format(
                degrees=prose_number(np.degrees(np.arcsin(EARTH_RADIUS_KM / height))),
                altitude_km=prose_number(altitude_km)))
    t = b - np.sqrt(disc)
    return t * ux, t * uy, height + t * uz


def _surface_distance(p, q, curved_earth=True):
    """Distance (km) along the ground between two points from :func:`ground_point`."""
    chord = np.sqrt(sum((a - b) ** 2 for a, b in zip(p, q)))
    if not curved_earth:
        return chord
    return 2 * EARTH_RADIUS_KM * np.arcsin(np.minimum(chord / (2 * EARTH_RADIUS_KM), 1.0))


def orbit_coordinates(point):
    """A ground point's (across, along) km in the orbit's grid: R·asin(x/R), R·atan2(y, z).

    Parameters
    ----------
    point : tuple of ndarray
        ``(x, y, z)`` km on the sphere, as :func:`ground_point` gives it.

    Returns
    -------
    tuple of ndarray
        ``(across, along)`` km along the Earth's surface.
    """
    x, y, z = point
    return EARTH_RADIUS_KM * np.arcsin(x / EARTH_RADIUS_KM), EARTH_RADIUS_KM * np.arctan2(y, z)


def attitude_displacement(angle_deg, altitude_km, curved_earth=True, scan_angle_deg=0.0,
                          axis="roll"):
    """Ground shift (km) of the point seen at a scan angle when the platform rolls or pitches.

    A **roll** turns the platform about the along-track axis, the axis the scan
    mirror turns about: it adds ``angle_deg`` to every scan angle, so the
    point seen at scan angle θ moves across track from d(θ) to d(θ + angle),
    with d of :func:`ground_distance`. That is h·tan(angle) only at nadir:
    towards the swath edge the same roll moves the ground more (0.1° from
    705 km: 1.23 km at nadir, about 6.0 km at 55° on a curved Earth, 3.75 km
    on a flat one).

    A **pitch** turns the platform about the across-track axis: the ray seen
    at scan angle θ swings along track, by h·tan(angle) on a flat Earth at
    every θ and a little more towards the edge on a curved one.

    Parameters
    ----------
    angle_deg : float or ndarray
        Roll or pitch angle (degrees); its sign gives the displacement's.
    altitude_km : float
    curved_earth : bool
    scan_angle_deg : float or ndarray
        Where in the swath (0, the default, is nadir).
    axis : {"roll", "pitch"}

    Returns
    -------
    float or ndarray
        km, across track for a roll, along track for a pitch.

    Raises
    ------
    ValueError
        For an unknown axis, or angles that look beyond the horizon.

    Examples
    --------
    >>> round(float(attitude_displacement(0.1, 705.0)), 2)             # nadir
    1.23
    >>> round(float(attitude_displacement(0.1, 705.0, scan_angle_deg=55.0)), 1)
    6.0
    >>> round(float(attitude_displacement(0.1, 705.0, False, 55.0)), 2)
    3.75
    """
    if axis not in ("roll", "pitch"):
        raise RsgeoError(_("axis must be 'roll' or 'pitch', got {axis!r}").format(axis=axis))
    angle = np.asarray(angle_deg, dtype=np.float64)
    scan = np.asarray(scan_angle_deg, dtype=np.float64)
    if axis == "roll":
        _check_scan(scan + angle, altitude_km)
        return (ground_distance(scan + angle, altitude_km, curved_earth)
                - ground_distance(scan, altitude_km, curved_earth))
    theta = _check_scan(scan, altitude_km)
    before = ground_point(altitude_km, theta, 0.0, curved_earth=curved_earth)
    after = ground_point(altitude_km, theta, np.radians(angle), curved_earth=curved_earth)
    return np.sign(angle) * _surface_distance(before, after, curved_earth)


def scan_footprint(scan_angle_deg, altitude_km, detectors=10, nadir_pixel_km=1.0,
                   curved_earth=True):
    """Along-track length (km) of the ground one whiskbroom scan covers at a scan angle.

    MODIS records ``detectors`` lines per turn of its scan mirror (10 for the
    1 km bands); the detectors sit side by side along track, each seeing
    β = nadir pixel / h. The scan's footprint runs from the first detector's
    outer edge to the last one's: ``detectors × nadir_pixel_km`` at nadir,
    longer towards the edge, like the along-track pixel of :func:`pixel_size`.

    Parameters
    ----------
    scan_angle_deg : float or ndarray
    altitude_km : float
    detectors : int
        Detectors along track (lines per scan).
    nadir_pixel_km : float
    curved_earth : bool

    Returns
    -------
    float or ndarray
        Footprint length along track, km.

    Raises
    ------
    ValueError
        For a non-positive detector count or pixel, or a scan angle beyond the horizon.

    Examples
    --------
    >>> round(float(scan_footprint(0.0, 705.0)), 2), round(float(scan_footprint(55.0, 705.0)), 1)
    (10.0, 20.1)
    """
    if int(detectors) != detectors or detectors < 1:
        raise RsgeoError(_("detectors must be a positive whole number, got {detectors!r}").format(
                detectors=detectors))
    as_number(nadir_pixel_km, "nadir_pixel_km", low=1e-12, why=N_("a size"))
    theta = _check_scan(scan_angle_deg, altitude_km)
    half = detectors * nadir_pixel_km / altitude_km / 2
    first = ground_point(altitude_km, theta, epsilon=-half, curved_earth=curved_earth)
    last = ground_point(altitude_km, theta, epsilon=half, curved_earth=curved_earth)
    return _surface_distance(first, last, curved_earth)


def bowtie_overlap(scan_angle_deg, altitude_km, detectors=10, nadir_pixel_km=1.0,
                   curved_earth=True):
    """Fraction of a scan's footprint that the next scan covers again: the MODIS bow-tie effect.

    The platform advances one nadir footprint (``detectors × nadir_pixel_km``)
    per scan, so successive scans abut at nadir; away from nadir each
    footprint (:func:`scan_footprint`) is longer than the advance and the
    scans overlap by 1 − advance / footprint.

    Parameters
    ----------
    scan_angle_deg, altitude_km, detectors, nadir_pixel_km, curved_earth
        As in :func:`scan_footprint`.

    Returns
    -------
    float or ndarray
        Overlap fraction, 0 (scans just touch) to 1.

    Raises
    ------
    ValueError
        As :func:`scan_footprint`.

    Examples
    --------
    >>> round(float(bowtie_overlap(55.0, 705.0)), 2)       # MODIS swath edge: about half
    0.5
    """
    footprint = scan_footprint(scan_angle_deg, altitude_km, detectors, nadir_pixel_km,
                               curved_earth)
    advance = scan_footprint(0.0, altitude_km, detectors, nadir_pixel_km, curved_earth)
    return np.maximum(0.0, 1.0 - advance / footprint)


def scan_edges(scan_index, scan_angle_deg, altitude_km, detectors=10, nadir_pixel_km=1.0,
               curved_earth=True):
    """Across-track position and along-track edges (km) of scan number ``scan_index``'s footprint.

    For drawing the bow-tie: scan k is centred k advances along track (one
    advance = the nadir footprint of :func:`scan_footprint`).

    Parameters
    ----------
    scan_index : int
        Scan number, 0 at the reference scan.
    scan_angle_deg, altitude_km, detectors, nadir_pixel_km, curved_earth
        As in :func:`scan_footprint`.

    Returns
    -------
    across_km, first_km, last_km : ndarray
        Ground distance from nadir (signed like the scan angle) and the
        footprint's two along-track edges, in the orbit-aligned grid
        (along = R·atan2(y, z) on a curved Earth).

    Raises
    ------
    ValueError
        As :func:`scan_footprint`.

    Examples
    --------
    >>> across, first, last = scan_edges(1, [0.0], 705.0)
    >>> round(float(first[0]), 2), round(float(last[0]), 2)
    (5.0, 15.0)
    """
    theta = _check_scan(scan_angle_deg, altitude_km)
    half = detectors * nadir_pixel_km / altitude_km / 2
    advance = scan_footprint(0.0, altitude_km, detectors, nadir_pixel_km, curved_earth)
    edges = []
    for epsilon in (-half, half):
        point = ground_point(altitude_km, theta, epsilon=epsilon, curved_earth=curved_earth)
        edges.append(orbit_coordinates(point)[1] if curved_earth else point[1])
    across = ground_distance(np.degrees(theta), altitude_km, curved_earth)
    return across, scan_index * advance + edges[0], scan_index * advance + edges[1]


# --------------------------------------------------------------------------
# The forward simulator and its exact correction
