"""Relief displacement: where planar models stop.

Every model of the georeferencing chapters maps a plane to a plane. The ground
has height: a point at elevation h seen at view zenith angle θ lands
h·tan θ away from where a point at the datum would (:func:`relief_displacement`);
on a vertical frame photograph a point r millimetres from the centre moves
r·h / H (:func:`relief_displacement_photo`). No polynomial in (x, y) removes
that, because the displacement depends on h, which (x, y) do not give.

:func:`occluded` finds the ground that buildings and trees hide from an oblique view.
"""

import numpy as np

from .errors import RsgeoError
from .language import _, prose_number
from .validation import (
    as_broadcast,
    as_finite,
    as_number,
    few_values,
)

__all__ = ["relief_displacement", "relief_displacement_photo", "height_error_budget", "occluded"]



def relief_displacement(height_m, view_zenith_deg):
    """Horizontal displacement of a point at height h seen at view zenith θ: h·tan θ.

    Parameters
    ----------
    height_m : float or array_like
        Height above the datum the image was mapped to (m); negative below it.
    view_zenith_deg : float or array_like
        Angle between the line of sight and the vertical at the ground, in
        degrees, from 0 (nadir) to below 90.

    Returns
    -------
    float or ndarray
        Displacement in metres, away from the nadir for a positive height.

    Raises
    ------
    ValueError
        If an angle is outside [0, 90) or a value is not finite.

    Examples
    --------
    >>> round(float(relief_displacement(500.0, 8.2)), 1)   # Landsat's swath edge
    72.1
    >>> round(float(relief_displacement(100.0, 45.0)), 6)
    100.0
    """
    height, angle = as_broadcast([as_finite(height_m, "height_m"),
                                  as_finite(view_zenith_deg, "view_zenith_deg")],
                                 ["height_m", "view_zenith_deg"])
    if np.any((angle < 0) | (angle >= 90)):
        raise RsgeoError(_("view_zenith_deg must be in [0, 90) degrees (0 = nadir), got "
                           "{few}").format(few=few_values(angle[(angle < 0) | (angle >= 90)])))
    result = height * np.tan(np.radians(angle))
    return float(result) if result.ndim == 0 else result


def relief_displacement_photo(height_m, radial_distance_mm, flying_height_m):
    """Relief displacement on a vertical frame photograph: d = r·h / H.

    Parameters
    ----------
    height_m : float or array_like
        Height of the point above the datum (m).
    radial_distance_mm : float or array_like
        Distance of the point's image from the photo's principal point (mm).
    flying_height_m : float
        Flying height above the datum (m); must be above every height.

    Returns
    -------
    float or ndarray
        Displacement on the photo in mm, radial (outwards for h > 0). Times
        the scale number (H / focal length) it is metres on the ground.

    Raises
    ------
    ValueError
        If a value is not finite, the radial distance is negative, or the
        flying height is not above every height.

    Examples
    --------
    >>> relief_displacement_photo(50.0, 100.0, 4500.0)   # 1:30,000 with a 150 mm lens
    1.1111111111111112
    """
    height, radius = as_broadcast([as_finite(height_m, "height_m"),
                                   as_finite(radial_distance_mm, "radial_distance_mm")],
                                  ["height_m", "radial_distance_mm"])
    flying = as_number(flying_height_m, "flying_height_m")
    if np.any(radius < 0):
        raise RsgeoError(_("radial_distance_mm must be >= 0 (a distance from the "
                           "principal point), got {few}").format(
                               few=few_values(radius[radius < 0])))
    if np.any(height >= flying):
        raise RsgeoError(_("flying_height_m ({flying:g} m) must be above every height; "
                           "got heights up to {value:g} m").format(
                flying=prose_number(flying), value=prose_number(float(np.max(height)))))
    result = radius * height / flying
    return float(result) if result.ndim == 0 else result


def height_error_budget(position_error_m, view_zenith_deg):
    """The largest DEM height error a horizontal position budget allows: Δh = Δx / tan θ.

    Parameters
    ----------
    position_error_m : float
        Allowed horizontal error (m), > 0.
    view_zenith_deg : float
        View zenith angle (degrees), in (0, 90).

    Returns
    -------
    float
        Height error (m) that moves a point by ``position_error_m``.

    Raises
    ------
    ValueError
        If the budget is not positive or the angle is not in (0, 90).

    Examples
    --------
    >>> round(height_error_budget(10.0, 30.0), 2)
    17.32
    """
    budget = as_number(position_error_m, "position_error_m")
    angle = as_number(view_zenith_deg, "view_zenith_deg")
    if budget <= 0:
        raise RsgeoError(_("position_error_m must be > 0, got {budget:g}").format(
                budget=prose_number(budget)))
    if not 0 < angle < 90:
        raise RsgeoError(_("view_zenith_deg must be in (0, 90) degrees (at nadir any "
                           "height error is allowed), got {angle:g}").format(
                angle=prose_number(angle)))
    return float(budget / np.tan(np.radians(angle)))


def occluded(distance_m, height_m, view_zenith_deg):
    """Which points of a surface profile the sensor cannot see: hidden behind higher ground.

    The profile runs away from the sensor (its first point is the nearest), in the plane of
    the lines of sight, which are parallel (a satellite is far away) and lean
    ``view_zenith_deg`` from the vertical. A point is hidden when the line from it towards the
    sensor passes below the surface somewhere nearer the sensor: at a point j nearer than i,
    that line is (d_i - d_j) / tan θ above h_i, so i is hidden if h_j + d_j / tan θ >
    h_i + d_i / tan θ for some j < i, a running maximum. Between the samples the surface is
    taken as straight, for which testing the samples is exact. On a DSM (buildings, tree
    canopy) the hidden ground behind each building is what an orthoimage cannot show: a DTM
    orthoimage leans each roof over it by h·tan θ (:func:`relief_displacement`); a "true
    orthoimage" needs the DSM and another view for the hidden part.

    Parameters
    ----------
    distance_m : (n,) array_like
        Horizontal distance of each point along the profile (m), strictly increasing away
        from the sensor.
    height_m : (n,) array_like
        Surface height at each point (m).
    view_zenith_deg : float
        View zenith angle of the lines of sight, in [0, 90) degrees.

    Returns
    -------
    ndarray of bool
        True where the point is hidden (0 is seen at nadir: nothing hides).

    Raises
    ------
    ValueError
        If the arrays are not 1-D of the same length, hold NaN, the distances do not
        increase, or the angle is outside [0, 90).

    Examples
    --------
    A 10 m wall at 45°: it hides the next 10 m of ground behind it.

    >>> d = np.arange(0.0, 30.0, 2.0)
    >>> h = np.where(d == 10.0, 10.0, 0.0)
    >>> d[occluded(d, h, 45.0)].tolist()
    [12.0, 14.0, 16.0, 18.0]
    """
    distance = as_finite(distance_m, "distance_m")
    height = as_finite(height_m, "height_m")
    angle = as_number(view_zenith_deg, "view_zenith_deg")
    if distance.ndim != 1 or distance.shape != height.shape:
        raise RsgeoError(_("distance_m and height_m must be 1-D of the same length, got "
                           "shapes {a} and {b}").format(a=distance.shape, b=height.shape))
    if distance.size > 1 and not (np.diff(distance) > 0).all():
        raise RsgeoError(_("distance_m must increase strictly, away from the sensor; reverse "
                           "both arrays if the sensor is at the profile's other end"))
    if not 0 <= angle < 90:
        raise RsgeoError(_("view_zenith_deg must be in [0, 90) degrees, got {angle:g}").format(
            angle=angle))
    if angle == 0 or distance.size < 2:
        return np.zeros(distance.shape, dtype=bool)
    # a line of sight's height above its point, measured back at distance 0: what is in front
    # of a point hides it if it reaches above the point's line
    reach = height + distance / np.tan(np.radians(angle))
    in_front = np.maximum.accumulate(np.concatenate([[-np.inf], reach[:-1]]))
    return in_front > reach


