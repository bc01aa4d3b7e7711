"""Systematic distortions combined into one model between pixel grids, its forward simulation and
its exact correction (chapter 1's "Remoção de erros sistemáticos").
"""

import warnings
from dataclasses import dataclass, replace

import numpy as np

from ..distortion import EARTH_RADIUS_KM, ground_point, orbit_coordinates
from ..errors import GridError, ModelError, RsgeoError
from ..language import N_, _, prose_number
from ..resample import grid_positions, interpolate
from ..transforms import GeometricModel, InverseModel
from ..validation import as_number, as_points, as_shape

__all__ = ["SystematicDistortion", "simulate", "correct", "distorted_grid"]




# its Parameters are the dataclass's fields, which numpydoc's AST reading does not see
@dataclass
class SystematicDistortion(GeometricModel):  # numpydoc ignore=PR02
    """A combination of systematic distortions, as a mapping between pixel grids.

    Rows are along track (line by line in time), columns across track; the
    centre of a grid of ``shape`` is nadir. It follows rsgeo's mapping
    protocol: ``distortion(points)`` maps (col, row) positions on the true
    (corrected) grid to where the distorted image records them, and
    ``distortion.inverse()`` maps recorded positions back to the true grid
    (the systematic correction), solved exactly; ``residuals(src, dst)`` as
    every model has.

    Parameters
    ----------
    skew_per_line : float
        Earth rotation: columns of offset per line (the km offset of
        :func:`~rsgeo.distortion.earth_rotation_skew` divided by pixel size and line count).
        Positive: each line's ground lies this much further towards column 0
        (west, on a descending pass shown north up) than the previous line's,
        so the recorded image shows features sliding towards higher columns.
    scale : float
        Altitude change: h / h_nominal; above 1 the sensor sees more ground
        per pixel, so the image shrinks.
    roll_px, pitch_px : float
        Attitude, in instantaneous fields of view (nadir pixels of angle): the
        recorded content moves towards higher columns (roll) or rows (pitch).
        Without view geometry this is a uniform shift of the whole image, the
        narrow-field approximation; with view geometry the angle is applied in
        scan-angle space, so a roll moves the ground more towards the swath
        edge (:func:`~rsgeo.distortion.attitude_displacement`).
    yaw_deg : float
        Constant yaw: rotation of the image about nadir.
    yaw_rate_deg_per_line : float
        Varying yaw: the rotation grows line by line (the lecture's "Yaw - var.").
    view_altitude_km, nadir_pixel_km : float or None
        Wide field of view: when given, columns are scan angles of equal
        steps (nadir pixel / altitude), so pixels away from nadir cover more
        ground (the panoramic distortion on a curved Earth). The true grid is
        then the orbit-aligned ground grid of :func:`~rsgeo.distortion.scan_edges` in nadir pixels.
    roll_deg, pitch_deg : float
        Attitude in degrees, added to ``roll_px`` and ``pitch_px``; they need
        the view geometry (the altitude turns an angle into ground).
    shape : (rows, cols), optional
        The grid whose centre is nadir; needed to map points
        (:meth:`on_grid` sets it). :func:`simulate` and :func:`correct` use
        the image's shape.

    Raises
    ------
    ValueError
        For a non-positive scale, only one of the two view-geometry values,
        an attitude in degrees without view geometry, or a shape that is not
        two positive whole numbers.

    Examples
    --------
    >>> drift = SystematicDistortion(yaw_rate_deg_per_line=0.05, shape=(300, 300))
    >>> recorded = drift([[10.0, 200.0]])
    >>> drift.inverse()(recorded).round(9) + 0.0
    array([[ 10., 200.]])
    """

    skew_per_line: float = 0.0
    scale: float = 1.0
    roll_px: float = 0.0
    pitch_px: float = 0.0
    yaw_deg: float = 0.0
    yaw_rate_deg_per_line: float = 0.0
    view_altitude_km: float = None
    nadir_pixel_km: float = None
    roll_deg: float = 0.0
    pitch_deg: float = 0.0
    shape: tuple = None

    def __post_init__(self):
        as_number(self.scale, "scale", low=1e-6, why=N_("a ratio of altitudes"))
        if self.shape is not None:
            self.shape = as_shape(self.shape)
        if (self.view_altitude_km is None) != (self.nadir_pixel_km is None):
            raise RsgeoError(_("view_altitude_km and nadir_pixel_km go together: give both or "
                               "neither"))
        if self.view_altitude_km is None and (self.roll_deg or self.pitch_deg):
            raise RsgeoError(_("roll_deg and pitch_deg need view_altitude_km and nadir_pixel_km "
                               "(an angle moves the ground by an amount that depends on the "
                               "altitude); without them give roll_px and pitch_px"))

    @property
    def _ifov(self):
        return self.nadir_pixel_km / self.view_altitude_km

    def attitude_rad(self):
        """Total (roll, pitch) in radians, with view geometry: degrees plus pixels × IFOV.

        Returns
        -------
        roll, pitch : float
            Radians.
        """
        if self.view_altitude_km is None:
            raise RsgeoError(_("attitude in radians needs view_altitude_km and nadir_pixel_km"))
        return (np.radians(self.roll_deg) + self.roll_px * self._ifov,
                np.radians(self.pitch_deg) + self.pitch_px * self._ifov)

    def with_knowledge_errors(self, roll_deg=0.0, pitch_deg=0.0, yaw_deg=0.0, across_km=0.0,
                              along_km=0.0, radial_km=0.0):
        """The model a ground station would use: this one, its platform data off by these errors.

        Attitude errors add to the angles; ephemeris (position) errors across
        and along track act, near nadir, as a roll or pitch of position / h
        and are folded into them; an altitude error changes the scale by
        (h + radial) / h.

        Parameters
        ----------
        roll_deg, pitch_deg, yaw_deg : float
            Attitude knowledge errors, degrees.
        across_km, along_km, radial_km : float
            Ephemeris knowledge errors, km.

        Returns
        -------
        SystematicDistortion

        Raises
        ------
        ValueError
            Without view geometry (an angle or a position needs the altitude).

        Examples
        --------
        >>> true = SystematicDistortion(view_altitude_km=778.0, nadir_pixel_km=0.01)
        >>> known = true.with_knowledge_errors(roll_deg=0.01)
        >>> round(known.roll_deg, 3)
        0.01
        """
        if self.view_altitude_km is None:
            raise RsgeoError(_("knowledge errors need view_altitude_km and nadir_pixel_km: the "
                               "altitude turns angles and positions into pixels"))
        height = self.view_altitude_km
        return replace(self,
                       roll_deg=float(self.roll_deg + roll_deg + np.degrees(across_km / height)),
                       pitch_deg=float(self.pitch_deg + pitch_deg + np.degrees(along_km / height)),
                       yaw_deg=float(self.yaw_deg + yaw_deg),
                       scale=float(self.scale * (height + radial_km) / height))

    def _yaw(self, rows_from_centre):
        return np.radians(self.yaw_deg + self.yaw_rate_deg_per_line * rows_from_centre)

    def on_grid(self, shape):
        """This distortion on a grid of ``shape`` (rows, cols), whose centre is nadir.

        Parameters
        ----------
        shape : (rows, cols)

        Returns
        -------
        SystematicDistortion
            A copy with ``shape`` set, ready to map points.

        Raises
        ------
        ValueError
            If the shape is not two positive whole numbers.
        """
        return replace(self, shape=as_shape(shape))

    def _grid(self):
        if self.shape is None:
            raise GridError(_("a SystematicDistortion maps points on a grid whose centre is "
                              "nadir: give shape=(rows, cols), or use distortion.on_grid(shape)"))
        return self.shape

    def __call__(self, points):
        """Distorted-image (col, row) of true-grid (col, row) positions.

        Parameters
        ----------
        points : (n, 2) array_like
            (col, row) on the true grid of ``shape``.

        Returns
        -------
        ndarray, shape (n, 2)
            Where the distorted image records them.

        Raises
        ------
        ValueError
            If the points are not (n, 2) finite numbers or ``shape`` is not set.
        """
        points = as_points(points)
        return np.column_stack(self._true_to_image(points[:, 0], points[:, 1], self._grid()))

    def inverse(self):
        """The systematic correction: true-grid (col, row) of distorted-image positions.

        The distortions are undone in reverse order; a varying yaw makes the
        rotation angle depend on the true row, solved by Newton's method per
        point and checked by mapping the answer forward again.

        Returns
        -------
        InverseModel
            Callable on (n, 2) recorded positions; raises ``ValueError`` for
            points where no true position maps there within 1e-6 pixel (a yaw
            rate so large that the distortion folds the grid over itself).

        Raises
        ------
        ValueError
            If ``shape`` is not set.
        """
        shape = self._grid()

        def solve(points):
            cols, rows = self._image_to_true(points[:, 0], points[:, 1], shape, strict=True)
            return np.column_stack([cols, rows])

        return InverseModel(self, solve)

    def _true_to_image(self, cols, rows, shape):
        """Distorted-image (col, row) of true-grid positions; shape = (rows, cols) of the grid."""
        centre_c, centre_r = shape[1] / 2, shape[0] / 2
        c, r = np.asarray(cols, float) - centre_c, np.asarray(rows, float) - centre_r
        angle = self._yaw(r)
        c, r = c * np.cos(angle) + r * np.sin(angle), -c * np.sin(angle) + r * np.cos(angle)
        c = c + self.skew_per_line * (r + centre_r)
        if self.view_altitude_km is None:
            c, r = c + self.roll_px, r + self.pitch_px
            return c / self.scale + centre_c, r / self.scale + centre_r
        c, r = c / self.scale, r / self.scale
        # ground (orbit-aligned grid) -> the scan angle and line that see it, on a sphere
        roll, pitch = self.attitude_rad()
        height = EARTH_RADIUS_KM + self.view_altitude_km
        alpha = c * self.nadir_pixel_km / EARTH_RADIUS_KM
        beta = np.arcsin(height * np.sin(-pitch) / (EARTH_RADIUS_KM * np.cos(alpha))) + pitch
        look = (EARTH_RADIUS_KM * np.sin(alpha), EARTH_RADIUS_KM * np.cos(alpha) * np.sin(beta),
                EARTH_RADIUS_KM * np.cos(alpha) * np.cos(beta) - height)
        theta = np.arcsin(look[0] / np.sqrt(sum(v ** 2 for v in look)))
        r = r - EARTH_RADIUS_KM * beta / self.nadir_pixel_km
        c = (theta + roll) / self._ifov
        return c + centre_c, r + centre_r

    def _image_to_true(self, cols, rows, shape, strict=True):
        """Inverse of ``_true_to_image`` on arrays of any shape.

        With ``strict``, raise where no true position maps onto the input;
        otherwise return NaN there.
        """
        centre_c, centre_r = shape[1] / 2, shape[0] / 2
        image_c, image_r = np.asarray(cols, float), np.asarray(rows, float)
        c, r = image_c - centre_c, image_r - centre_r
        if self.view_altitude_km is not None:
            roll, pitch = self.attitude_rad()
            point = ground_point(self.view_altitude_km, c * self._ifov - roll, -pitch)
            across, along = orbit_coordinates(point)
            c, r = across / self.nadir_pixel_km, r + along / self.nadir_pixel_km
            c, r = c * self.scale, r * self.scale
        else:
            c, r = c * self.scale, r * self.scale
            c, r = c - self.roll_px, r - self.pitch_px
        c = c - self.skew_per_line * (r + centre_r)
        # Undo the yaw: (c, r) is the true position rotated by an angle that depends on the
        # true row r_t, so r_t solves g(r_t) = r_t - (c sin θ(r_t) + r cos θ(r_t)) = 0.
        c_rot, r_rot = c, r
        r_true = np.array(r_rot, dtype=float, copy=True)
        rate = np.radians(self.yaw_rate_deg_per_line)
        for _iteration in range(60):
            angle = self._yaw(r_true)
            g = r_true - (c_rot * np.sin(angle) + r_rot * np.cos(angle))
            slope = 1 - rate * (c_rot * np.cos(angle) - r_rot * np.sin(angle))
            slope = np.where(np.abs(slope) < 1e-12, 1e-12, slope)
            r_true = r_true - g / slope
            if np.all(np.abs(g) < 1e-11 * (1 + np.abs(r_true))):
                break
        angle = self._yaw(r_true)
        c_true = c_rot * np.cos(angle) - r_rot * np.sin(angle)
        c_true, r_true = c_true + centre_c, r_true + centre_r
        # the answer must map forward onto the input, and be the only one that does
        back_c, back_r = self._true_to_image(c_true, r_true, shape)
        wrong = ~(np.hypot(back_c - image_c, back_r - image_r) < 1e-6)
        wrong = wrong | _yaw_roots(c_rot, r_rot, np.radians(self.yaw_deg), rate) > 1
        if wrong.any():
            if strict:
                index = np.flatnonzero(np.ravel(wrong))[0]
                first = [float(np.ravel(image_c)[index]), float(np.ravel(image_r)[index])]
                raise ModelError(
                    _("{value} of {wrong_size} recorded points (first: {first}) have no "
                      "single true position: the inverse did not converge, or several "
                      "true positions map there. A yaw rate of "
                      "{yaw_rate_deg_per_line}°/line turns the lines so fast that the "
                      "grid folds over itself beyond {value2:.3g} px from nadir; use a "
                      "smaller rate or points nearer nadir").format(
                        value=int(wrong.sum()), wrong_size=wrong.size, first=first,
                        yaw_rate_deg_per_line=self.yaw_rate_deg_per_line,
                        value2=prose_number(1 / max(abs(rate), 1e-300))))
            c_true, r_true = np.where(wrong, np.nan, c_true), np.where(wrong, np.nan, r_true)
        return c_true, r_true


def _yaw_roots(c_rot, r_rot, yaw, rate):
    """How many true rows r solve r = ρ cos(yaw + rate·r - φ) for a yaw-rotated (c_rot, r_rot).

    The varying yaw's inverse is unique where |rate|·ρ < 1 (ρ = the distance
    from nadir): there the equation's left side grows faster than its right.
    Elsewhere its roots, all within [-ρ, ρ], are counted by sign changes on a
    grid finer than the cosine's period.
    """
    c_rot, r_rot = np.broadcast_arrays(np.asarray(c_rot, float), np.asarray(r_rot, float))
    radius = np.hypot(c_rot, r_rot)
    counts = np.ones(radius.shape, dtype=int)
    folded = np.abs(rate) * radius >= 1
    if not folded.any():
        return counts
    rho, phi = radius[folded], np.arctan2(c_rot[folded], r_rot[folded])
    samples = int(np.ceil(16 * np.abs(rate) * rho.max() / np.pi)) + 33
    found = np.empty(rho.size, dtype=int)
    for start in range(0, rho.size, 4096):
        part = slice(start, start + 4096)
        r = rho[part, None] * np.linspace(-1, 1, samples)[None, :]
        g = r - rho[part, None] * np.cos(yaw + rate * r - phi[part, None])
        found[part] = np.count_nonzero(np.diff(np.sign(g), axis=1) != 0, axis=1)
    counts[folded] = found
    return counts


def _on_image_grid(distortion, shape):
    """``distortion`` on the image's grid; refuse a distortion set for another grid."""
    if not isinstance(distortion, SystematicDistortion):
        raise TypeError(_("distortion must be a SystematicDistortion, got {kind}").format(
                kind=type(distortion).__name__))
    if distortion.shape is not None and tuple(distortion.shape) != tuple(shape):
        raise GridError(_("the distortion is set on a {distortion_shape} grid but the "
                          "image is {shape}; use distortion.on_grid(image.shape[-2:])").format(
                distortion_shape=distortion.shape, shape=tuple(shape)))
    return distortion.on_grid(shape)


def simulate(image, distortion, method="bilinear", nodata=0):
    """Apply a systematic distortion to an image: what the sensor would record.

    Each recorded cell asks the distortion's inverse where on the true ground
    it looks, and interpolates the true image there.

    Parameters
    ----------
    image : ndarray
        The true scene, 2-D or bands first.
    distortion : SystematicDistortion
        Its grid is the image's (its ``shape``, if set, must match).
    method : {"nearest", "bilinear", "cubic"}
        Interpolator (:func:`rsgeo.resample.interpolate`).
    nodata : number
        Value of cells that see ground outside the scene.

    Returns
    -------
    ndarray
        Same shape and dtype; cells that see ground outside the scene get
        nodata, and so do cells where the inverse does not exist (a warning
        says how many).

    Raises
    ------
    ValueError
        If the distortion is not a :class:`SystematicDistortion` or is set on
        another grid, or as :func:`rsgeo.resample.interpolate`.

    Warns
    -----
    RuntimeWarning
        When some recorded cells have no true position (a yaw rate that folds the grid).
    """
    shape = np.shape(image)[-2:]
    distortion = _on_image_grid(distortion, shape)
    cols, rows = grid_positions(shape)
    true_c, true_r = distortion._image_to_true(cols, rows, shape, strict=False)
    lost = ~np.isfinite(true_c)
    if lost.any():
        warnings.warn(f"{int(lost.sum())} of {lost.size} recorded cells have no true position "
                      "(the distortion folds the grid over itself there); they get nodata",
                      RuntimeWarning, stacklevel=2)
        true_c, true_r = np.where(lost, -1.0, true_c), np.where(lost, -1.0, true_r)
    return interpolate(image, true_c, true_r, method, nodata)


def correct(distorted, distortion, method="bilinear", nodata=0):
    """The systematic correction: resample the distorted image back onto the true grid.

    Each true-grid cell asks the known model where the sensor recorded it
    (``distortion(points)``) and interpolates there.

    Parameters
    ----------
    distorted : ndarray
        The recorded image, 2-D or bands first.
    distortion : SystematicDistortion
        The model of the distortion (exact, or known with errors); its grid is
        the image's.
    method : {"nearest", "bilinear", "cubic"}
    nodata : number
        Value of true cells recorded outside the image.

    Returns
    -------
    ndarray
        Same shape and dtype.

    Raises
    ------
    ValueError
        As :func:`simulate`.
    """
    shape = np.shape(distorted)[-2:]
    distortion = _on_image_grid(distortion, shape)
    cols, rows = grid_positions(shape)
    image_c, image_r = distortion._true_to_image(cols, rows, shape)
    return interpolate(distorted, image_c, image_r, method, nodata)


def distorted_grid(distortion, shape, step=32):
    """Lines of the true grid drawn where the distorted image records them (for plots).

    Parameters
    ----------
    distortion : SystematicDistortion
    shape : (rows, cols)
        The true grid.
    step : float
        Spacing of the grid lines, pixels.

    Returns
    -------
    list of (cols, rows) arrays
        One per grid line, rows first then columns.

    Raises
    ------
    ValueError
        As :func:`simulate`.
    """
    distortion = _on_image_grid(distortion, shape)
    lines = []
    for r in np.arange(0, shape[0] + 1, step):
        c = np.linspace(0, shape[1], 200)
        lines.append(distortion._true_to_image(c, np.full_like(c, r), shape))
    for c in np.arange(0, shape[1] + 1, step):
        r = np.linspace(0, shape[0], 200)
        lines.append(distortion._true_to_image(np.full_like(r, c), r, shape))
    return lines
