"""A frame camera, rigorously: interior and exterior orientation, the collinearity equations and
space resection from GCPs by least squares (chapter 4d).

A frame camera (an aerial mapping camera, a drone's camera) takes the whole image at one instant
from one point, the **projection centre** C = (X0, Y0, Z0): a ground point, its image and C lie on
one straight line. That is the collinearity condition.

Notes
-----
The conventions:

- **Object space**: a right-handed Cartesian system (X, Y, Z) in metres, such as a local
  tangent plane's east, north and up (:func:`rsgeo.local_frame.to_local_tangent_plane`). Map
  coordinates with heights are not Cartesian: taken as X, Y, Z, UTM's scale factor k stretches
  the ground and puts the projection centre about H (k - 1) too high, 0.4 m for a camera 3 km
  above Olinda, twice its standard deviation in chapter 4d's resection; convert GCPs into a
  tangent plane first, and the projection centre back.
- **Photo coordinates** (x, y) in millimetres, on the image plane, origin at the image's centre,
  x to the right (along the columns), y up (against the rows). The **interior orientation** puts
  the projection centre at the principal point (xp, yp) and the principal distance (the focal
  length) c above the image plane.
- **Pixels**: GDAL's (col, row), continuous, the image's top-left corner at (0, 0), so the centre
  of pixel ``image[r, c]`` is (c + 0.5, r + 0.5): col = cols / 2 + x / pitch and
  row = rows / 2 - y / pitch.
- **Rotation**: the photogrammetric ω-φ-κ sequence of Kraus (Photogrammetry, vol. 1, §2.1) and
  of the ASPRS Manual of Photogrammetry: R = R_ω R_φ R_κ, primary axis X (ω), secondary Y (φ),
  tertiary Z (κ), angles positive anticlockwise seen from the axis's positive end, and R turns
  image-space vectors into object space: X - X0 = λ R (x - xp, y - yp, -c). The ASPRS Manual's
  (and Wolf's) orientation matrix is its transpose, M = Rᵀ = M_κ M_φ M_ω. A vertical
  photograph has ω = φ = 0; κ is then the angle from the X axis (east) to the photo's x axis.

The collinearity equations, with (ΔX, ΔY, ΔZ) = (X - X0, Y - Y0, Z - Z0) and r_ij the elements
of R::

    x = xp - c (r11 ΔX + r21 ΔY + r31 ΔZ) / (r13 ΔX + r23 ΔY + r33 ΔZ)
    y = yp - c (r12 ΔX + r22 ΔY + r32 ΔZ) / (r13 ΔX + r23 ΔY + r33 ΔZ)

An optional radial lens distortion k1 (per mm²) moves the point away from the principal point:
x_d - xp = (x - xp)(1 + k1 ρ²), the same for y, with ρ the ideal point's distance from (xp, yp).

On a plane Z = h the equations are a plane homography, the 8-parameter projective model of
chapter 3b (:meth:`FrameCamera.homography`); off the plane, relief moves a point radially by
d = r·h/H on a vertical photograph (:func:`rsgeo.relief.relief_displacement_photo`), which no
plane-to-plane model can follow.

References
----------
Kraus, K. (2007). Photogrammetry: Geometry from Images and Laser Scans, 2nd ed., vol. 1,
de Gruyter, §2.1 (rotations), §4.1 (space resection).
McGlone, J. C. (ed.) (2013). Manual of Photogrammetry, 6th ed., ASPRS (collinearity, resection).
Wolf, P. R., Dewitt, B. A., Wilkes, B. E. (2014). Elements of Photogrammetry with Applications
in GIS, 4th ed., McGraw-Hill, appendices C and D (the rotation matrix, the linearised
collinearity equations, space resection).
Hartley, R., Zisserman, A. (2004). Multiple View Geometry in Computer Vision, 2nd ed.,
Cambridge University Press, §7.1 (the normalised direct linear transformation).

Examples
--------
>>> from rsgeo.sensors import ExteriorOrientation, FrameCamera, InteriorOrientation
>>> interior = InteriorOrientation(focal_mm=100.0, pixel_mm=0.01, size=(2000, 1500))
>>> camera = FrameCamera(interior, ExteriorOrientation(1000.0, 2000.0, 1500.0, 0, 0, 0))
>>> camera.project([[1000.0, 2000.0, 0.0], [1150.0, 2000.0, 0.0]]).tolist()  # 10 cm pixels
[[1000.0, 750.0], [2000.0, 750.0]]
"""

from dataclasses import dataclass

import numpy as np

from ..errors import GCPError, ModelError
from ..language import N_, _
from ..transforms import MatrixModel, fit_transform
from ..validation import (
    as_finite,
    as_integer,
    as_number,
    as_points,
    as_points_3d,
    few_values,
)

__all__ = ["PARAMETERS", "UNITS", "InteriorOrientation", "ExteriorOrientation", "FrameCamera",
           "Resection", "rotation_matrix", "angles_from_rotation", "resect"]

#: The exterior orientation's parameters, in the order of every vector and covariance matrix.
PARAMETERS = ("X0", "Y0", "Z0", "omega", "phi", "kappa")
#: Their units: the projection centre in metres, the angles in degrees.
UNITS = ("m", "m", "m", "°", "°", "°")

# derivatives of the elementary rotations: dR_ω/dω = G_X R_ω, and so on
_GENERATORS = (np.array([[0.0, 0, 0], [0, 0, -1], [0, 1, 0]]),
               np.array([[0.0, 0, 1], [0, 0, 0], [-1, 0, 0]]),
               np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 0]]))


def _elementary(omega, phi, kappa):
    """R_ω, R_φ, R_κ (radians), Kraus's elementary rotations about X, Y and Z."""
    co, so, cp, sp, ck, sk = (np.cos(omega), np.sin(omega), np.cos(phi), np.sin(phi),
                              np.cos(kappa), np.sin(kappa))
    return (np.array([[1.0, 0, 0], [0, co, -so], [0, so, co]]),
            np.array([[cp, 0, sp], [0, 1.0, 0], [-sp, 0, cp]]),
            np.array([[ck, -sk, 0], [sk, ck, 0], [0, 0, 1.0]]))


def rotation_matrix(omega_deg, phi_deg, kappa_deg):
    """The rotation R = R_ω R_φ R_κ from image space to object space (Kraus's ω-φ-κ).

    Parameters
    ----------
    omega_deg, phi_deg, kappa_deg : float
        The rotations about the X (primary), Y (secondary) and Z (tertiary) axes, in degrees.

    Returns
    -------
    ndarray, shape (3, 3)
        R; the ASPRS Manual's orientation matrix M is its transpose.

    Raises
    ------
    TypeError
        If an angle is not a number.
    rsgeo.errors.RsgeoError
        If an angle is not finite.

    Examples
    --------
    >>> rotation_matrix(0, 0, 90).round(12) + 0.0      # x axis of the photo towards north
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    angles = [np.radians(as_number(value, name)) for value, name in
              ((omega_deg, "omega_deg"), (phi_deg, "phi_deg"), (kappa_deg, "kappa_deg"))]
    r_omega, r_phi, r_kappa = _elementary(*angles)
    return r_omega @ r_phi @ r_kappa


def angles_from_rotation(rotation):
    """The ω, φ, κ (degrees) of a rotation R = R_ω R_φ R_κ: the inverse of
    :func:`rotation_matrix`.

    Parameters
    ----------
    rotation : (3, 3) array_like
        A rotation matrix (orthonormal, determinant +1).

    Returns
    -------
    tuple of float
        (omega, phi, kappa) in degrees, φ in [-90°, 90°], ω and κ in (-180°, 180°].

    Raises
    ------
    GCPError
        If the matrix is not 3 × 3, not finite, or not a rotation (to 1e-6).

    Examples
    --------
    >>> [round(a, 9) for a in angles_from_rotation(rotation_matrix(2.0, -1.5, 30.0))]
    [2.0, -1.5, 30.0]
    """
    matrix = np.asarray(rotation, dtype=np.float64)
    if (matrix.shape != (3, 3) or not np.isfinite(matrix).all()
            or not np.allclose(matrix @ matrix.T, np.eye(3), atol=1e-6)
            or np.linalg.det(matrix) < 0):
        raise GCPError(_("rotation must be a 3 × 3 rotation matrix (orthonormal, determinant "
                         "+1), got {matrix}").format(matrix=np.round(matrix, 6).tolist()))
    # r13 = sin φ, r23 = -sin ω cos φ, r33 = cos ω cos φ, r12 = -cos φ sin κ, r11 = cos φ cos κ
    phi = np.arcsin(np.clip(matrix[0, 2], -1.0, 1.0))
    omega = np.arctan2(-matrix[1, 2], matrix[2, 2])
    kappa = np.arctan2(-matrix[0, 1], matrix[0, 0])
    return tuple(float(np.degrees(a)) for a in (omega, phi, kappa))


@dataclass(frozen=True)
class InteriorOrientation:
    """A frame camera's interior orientation: the geometry inside the camera.

    What a camera calibration report gives: the principal distance (calibrated focal length),
    the principal point's offset from the image centre and the lens distortion, with the
    sensor's pixel pitch and size. Give the attributes as arguments, in this order.

    Attributes
    ----------
    focal_mm : float
        The principal distance c (mm), > 0.
    pixel_mm : float
        The pixel pitch (mm), square pixels, > 0.
    size : (int, int)
        The image's (cols, rows), GDAL's (width, height).
    principal_point_mm : (float, float)
        The principal point (xp, yp) in photo coordinates (mm from the image centre, x right,
        y up).
    k1 : float
        Radial distortion (per mm²): x_d - xp = (x - xp)(1 + k1 ρ²); 0 for none.

    Raises
    ------
    TypeError
        If a value is not a number.
    rsgeo.errors.RsgeoError
        If the focal length or the pitch is not positive, or the size is not two positive
        integers.
    rsgeo.errors.ModelError
        If k1 < 0 folds the distortion within the image: the distorted radius
        ρ (1 + k1 ρ²) stops growing before the farthest corner (k1 must be at least
        -4 / (27 R²), R the corner's distance from the principal point in mm).

    Examples
    --------
    >>> interior = InteriorOrientation(100.0, 0.006, (8000, 6000))
    >>> interior.focal_px, interior.to_photo([[4000.0, 3000.0]]).tolist()
    (16666.666666666668, [[0.0, 0.0]])
    """

    focal_mm: float
    pixel_mm: float
    size: tuple
    principal_point_mm: tuple = (0.0, 0.0)
    k1: float = 0.0

    def __post_init__(self):
        set_ = object.__setattr__                   # frozen: the checked values replace the given
        set_(self, "focal_mm", as_number(self.focal_mm, "focal_mm", low=0.0))
        set_(self, "pixel_mm", as_number(self.pixel_mm, "pixel_mm", low=0.0))
        if not (self.focal_mm > 0 and self.pixel_mm > 0):
            raise GCPError(_("focal_mm and pixel_mm must be positive lengths in mm, got {f} and "
                             "{p}").format(f=self.focal_mm, p=self.pixel_mm))
        if np.ndim(self.size) != 1 or len(self.size) != 2:
            raise GCPError(_("size must be the image's (cols, rows), got {size!r}").format(
                size=self.size))
        set_(self, "size", tuple(as_integer(v, name, low=1) for v, name in
                                 zip(self.size, ("size[0] (cols)", "size[1] (rows)"))))
        if np.ndim(self.principal_point_mm) != 1 or len(self.principal_point_mm) != 2:
            raise GCPError(_("principal_point_mm must be (xp, yp) in mm, got {pp!r}").format(
                pp=self.principal_point_mm))
        set_(self, "principal_point_mm", tuple(
            as_number(v, name) for v, name in zip(self.principal_point_mm,
                                                  ("principal_point_mm[0]",
                                                   "principal_point_mm[1]"))))
        set_(self, "k1", as_number(self.k1, "k1"))
        if self.k1 < 0 and self.fold_radius_mm * 2.0 / 3.0 <= self._corner_radius_mm():
            # ρ (1 + k1 ρ²) rises to (2/3) ρ* at ρ* = 1 / sqrt(-3 k1), then falls back to 0:
            # measured points beyond (2/3) ρ* have no undistorted position, and ground points
            # beyond ρ* land back inside the image, over others (10 mm off axis with
            # k1 = -0.01 per mm² lands on the principal point)
            raise ModelError(_(
                "the radial distortion k1 = {k1} per mm² folds within the image: the distorted "
                "radius rho (1 + k1 rho²) is largest, {largest:.4g} mm, at rho = {fold:.4g} mm "
                "and falls beyond it, but the image's corners are {corner:.4g} mm from the "
                "principal point; a calibrated lens is monotonic over its image, so k1 must be "
                ">= {least:.4g} here (check its unit: per mm², not per pixel² or per m²)").format(
                    k1=self.k1, largest=self.fold_radius_mm * 2.0 / 3.0,
                    fold=self.fold_radius_mm, corner=self._corner_radius_mm(),
                    least=-4.0 / (27.0 * self._corner_radius_mm() ** 2)))

    @property
    def fold_radius_mm(self):
        """The ideal radius where the radial distortion turns back, mm (inf where it does not).

        With k1 < 0 the distorted radius ρ (1 + k1 ρ²) is largest at ρ = 1 / sqrt(-3 k1) and
        falls beyond it; the lens model holds only inside that radius.

        Returns
        -------
        float
        """
        return 1.0 / np.sqrt(-3.0 * self.k1) if self.k1 < 0 else np.inf

    def _corner_radius_mm(self):
        """The distance from the principal point to the farthest image corner, mm."""
        cols, rows = self.size
        xp, yp = self.principal_point_mm
        half_x, half_y = cols / 2 * self.pixel_mm, rows / 2 * self.pixel_mm
        return float(max(np.hypot(sx * half_x - xp, sy * half_y - yp)
                         for sx in (-1, 1) for sy in (-1, 1)))

    @property
    def focal_px(self):
        """The principal distance in pixels, c / pitch.

        Returns
        -------
        float
        """
        return self.focal_mm / self.pixel_mm

    def to_photo(self, image_xy):
        """Photo coordinates (x, y) in mm of image positions (col, row), as measured.

        Parameters
        ----------
        image_xy : (n, 2) array_like
            GDAL's (col, row).

        Returns
        -------
        ndarray, shape (n, 2)
            (x, y) in mm from the image centre, x right, y up (distortion not removed).

        Raises
        ------
        GCPError
            If the points are not (n, 2) finite numbers.
        """
        image_xy = as_points(image_xy, "image_xy")
        cols, rows = self.size
        return np.column_stack([(image_xy[:, 0] - cols / 2) * self.pixel_mm,
                                (rows / 2 - image_xy[:, 1]) * self.pixel_mm])

    def to_image(self, photo_xy):
        """Image positions (col, row) of photo coordinates (x, y) in mm: :meth:`to_photo`'s
        inverse.

        Parameters
        ----------
        photo_xy : (n, 2) array_like
            (x, y) in mm from the image centre, x right, y up.

        Returns
        -------
        ndarray, shape (n, 2)
            GDAL's (col, row).

        Raises
        ------
        GCPError
            If the points are not (n, 2) finite numbers.
        """
        photo_xy = as_points(photo_xy, "photo_xy")
        cols, rows = self.size
        return np.column_stack([cols / 2 + photo_xy[:, 0] / self.pixel_mm,
                                rows / 2 - photo_xy[:, 1] / self.pixel_mm])

    def _undistort(self, photo_xy):
        """(x - xp, y - yp) of the ideal (undistorted) points, from measured photo coordinates."""
        offset = photo_xy - np.asarray(self.principal_point_mm)
        if self.k1 == 0.0:
            return offset
        measured = np.hypot(offset[:, 0], offset[:, 1])
        ideal = measured.copy()
        for _step in range(50):                 # Newton on ρ (1 + k1 ρ²) = ρ_measured
            slope = 1.0 + 3.0 * self.k1 * ideal**2
            if (slope <= 0).any():
                raise ModelError(_("the radial distortion k1 = {k1} folds the image over "
                                   "itself at these points; they are beyond the lens's "
                                   "calibrated field").format(k1=self.k1))
            change = (ideal * (1.0 + self.k1 * ideal**2) - measured) / slope
            ideal -= change
            if np.abs(change).max() < 1e-13 * max(1.0, measured.max()):
                break
        ratio = np.divide(ideal, measured, out=np.ones_like(ideal), where=measured > 0)
        return offset * ratio[:, np.newaxis]


@dataclass(frozen=True)
class ExteriorOrientation:
    """A frame camera's exterior orientation: where the photo was taken and how it was turned.

    Give the attributes as arguments, in this order.

    Attributes
    ----------
    x0, y0, z0 : float
        The projection centre (m) in the object (ground) coordinates.
    omega, phi, kappa : float
        The ω-φ-κ rotation (degrees) of :func:`rotation_matrix`.

    Raises
    ------
    TypeError
        If a value is not a number.
    rsgeo.errors.RsgeoError
        If a value is not finite.

    Examples
    --------
    >>> ExteriorOrientation(500.0, 800.0, 3000.0, 1.0, -2.0, 45.0).as_array().tolist()
    [500.0, 800.0, 3000.0, 1.0, -2.0, 45.0]
    """

    x0: float
    y0: float
    z0: float
    omega: float
    phi: float
    kappa: float

    def __post_init__(self):
        for name in ("x0", "y0", "z0", "omega", "phi", "kappa"):
            object.__setattr__(self, name, as_number(getattr(self, name), name))

    @classmethod
    def from_array(cls, values):
        """An exterior orientation from the six values in ``PARAMETERS`` order.

        Parameters
        ----------
        values : array_like, shape (6,)
            X0, Y0, Z0 (m), omega, phi, kappa (degrees).

        Returns
        -------
        ExteriorOrientation

        Raises
        ------
        GCPError
            If there are not six values.
        """
        values = np.asarray(values, dtype=np.float64)
        if values.shape != (6,):
            raise GCPError(_("an exterior orientation has six values (X0, Y0, Z0, omega, phi, "
                             "kappa), got shape {shape}").format(shape=values.shape))
        return cls(*(float(v) for v in values))

    def as_array(self):
        """The six values in ``PARAMETERS`` order.

        Returns
        -------
        ndarray, shape (6,)
            X0, Y0, Z0 (m), omega, phi, kappa (degrees).
        """
        return np.array([self.x0, self.y0, self.z0, self.omega, self.phi, self.kappa])

    @property
    def centre(self):
        """The projection centre (X0, Y0, Z0), m.

        Returns
        -------
        ndarray, shape (3,)
        """
        return np.array([self.x0, self.y0, self.z0])

    def rotation(self):
        """R = R_ω R_φ R_κ, image space to object space (:func:`rotation_matrix`).

        Returns
        -------
        ndarray, shape (3, 3)
        """
        return rotation_matrix(self.omega, self.phi, self.kappa)


#: what the three columns of ground points are, for the messages
_GROUND = N_("X, Y, Z in metres")


def _collinearity(params, ground, interior, jacobian=False):
    """Image (col, row) of ``ground`` for params (X0, Y0, Z0, ω, φ, κ in radians); with the
    (n, 2, 6) analytic Jacobian. Also returns W, the depth term (< 0 in front of the camera)."""
    r_omega, r_phi, r_kappa = _elementary(*params[3:])
    rotation = r_omega @ r_phi @ r_kappa
    delta = ground - params[:3]
    u = delta @ rotation                          # rows: Rᵀ (P - C) = M (P - C) = (U, V, W)
    big_u, big_v, w = u[:, 0], u[:, 1], u[:, 2]
    c = interior.focal_mm
    with np.errstate(divide="ignore", invalid="ignore"):
        a, b = -c * big_u / w, -c * big_v / w     # ideal (x - xp, y - yp), mm
    factor = 1.0 + interior.k1 * (a**2 + b**2)
    xp, yp = interior.principal_point_mm
    cols, rows = interior.size
    pitch = interior.pixel_mm
    image = np.column_stack([cols / 2 + (xp + a * factor) / pitch,
                             rows / 2 - (yp + b * factor) / pitch])
    if not jacobian:
        return image, w, None
    derivatives = (_GENERATORS[0] @ rotation, r_omega @ _GENERATORS[1] @ r_phi @ r_kappa,
                   rotation @ _GENERATORS[2])
    du = np.empty((len(ground), 3, 6))
    du[:, :, :3] = -rotation.T                    # d(Rᵀ (P - C)) / dC
    for k, d_rotation in enumerate(derivatives):
        du[:, :, 3 + k] = delta @ d_rotation
    w2 = (w**2)[:, np.newaxis]
    da = -c * (du[:, 0] * w[:, np.newaxis] - big_u[:, np.newaxis] * du[:, 2]) / w2
    db = -c * (du[:, 1] * w[:, np.newaxis] - big_v[:, np.newaxis] * du[:, 2]) / w2
    k1 = interior.k1
    f, ab = factor[:, np.newaxis], (2 * k1 * a * b)[:, np.newaxis]
    d_col = ((f + 2 * k1 * (a**2)[:, np.newaxis]) * da + ab * db) / pitch
    d_row = -(ab * da + (f + 2 * k1 * (b**2)[:, np.newaxis]) * db) / pitch
    return image, w, np.stack([d_col, d_row], axis=1)


def _ideal_radius(exterior, ground, interior):
    """The undistorted distance (mm) of each ground point's image from the principal point."""
    params = _radians(exterior.as_array())
    r_omega, r_phi, r_kappa = _elementary(*params[3:])
    u = (ground - params[:3]) @ (r_omega @ r_phi @ r_kappa)
    with np.errstate(divide="ignore", invalid="ignore"):
        return interior.focal_mm * np.hypot(u[:, 0], u[:, 1]) / np.abs(u[:, 2])


def _radians(values):
    """Parameters with the angles (last three) from degrees to radians."""
    values = np.array(values, dtype=np.float64)
    values[3:] = np.radians(values[3:])
    return values


def _degrees(values):
    values = np.array(values, dtype=np.float64)
    values[3:] = np.degrees(values[3:])
    return values


class FrameCamera:
    """A frame camera: interior and exterior orientation, and the collinearity equations.

    Parameters
    ----------
    interior : InteriorOrientation
        The camera's geometry (focal length, principal point, pixel pitch, distortion).
    exterior : ExteriorOrientation
        Where the photo was taken and the camera's rotation.

    Raises
    ------
    TypeError
        If ``interior`` or ``exterior`` is not of its type.

    Examples
    --------
    >>> interior = InteriorOrientation(100.0, 0.01, (2000, 1500))
    >>> camera = FrameCamera(interior, ExteriorOrientation(0.0, 0.0, 1000.0, 0, 0, 0))
    >>> camera.ground_at_height([[1000.0, 750.0], [2000.0, 0.0]], 0.0).tolist()
    [[0.0, 0.0, 0.0], [100.0, 75.0, 0.0]]
    """

    def __init__(self, interior, exterior):
        if not isinstance(interior, InteriorOrientation):
            raise TypeError(_("interior must be an InteriorOrientation, got {kind}").format(
                kind=type(interior).__name__))
        if not isinstance(exterior, ExteriorOrientation):
            raise TypeError(_("exterior must be an ExteriorOrientation, got {kind}").format(
                kind=type(exterior).__name__))
        self.interior = interior
        self.exterior = exterior

    def __repr__(self):
        return f"FrameCamera({self.interior!r}, {self.exterior!r})"

    def project(self, ground):
        """The collinearity equations: image positions (col, row) of ground points (X, Y, Z).

        Parameters
        ----------
        ground : (n, 3) array_like
            Object coordinates (m).

        Returns
        -------
        ndarray, shape (n, 2)
            GDAL's (col, row); positions outside the image are returned too.

        Raises
        ------
        GCPError
            If ``ground`` is not (n, 3) finite numbers.
        ModelError
            If a point lies behind the camera or in the plane through the projection centre
            parallel to the image (it has no image).
        """
        ground = as_points_3d(ground, "ground", _GROUND)
        image, w, _none = _collinearity(_radians(self.exterior.as_array()), ground,
                                        self.interior)
        behind = ~(w < 0)
        if behind.any():
            raise ModelError(_("ground points {rows} lie behind the camera (or level with its "
                               "projection centre) and have no image").format(
                                   rows=np.flatnonzero(behind)[:5].tolist()))
        if self.interior.k1 < 0:
            ideal = _ideal_radius(self.exterior, ground, self.interior)
            folded = ideal >= self.interior.fold_radius_mm
            if folded.any():
                raise ModelError(_(
                    "ground points {rows} are {ideal} mm off axis in the photo, beyond the "
                    "{fold:.4g} mm where the radial distortion k1 = {k1} turns back: their "
                    "image would land inside the frame, over other points; they are outside "
                    "the lens's field").format(
                        rows=np.flatnonzero(folded)[:5].tolist(),
                        ideal=few_values(ideal[folded]), fold=self.interior.fold_radius_mm,
                        k1=self.interior.k1))
        return image

    def jacobian(self, ground):
        """Derivatives of the image positions by the exterior orientation, analytically.

        Parameters
        ----------
        ground : (n, 3) array_like
            Object coordinates (m).

        Returns
        -------
        ndarray, shape (n, 2, 6)
            d(col, row) / d(X0, Y0, Z0, omega, phi, kappa): pixels per metre for the projection
            centre, pixels per degree for the angles.

        Raises
        ------
        GCPError
            If ``ground`` is not (n, 3) finite numbers.
        """
        ground = as_points_3d(ground, "ground", _GROUND)
        _image, _w, jac = _collinearity(_radians(self.exterior.as_array()), ground,
                                        self.interior, jacobian=True)
        jac[:, :, 3:] *= np.pi / 180.0
        return jac

    def ground_at_height(self, image_xy, height):
        """Where the rays of image points meet the horizontal plane(s) Z = height (monoplotting).

        Parameters
        ----------
        image_xy : (n, 2) array_like
            GDAL's (col, row), as measured (the distortion is removed first).
        height : float or array_like, shape (n,)
            The height Z (m) of each point's plane.

        Returns
        -------
        ndarray, shape (n, 3)
            (X, Y, Z) on the ray of each image point, at its height.

        Raises
        ------
        TypeError
            If ``height`` is a bool or text.
        GCPError
            If the points are not (n, 2) finite numbers or the heights are not finite or do not
            match them.
        ModelError
            If a ray does not reach its plane in front of the camera (it points above the
            horizon, or the plane is above the camera).
        """
        photo = self.interior._undistort(self.interior.to_photo(image_xy))
        heights = as_finite(height, "height", error=GCPError)
        if heights.ndim > 1 or heights.size not in (1, len(photo)):
            raise GCPError(_("height must be one finite number or one per point ({n}), got "
                             "shape {shape}").format(n=len(photo), shape=heights.shape))
        heights = np.broadcast_to(heights.ravel(), (len(photo),))
        rays = np.column_stack([photo, np.full(len(photo), -self.interior.focal_mm)])
        rays = rays @ self.exterior.rotation().T          # R (x - xp, y - yp, -c)
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = (heights - self.exterior.z0) / rays[:, 2]
        bad = ~(scale > 0) | ~np.isfinite(scale)
        if bad.any():
            raise ModelError(_("the rays of image points {rows} do not reach their height in "
                               "front of the camera").format(
                                   rows=np.flatnonzero(bad)[:5].tolist()))
        return self.exterior.centre + scale[:, np.newaxis] * rays

    def homography(self, height=0.0):
        """The projective model the camera is on the plane Z = height: map (X, Y) -> (col, row).

        Parameters
        ----------
        height : float
            The plane's height (m).

        Returns
        -------
        rsgeo.transforms.MatrixModel
            Of kind ``"projective"``, exact for every point of the plane.

        Raises
        ------
        ModelError
            If the camera has lens distortion (k1 ≠ 0): its image of a plane is not a
            homography until the distortion is removed.
        TypeError
            If ``height`` is not a number.
        """
        height = as_number(height, "height")
        if self.interior.k1 != 0.0:
            raise ModelError(_("a camera with radial distortion (k1 = {k1}) does not image a "
                               "plane by a homography; remove the distortion first").format(
                                   k1=self.interior.k1))
        cols, rows = self.interior.size
        pitch, c = self.interior.pixel_mm, self.interior.focal_mm
        xp, yp = self.interior.principal_point_mm
        to_pixels = np.array([[-c / pitch, 0.0, cols / 2 + xp / pitch],
                              [0.0, c / pitch, rows / 2 - yp / pitch],
                              [0.0, 0.0, 1.0]])           # (U, V, W) -> (col w, row w, w)
        x0, y0, z0 = self.exterior.centre
        to_centre = np.array([[1.0, 0.0, -x0], [0.0, 1.0, -y0], [0.0, 0.0, height - z0]])
        return MatrixModel(to_pixels @ self.exterior.rotation().T @ to_centre, "projective")


@dataclass
class Resection:
    """The result of :func:`resect`: the exterior orientation and its precision.

    Attributes
    ----------
    camera : FrameCamera
        The camera with the estimated exterior orientation.
    initial : ExteriorOrientation
        Where the adjustment started.
    initial_method : str
        How the start was found: ``"given"``, ``"dlt"`` (direct linear transformation, GCPs not
        on one plane), ``"projective"`` (the plane homography of chapter 3b, decomposed) or
        ``"vertical"`` (a vertical photograph assumed, from a Helmert fit).
    residuals : ndarray, shape (n, 2)
        projected - measured (col, row) at each GCP, pixels.
    sigma0_px : float
        The a-posteriori standard deviation of unit weight, sqrt(vᵀv / (2n - 6)), pixels; NaN
        without redundancy (3 GCPs).
    cofactor : ndarray, shape (6, 6)
        (AᵀA)⁻¹, A the Jacobian, in the units of ``UNITS`` per pixel: the covariance of a
        measurement error of one pixel (times the a-priori variance in px², it is the
        a-priori covariance).
    covariance : ndarray, shape (6, 6)
        sigma0² × cofactor, the a-posteriori covariance (m², m·°, °²); NaN without redundancy.
    iterations : int
        Gauss-Newton steps taken.
    redundancy : int
        2n - 6: observations less parameters.
    """

    camera: FrameCamera
    initial: ExteriorOrientation
    initial_method: str
    residuals: np.ndarray
    sigma0_px: float
    cofactor: np.ndarray
    covariance: np.ndarray
    iterations: int
    redundancy: int

    @property
    def exterior(self):
        """The estimated exterior orientation.

        Returns
        -------
        ExteriorOrientation
        """
        return self.camera.exterior

    @property
    def std(self):
        """The a-posteriori standard deviations of X0, Y0, Z0 (m) and ω, φ, κ (°).

        Returns
        -------
        ndarray, shape (6,)
        """
        return np.sqrt(np.diag(self.covariance))

    @property
    def correlation(self):
        """The parameters' correlation matrix (from :attr:`cofactor`, so defined without
        redundancy too).

        Returns
        -------
        ndarray, shape (6, 6)
        """
        scale = np.sqrt(np.diag(self.cofactor))
        return self.cofactor / np.outer(scale, scale)

    @property
    def rms_px(self):
        """The lecture's RMS of the GCP residuals, sqrt(Σ R_i² / n), pixels.

        Returns
        -------
        float
        """
        return float(np.sqrt(np.mean(np.sum(self.residuals**2, axis=1))))

    def table(self, truth=None):
        """The estimate with its standard deviation, and against a known truth when given.

        Parameters
        ----------
        truth : ExteriorOrientation, optional
            The true orientation (synthetic data): adds the error and the error in standard
            deviations.

        Returns
        -------
        pandas.DataFrame
            One row per parameter (``PARAMETERS``): unit, estimate, std; with ``truth``
            also true, error, and error / std.

        Raises
        ------
        TypeError
            If ``truth`` is not an ExteriorOrientation.
        """
        import pandas as pd  # only here: rsgeo.sensors loads without pandas

        frame = pd.DataFrame({"unit": UNITS, "estimate": self.exterior.as_array(),
                              "std": self.std}, index=pd.Index(PARAMETERS, name="parameter"))
        if truth is not None:
            if not isinstance(truth, ExteriorOrientation):
                raise TypeError(_("truth must be an ExteriorOrientation, got {kind}").format(
                    kind=type(truth).__name__))
            frame["true"] = truth.as_array()
            frame["error"] = frame["estimate"] - frame["true"]
            frame["error / std"] = frame["error"] / frame["std"]
        return frame


def _spread_check(points, name, what):
    """Raise unless ``points`` span at least a plane (2-D extent), no three the same line."""
    centred = points - points.mean(axis=0)
    singular = np.linalg.svd(centred, compute_uv=False)
    if not singular[1] > 1e-9 * max(singular[0], 1e-300):
        raise GCPError(_("the {name} points all lie on one line (or coincide); space resection "
                         "needs {what}").format(name=name, what=what))
    return singular


def _normalised_rays(image, interior):
    """(-(x - xp)/c, -(y - yp)/c): the measured points as rays (x̂, ŷ, 1) ∝ M (P - C)."""
    ideal = interior._undistort(interior.to_photo(image))
    return -ideal / interior.focal_mm


def _from_matrix_and_centre(m_matrix, centre):
    """Parameters (radians) from M = Rᵀ and the projection centre."""
    angles = np.radians(angles_from_rotation(m_matrix.T))
    return np.concatenate([centre, angles])


def _start_dlt(ground, rays):
    """The 11-parameter DLT (normalised, Hartley & Zisserman §7.1): 6+ GCPs off one plane."""
    g_origin, g_scale = ground.mean(axis=0), np.sqrt(np.mean(np.sum((ground - ground.mean(
        axis=0))**2, axis=1)) / 3)
    r_origin, r_scale = rays.mean(axis=0), np.sqrt(np.mean(np.sum((rays - rays.mean(
        axis=0))**2, axis=1)) / 2)
    g = np.column_stack([(ground - g_origin) / g_scale, np.ones(len(ground))])
    q = (rays - r_origin) / r_scale
    zero = np.zeros_like(g)
    system = np.vstack([np.hstack([g, zero, -q[:, :1] * g]), np.hstack([zero, g, -q[:, 1:] * g])])
    p_normal = np.linalg.svd(system)[2][-1].reshape(3, 4)
    to_rays = np.array([[r_scale, 0, r_origin[0]], [0, r_scale, r_origin[1]], [0, 0, 1.0]])
    from_ground = np.diag([1 / g_scale] * 3 + [1.0])
    from_ground[:3, 3] = -g_origin / g_scale
    p_matrix = to_rays @ p_normal @ from_ground      # (x̂, ŷ, 1) ∝ P (X, Y, Z, 1)
    null = np.linalg.svd(p_matrix)[2][-1]
    if abs(null[3]) < 1e-12 * np.abs(null).max():
        return None
    centre = null[:3] / null[3]
    u, _s, vt = np.linalg.svd(p_matrix[:, :3])
    m_matrix = u @ vt
    if np.linalg.det(m_matrix) < 0:
        m_matrix = -m_matrix
    return _from_matrix_and_centre(m_matrix, centre)


def _start_projective(ground, rays):
    """The plane homography (chapter 3b's projective model) through the GCPs' best-fit plane,
    decomposed as H ∝ [M e1, M e2, M (P̄ - C)]: 4+ GCPs, exact when they are coplanar."""
    origin = ground.mean(axis=0)
    axes = np.linalg.svd(ground - origin)[2]
    e1, e2 = axes[0], axes[1]
    e3 = np.cross(e1, e2)
    in_plane = (ground - origin) @ np.column_stack([e1, e2])
    h = fit_transform(in_plane, rays, "projective").matrix      # h[2, 2] = 1
    mu = -(np.linalg.norm(h[:, 0]) + np.linalg.norm(h[:, 1])) / 2   # W < 0 at the centroid
    m1, m2 = h[:, 0] / mu, h[:, 1] / mu
    u, _s, vt = np.linalg.svd(np.column_stack([m1, m2, np.cross(m1, m2)]))
    m_matrix = u @ vt @ np.vstack([e1, e2, e3])                 # M E = B, E orthonormal
    if np.linalg.det(m_matrix) < 0:
        return None
    centre = origin - m_matrix.T @ (h[:, 2] / mu)
    return _from_matrix_and_centre(m_matrix, centre)


def _start_vertical(ground, rays, interior):
    """A vertical photograph (ω = φ = 0) fitted as a Helmert from (X, Y) to the photo: any 2+
    GCPs not on one point (the start for 3 GCPs)."""
    photo = rays * -interior.focal_mm                           # (x - xp, y - yp), mm
    helmert = fit_transform(ground[:, :2], photo, "helmert").matrix
    a, b = helmert[0, 0], helmert[1, 0]
    scale = float(np.hypot(a, b))                               # mm on the photo per metre
    kappa = np.arctan2(-b, a)                                   # x = s (cos κ ΔX + sin κ ΔY)
    nadir = np.linalg.solve(helmert[:2, :2], -helmert[:2, 2])   # ground under (xp, yp)
    z0 = ground[:, 2].mean() + interior.focal_mm / scale
    return np.array([nadir[0], nadir[1], z0, 0.0, 0.0, kappa])


def _misfit(params, ground, image, interior):
    """RMS of the reprojection (inf when a GCP is behind the camera)."""
    projected, w, _none = _collinearity(params, ground, interior)
    if not (w < 0).all() or not np.isfinite(projected).all():
        return np.inf
    return float(np.sqrt(np.mean((projected - image) ** 2)))


def resect(ground, image, interior, initial=None, max_iterations=50, tolerance=1e-10):
    """Space resection: the exterior orientation of a frame photo from GCPs, by least squares.

    The collinearity equations are linearised about the current orientation and the six
    unknowns (X0, Y0, Z0, ω, φ, κ) corrected by Gauss-Newton (analytic Jacobian, steps halved
    while they make the fit worse) until a step is below ``tolerance``. The interior orientation
    is known (a calibrated camera) and every image coordinate has the same weight. Without an
    ``initial`` orientation the start comes from a linear solution: the DLT when 6 or more GCPs
    are not on one plane, the projective model of the GCPs' plane (chapter 3b) from 4 GCPs, a
    vertical photograph for 3; the one that reprojects best is used.

    Parameters
    ----------
    ground : (n, 3) array_like
        The GCPs' object coordinates (X, Y, Z), m.
    image : (n, 2) array_like
        Their measured image positions, GDAL's (col, row).
    interior : InteriorOrientation
        The calibrated camera.
    initial : ExteriorOrientation, optional
        Where to start; default: found as above.
    max_iterations : int
        At most this many Gauss-Newton steps.
    tolerance : float
        Stop when a step moves the centre by less than ``tolerance`` times the camera's
        distance from the GCPs and every angle by less than ``tolerance`` radians.

    Returns
    -------
    Resection
        The orientation, residuals, sigma0 (a posteriori), covariance and standard deviations.

    Raises
    ------
    GCPError
        Fewer than 3 GCPs; ``ground`` and ``image`` of different lengths; GCPs on one line on
        the ground or in the image; a geometry that does not determine the orientation (the
        normal matrix is singular: the projection centre on the critical cylinder through the
        GCPs, or GCPs bunched together).
    ModelError
        If the adjustment does not converge within ``max_iterations``, or the start puts GCPs
        behind the camera.
    TypeError
        If ``interior`` or ``initial`` is not of its type, or a value is not a number.

    Examples
    --------
    >>> interior = InteriorOrientation(100.0, 0.01, (2000, 1500))
    >>> truth = FrameCamera(interior, ExteriorOrientation(500.0, 800.0, 1200.0, 2, -3, 40))
    >>> ground = [[300, 700, 10], [650, 640, 35], [700, 950, 0], [420, 990, 20], [500, 800, 60]]
    >>> fit = resect(ground, truth.project(ground), interior)
    >>> fit.exterior.as_array().round(6).tolist(), fit.redundancy
    ([500.0, 800.0, 1200.0, 2.0, -3.0, 40.0], 4)
    """
    if not isinstance(interior, InteriorOrientation):
        raise TypeError(_("interior must be an InteriorOrientation, got {kind}").format(
            kind=type(interior).__name__))
    if initial is not None and not isinstance(initial, ExteriorOrientation):
        raise TypeError(_("initial must be an ExteriorOrientation or None, got {kind}").format(
            kind=type(initial).__name__))
    ground = as_points_3d(ground, "ground", _GROUND)
    image = as_points(image, "image")
    max_iterations = as_integer(max_iterations, "max_iterations", low=1)
    tolerance = as_number(tolerance, "tolerance", low=0.0)
    if len(ground) != len(image):
        raise GCPError(_("ground and image must hold the same GCPs, got {n} and {m} points")
                       .format(n=len(ground), m=len(image)))
    if len(ground) < 3:
        raise GCPError(_("space resection needs at least 3 GCPs (6 unknowns, 2 equations per "
                         "GCP; 4 or more for redundancy, a sigma0 and a covariance), got {n}")
                       .format(n=len(ground)))
    spread = _spread_check(ground, "ground", _("GCPs that span a plane at least"))
    _spread_check(image, "image", _("GCPs spread over the image, not along one line"))
    origin = ground.mean(axis=0)                    # UTM-sized numbers: work from the centroid
    local = ground - origin
    rays = _normalised_rays(image, interior)
    if initial is not None:
        start, method = _radians(initial.as_array()), "given"
        start[:3] -= origin
    else:
        starts = {"vertical": lambda: _start_vertical(local, rays, interior)}
        if len(ground) >= 4:
            starts["projective"] = lambda: _start_projective(local, rays)
        if len(ground) >= 6 and spread[2] > 1e-3 * spread[0]:
            starts["dlt"] = lambda: _start_dlt(local, rays)
        candidates = {}
        for name, start_from in starts.items():
            try:                                    # a degenerate linear start is skipped
                candidates[name] = start_from()
            except (GCPError, np.linalg.LinAlgError):
                candidates[name] = None
        misfits = {name: _misfit(value, local, image, interior)
                   for name, value in candidates.items() if value is not None}
        if not misfits:
            raise GCPError(_("no linear start fits these GCPs; give an initial exterior "
                             "orientation"))
        method = min(misfits, key=misfits.get)
        start = candidates[method]
    params = start.copy()
    if not np.isfinite(_misfit(params, local, image, interior)):
        raise ModelError(_("the initial orientation puts GCPs behind the camera; give an "
                           "initial exterior orientation above the ground, looking at it"))
    cost = _misfit(params, local, image, interior)
    for iterations in range(1, max_iterations + 1):  # noqa: B007  (reported in the result)
        projected, w, jac = _collinearity(params, local, interior, jacobian=True)
        design = jac.reshape(-1, 6)
        scale = np.linalg.norm(design, axis=0)
        scale[scale == 0] = 1.0
        step = np.linalg.lstsq(design / scale, (image - projected).ravel(), rcond=None)[0]
        step /= scale
        for _halving in range(30):                  # Gauss-Newton, steps halved while worse
            trial = params + step
            trial_cost = _misfit(trial, local, image, interior)
            if trial_cost <= cost * (1 + 1e-12) or np.abs(step).max() == 0:
                break
            step = step / 2
        params, cost = trial, trial_cost
        depth = float(np.abs(w).mean())             # the camera's distance along its axis, m
        if (np.abs(step[:3]).max() <= tolerance * depth
                and np.abs(step[3:]).max() <= tolerance):
            break
    else:
        raise ModelError(_("space resection did not converge in {n} iterations (last step "
                           "{step}); check the GCPs for blunders, or give an initial exterior "
                           "orientation").format(n=max_iterations,
                                                 step=np.round(_degrees(step), 9).tolist()))
    projected, w, jac = _collinearity(params, local, interior, jacobian=True)
    design = jac.reshape(-1, 6)
    scale = np.linalg.norm(design, axis=0)
    normal = (design / scale).T @ (design / scale)
    condition = np.linalg.cond(normal)
    if not condition < 1e12:
        raise GCPError(_("the GCPs do not determine the camera's orientation (normal matrix "
                         "condition {condition:.1e}): the projection centre may lie on the "
                         "critical cylinder through three GCPs, or the GCPs are bunched "
                         "together; add GCPs spread over the image").format(condition=condition))
    to_degrees = np.array([1.0, 1.0, 1.0] + [180.0 / np.pi] * 3)
    cofactor = np.linalg.inv(normal) / np.outer(scale, scale) * np.outer(to_degrees, to_degrees)
    residuals = projected - image
    redundancy = 2 * len(ground) - 6
    sigma0 = (float(np.sqrt(np.sum(residuals**2) / redundancy)) if redundancy > 0 else np.nan)
    estimate = _degrees(params)
    estimate[:3] += origin
    estimate[3:] = (estimate[3:] + 180.0) % 360.0 - 180.0      # angles in [-180°, 180°)
    initial_values = _degrees(start)
    initial_values[:3] += origin
    return Resection(camera=FrameCamera(interior, ExteriorOrientation.from_array(estimate)),
                     initial=ExteriorOrientation.from_array(initial_values),
                     initial_method=method, residuals=residuals, sigma0_px=sigma0,
                     cofactor=cofactor, covariance=sigma0**2 * cofactor, iterations=iterations,
                     redundancy=redundancy)
