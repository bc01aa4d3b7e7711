"""Models that are one 3x3 homogeneous matrix: linear, Helmert, projective (QGIS's
Georeferencer's).
"""



import numpy as np

from ..errors import GCPError, ModelError
from ..language import _
from ..validation import as_points
from ._base import GeometricModel

__all__ = [
    "N_PARAMETERS", "MatrixModel", "fit_linear", "fit_helmert", "fit_projective",
]

# --- Matrix models: linear, Helmert, projective --------------------------------------------------


#: The free parameters of each matrix model (the registry's, rsgeo.transforms.REGISTRY).
N_PARAMETERS = {"linear": 4, "helmert": 4, "projective": 8}


def _centre_scale(points):
    """Mean and RMS distance of the centred coordinates (1 if the points coincide)."""
    origin = points.mean(axis=0)
    scale = float(np.sqrt(np.mean((points - origin) ** 2))) or 1.0
    return origin, scale


def _normaliser(points):
    """3×3 matrix that centres ``points`` and divides by their RMS coordinate (scikit-image's)."""
    origin, scale = _centre_scale(points)
    matrix = np.eye(3)
    matrix[:2, 2] = -origin
    matrix[:2] /= scale
    return matrix


class MatrixModel(GeometricModel):
    """A model that is a 3×3 homogeneous matrix: linear, Helmert or projective.

    ``model(p)`` = (H [x, y, 1]ᵀ) divided by its third component. Its
    :meth:`inverse` is exact (the inverse matrix), of the same kind.

    Parameters
    ----------
    matrix : (3, 3) array_like
        Homogeneous matrix, ``matrix[2, 2]`` = 1.
    kind : {"linear", "helmert", "projective"}
    src, dst : (n, 2) ndarray or None
        The GCPs the model was fitted on (swapped in the inverse).

    Attributes
    ----------
    kind : str
    n_parameters : int
        Free parameters: 4 (linear, Helmert) or 8 (projective), as
        :data:`~rsgeo.transforms.REGISTRY` says.
    """

    KINDS = ("linear", "helmert", "projective")

    def __init__(self, matrix, kind, src=None, dst=None):
        matrix = np.asarray(matrix, dtype=np.float64)
        if matrix.shape != (3, 3) or not np.isfinite(matrix).all():
            raise GCPError(_("matrix must be a finite 3×3 array, got shape "
                             "{matrix_shape}").format(matrix_shape=matrix.shape))
        if kind not in self.KINDS:
            raise GCPError(_("a matrix model's kind must be one of {KINDS}, got {kind!r}").format(
                    KINDS=list(self.KINDS), kind=kind))
        self.matrix = matrix / matrix[2, 2]
        self.kind = kind
        self.n_parameters = N_PARAMETERS[kind]
        self.src = None if src is None else np.array(src, dtype=np.float64)
        self.dst = None if dst is None else np.array(dst, dtype=np.float64)

    def __call__(self, points):
        """Map (n, 2) points through the matrix.

        Parameters
        ----------
        points : (n, 2) array_like

        Returns
        -------
        ndarray, shape (n, 2)

        Raises
        ------
        ModelError
            If the points are not (n, 2) finite numbers (a ``ValueError``), or
            a point lies on a projective model's vanishing line (it maps to
            infinity).
        """
        points = as_points(points)
        homogeneous = np.column_stack([points, np.ones(len(points))]) @ self.matrix.T
        w = homogeneous[:, 2]
        if (np.abs(w) < 1e-12).any():
            raise ModelError(_("some points lie on the projective model's vanishing line and "
                               "map to infinity; keep the points inside the GCPs' area"))
        return homogeneous[:, :2] / w[:, np.newaxis]

    def kernel_form(self):
        """The model packed for the warp kernels (see ``rsgeo._kernels.transformer``).

        Returns
        -------
        (str, ndarray)
            ``("projective", the matrix's 9 entries row by row)``; a linear or
            Helmert matrix is a projective one with a last row of (0, 0, 1).
        """
        return "projective", self.matrix.ravel().copy()

    def inverse(self):
        """The exact inverse: the inverse matrix, same kind, src and dst swapped.

        Returns
        -------
        MatrixModel

        Raises
        ------
        ModelError
            If the matrix is singular (the model collapses the plane).
        """
        if abs(np.linalg.det(self.matrix)) < 1e-300:
            raise ModelError(_("the model's matrix is singular and has no inverse"))
        return MatrixModel(np.linalg.inv(self.matrix), self.kind, self.dst, self.src)

    def __repr__(self):
        return f"MatrixModel(kind={self.kind!r}, matrix={self.matrix.tolist()!r})"


def fit_linear(src, dst):
    """Scale and offset per axis: u = a x + c, v = b y + d (QGIS's Linear, a world file)."""
    matrix = np.eye(3)
    for axis in range(2):
        x = src[:, axis] - src[:, axis].mean()
        if not np.abs(x).max() > 1e-12 * max(1.0, np.abs(src[:, axis]).max()):
            raise GCPError(_("a 'linear' model needs GCPs at two different {value} "
                             "coordinates at least; spread the GCPs over the image").format(
                    value='xy'[axis]))
        scale = float(x @ (dst[:, axis] - dst[:, axis].mean()) / (x @ x))
        matrix[axis, axis] = scale
        matrix[axis, 2] = dst[:, axis].mean() - scale * src[:, axis].mean()
    return MatrixModel(matrix, "linear", src, dst)


def fit_helmert(src, dst):
    """Similarity by least squares on centred coordinates (the same as Umeyama's solution).

    The handedness (with or without a reflection, as from map y-up to image rows-down) is the
    one the GCPs call for: the sign of their cross-covariance's determinant."""
    src_origin, dst_origin = src.mean(axis=0), dst.mean(axis=0)
    p, q = src - src_origin, dst - dst_origin
    spread = float((p**2).sum())
    if not spread > 0 or np.linalg.matrix_rank(p, tol=1e-12 * np.sqrt(spread)) < 1:
        raise GCPError(_("a 'helmert' model needs at least two distinct GCPs; these all fall on "
                         "the same point"))
    flip = 1.0 if np.linalg.det(p.T @ q) >= 0 else -1.0
    q = q * [1.0, flip]
    a = float((p[:, 0] * q[:, 0] + p[:, 1] * q[:, 1]).sum() / spread)
    b = float((p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]).sum() / spread)
    linear = np.array([[a, -b], [flip * b, flip * a]])
    matrix = np.eye(3)
    matrix[:2, :2] = linear
    matrix[:2, 2] = dst_origin - linear @ src_origin
    return MatrixModel(matrix, "helmert", src, dst)


def fit_projective(src, dst):
    """Normalised direct linear transform (Hartley), smallest singular vector: the estimate
    of scikit-image's ProjectiveTransform and of QGIS's Georeferencer."""
    for name, points in (("src", src), ("dst", dst)):
        centred = points - points.mean(axis=0)
        singular = np.linalg.svd(centred, compute_uv=False)
        if not singular[1] > 1e-9 * max(singular[0], 1e-300):
            raise GCPError(_("the {name} points are collinear (or coincide): a "
                             "'projective' model needs at least 4 GCPs, no three of "
                             "them on one line, spread over the image").format(name=name))
    src_norm, dst_norm = _normaliser(src), _normaliser(dst)
    s = np.column_stack([src, np.ones(len(src))]) @ src_norm.T
    d = np.column_stack([dst, np.ones(len(dst))]) @ dst_norm.T
    zero = np.zeros((len(s), 3))
    rows_u = np.hstack([s, zero, -s * d[:, :1]])
    rows_v = np.hstack([zero, s, -s * d[:, 1:2]])
    system = np.vstack([rows_u, rows_v])
    singular, vt = np.linalg.svd(system)[1:]
    if len(singular) >= 8 and not singular[7] > 1e-10 * singular[0]:
        raise GCPError(_("the GCPs do not determine a 'projective' model: three of the four are "
                         "collinear or points repeat; use 4 GCPs, no three on one line"))
    h = vt[-1].reshape(3, 3)
    if abs(h[2, 2]) < 1e-12 * np.abs(h).max():
        raise GCPError(_("the GCPs put the projective model's vanishing line through their "
                         "centre; they are degenerate (check for swapped points)"))
    matrix = np.linalg.inv(dst_norm) @ h @ src_norm
    return MatrixModel(matrix, "projective", src, dst)

