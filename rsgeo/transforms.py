"""Geometric models fitted to GCPs: one protocol, one registry of kinds, one Newton inverse.

After scikit-image's ``transform/_geometric.py``: every model follows the protocol of
:class:`GeometricModel` (``model(points)`` on (n, 2) arrays, ``model.residuals(src, dst)``,
``model.inverse()``), and the kinds QGIS's Georeferencer offers - linear, Helmert, polynomial of
degree 1 to 3, projective, thin-plate spline - are declared once, in :data:`REGISTRY`, each with
its fit function, its number of parameters and its minimum number of GCPs. :func:`fit_transform`,
:func:`min_gcps` and :func:`n_parameters` read the registry; nothing else lists the kinds.

The lecture's "Transformações polinomiais": two Cartesian systems - map coordinates (x, y) of
the GCPs and image coordinates of the distorted image - are related by polynomials
u = f(x, y), v = g(x, y) of degree 1 to 3,

    u = a0 + a1 x + a2 y + a3 xy + a4 x² + a5 y²        (degree 2)
    v = b0 + b1 x + b2 y + b3 xy + b4 x² + b5 y²,

whose coefficients come from a linear system built from the GCPs, solved here by least squares.
As GDAL does, x and y are measured from the GCPs' mean, so a third-degree fit on UTM-sized
numbers stays well conditioned; the fit is also scaled internally, which changes nothing but the
rounding.

Image coordinates follow GDAL: (col, row) = (pixel, line), continuous, with the image's top-left
corner at (0, 0).
"""

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from math import comb

import numpy as np

from ._checks import as_integer, as_number, as_points
from ._i18n import N_, _
from .errors import GCPError, ModelError


def _compiled(name):
    """One of rsgeo's compiled modules (Numba), imported when a model is first evaluated, so
    that reading GCPs (rsgeo.gcp, rsgeo.data) does not load the compiler."""
    return importlib.import_module(f"rsgeo.{name}")

__all__ = [
    "GEOREFERENCER_MODELS",
    "KINDS",
    "ORDERS",
    "REGISTRY",
    "GeometricModel",
    "InverseModel",
    "MatrixModel",
    "ModelKind",
    "PolynomialModel",
    "TPSModel",
    "design_matrix",
    "fit_polynomial",
    "fit_transform",
    "min_gcps",
    "n_parameters",
    "newton_inverse",
    "outside_hull",
    "registered",
    "term_names",
]


# --- The protocol --------------------------------------------------------------------------------


class GeometricModel:
    """The mapping protocol every rsgeo model and distortion follows (after scikit-image).

    A geometric model maps points of one coordinate system (``src``) to
    another (``dst``). Subclasses define ``__call__`` and
    :meth:`inverse`; :meth:`residuals` and :meth:`rms` come with the protocol.

    - ``model(points)``: (n, 2) array in, (n, 2) array out;
    - ``model.residuals(src, dst)``: per-point distance ``|model(src) - dst|``;
    - ``model.inverse()``: the model of the other direction, with the same protocol.

    References
    ----------
    scikit-image, ``skimage.transform``: geometric transforms are
    callable on (n, 2) arrays and have ``residuals`` and ``inverse``.
    """

    def __call__(self, points):
        """Map (n, 2) ``src`` points to (n, 2) ``dst`` points.

        Parameters
        ----------
        points : (n, 2) array_like

        Returns
        -------
        ndarray, shape (n, 2)

        Raises
        ------
        NotImplementedError
            In the base class: a model defines its own mapping.
        """
        raise NotImplementedError(_("{kind} does not define its mapping").format(
                kind=type(self).__name__))

    def inverse(self):
        """The model of the other direction (dst -> src).

        Returns
        -------
        GeometricModel

        Raises
        ------
        NotImplementedError
            In the base class: a model defines its own inverse.
        """
        raise NotImplementedError(_("{kind} does not define its inverse").format(
                kind=type(self).__name__))

    def outside_gcps(self, points):
        """How far each point lies outside the GCPs' convex hull, in GCP extents (0 inside).

        A model is only trustworthy where its GCPs are: a polynomial of degree
        2 or 3 grows like the cube of the distance beyond them (GCPs clustered
        in 500 m fit to 0.35 px and are 89,000 px off at a far corner). See
        :func:`outside_hull`; :func:`rsgeo.accuracy.predicted_error_map` gives
        the predicted error itself.

        Parameters
        ----------
        points : (n, 2) array_like
            Points in the model's input (``src``) coordinates.

        Returns
        -------
        ndarray, shape (n,)
            Distance beyond the hull divided by the larger side of the GCPs'
            bounding box: 0 inside, 1 a whole extent away.

        Raises
        ------
        GCPError
            If the points are not (n, 2) finite numbers.
        """
        return outside_hull(self.src, points)

    def residuals(self, src, dst):
        """Distance between where the model puts each ``src`` point and its ``dst`` point.

        The lecture's R_i = sqrt(dx² + dy²), (dx, dy) = model(src_i) - dst_i, in
        dst units (pixels for a map -> image model).

        Parameters
        ----------
        src, dst : (n, 2) array_like
            The same n points in both coordinate systems.

        Returns
        -------
        ndarray, shape (n,)

        Raises
        ------
        GCPError
            If the arrays are not (n, 2) of the same length or hold NaN.

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10]], dtype=float)
        >>> model = fit_polynomial(src, src + 1, 1)
        >>> model.residuals(src, src + [[1, 1], [1, 1], [4, 5]]).round(6) + 0.0
        array([0., 0., 5.])
        """
        return _residual_vectors(self, src, dst)[1]

    def rms(self, src, dst):
        """The lecture's RMS of :meth:`residuals`: sqrt(Σ R_i² / n).

        Parameters
        ----------
        src, dst : (n, 2) array_like
            The same n points (n >= 1) in both coordinate systems.

        Returns
        -------
        float

        Raises
        ------
        GCPError
            As :meth:`residuals`, or when there is no point.

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10]], dtype=float)
        >>> round(fit_polynomial(src, src, 1).rms(src, src + [[3, 4], [0, 0], [0, 0]]), 4)
        2.8868
        """
        predicted, _ = _residual_vectors(self, src, dst)
        return _rms_of(predicted - as_points(dst, "dst"))


def _same_points(src, dst):
    """src and dst as (n, 2) arrays holding the same number of points."""
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise GCPError(_("src and dst must hold the same points, got {n_src} and {n_dst}").format(
                n_src=len(src), n_dst=len(dst)))
    return src, dst


def _residual_vectors(model, src, dst):
    """model(src) and |model(src) - dst|, with the inputs checked."""
    src, dst = _same_points(src, dst)
    predicted = np.asarray(model(src), dtype=np.float64)
    if predicted.shape != dst.shape:
        raise GCPError(_("the model must return an (n, 2) array, got shape "
                         "{predicted_shape}").format(predicted_shape=predicted.shape))
    return predicted, np.hypot(*(predicted - dst).T)


def _rms_of(difference):
    """The lecture's RMS of (n, 2) differences, sqrt(mean(dx² + dy²)); rsgeo.accuracy's too."""
    if len(difference) == 0:
        raise GCPError(_("predicted and observed hold no points; the RMS needs at least one"))
    return float(np.sqrt(np.mean(np.sum(difference ** 2, axis=1))))


def outside_hull(gcps, points):
    """Distance of each point beyond the convex hull of ``gcps``, in units of the GCPs' extent.

    0 for a point inside the hull (or on it); otherwise its distance to the
    hull divided by the larger side of the GCPs' bounding box. Use it to see
    where a model extrapolates: beyond about 0.1 a degree-2 or -3 polynomial
    is no longer controlled by its GCPs.

    Parameters
    ----------
    gcps : (n, 2) array_like
        The GCPs' positions (a model's ``src``).
    points : (m, 2) array_like
        The points to rate, in the same coordinates.

    Returns
    -------
    ndarray, shape (m,)

    Raises
    ------
    GCPError
        If either array is not (n, 2) finite numbers.

    Examples
    --------
    >>> square = [[0, 0], [10, 0], [0, 10], [10, 10]]
    >>> outside_hull(square, [[5, 5], [15, 5], [10, 30]]).tolist()
    [0.0, 0.5, 2.0]
    """
    from scipy.spatial import ConvexHull, QhullError

    gcps = as_points(gcps, "gcps")
    points = as_points(points, "points")
    extent = float(np.ptp(gcps, axis=0).max()) or 1.0
    try:
        corners = gcps[ConvexHull(gcps).vertices]
    except (QhullError, ValueError):          # fewer than 3 points or collinear: their segment
        ends = np.argsort(gcps @ (gcps[np.argmax(np.hypot(*(gcps - gcps[0]).T))] - gcps[0]))
        corners = gcps[[ends[0], ends[-1]]]
    start, end = corners, np.roll(corners, -1, axis=0)
    edge = end - start
    length2 = np.maximum(np.sum(edge**2, axis=1), 1e-300)
    distance = np.empty(len(points))
    for first in range(0, len(points), 65536):         # bounded memory for large grids
        p = points[first:first + 65536, np.newaxis, :]
        t = np.clip(np.sum((p - start) * edge, axis=2) / length2, 0.0, 1.0)
        nearest = np.hypot(*np.moveaxis(p - (start + t[..., np.newaxis] * edge), 2, 0))
        inside = np.zeros(len(p), bool)
        if len(corners) >= 3:                               # counter-clockwise hull
            cross = edge[:, 0] * (p[..., 1] - start[:, 1]) - edge[:, 1] * (p[..., 0] - start[:, 0])
            inside = (cross >= -1e-12 * extent**2).all(axis=1)
        distance[first:first + 65536] = np.where(inside, 0.0, nearest.min(axis=1))
    return distance / extent


class InverseModel(GeometricModel):
    """The exact inverse of a model, found point by point by solving model(p) = q.

    Made by a model's ``inverse()``; ``inverse()`` of this returns the model.

    Parameters
    ----------
    forward : GeometricModel
        The model inverted.
    solve : callable
        (n, 2) dst points -> (n, 2) src points; raises ``ValueError`` where it
        finds no inverse.
    """

    def __init__(self, forward, solve):
        self.forward = forward
        self._solve = solve

    def __call__(self, points):
        """The src points that ``forward`` maps onto these dst points.

        Parameters
        ----------
        points : (n, 2) array_like

        Returns
        -------
        ndarray, shape (n, 2)

        Raises
        ------
        ValueError
            If the points are not (n, 2) finite numbers; ``ModelError`` if the
            solution does not converge (the model folds or is singular there).
        """
        return self._solve(as_points(points))

    def inverse(self):
        """The forward model.

        Returns
        -------
        GeometricModel
        """
        return self.forward

    def __repr__(self):
        return f"InverseModel(of {self.forward!r})"


def newton_inverse(model, start, tolerance, max_iterations, failure, floor=0.0):
    """The exact inverse of ``model`` by Newton's method, started from an approximate inverse.

    Each point q starts from ``start(q)`` and is polished with ``model.jacobian``
    until ``|model(p) - q|`` is within ``tolerance`` times the extent of the
    GCPs' ``model.dst``. Shared by every model whose inverse has no closed form
    (polynomials, thin-plate splines): inside the GCPs' area a well-posed model
    is one-to-one and this converges in a few steps.

    Parameters
    ----------
    model : GeometricModel
        With ``jacobian(points)`` (shape (n, 2, 2)) and ``dst`` (its GCPs).
    start : callable
        (n, 2) dst points -> first guesses of the src points (e.g. the model
        fitted the other way round, as GDAL does).
    tolerance : float
        Largest accepted ``|model(p) - q|``, relative to the extent of ``dst``.
    max_iterations : int
        Newton steps at most.
    failure : callable
        ``failure(failed, targets)`` -> the message of the ``ModelError`` raised
        when the points flagged in ``failed`` did not converge.
    floor : float
        Smallest accepted limit, in dst units: what float64 evaluation of the
        model can reach (a thin-plate spline on thousands of GCPs cannot be
        evaluated closer than its rounding, so a limit below it never converges).

    Returns
    -------
    InverseModel
        Callable on (n, 2) dst points; raises ``ModelError`` for points where
        Newton's method does not converge (the model folds or its Jacobian is
        singular there).

    Raises
    ------
    ValueError
        If ``tolerance`` is negative or not a number.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5], [5, 0]], dtype=float)
    >>> model = fit_polynomial(src, src + 0.01 * src**2, 2)
    >>> inverse = newton_inverse(model, model.reverse(), 1e-9, 50, lambda failed, q: "folds")
    >>> inverse(model([[3.0, 7.0]])).round(9) + 0.0
    array([[3., 7.]])
    """
    extent = float(np.abs(model.dst - model.dst.mean(axis=0)).max()) or 1.0
    relative = as_number(tolerance, "tolerance", low=0, why=N_("relative to the dst extent"))
    limit = max(relative * extent, as_number(floor, "floor", low=0, why=N_("dst units")))

    def solve(targets):
        points = start(targets)
        error = np.full(len(targets), np.inf)
        for _iteration in range(int(max_iterations)):
            difference = model(points) - targets
            error = np.hypot(difference[:, 0], difference[:, 1])
            if not (error > limit).any():
                break
            jacobian = model.jacobian(points)
            usable = np.abs(np.linalg.det(jacobian)) > 1e-300
            step = np.zeros_like(points)
            step[usable] = np.linalg.solve(jacobian[usable], difference[usable][..., None])[..., 0]
            points = points - step
        failed = ~(error <= limit)
        if failed.any():
            raise ModelError(failure(failed, targets))
        return points

    return InverseModel(model, solve)


# --- Polynomials (GDAL's centred, normalised least squares) --------------------------------------

ORDERS = (1, 2, 3)

# (power of x, power of y) of every term, in the lecture's order:
# 1, x, y, xy, x², y², then the cubic terms.
_TERMS = ((0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2), (2, 1), (1, 2), (3, 0), (0, 3))


def _check_order(order):
    order = as_integer(order, "order", why=N_("a polynomial's degree: 1, 2 or 3"))
    if order not in ORDERS:
        raise GCPError(_("polynomial order must be 1, 2 or 3 (the lecture's degrees), "
                         "got {order!r}").format(order=order))
    return int(order)


def _n_terms(order):
    """Terms of a polynomial of degree ``order``, (n+1)(n+2)/2: its minimum number of GCPs."""
    return comb(order + 2, 2)


def term_names(order, variables=("x", "y")):
    """Names of the polynomial's terms in the lecture's order.

    Parameters
    ----------
    order : {1, 2, 3}
        Degree of the polynomial.
    variables : (str, str)
        Names of the two input coordinates.

    Returns
    -------
    list of str
        ``min_gcps(order)`` names, "1" for the constant.

    Raises
    ------
    GCPError
        If the order is not 1, 2 or 3.

    Examples
    --------
    >>> term_names(2)
    ['1', 'x', 'y', 'xy', 'x²', 'y²']
    """
    superscript = {1: "", 2: "²", 3: "³"}
    names = []
    for px, py in _TERMS[:_n_terms(_check_order(order))]:
        name = ((variables[0] + superscript[px] if px else "")
                + (variables[1] + superscript[py] if py else ""))
        names.append(name or "1")
    return names


def design_matrix(points, order):
    """The linear system's matrix: one row per GCP, one column per term.

    Row i is (1, x_i, y_i, x_i y_i, x_i², y_i², ...) in the lecture's order,
    for the coordinates as given (centre them first for a stable fit).

    Parameters
    ----------
    points : (n, 2) array_like
        GCP coordinates (x, y).
    order : {1, 2, 3}

    Returns
    -------
    ndarray, shape (n, min_gcps(order))

    Raises
    ------
    GCPError
        If the points are not (n, 2) finite numbers or the order is not 1-3.

    Examples
    --------
    >>> design_matrix([[2.0, 3.0]], 2)
    array([[1., 2., 3., 6., 4., 9.]])
    """
    points = as_points(points)
    order = _check_order(order)
    x, y = points[:, 0], points[:, 1]
    return np.column_stack([x**px * y**py for px, py in _TERMS[:_n_terms(order)]])


def _normalised_design(points, order, origin=None, scale=None):
    """Design matrix on coordinates centred on ``origin`` (default: their mean) and divided by
    ``scale`` (default: their largest centred magnitude), with the origin and scale used."""
    if origin is None:
        origin = points.mean(axis=0)
    if scale is None:
        scale = float(np.abs(points - origin).max()) or 1.0
    return design_matrix((points - origin) / scale, order), origin, scale


def _powers(m):
    """Total degree of each of the first ``m`` terms (how a term scales with the coordinates)."""
    return np.array([px + py for px, py in _TERMS[:m]])


@dataclass
class PolynomialModel(GeometricModel):
    """A fitted polynomial mapping from ``src`` to ``dst`` coordinates.

    Call it on an (n, 2) array of src points to get the (n, 2) dst points.

    Attributes
    ----------
    order : int
        Degree, 1 to 3.
    coefficients : ndarray, shape (2, m)
        Row 0 the a_i of the first output, row 1 the b_i of the second, in the
        lecture's term order, for src coordinates measured from ``origin``.
    origin : ndarray, shape (2,)
        Mean of the fitting GCPs' src coordinates (GDAL centres the same way).
    src, dst : ndarray
        The GCPs the model was fitted on.
    """

    order: int
    coefficients: np.ndarray
    origin: np.ndarray
    scale: float
    src: np.ndarray = field(repr=False)
    dst: np.ndarray = field(repr=False)

    kind = "polynomial"

    def __post_init__(self):
        # the model's own copies: editing the caller's arrays afterwards must not move it
        self.coefficients = np.array(self.coefficients, dtype=np.float64)
        self.origin = np.array(self.origin, dtype=np.float64)
        self.src = np.array(self.src, dtype=np.float64)
        self.dst = np.array(self.dst, dtype=np.float64)

    @property
    def n_parameters(self):
        """Free parameters: two coefficients per term.

        Returns
        -------
        int
            6, 12 or 20 for orders 1, 2, 3.
        """
        return int(self.coefficients.size)

    def __call__(self, points):
        # one evaluation for every caller: the same compiled code the warp kernels run
        return _compiled("transformer").polynomial_many(self.kernel_form()[1],
                                                          as_points(points))

    def kernel_form(self):
        """The model packed for the warp kernels (see :mod:`rsgeo.transformer`).

        Returns
        -------
        (str, ndarray)
            ``("polynomial", parameters)``.
        """
        return "polynomial", _compiled("transformer").polynomial_parameters(
            self.order, self.origin, self.scale, self._scaled_coefficients())

    def _scaled_coefficients(self):
        return self.coefficients * self.scale**_powers(self.coefficients.shape[1])

    def reverse(self):
        """The reverse polynomial (dst -> src), fitted separately on the same GCPs, as GDAL does.

        A polynomial's inverse is not a polynomial, so GDAL fits both
        directions by least squares (``GDALCreateGCPTransformer``); so does
        this. It is an approximation of :meth:`inverse` (exact for order 1 on
        GCPs that fit exactly).

        Returns
        -------
        PolynomialModel
            Fitted from ``dst`` to ``src``, same order.

        Raises
        ------
        GCPError
            As :func:`fit_polynomial` (e.g. the dst points are collinear).

        References
        ----------
        GDAL, ``alg/gdal_crs.cpp``: forward and reverse polynomials are
        both fitted to the GCPs.
        """
        return fit_polynomial(self.dst, self.src, self.order)

    def jacobian(self, points):
        """Partial derivatives of the model at each point, shape (n, 2, 2).

        ``J[i, k, l]`` = d output_k / d input_l at point i.

        Parameters
        ----------
        points : (n, 2) array_like
            src points.

        Returns
        -------
        ndarray, shape (n, 2, 2)

        Raises
        ------
        ValueError
            If the points are not (n, 2) finite numbers.

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10]], dtype=float)
        >>> fit_polynomial(src, src * [2, 3], 1).jacobian([[1.0, 1.0]]).round(6) + 0.0
        array([[[2., 0.],
                [0., 3.]]])
        """
        scaled = (as_points(points) - self.origin) / self.scale
        x, y = scaled[:, 0], scaled[:, 1]
        terms = _TERMS[:self.coefficients.shape[1]]
        d_dx = np.column_stack([px * x**max(px - 1, 0) * y**py for px, py in terms]) / self.scale
        d_dy = np.column_stack([py * x**px * y**max(py - 1, 0) for px, py in terms]) / self.scale
        coefficients = self._scaled_coefficients()
        return np.stack([d_dx @ coefficients.T, d_dy @ coefficients.T], axis=-1)

    def inverse(self, tolerance=1e-9, max_iterations=50, reach=1.0):
        """The exact inverse (dst -> src), by Newton's method on this polynomial.

        Each point starts from :meth:`reverse` (the separately fitted
        polynomial) and is polished until model(p) = q within ``tolerance``
        times the GCPs' dst extent (:func:`newton_inverse`). Inside the GCPs'
        area a well-posed model is one-to-one and this converges in a few steps.

        A polynomial of degree 2 or 3 maps several points onto the same one:
        far from its GCPs Newton's method can converge to another preimage.
        For order >= 2 a solution is refused (``ModelError``) when it lies
        more than ``reach`` GCP extents outside the GCPs' convex hull
        (:func:`outside_hull`) or where the polynomial's Jacobian has the
        other sign than at the GCPs (the other side of a fold).

        Parameters
        ----------
        tolerance : float
            Largest accepted ``|model(p) - q|``, relative to the extent of ``dst``.
        max_iterations : int
            Newton steps at most.
        reach : float
            For order >= 2: farthest accepted preimage beyond the GCPs' hull,
            in GCP extents (1: one extent away).

        Returns
        -------
        InverseModel
            Callable on (n, 2) dst points; raises ``ModelError`` for points
            where the polynomial has no inverse (it folds there, or its
            Jacobian is singular), typically far outside the GCPs, or whose
            preimage lies beyond ``reach`` (another preimage).

        Raises
        ------
        GCPError
            If the reverse polynomial cannot be fitted (see :meth:`reverse`).

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5], [5, 0]], dtype=float)
        >>> model = fit_polynomial(src, src + 0.01 * src**2, 2)
        >>> model.inverse()(model([[3.0, 7.0]])).round(9) + 0.0
        array([[3., 7.]])
        """
        def failure(failed, targets):
            first = targets[np.flatnonzero(failed)[0]]
            return _("the order-{order} polynomial has no inverse at {count} of {n} points "
                     "(first: {first}): Newton's method did not converge, so the polynomial "
                     "folds or is singular there; keep the points inside the GCPs' area").format(
                order=self.order, count=failed.sum(), n=len(targets), first=first.tolist())

        reach = as_number(reach, "reach", low=0, why=N_("GCP extents beyond the GCPs' hull"))
        newton = newton_inverse(self, self.reverse(), tolerance, max_iterations, failure)
        if self.order == 1:
            return newton
        sign = np.sign(np.median(np.linalg.det(self.jacobian(self.src))))

        def solve(targets):
            points = newton(targets)
            beyond = self.outside_gcps(points)
            other_sheet = np.sign(np.linalg.det(self.jacobian(points))) != sign
            far = (beyond > reach) | other_sheet
            if far.any():
                first = int(np.flatnonzero(far)[0])
                raise ModelError(_(
                    "the order-{order} polynomial's preimage of {count} of {n} points lies far "
                    "outside its GCPs (first: {target} -> {point}, {beyond:.3g} GCP extents "
                    "beyond their hull{fold}): a polynomial of degree 2 or 3 has other "
                    "preimages there and none is trustworthy; keep the points inside the "
                    "GCPs' area, add GCPs there, or use order 1").format(
                        order=self.order, count=int(far.sum()), n=len(targets),
                        target=targets[first].tolist(), point=points[first].round(3).tolist(),
                        beyond=float(beyond[first]),
                        fold=_(", across a fold") if other_sheet[first] else ""))
            return points

        return InverseModel(self, solve)

    def standard_errors(self):
        """Standard error of every coefficient, shape (2, m), from the least-squares covariance.

        cov = s² (AᵀA)⁻¹ per output, s² = Σ residual² / (n − m); see
        :func:`rsgeo.accuracy.coefficient_standard_errors`.

        Returns
        -------
        ndarray, shape (2, m)
            Row 0 the standard errors of the a_i, row 1 those of the b_i.

        Raises
        ------
        GCPError
            If the model has no redundant GCP.
        """
        n, m = len(self.src), self.coefficients.shape[1]
        if n <= m:
            raise GCPError(_("standard errors of an order-{order} model need more than "
                             "{m} GCPs (one redundant GCP at least), got {n}").format(
                    order=self.order, m=m, n=n))
        matrix = _normalised_design(self.src, self.order, self.origin, self.scale)[0]
        residual = self(self.src) - self.dst
        variance = np.sum(residual**2, axis=0) / (n - m)            # s² for u and for v
        unscaled = np.diag(np.linalg.inv(matrix.T @ matrix))        # on the scaled terms
        return np.sqrt(variance[:, np.newaxis] * unscaled[np.newaxis, :]) / self.scale**_powers(m)

    def coefficient_summary(self, names=("a", "b")):
        """Coefficients with their standard errors, as a pandas DataFrame.

        Columns: ``value``, ``standard error`` and ``|value| / SE`` (how many
        standard errors the coefficient is from zero: under about 2, the GCPs
        cannot tell it from zero). Rows named as in :meth:`coefficient_table`.

        Parameters
        ----------
        names : (str, str)
            Letters of the two outputs' coefficients.

        Returns
        -------
        pandas.DataFrame
            One row per coefficient.

        Raises
        ------
        GCPError
            If the model has no redundant GCP (no standard error) or ``names``
            is not two strings.
        """
        import pandas as pd

        index = list(self.coefficient_table(names))
        errors = self.standard_errors()
        values = self.coefficients.ravel()
        return pd.DataFrame({"value": values, "standard error": errors.ravel(),
                             "|value| / SE": np.abs(values) / errors.ravel()}, index=index)

    def coefficient_table(self, names=("a", "b")):
        """Coefficients as {"a0 (1)": value, ...}: term names in the lecture's order.

        The variables are measured from the GCPs' mean (``origin``).

        Parameters
        ----------
        names : (str, str)
            Letters of the two outputs' coefficients.

        Returns
        -------
        dict
            ``{"a0 (1)": value, "a1 (x)": value, ...}``, then the b coefficients.

        Raises
        ------
        GCPError
            If ``names`` is not two strings.
        """
        if len(names) != 2 or not all(isinstance(name, str) for name in names):
            raise GCPError(_("names must be two strings (one letter per output), got "
                             "{names!r}").format(names=names))
        table = {}
        for row, letter in enumerate(names):
            for index, term in enumerate(term_names(self.order)):
                table[f"{letter}{index} ({term})"] = float(self.coefficients[row, index])
        return table


#: Largest accepted condition number of the normalised design of an order-n polynomial is this
#: to the power n: a design's condition number grows like (length / width)^n for GCPs that
#: spread over a strip, so this refuses GCPs whose strip is more than 1000 times longer than
#: wide. There a GCP error of 0.1 px across the strip tilts the fit by a pixel 10 strip widths
#: away at order 1 (and far more at orders 2 and 3): the coefficients say nothing. QGIS's own
#: test GCPs (a 1.5 km × 62 km strip, condition 2.9e6 at order 3) stay well below it.
_MAX_SPREAD_RATIO = 1000.0


def fit_polynomial(src, dst, order):
    """Least-squares polynomial of degree ``order`` from ``src`` to ``dst`` points.

    Lecture, slide "Transformações polinomiais": u = f(x, y), v = g(x, y), the
    coefficients from the linear system of the GCPs. With exactly
    ``min_gcps(order)`` GCPs the polynomial passes through every one.

    Parameters
    ----------
    src : (n, 2) array_like
        Coordinates the model is applied to (for resampling: map x, y).
    dst : (n, 2) array_like
        Coordinates it must reproduce (for resampling: image col, row).
    order : {1, 2, 3}

    Returns
    -------
    PolynomialModel

    Raises
    ------
    GCPError
        If the arrays are not (n, 2) of the same length, hold NaN or infinity,
        the order is not 1-3, there are fewer GCPs than ``min_gcps(order)``,
        or the GCPs are collinear or repeated so that the system has no unique
        solution, or nearly collinear (the normalised design's condition
        number above 1000**order, ``_MAX_SPREAD_RATIO``).
    TypeError
        If an array is complex, bool or text, or the order is not a number
        (True, "2").

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> model = fit_polynomial(src, src * 2 + 1, order=1)
    >>> model([[5.0, 5.0]]).round(6)
    array([[11., 11.]])
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    order = _check_order(order)
    if len(src) != len(dst):
        raise GCPError(_("src and dst must hold the same GCPs, got {n_src} and {n_dst} points")
                       .format(n_src=len(src), n_dst=len(dst)))
    needed = _n_terms(order)
    if len(src) < needed:
        raise GCPError(_("order {order} needs at least {n} GCPs, got {got}").format(
            order=order, n=needed, got=len(src)))
    matrix, origin, scale = _normalised_design(src, order)
    rank = np.linalg.matrix_rank(matrix)
    if rank < needed:
        raise GCPError(_(
            "the GCPs do not determine an order-{order} polynomial: they are collinear, repeated "
            "or too clustered (rank {rank} of the {n} needed); spread the GCPs over the image")
            .format(order=order, rank=rank, n=needed))
    condition = float(np.linalg.cond(matrix))
    if condition > _MAX_SPREAD_RATIO**order:
        raise GCPError(_(
            "the GCPs are (nearly) collinear for an order-{order} polynomial: its design's "
            "condition number is {condition:.3g} (above {limit:.0e}), so the GCPs spread about "
            "{ratio:.0f} times less across than along and the coefficients would be set by their "
            "errors; add GCPs off the line they follow (spread them over the image) or use a "
            "lower order").format(order=order, condition=condition,
                                  limit=_MAX_SPREAD_RATIO**order,
                                  ratio=condition ** (1 / order)))
    scaled = np.linalg.lstsq(matrix, dst, rcond=None)[0]
    coefficients = (scaled / scale**_powers(needed)[:, np.newaxis]).T
    return PolynomialModel(order, coefficients, origin, scale, src, dst)


# --- Matrix models: linear, Helmert, projective --------------------------------------------------


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
        Free parameters: 4 (linear, Helmert) or 8 (projective), from :data:`REGISTRY`.
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
        self.n_parameters = n_parameters(kind)
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
        """The model packed for the warp kernels (see :mod:`rsgeo.transformer`).

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


def _fit_linear(src, dst):
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


def _fit_helmert(src, dst):
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


def _fit_projective(src, dst):
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


# --- Thin-plate spline ---------------------------------------------------------------------------


class TPSModel(GeometricModel):
    """Thin-plate spline through every GCP, GDAL's (``gdalwarp -tps``), bit for bit.

    u(x, y) = a0 + a1 x + a2 y + Σ w_i r_i² log r_i², the same for v, with
    r_i the distance to GCP i (x and y measured from the GCPs' mean); the
    weights make it pass through every GCP and its bending energy is the
    smallest that does. Solved and evaluated as GDAL's ``VizGeorefSpline2D``
    does (:mod:`rsgeo.thin_plate`): the same LU decomposition, the same
    order of operations, GDAL's faster logarithm for the grouped terms, so
    its values equal GDAL's to the last bit. It therefore misses its GCPs by
    GDAL's rounding (about 1e-11 px with tens of GCPs, 1e-7 px with
    thousands), and GCPs nearly on one line (r² of their x and y above 0.99,
    or one extent under a thousandth of the other) give GDAL's
    piecewise-linear interpolation along that line instead of a spline.

    Parameters
    ----------
    src, dst : (n, 2) ndarray
        The GCPs, checked by :func:`fit_transform`.

    skipped : sequence of int
        Rows of the GCPs given to :func:`fit_transform` that repeated an
        earlier GCP exactly (same src and dst) and were left out, as GDAL's
        TPS transformer does.

    Attributes
    ----------
    kind : str
        "tps".
    n_parameters : int
        2 (n + 3): n weights and 3 affine coefficients per output.
    skipped : tuple of int
        The exact duplicates left out.
    packed : ndarray
        The solved spline, read-only, for :func:`rsgeo.thin_plate.evaluate`
        (its layout is in that module's docstring).
    """

    kind = "tps"

    def __init__(self, src, dst, skipped=()):
        self.src = np.array(src, dtype=np.float64)
        self.dst = np.array(dst, dtype=np.float64)
        self.skipped = tuple(skipped)
        self.n_parameters = n_parameters("tps", n_gcps=len(self.src))
        self.packed = _compiled("thin_plate").solve(self.src, self.dst)
        self.packed.flags.writeable = False
        self._floor = None

    def __call__(self, points):
        """Evaluate the spline at (n, 2) points.

        Parameters
        ----------
        points : (n, 2) array_like

        Returns
        -------
        ndarray, shape (n, 2)

        Raises
        ------
        ValueError
            If the points are not (n, 2) finite numbers.
        """
        return _evaluate_tps(self.packed, points)

    def kernel_form(self):
        """The model packed for the warp kernels (see :mod:`rsgeo.transformer`).

        Returns
        -------
        (str, ndarray)
            ``("tps", packed)``: :attr:`packed`.
        """
        return "tps", self.packed

    def reverse(self):
        """A thin-plate spline fitted the other way round (dst -> src), as GDAL does.

        GDAL's TPS transformer fits a second spline from dst to src on the
        same GCPs, the start of its inversion (:meth:`inverse`); rasterio's
        ``GCPTransformer(gcps, tps=True).rowcol`` is this spline. Both pass
        through every GCP, so they are inverse at the GCPs and only
        approximately so between them (a tenth of a pixel).

        Returns
        -------
        TPSModel

        Raises
        ------
        GCPError
            If the dst points are repeated or collinear.
        """
        return fit_transform(self.dst, self.src, "tps")

    def jacobian(self, points, step=1e-4):
        """Partial derivatives at each point, shape (n, 2, 2), by central differences.

        ``step`` is relative to the GCPs' src extent; the spline is smooth, so
        the error is of order step².

        Parameters
        ----------
        points : (n, 2) array_like
        step : float
            Difference step, relative to the src extent.

        Returns
        -------
        ndarray, shape (n, 2, 2)
            ``J[i, k, l]`` = d output_k / d input_l at point i.

        Raises
        ------
        ValueError
            If the points are not (n, 2) finite numbers.
        """
        points = as_points(points)
        h = as_number(step, "step", low=1e-12, high=1e-1) * (
            float(np.abs(self.src - self.src.mean(axis=0)).max()) or 1.0)
        columns = []
        for axis in range(2):
            offset = np.zeros(2)
            offset[axis] = h
            columns.append((self(points + offset) - self(points - offset)) / (2 * h))
        return np.stack(columns, axis=-1)

    def inverse(self, tolerance=1e-10, max_iterations=None):
        """The inverse (dst -> src), by GDAL's Newton's method on this spline.

        What gdalwarp computes for each output cell when the spline is fitted
        image -> map (``gdalwarp -tps``; GDAL's ``GDALTPSTransform`` from dst
        to src): each point starts from :meth:`reverse`, the spline fitted the
        other way round, and is refined by ``GDALGenericInverse2D`` - Newton's
        method with the Jacobian estimated once, at the start, by forward
        differences - until both coordinates of model(p) are within 1e-12 of
        the target's largest coordinate, in at most ``max_iterations`` steps.
        The result equals GDAL's to the last bit, and the warp kernels compute
        the same (the inverse's ``kernel_form``).

        GDAL keeps its last step where it has not converged (its Jacobian,
        estimated once, can be far from the one at the root where the spline
        bends strongly: a few 1e-9 of the extent off after 15 steps). Here,
        for those points only, Newton's method goes on from that step with
        the Jacobian at every step (:func:`newton_inverse`) until
        ``|model(p) - q|`` is within ``tolerance`` times the dst extent, or
        within what float64 evaluation of the spline can reach
        (:meth:`evaluation_floor`: a spline through thousands of noisy GCPs
        sums terms far larger than its value); otherwise ``ModelError``. The
        warp kernels, like gdalwarp, use GDAL's steps alone.

        Parameters
        ----------
        tolerance : float
            Largest accepted ``|model(p) - q|`` where GDAL's own test fails,
            relative to the extent of ``dst``.
        max_iterations : int, optional
            Newton steps at most, GDAL's (by default its 15,
            :data:`rsgeo.thin_plate.GDAL_STEPS`) and again as many for the
            points they leave short.

        Returns
        -------
        InverseModel
            Raises ``ModelError`` at points where the refinement does not
            converge (the spline folds there); its ``packed`` attribute is
            :func:`rsgeo.thin_plate.pack_inverse` of this spline and its reverse.

        Raises
        ------
        GCPError
            If the reverse spline cannot be fitted (repeated or collinear dst).
        ValueError
            If ``tolerance`` is negative or ``max_iterations`` not an integer >= 0.
        """
        if max_iterations is None:
            max_iterations = _compiled("thin_plate").GDAL_STEPS
        return _TPSInverse(self, self.reverse(), tolerance, max_iterations)

    def evaluation_floor(self):
        """How closely float64 evaluation of this spline can meet a target, dst units.

        Ten times its largest miss at its own GCPs, where it passes exactly in
        exact arithmetic: what is left is the rounding of the linear solve and
        of the sums of the kernel terms (and of GDAL's faster logarithm).

        Returns
        -------
        float
        """
        if self._floor is None:
            miss = np.hypot(*(self(self.src) - self.dst).T).max()
            self._floor = 10.0 * float(miss)
        return self._floor

    def __repr__(self):
        return f"TPSModel(n_gcps={len(self.src)})"


def _evaluate_tps(packed, points):
    """A packed spline (or GDAL's inversion of one) at (n, 2) points, compiled."""
    points = np.ascontiguousarray(as_points(points))
    out = np.empty_like(points)
    _compiled("thin_plate").evaluate_many(packed, points, out)
    return out


class _TPSInverse(InverseModel):
    """A :class:`TPSModel` inverted as GDAL's TPS transformer does (:meth:`TPSModel.inverse`)."""

    def __init__(self, forward, reverse, tolerance, max_iterations):
        self.packed = _compiled("thin_plate").pack_inverse(forward.packed, reverse.packed,
                                                            max_iterations)
        self.packed.flags.writeable = False
        self._tolerance = as_number(tolerance, "tolerance", low=0,
                                    why=N_("relative to the dst extent"))
        self._max_iterations = int(self.packed[1])
        super().__init__(forward, self._solve_points)

    def kernel_form(self):
        """The inversion packed for the warp kernels (see :mod:`rsgeo.transformer`).

        Returns
        -------
        (str, ndarray)
            ``("tps", packed)``: GDAL's steps only, as gdalwarp computes them.
        """
        return "tps", self.packed

    def _solve_points(self, targets):
        targets = np.ascontiguousarray(targets)
        points = np.empty_like(targets)
        converged = np.empty(len(targets), dtype=bool)
        _compiled("thin_plate").invert_many(self.packed, targets, points, converged)
        if not converged.all():
            # GDAL would keep its last step; go on from it with the full Jacobian at each step
            rest = ~converged
            polish = newton_inverse(self.forward, lambda _targets: points[rest], self._tolerance,
                                    self._max_iterations, _tps_inverse_failure,
                                    floor=self.forward.evaluation_floor())
            points[rest] = polish(targets[rest])
        return points


def _tps_inverse_failure(failed, targets):
    return _("the thin-plate spline has no inverse at {failed} of {total} points: Newton's "
             "method did not converge (the spline folds there); keep the points inside the "
             "GCPs' area").format(failed=int(failed.sum()), total=len(targets))


#: GCPs whose src points are closer than this fraction of the GCPs' src extent while their
#: dst points are not (relative to the dst extent) make a thin-plate spline bend to reach both:
#: 1 cm apart with different targets put it 1,674 px off at the scene's centre.
_TPS_NEAR = 1e-4


def _fit_tps(src, dst):
    """The spline through every GCP; exact duplicates skipped (as GDAL does), conflicting or
    nearly coincident src points with different dst refused."""
    _unique, first, inverse_index = np.unique(src, axis=0, return_index=True,
                                              return_inverse=True)
    inverse_index = np.ravel(inverse_index)
    skipped = []
    conflicts = []
    for row in range(len(src)):
        earlier = int(first[inverse_index[row]])
        if earlier != row:
            if np.array_equal(dst[row], dst[earlier]):
                skipped.append(row)
            else:
                conflicts.append((earlier, row))
    if conflicts:
        raise GCPError(_(
            "a 'tps' model needs one dst point per src point, but rows {pairs} have the same "
            "src point and different dst points (a spline cannot pass through two targets at "
            "one place); remove or correct one of each pair").format(
                pairs=", ".join(f"{a} and {b}" for a, b in conflicts[:5])))
    if skipped:
        keep = np.setdiff1d(np.arange(len(src)), skipped)
        src, dst = src[keep], dst[keep]
    else:
        keep = np.arange(len(src))
    from scipy.spatial import cKDTree

    src_extent = float(np.ptp(src, axis=0).max()) or 1.0
    dst_extent = float(np.ptp(dst, axis=0).max()) or 1.0
    pairs = cKDTree(src).query_pairs(_TPS_NEAR * src_extent, output_type="ndarray")
    if len(pairs):
        apart = np.hypot(*(dst[pairs[:, 0]] - dst[pairs[:, 1]]).T) > _TPS_NEAR * dst_extent
        pairs = pairs[apart]
    if len(pairs):
        a, b = keep[pairs[0]]
        raise GCPError(_(
            "a 'tps' model cannot pass through GCPs {count} pair(s) of which are nearly at one "
            "src point but go to different dst points (first: rows {a} and {b}, {distance:.3g} "
            "apart in src, {gap:.3g} in dst; the spline would bend wildly between them); "
            "remove or correct one of each pair (src points closer than {near:g} of the GCPs' "
            "extent must also agree in dst)").format(
                count=len(pairs), a=int(a), b=int(b),
                distance=float(np.hypot(*(src[pairs[0, 0]] - src[pairs[0, 1]]))),
                gap=float(np.hypot(*(dst[pairs[0, 0]] - dst[pairs[0, 1]]))), near=_TPS_NEAR))
    centred = (src - src.mean(axis=0)) / (np.abs(src - src.mean(axis=0)).max() or 1.0)
    if np.linalg.matrix_rank(np.column_stack([np.ones(len(src)), centred]), tol=1e-9) < 3:
        raise GCPError(_("a 'tps' model needs at least 3 GCPs that are not collinear (its "
                         "affine part is fixed by them); spread the GCPs over the image"))
    return TPSModel(src, dst, skipped)


# --- The registry: every kind once, and what is derived from it ----------------------------------


@dataclass(frozen=True)
class ModelKind:
    """One entry of :data:`REGISTRY`: a model kind (and order) QGIS's Georeferencer offers.

    Attributes
    ----------
    label : str
        Its name in tables ("polynomial 2").
    kind : str
        ``fit_transform``'s ``kind``.
    order : int or None
        The polynomial's degree; None for the other kinds.
    fit : callable
        ``fit(src, dst)`` on checked (n, 2) arrays -> a :class:`GeometricModel`.
    min_gcps : int
        Fewest GCPs that determine the model.
    n_parameters : int or None
        Free parameters; None when they grow with the GCPs (a TPS has 2 (n + 3)).
    """

    label: str
    kind: str
    order: int | None
    fit: Callable = field(repr=False)
    min_gcps: int
    n_parameters: int | None


#: Every model kind rsgeo fits, in QGIS's Georeferencer's order. A polynomial's minimum is its
#: number of terms, (n+1)(n+2)/2; "tps" needs 3 GCPs for its affine part (GDAL accepts fewer and
#: returns a degenerate mapping).
REGISTRY = (
    ModelKind("linear", "linear", None, _fit_linear, 2, 4),
    ModelKind("helmert", "helmert", None, _fit_helmert, 2, 4),
    *(ModelKind(f"polynomial {n}", "polynomial", n,
                lambda src, dst, n=n: fit_polynomial(src, dst, n), _n_terms(n), 2 * _n_terms(n))
      for n in ORDERS),
    ModelKind("projective", "projective", None, _fit_projective, 4, 8),
    ModelKind("tps", "tps", None, _fit_tps, 3, None),
)

#: The kinds :func:`fit_transform` accepts.
KINDS = tuple(dict.fromkeys(entry.kind for entry in REGISTRY))

#: The models QGIS's Georeferencer offers, as (label, kind, order).
GEOREFERENCER_MODELS = tuple((entry.label, entry.kind, entry.order) for entry in REGISTRY)


def registered(kind, order=None, caller="min_gcps"):
    """The :data:`REGISTRY` entry of a kind (and order), with both checked.

    Parameters
    ----------
    kind : {"linear", "helmert", "polynomial", "projective", "tps"} or {1, 2, 3}
        Model kind, or directly the polynomial's degree.
    order : {1, 2, 3} or None
        Degree, only with ``kind="polynomial"``.
    caller : str
        The function named in the message when the order is given twice.

    Returns
    -------
    ModelKind

    Raises
    ------
    GCPError
        If the kind is unknown, the order is not 1, 2 or 3, a polynomial has no
        order or another kind has one.

    Examples
    --------
    >>> registered("polynomial", 2).min_gcps, registered(2).label
    (6, 'polynomial 2')
    """
    if not isinstance(kind, str):
        if order is not None:
            raise GCPError(_("give the polynomial's order once: {caller}(order) or "
                             "{caller}('polynomial', order)").format(caller=caller))
        kind, order = "polynomial", kind
    if kind not in KINDS:
        raise GCPError(_("unknown transformation kind {kind!r}; choose one of {listed}").format(
                kind=kind, listed=', '.join(map(repr, KINDS))))
    if kind == "polynomial":
        if order is None:
            raise GCPError(_("kind 'polynomial' needs an order: 1, 2 or 3"))
        order = _check_order(order)
    elif order is not None:
        raise GCPError(_("kind {kind!r} has no order (got order={order!r}); only "
                         "'polynomial' takes one").format(kind=kind, order=order))
    return next(entry for entry in REGISTRY if (entry.kind, entry.order) == (kind, order))


def min_gcps(kind, order=None):
    """Minimum number of GCPs that determine a model: (n+1)(n+2)/2 for a polynomial.

    Lecture, slide "Transformações polinomiais": the degree fixes the minimum
    number of GCPs needed to solve the linear system. ``min_gcps(order)`` with
    an integer is the polynomial of that order. Other kinds: "linear" and
    "helmert" 2, "projective" 4, "tps" 3 (its affine part needs three
    non-collinear points; GDAL accepts fewer and returns a degenerate mapping).
    Read from :data:`REGISTRY`.

    Parameters
    ----------
    kind : {"linear", "helmert", "polynomial", "projective", "tps"} or {1, 2, 3}
        Model kind, or directly the polynomial's degree.
    order : {1, 2, 3} or None
        Degree, only with ``kind="polynomial"``.

    Returns
    -------
    int
        3, 6 or 10 for polynomials of order 1, 2, 3; 2, 2, 4, 3 for the others.

    Raises
    ------
    GCPError
        If the kind is unknown, the order is not 1, 2 or 3, a polynomial has no
        order or another kind has one.

    Examples
    --------
    >>> [min_gcps(n) for n in (1, 2, 3)]
    [3, 6, 10]
    >>> min_gcps("projective"), min_gcps("polynomial", 2)
    (4, 6)
    """
    return registered(kind, order).min_gcps


def n_parameters(kind, order=None, n_gcps=None):
    """Free parameters of a model kind (both outputs together), read from :data:`REGISTRY`.

    Parameters
    ----------
    kind : {"linear", "helmert", "polynomial", "projective", "tps"} or {1, 2, 3}
        As :func:`min_gcps`.
    order : {1, 2, 3} or None
        Degree, only with ``kind="polynomial"``.
    n_gcps : int, optional
        Number of GCPs; needed for "tps", whose parameters are 2 (n + 3).

    Returns
    -------
    int
        4 (linear, Helmert), 6, 12, 20 (polynomials of order 1-3), 8
        (projective), 2 (n + 3) (TPS).

    Raises
    ------
    GCPError
        As :func:`min_gcps`, or for "tps" without ``n_gcps``.

    Examples
    --------
    >>> n_parameters("helmert"), n_parameters(2), n_parameters("tps", n_gcps=10)
    (4, 12, 26)
    """
    entry = registered(kind, order, "n_parameters")
    if entry.n_parameters is not None:
        return entry.n_parameters
    if n_gcps is None:
        raise GCPError(_("the parameters of a {entry_kind!r} model grow with its GCPs; "
                         "give n_gcps").format(entry_kind=entry.kind))
    return 2 * (int(n_gcps) + 3)


def _fit_inputs(src, dst, kind, order):
    """Checked (n, 2) arrays and the registry entry; enough GCPs for the kind."""
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    entry = registered(kind, order, "fit_transform")
    if len(src) != len(dst):
        raise GCPError(_("src and dst must hold the same GCPs, got {n_src} and {n_dst} "
                         "points").format(n_src=len(src), n_dst=len(dst)))
    if len(src) < entry.min_gcps:
        raise GCPError((_("an order-{order} polynomial needs at least {min_gcps} GCPs, got "
                          "{n_src}") if entry.kind == "polynomial" else
                        _("a {kind!r} model needs at least {min_gcps} GCPs, got {n_src}")).format(
                order=entry.order, kind=entry.kind, min_gcps=entry.min_gcps, n_src=len(src)))
    return src, dst, entry


def fit_transform(src, dst, kind, order=None):
    """Fit one of QGIS's Georeferencer models to GCPs, mapping ``src`` to ``dst``.

    ============  =====================================================  ==========
    kind          model                                                  min GCPs
    ============  =====================================================  ==========
    "linear"      u = a x + c, v = b y + d (scale and offset per axis)   2
    "helmert"     rotation, one scale, translation (similarity)          2
    "polynomial"  degree ``order`` 1-3, GDAL's least squares             3, 6, 10
    "projective"  8-parameter plane homography (tilted frame camera)     4
    "tps"         thin-plate spline, exact at every GCP (GDAL ``-tps``)  3
    ============  =====================================================  ==========

    Every model follows the protocol of :class:`GeometricModel` and has
    ``kind`` and ``n_parameters``. ``inverse()`` is exact for linear, Helmert
    and projective (matrix inverse) and for polynomials (Newton's method);
    a TPS's ``inverse()`` solves the spline itself by Newton's method, to
    ``tolerance`` times the GCPs' dst extent (a ``ValueError`` where it does
    not converge), starting from :meth:`TPSModel.reverse`, the second spline
    fitted the other way round, which is only approximately inverse between
    the GCPs. Helmert includes a reflection when the GCPs need one (map y
    up, image rows down).

    Parameters
    ----------
    src : (n, 2) array_like
        Coordinates the model is applied to (for resampling: map x, y).
    dst : (n, 2) array_like
        Coordinates it must reproduce (for resampling: image col, row).
    kind : {"linear", "helmert", "polynomial", "projective", "tps"}
        Or directly a polynomial's order, as :func:`min_gcps`.
    order : {1, 2, 3} or None
        Only for ``kind="polynomial"``.

    Returns
    -------
    GeometricModel
        :class:`MatrixModel`, :class:`PolynomialModel` or :class:`TPSModel`.

    Raises
    ------
    GCPError
        Unknown kind; an order for a kind that has none (or none for a
        polynomial); fewer GCPs than ``min_gcps(kind, order)``; collinear
        points for projective, TPS or polynomial (nearly collinear for a
        polynomial); for TPS, src points repeated or closer than 1e-4 of the
        GCPs' extent with different dst points (exact duplicates, same src and
        same dst, are skipped as GDAL does and listed in ``model.skipped``).
    TypeError
        If an array is complex, bool or text, or the order is not a number.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> model = fit_transform(src, src * 2 + 1, "helmert")
    >>> model.kind, model.n_parameters, model([[5.0, 5.0]]).round(6).tolist()
    ('helmert', 4, [[11.0, 11.0]])
    """
    src, dst, entry = _fit_inputs(src, dst, kind, order)
    return entry.fit(src, dst)
