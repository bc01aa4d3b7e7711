"""Georeferencing with ground control points: polynomial models, residuals, RMS.

The lecture's "Transformações polinomiais": two Cartesian systems - map
coordinates (x, y) of the GCPs and image coordinates of the distorted image -
are related by polynomials u = f(x, y), v = g(x, y) of degree 1 to 3,

    u = a0 + a1 x + a2 y + a3 xy + a4 x² + a5 y²        (degree 2)
    v = b0 + b1 x + b2 y + b3 xy + b4 x² + b5 y²,

whose coefficients come from a linear system built from the GCPs, solved here
by least squares. As GDAL does, x and y are measured from the GCPs' mean, so a
third-degree fit on UTM-sized numbers stays well conditioned; the fit is also
scaled internally, which changes nothing but the rounding.

Image coordinates follow GDAL: (col, row) = (pixel, line), continuous, with the
image's top-left corner at (0, 0).
"""

import csv
import io
from dataclasses import dataclass, field
from math import comb

import numpy as np
from scipy.interpolate import RBFInterpolator

from ._checks import as_points, as_shape, check_range
from ._i18n import _

__all__ = [
    "ORDERS", "min_gcps", "term_names", "design_matrix", "GeometricModel", "InverseModel",
    "PolynomialModel", "fit_polynomial", "coefficient_standard_errors", "residuals",
    "rms_error", "mean_error", "refine_gcps", "fit_with_check_points", "leave_one_out_errors",
    "condition_number", "hull_coverage", "predicted_error_map", "measure_shifts",
    "GeotransformCheck", "compare_with_geotransform", "offsets_against_reference", "GCPSet",
    "read_points", "write_points", "KINDS", "MatrixModel", "TPSModel", "fit_transform",
    "GEOREFERENCER_MODELS", "transform_leave_one_out", "compare_models",
]

ORDERS = (1, 2, 3)

# (power of x, power of y) of every term, in the lecture's order:
# 1, x, y, xy, x², y², then the cubic terms.
_TERMS = ((0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2), (2, 1), (1, 2), (3, 0), (0, 3))


def _check_order(order):
    if order not in ORDERS:
        raise ValueError(f"polynomial order must be 1, 2 or 3 (the lecture's degrees), got {order!r}")
    return int(order)


def min_gcps(kind, order=None):
    """Minimum number of GCPs that determine a model: (n+1)(n+2)/2 for a polynomial.

    Lecture, slide "Transformações polinomiais": the degree fixes the minimum
    number of GCPs needed to solve the linear system. ``min_gcps(order)`` with
    an integer is the polynomial of that order. Other kinds: "linear" and
    "helmert" 2, "projective" 4, "tps" 3 (its affine part needs three
    non-collinear points; GDAL accepts fewer and returns a degenerate mapping).

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
    ValueError
        If the kind is unknown, the order is not 1, 2 or 3, a polynomial has no
        order or another kind has one.

    Examples
    --------
    >>> [min_gcps(n) for n in (1, 2, 3)]
    [3, 6, 10]
    >>> min_gcps("projective"), min_gcps("polynomial", 2)
    (4, 6)
    """
    if not isinstance(kind, str):
        if order is not None:
            raise ValueError("give the polynomial's order once: min_gcps(order) or "
                             "min_gcps('polynomial', order)")
        kind, order = "polynomial", kind
    order = _check_kind(kind, order)
    if kind == "polynomial":
        return comb(order + 2, 2)
    return _FIXED_MINIMUM[kind]


_minimum_gcps = min_gcps


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
    ValueError
        If the order is not 1, 2 or 3.

    Examples
    --------
    >>> term_names(2)
    ['1', 'x', 'y', 'xy', 'x²', 'y²']
    """
    superscript = {1: "", 2: "²", 3: "³"}
    names = []
    for px, py in _TERMS[:min_gcps(order)]:
        name = (variables[0] + superscript[px] if px else "") + (variables[1] + superscript[py] if py else "")
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
    ValueError
        If the points are not (n, 2) finite numbers or the order is not 1-3.

    Examples
    --------
    >>> design_matrix([[2.0, 3.0]], 2)
    array([[1., 2., 3., 6., 4., 9.]])
    """
    points = as_points(points)
    order = _check_order(order)
    x, y = points[:, 0], points[:, 1]
    return np.column_stack([x**px * y**py for px, py in _TERMS[:min_gcps(order)]])


def _normalised_design(points, order, origin=None, scale=None):
    """Design matrix on coordinates centred on ``origin`` (default: their mean) and divided by
    ``scale`` (default: their largest centred magnitude), with the origin and scale used."""
    if origin is None:
        origin = points.mean(axis=0)
    if scale is None:
        scale = float(np.abs(points - origin).max()) or 1.0
    return design_matrix((points - origin) / scale, order), origin, scale


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
        raise NotImplementedError(f"{type(self).__name__} does not define its mapping")

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
        raise NotImplementedError(f"{type(self).__name__} does not define its inverse")

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
        ValueError
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
        ValueError
            As :meth:`residuals`, or when there is no point.

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10]], dtype=float)
        >>> round(fit_polynomial(src, src, 1).rms(src, src + [[3, 4], [0, 0], [0, 0]]), 4)
        2.8868
        """
        predicted, _ = _residual_vectors(self, src, dst)
        return rms_error(predicted, as_points(dst, "dst"))


def _residual_vectors(model, src, dst):
    """model(src) and |model(src) - dst|, with the inputs checked."""
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise ValueError(f"src and dst must hold the same points, got {len(src)} and {len(dst)}")
    predicted = np.asarray(model(src), dtype=np.float64)
    if predicted.shape != dst.shape:
        raise ValueError(f"the model must return an (n, 2) array, got shape {predicted.shape}")
    return predicted, np.hypot(*(predicted - dst).T)


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
            If the points are not (n, 2) finite numbers, or the solution does
            not converge (the model folds or is singular there).
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
        scaled_terms, _, _ = _normalised_design(as_points(points), self.order, self.origin, self.scale)
        return scaled_terms @ self._scaled_coefficients().T

    def _scaled_coefficients(self):
        powers = np.array([px + py for px, py in _TERMS[:self.coefficients.shape[1]]])
        return self.coefficients * self.scale**powers

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
        ValueError
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

    def inverse(self, tolerance=1e-9, max_iterations=50):
        """The exact inverse (dst -> src), by Newton's method on this polynomial.

        Each point starts from :meth:`reverse` (the separately fitted
        polynomial) and is polished until model(p) = q within ``tolerance``
        times the GCPs' dst extent. Inside the GCPs' area a well-posed model is
        one-to-one and this converges in a few steps.

        Parameters
        ----------
        tolerance : float
            Largest accepted ``|model(p) - q|``, relative to the extent of ``dst``.
        max_iterations : int

        Returns
        -------
        InverseModel
            Callable on (n, 2) dst points; raises ``ValueError`` for points
            where the polynomial has no inverse (it folds there, or its
            Jacobian is singular), typically far outside the GCPs.

        Raises
        ------
        ValueError
            If the reverse polynomial cannot be fitted (see :meth:`reverse`).

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5], [5, 0]], dtype=float)
        >>> model = fit_polynomial(src, src + 0.01 * src**2, 2)
        >>> model.inverse()(model([[3.0, 7.0]])).round(9) + 0.0
        array([[3., 7.]])
        """
        start = self.reverse()
        extent = float(np.abs(self.dst - self.dst.mean(axis=0)).max()) or 1.0
        limit = check_range(tolerance, "tolerance", low=0, why="relative to the dst extent") * extent

        def solve(targets):
            points = start(targets)
            error = np.full(len(targets), np.inf)
            for _ in range(int(max_iterations)):
                difference = self(points) - targets
                error = np.hypot(difference[:, 0], difference[:, 1])
                if not (error > limit).any():
                    break
                jacobian = self.jacobian(points)
                determinant = np.linalg.det(jacobian)
                usable = np.abs(determinant) > 1e-300
                step = np.zeros_like(points)
                step[usable] = np.linalg.solve(jacobian[usable], difference[usable][..., None])[..., 0]
                points = points - step
            failed = ~(error <= limit)
            if failed.any():
                first = targets[np.flatnonzero(failed)[0]]
                raise ValueError(
                    f"the order-{self.order} polynomial has no inverse at {failed.sum()} of "
                    f"{len(targets)} points (first: {first.tolist()}): Newton's method did not "
                    "converge, so the polynomial folds or is singular there; keep the points "
                    "inside the GCPs' area")
            return points

        return InverseModel(self, solve)

    def standard_errors(self):
        """Standard error of every coefficient, shape (2, m): see :func:`coefficient_standard_errors`.

        Returns
        -------
        ndarray, shape (2, m)
            As :func:`coefficient_standard_errors`.

        Raises
        ------
        ValueError
            If the model has no redundant GCP.
        """
        return coefficient_standard_errors(self)

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
        ValueError
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
        ValueError
            If ``names`` is not two strings.
        """
        if len(names) != 2 or not all(isinstance(name, str) for name in names):
            raise ValueError(f"names must be two strings (one letter per output), got {names!r}")
        table = {}
        for row, letter in enumerate(names):
            for index, term in enumerate(term_names(self.order)):
                table[f"{letter}{index} ({term})"] = float(self.coefficients[row, index])
        return table


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
    ValueError
        If the arrays are not (n, 2) of the same length, hold NaN or infinity,
        the order is not 1-3, there are fewer GCPs than ``min_gcps(order)``,
        or the GCPs are collinear or repeated so that the system has no unique
        solution.

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
        raise ValueError(_("src and dst must hold the same GCPs, got {n_src} and {n_dst} points")
                         .format(n_src=len(src), n_dst=len(dst)))
    needed = min_gcps(order)
    if len(src) < needed:
        raise ValueError(_("order {order} needs at least {n} GCPs, got {got}").format(
            order=order, n=needed, got=len(src)))
    matrix, origin, scale = _normalised_design(src, order)
    rank = np.linalg.matrix_rank(matrix)
    if rank < needed:
        raise ValueError(_(
            "the GCPs do not determine an order-{order} polynomial: they are collinear, repeated "
            "or too clustered (rank {rank} of the {n} needed); spread the GCPs over the image")
            .format(order=order, rank=rank, n=needed))
    scaled = np.linalg.lstsq(matrix, dst, rcond=None)[0]
    powers = np.array([px + py for px, py in _TERMS[:needed]])
    coefficients = (scaled / scale**powers[:, np.newaxis]).T
    return PolynomialModel(order, coefficients, origin, scale, src, dst)


def coefficient_standard_errors(model):
    """Standard errors of a fitted polynomial's coefficients, from the least-squares covariance.

    For each output coordinate separately (u, then v), with A the design
    matrix of the fitting GCPs in the lecture's term order (x, y measured from
    ``model.origin``), n GCPs and m coefficients, the textbook covariance of
    the coefficients is

        cov = s² (AᵀA)⁻¹,   s² = Σ residual² / (n − m),

    and a coefficient's standard error is the square root of its diagonal
    entry. A coefficient within about two standard errors of zero is not
    supported by the GCPs. It assumes independent GCP errors of equal
    variance; a blunder inflates s² and every standard error with it.

    Parameters
    ----------
    model : PolynomialModel
        As :func:`fit_polynomial` returns; its ``src`` and ``dst`` are the GCPs.

    Returns
    -------
    ndarray, shape (2, m)
        Row 0 the standard errors of the a_i, row 1 those of the b_i, in the
        order of ``model.coefficients``.

    Raises
    ------
    ValueError
        If the model has no redundant GCP (n <= m): s² cannot be estimated.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> dst = src * 2 + [[0, 0], [0, 0], [0, 0], [0, 0], [1, -1]]
    >>> coefficient_standard_errors(fit_polynomial(src, dst, 1)).round(3)
    array([[0.283, 0.063, 0.063],
           [0.283, 0.063, 0.063]])
    """
    if not isinstance(model, PolynomialModel):
        raise ValueError(f"model must be a PolynomialModel (from fit_polynomial), got {type(model).__name__}")
    n, m = len(model.src), model.coefficients.shape[1]
    if n <= m:
        raise ValueError(f"standard errors of an order-{model.order} model need more than {m} GCPs "
                         f"(one redundant GCP at least), got {n}")
    matrix, _, _ = _normalised_design(model.src, model.order, model.origin, model.scale)
    residual = model(model.src) - model.dst
    variance = np.sum(residual**2, axis=0) / (n - m)            # s² for u and for v
    unscaled = np.diag(np.linalg.inv(matrix.T @ matrix))        # on the scaled terms
    powers = np.array([px + py for px, py in _TERMS[:m]])
    return np.sqrt(variance[:, np.newaxis] * unscaled[np.newaxis, :]) / model.scale**powers


def residuals(model, src, dst):
    """Per-GCP residuals of a model: dx, dy and R_i = sqrt(dx² + dy²).

    Lecture, slide "Avaliação da transformação": R_i is the distance between
    the position the model gives and the GCP's own position, in dst units
    (pixels when the model goes map -> image).

    Parameters
    ----------
    model : callable
        A model on (n, 2) arrays (e.g. a :class:`PolynomialModel`).
    src, dst : (n, 2) array_like
        The GCPs in the model's input and output coordinates.

    Returns
    -------
    dx, dy, distance : ndarray
        ``model(src) - dst`` split in its two components, and its length.

    Raises
    ------
    ValueError
        If src and dst are not (n, 2) of the same length or hold NaN.
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise ValueError(f"src and dst must hold the same GCPs, got {len(src)} and {len(dst)} points")
    difference = model(src) - dst
    return difference[:, 0], difference[:, 1], np.hypot(difference[:, 0], difference[:, 1])


def rms_error(predicted, observed):
    """The lecture's RMS: sqrt( (1/n) Σ (x_i - x̄_i)² + (y_i - ȳ_i)² ).

    Lecture, slide "Avaliação da transformação". The lecture reads RMS = 2 as
    "the corrected pixels are on average 2 pixels from where they belong"; an
    RMS computed on the fitting GCPs describes those GCPs only: elsewhere the
    error can be larger (use check points or :func:`leave_one_out_errors`).

    Parameters
    ----------
    predicted, observed : (n, 2) array_like
        Where a model puts the points and where they are.

    Returns
    -------
    float
        In the points' units.

    Raises
    ------
    ValueError
        If the arrays differ in shape, are empty or hold NaN or infinity.

    Examples
    --------
    >>> rms_error([[0, 0], [3, 4]], [[0, 0], [0, 0]])
    3.5355339059327378
    """
    predicted = as_points(predicted, "predicted")
    observed = as_points(observed, "observed")
    if predicted.shape != observed.shape:
        raise ValueError(f"predicted and observed must have the same shape, got {predicted.shape} and {observed.shape}")
    if len(predicted) == 0:
        raise ValueError("predicted and observed hold no points; the RMS needs at least one")
    return float(np.sqrt(np.mean(np.sum((predicted - observed) ** 2, axis=1))))


def mean_error(predicted, observed, order):
    """QGIS Georeferencer's "mean error": sqrt(Σ R_i² / (n - m)), m = min_gcps(order).

    Dividing by the degrees of freedom rather than n makes it an unbiased
    estimate of the GCPs' error, where the lecture's RMS flatters a model that
    has nearly as many coefficients as GCPs.

    Parameters
    ----------
    predicted, observed : (n, 2) array_like
        Where the model puts the GCPs and where they are.
    order : {1, 2, 3}
        Degree of the polynomial.

    Returns
    -------
    float
        In the points' units.

    Raises
    ------
    ValueError
        If the arrays differ in shape or hold NaN, or n <= m: with no
        redundant GCP the error cannot be estimated.
    """
    predicted = as_points(predicted, "predicted")
    observed = as_points(observed, "observed")
    if predicted.shape != observed.shape:
        raise ValueError(f"predicted and observed must have the same shape (one row per GCP), "
                         f"got {predicted.shape} and {observed.shape}")
    n, m = len(predicted), min_gcps(order)
    if n <= m:
        raise ValueError(f"the mean error of order {order} needs more than {m} GCPs, got {n}")
    return float(np.sqrt(np.sum((predicted - observed) ** 2) / (n - m)))


def refine_gcps(src, dst, order, tolerance, min_gcps=None):
    """Drop bad GCPs one by one, like ``gdalwarp -refine_gcps tolerance min_gcps``.

    GDAL's ``remove_outliers`` (alg/gdal_crs.cpp): fit, find the single GCP
    with the largest residual ``|model(src) - dst|``; if it is at least
    ``tolerance``, drop it and refit; stop when none is, or when only
    ``min_gcps`` remain.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        GCPs; GDAL fits pixel -> map here, so its tolerance is in map units.
    order : {1, 2, 3}
    tolerance : float
        Residual, in dst units, from which a GCP counts as an outlier.
    min_gcps : int, optional
        Never go below this many GCPs; default the order's minimum.

    Returns
    -------
    model : PolynomialModel
        Fitted on the kept GCPs.
    kept : ndarray of bool, shape (n,)
        True for the GCPs that survived.

    Raises
    ------
    ValueError
        As :func:`fit_polynomial`, or for a negative tolerance or a
        ``min_gcps`` below the order's minimum.
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    order = _check_order(order)
    floor = _minimum_gcps(order)   # the parameter min_gcps (GDAL's name) hides the function
    if min_gcps is None:
        min_gcps = floor
    if min_gcps < floor:
        raise ValueError(f"min_gcps must be at least {floor} for order {order}, got {min_gcps}")
    if min_gcps > len(src):
        raise ValueError(f"min_gcps ({min_gcps}) exceeds the number of GCPs ({len(src)}); "
                         "it must be between the order's minimum and the number of GCPs")
    if not np.isfinite(tolerance) or tolerance < 0:
        raise ValueError(f"tolerance must be a non-negative number (dst units), got {tolerance!r}")
    kept = np.ones(len(src), dtype=bool)
    model = fit_polynomial(src, dst, order)
    while kept.sum() > min_gcps:
        _, _, distance = residuals(model, src[kept], dst[kept])
        # Residuals below float32's epsilon count as zero, as in GDAL.
        distance = np.where(distance < np.finfo(np.float32).eps, 0.0, distance)
        worst = int(np.argmax(distance))
        if distance[worst] < tolerance:
            break
        kept[np.flatnonzero(kept)[worst]] = False
        model = fit_polynomial(src[kept], dst[kept], order)
    return model, kept


def _as_flags(flags, name):
    """``flags`` as a bool array; only booleans or 0/1 are accepted (0.5 or NaN would read as True)."""
    array = np.asarray(flags)
    if array.dtype != bool:
        try:
            numbers = array.astype(np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must hold True/False (or 1/0) flags, got {flags!r}") from None
        if not np.isin(numbers, (0.0, 1.0)).all():
            raise ValueError(f"{name} must hold True/False (or 1/0) flags, got values "
                             f"{np.unique(numbers[~np.isin(numbers, (0.0, 1.0))])[:5].tolist()}")
        array = numbers.astype(bool)
    return array


def fit_with_check_points(src, dst, order, is_check):
    """Fit on the GCPs not marked as check points; RMS on the GCPs and on the check points.

    The RMS on the fitting GCPs flatters high degrees (with the minimum number
    of GCPs it is zero whatever the model's quality); check points that were
    not used in the fit tell the truth.

    Parameters
    ----------
    src, dst : (n, 2) array_like
    order : {1, 2, 3}
    is_check : (n,) array_like of bool
        True for the check points, False for the GCPs used in the fit.

    Returns
    -------
    model : PolynomialModel
        Fitted on the GCPs.
    fit_rms, check_rms : float
        Lecture's RMS on the fitting GCPs and on the check points.

    Raises
    ------
    ValueError
        If ``is_check`` is not one True/False flag per GCP or marks none,
        or as :func:`fit_polynomial` for the remaining GCPs.
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    is_check = _as_flags(is_check, "is_check")
    if is_check.shape != (len(src),):
        raise ValueError(f"is_check must have one flag per GCP ({len(src)}), got shape {is_check.shape}")
    if not is_check.any():
        raise ValueError("is_check marks no check point; mark at least one GCP as a check point")
    model = fit_polynomial(src[~is_check], dst[~is_check], order)
    fit_rms = model.rms(src[~is_check], dst[~is_check])
    check_rms = model.rms(src[is_check], dst[is_check])
    return model, fit_rms, check_rms


def leave_one_out_errors(src, dst, order):
    """Each GCP's error when the model is fitted on all the others.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        The GCPs.
    order : {1, 2, 3}
        Degree of the polynomial.

    Returns
    -------
    ndarray, shape (n,)
        Distance between GCP i's dst and the prediction of the model fitted
        without GCP i. Needs ``min_gcps(order) + 1`` GCPs.

    Raises
    ------
    ValueError
        If src and dst differ in length or hold NaN, or there are fewer than
        ``min_gcps(order) + 1`` GCPs.
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise ValueError(f"src and dst must hold the same GCPs, got {len(src)} and {len(dst)} points")
    needed = min_gcps(order) + 1
    if len(src) < needed:
        raise ValueError(f"leave-one-out for order {order} needs at least {needed} GCPs (the "
                         f"minimum {needed - 1} once one is left out), got {len(src)}")
    errors = np.empty(len(src))
    for index in range(len(src)):
        others = np.arange(len(src)) != index
        model = fit_polynomial(src[others], dst[others], order)
        errors[index] = np.hypot(*(model(src[index:index + 1])[0] - dst[index]))
    return errors


def condition_number(src, order):
    """Condition number of the (centred, scaled) design matrix: large means badly placed GCPs.

    Parameters
    ----------
    src : (n, 2) array_like
        GCP positions in the model's input coordinates.
    order : {1, 2, 3}
        Degree of the polynomial.

    Returns
    -------
    float
        Ratio of the largest to the smallest singular value (>= 1).

    Raises
    ------
    ValueError
        If src is not (n, 2) finite numbers or the order is not 1-3.
    """
    matrix, _, _ = _normalised_design(as_points(src, "src"), order)
    return float(np.linalg.cond(matrix))


def hull_coverage(points, width, height):
    """Share of the image area (0-1) inside the convex hull of the GCPs' (col, row).

    The lecture: "a dispersão dos GCPs é muito importante" - a model is only
    trustworthy inside the area its GCPs span.

    Parameters
    ----------
    points : (n, 2) array_like
        GCP image positions (col, row).
    width, height : float
        The image's size, pixels.

    Returns
    -------
    float
        0 when the GCPs span no area (collinear or fewer than 3).

    Raises
    ------
    ValueError
        If the points are not (n, 2) finite numbers or the size is not positive.
    """
    from scipy.spatial import ConvexHull, QhullError

    points = as_points(points)
    width = check_range(width, "width", low=0, why="the image's width in pixels")
    height = check_range(height, "height", low=0, why="the image's height in pixels")
    if width == 0 or height == 0:
        raise ValueError(f"width and height must be positive (pixels), got {width} and {height}")
    clipped = np.clip(points, [0, 0], [width, height])
    try:
        area = ConvexHull(clipped).volume
    except QhullError:
        return 0.0  # collinear or too few points: no area at all
    return float(area / (width * height))


def predicted_error_map(src, order, x, y, gcp_error=1.0):
    """Standard deviation of the model's prediction over a grid, for GCP errors of ``gcp_error``.

    For least squares with independent GCP errors of standard deviation σ, the
    prediction at a point with terms a(x, y) has variance
    σ² a(x, y)ᵀ (AᵀA)⁻¹ a(x, y): small among the GCPs, growing fast away
    from them, faster for higher degrees.

    Parameters
    ----------
    src : (n, 2) array_like
        GCP positions in the model's input coordinates.
    order : {1, 2, 3}
    x, y : ndarray
        Grid of positions (same units as src), any shape.
    gcp_error : float
        σ, the standard deviation of one GCP's error (dst units).

    Returns
    -------
    ndarray, shape of x
        Predicted standard deviation of the model at each position.

    Raises
    ------
    ValueError
        If x and y differ in shape, gcp_error is negative, or the GCPs do not
        determine the polynomial.

    References
    ----------
    Draper, N. R. and Smith, H., *Applied Regression Analysis*, the
    variance of a predicted mean response, Var(ŷ₀) = σ² x₀ᵀ(XᵀX)⁻¹x₀.
    """
    gcp_error = check_range(gcp_error, "gcp_error", low=0, why="a standard deviation in dst units")
    if np.shape(x) != np.shape(y):
        raise ValueError(f"x and y must have the same shape, got {np.shape(x)} and {np.shape(y)}")
    matrix, origin, scale = _normalised_design(as_points(src, "src"), order)
    if np.linalg.matrix_rank(matrix) < matrix.shape[1]:
        raise ValueError(f"the GCPs do not determine an order-{order} polynomial (collinear or too few)")
    normal_inverse = np.linalg.inv(matrix.T @ matrix)
    grid = np.column_stack([np.ravel(x), np.ravel(y)])
    terms, _, _ = _normalised_design(grid, order, origin, scale)
    variance = np.einsum("ij,jk,ik->i", terms, normal_inverse, terms)
    return (gcp_error * np.sqrt(variance)).reshape(np.shape(x))


def measure_shifts(reference, moving, step=64, window=64, upsample=20, taper=False, valid=None,
                   details=False):
    """Local misregistration of ``moving`` against ``reference`` on a grid of check points.

    At every check point of a regular grid, the sub-pixel shift between the
    two images' windows is measured by phase correlation (scikit-image's
    ``phase_cross_correlation``): an independent measure of geometric error
    that needs no GCP.

    With ``taper=True`` each window is centred on its mean and multiplied
    by a Hann window, and plain (not phase-normalised) cross-correlation is
    used: on smooth scenes this avoids the pull towards zero shift that the
    windows' cut edges cause.

    Parameters
    ----------
    reference, moving : (rows, cols) array_like
        The two images, same shape.
    step : int
        Spacing of the check points, pixels.
    window : int
        Size of the square window compared at each point, pixels.
    upsample : int
        Sub-pixel precision: 1 / upsample pixel.
    taper : bool
        Hann-tapered cross-correlation instead of phase correlation.
    valid : (rows, cols) array_like of bool, optional
        False where a pixel must not be used (outside the moving image's
        footprint, cloud, water): a window with any such pixel is skipped.
    details : bool
        Also return every window's reliability (what
        :func:`rsgeo.tiepoints.correlation_tiepoints` filters on); then every
        window of the grid is returned, a skipped one with NaN shifts.

    Returns
    -------
    points : ndarray, shape (k, 2)
        (col, row) of each check point.
    shifts : ndarray, shape (k, 2)
        (dcol, drow) to move ``moving`` onto ``reference`` at that point, pixels.
    table : pandas.DataFrame
        Only with ``details=True``, one row per point: ``peak`` (height of the
        phase-correlation peak, 0-1), ``reliability`` (that peak over the rest
        of the correlation surface, in its standard deviations), ``error``
        (scikit-image's translation-invariant RMS error, 0-1), ``contrast``
        (the smaller standard deviation of the two windows) and ``skipped``
        ("" or why the window was not correlated: "constant", "invalid").

    Raises
    ------
    ValueError
        If the images differ in shape, are not 2-D or hold NaN, or step,
        window or upsample is not a positive whole number, or the window is
        larger than the images, or ``valid`` is not a mask of their shape.

    References
    ----------
    Guizar-Sicairos, M., Thurman, S. T. and Fienup, J. R. (2008),
    "Efficient subpixel image registration algorithms", Optics Letters 33(2).
    """
    from skimage.registration import phase_cross_correlation

    reference = np.asarray(reference, dtype=np.float64)
    moving = np.asarray(moving, dtype=np.float64)
    if reference.shape != moving.shape or reference.ndim != 2:
        raise ValueError(f"reference and moving must be 2-D images of the same shape, got "
                         f"{reference.shape} and {moving.shape}")
    if not (np.isfinite(reference).all() and np.isfinite(moving).all()):
        raise ValueError("reference and moving hold NaN or infinite values; crop or fill them first")
    for name, value in (("step", step), ("window", window), ("upsample", upsample)):
        if int(value) != value or value < 1:
            raise ValueError(f"{name} must be a positive whole number of pixels, got {value!r}")
    if window > min(reference.shape):
        raise ValueError(f"window ({window} px) is larger than the images {reference.shape}; "
                         "use a window no larger than the smaller side")
    if valid is not None:
        valid = np.asarray(valid)
        if valid.shape != reference.shape or valid.dtype != bool:
            raise ValueError(f"valid must be a boolean mask of the images' shape {reference.shape}, "
                             f"got {valid.dtype} of shape {valid.shape}")
    half = window // 2
    if taper:
        from skimage.filters import window as hann

        weights = hann("hann", (2 * half, 2 * half))
    points, shifts, rows = [], [], []
    for row in range(half, reference.shape[0] - half + 1, step):
        for col in range(half, reference.shape[1] - half + 1, step):
            a = reference[row - half:row + half, col - half:col + half]
            b = moving[row - half:row + half, col - half:col + half]
            skipped = ("invalid" if valid is not None
                       and not valid[row - half:row + half, col - half:col + half].all()
                       else "constant" if a.std() == 0 or b.std() == 0 else "")
            if skipped:
                if details:
                    points.append((col, row))
                    shifts.append((np.nan, np.nan))
                    rows.append({"peak": np.nan, "reliability": np.nan, "error": np.nan,
                                 "contrast": min(a.std(), b.std()), "skipped": skipped})
                continue
            contrast = min(a.std(), b.std())
            if taper:
                a, b = (a - a.mean()) * weights, (b - b.mean()) * weights
                shift, error, _ = phase_cross_correlation(a, b, upsample_factor=upsample,
                                                          normalization=None)
            else:
                shift, error, _ = phase_cross_correlation(a, b, upsample_factor=upsample)
            points.append((col, row))
            shifts.append((shift[1], shift[0]))
            if details:
                rows.append({**_correlation_peak(a, b), "error": error, "contrast": contrast,
                             "skipped": ""})
    points = np.array(points, dtype=float).reshape(-1, 2)
    shifts = np.array(shifts, dtype=float).reshape(-1, 2)
    if not details:
        return points, shifts
    import pandas as pd

    columns = ["peak", "reliability", "error", "contrast", "skipped"]
    return points, shifts, pd.DataFrame(rows, columns=columns)


def _correlation_peak(a, b):
    """Height of the phase-correlation surface's peak, and its distance from the rest in standard
    deviations (a sharp, lone peak is a reliable match; a peak among many is not)."""
    spectrum = np.fft.fft2(a) * np.conj(np.fft.fft2(b))
    surface = np.abs(np.fft.ifft2(spectrum / np.maximum(np.abs(spectrum), 1e-12 * np.abs(spectrum).max())))
    flat = surface.ravel()
    top = int(np.argmax(flat))
    rest = np.delete(flat, top)
    return {"peak": float(flat[top]), "reliability": float((flat[top] - rest.mean()) / (rest.std() or 1.0))}


def _check_transform(transform, name):
    """An affine.Affine-like geotransform that can be inverted."""
    try:
        determinant = transform.a * transform.e - transform.b * transform.d
    except AttributeError:
        raise ValueError(f"{name} must be an affine.Affine geotransform (pixel -> map), "
                         f"got {type(transform).__name__}") from None
    if not np.isfinite(determinant) or determinant == 0:
        raise ValueError(f"{name} cannot be inverted (its pixel axes are degenerate): {transform!r}")
    return transform


@dataclass
class GeotransformCheck:
    """A map -> image model compared with an image's own geotransform over the scene.

    Attributes
    ----------
    points : ndarray, shape (k, 2)
        (col, row) of the cell centres compared.
    differences : ndarray, shape (k, 2)
        (dcol, drow) = model(map point) - where the geotransform puts that map
        point, in pixels.
    rms : float
        RMS of the differences' lengths (the lecture's RMS, over the scene).
    mean_offset : ndarray, shape (2,)
        Mean (dcol, drow): the systematic part, a shift of the whole scene.
    centred_rms : float
        RMS once ``mean_offset`` is removed: the part a shift cannot explain.
    max_error : float
        Largest difference length, pixels.
    """

    points: np.ndarray = field(repr=False)
    differences: np.ndarray = field(repr=False)
    rms: float
    mean_offset: np.ndarray
    centred_rms: float
    max_error: float


def compare_with_geotransform(model, transform, shape, step=1):
    """Compare a GCP model (map -> image) with the image's own geotransform, over the scene.

    An image file's geotransform (pixel -> map) says where every pixel is on
    the map; if it is independent of the GCPs it is an independent check of a
    model fitted to them. At the centre of every ``step``-th cell, (col, row)
    -> map (x, y) by the geotransform, then back to the image by the model:
    the difference is where the two disagree, in pixels.

    Parameters
    ----------
    model : callable
        Map (x, y) -> image (col, row) on (n, 2) arrays, e.g. a
        :class:`PolynomialModel` from :meth:`GCPSet.fit`.
    transform : affine.Affine
        The image's geotransform, pixel (col, row) -> map (x, y), in the
        model's map coordinates (same CRS).
    shape : (rows, cols)
        The image's size.
    step : int
        Compare every ``step``-th row and column.

    Returns
    -------
    GeotransformCheck
        ``rms``, ``mean_offset`` (dcol, drow), ``centred_rms``, ``max_error``
        and the points and differences.

    Raises
    ------
    ValueError
        If the transform is not an invertible affine.Affine, the shape is not
        two positive integers, the step is not a positive integer, or the
        model gives NaN or the wrong shape.

    Examples
    --------
    >>> import affine
    >>> transform = affine.Affine(20, 0, 1000, 0, -20, 5000)
    >>> cols_rows = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> map_xy = np.column_stack(transform @ cols_rows.T)
    >>> model = fit_polynomial(map_xy, cols_rows + [0.0, 1.5], 1)   # 1.5 rows off
    >>> check = compare_with_geotransform(model, transform, (10, 10))
    >>> round(check.rms, 6), (check.mean_offset.round(6) + 0.0).tolist()
    (1.5, [0.0, 1.5])
    """
    transform = _check_transform(transform, "transform")
    rows, cols = as_shape(shape)
    if int(step) != step or step < 1:
        raise ValueError(f"step must be a positive whole number of pixels, got {step!r}")
    grid_rows, grid_cols = np.mgrid[0:rows:int(step), 0:cols:int(step)] + 0.5
    points = np.column_stack([grid_cols.ravel(), grid_rows.ravel()])
    map_xy = np.column_stack(transform @ (points[:, 0], points[:, 1]))
    predicted = np.asarray(model(map_xy), dtype=np.float64)
    if predicted.shape != points.shape or not np.isfinite(predicted).all():
        raise ValueError(f"model must return finite (n, 2) image positions, got shape {predicted.shape}")
    differences = predicted - points
    lengths = np.hypot(differences[:, 0], differences[:, 1])
    mean_offset = differences.mean(axis=0)
    centred = differences - mean_offset
    return GeotransformCheck(points, differences, float(np.sqrt(np.mean(lengths**2))), mean_offset,
                             float(np.sqrt(np.mean(np.sum(centred**2, axis=1)))), float(lengths.max()))


def offsets_against_reference(image, transform, reference, reference_transform, step=64,
                              window=96):
    """Where an image's content sits relative to its geotransform, measured on a finer reference.

    The reference (e.g. the 2.5 m HRC) is averaged over blocks of the image's
    pixel size (e.g. 8 × 8 for 20 m), sampled (bilinear) at the image's cell
    centres through both geotransforms, and compared with the image window by
    window by cross-correlation (:func:`measure_shifts` with ``taper=True``). No GCP is used: it is
    an independent measure of how far the two files' georeferencing disagree.

    Parameters
    ----------
    image : (rows, cols) array_like
        One band of the coarser image.
    transform : affine.Affine
        Its geotransform, north-up.
    reference : (rows, cols) array_like
        One band of the finer reference, in the same CRS, with a spectral
        response close to ``image``'s (a pan band against a red band, say).
    reference_transform : affine.Affine
        Its geotransform, north-up, with a pixel size that divides the image's.
    step, window : int
        Spacing and size of the correlation windows, in image pixels.

    Returns
    -------
    points : ndarray, shape (k, 2)
        (col, row) of each window's centre in the image.
    offsets : ndarray, shape (k, 2)
        (dcol, drow): where a feature is in the image minus where the image's
        geotransform puts the reference's same feature, in image pixels (the
        same sign as GCP image positions minus the geotransform's prediction).

    Raises
    ------
    ValueError
        If the images are not 2-D, the transforms are not north-up, the pixel
        sizes are not in a whole ratio, or the images barely overlap.
    """
    from scipy.ndimage import map_coordinates

    image = np.asarray(image, dtype=np.float64)
    reference = np.asarray(reference, dtype=np.float64)
    if image.ndim != 2 or reference.ndim != 2:
        raise ValueError(f"image and reference must be single bands (2-D), got shapes "
                         f"{image.shape} and {reference.shape}")
    for name, t in (("transform", transform), ("reference_transform", reference_transform)):
        _check_transform(t, name)
        if t.b != 0 or t.d != 0 or t.a <= 0 or t.e >= 0:
            raise ValueError(f"{name} must be north-up (no rotation terms), got {t!r}")
    ratio = transform.a / reference_transform.a
    factor = int(round(ratio))
    if factor < 1 or abs(ratio - factor) > 1e-6 or abs(-transform.e / -reference_transform.e - factor) > 1e-6:
        raise ValueError(f"the image's pixel ({transform.a}, {-transform.e}) must be a whole multiple "
                         f"of the reference's ({reference_transform.a}, {-reference_transform.e})")
    rows, cols = (n // factor * factor for n in reference.shape)
    blocks = reference[:rows, :cols].reshape(rows // factor, factor, cols // factor, factor).mean(axis=(1, 3))
    block_transform = reference_transform @ reference_transform.scale(factor)
    grid_rows, grid_cols = np.mgrid[0:image.shape[0], 0:image.shape[1]] + 0.5
    x, y = transform @ (grid_cols, grid_rows)
    block_cols, block_rows = ~block_transform @ (x, y)
    inside = ((block_cols >= 0.5) & (block_rows >= 0.5) & (block_cols <= blocks.shape[1] - 0.5)
              & (block_rows <= blocks.shape[0] - 0.5))
    if not inside.any():
        raise ValueError("the image and the reference do not overlap")
    used_rows, used_cols = np.flatnonzero(inside.any(axis=1)), np.flatnonzero(inside.any(axis=0))
    box = np.s_[used_rows[0]:used_rows[-1] + 1, used_cols[0]:used_cols[-1] + 1]
    if not inside[box].all() or min(inside[box].shape) < window:
        raise ValueError(f"the overlap {inside[box].shape} must be a full rectangle of at least "
                         f"{window} × {window} image pixels")
    sampled = map_coordinates(blocks, [block_rows[box] - 0.5, block_cols[box] - 0.5], order=1)
    points, shifts = measure_shifts(sampled, image[box], step=step, window=window, taper=True)
    return points + [used_cols[0], used_rows[0]], -shifts


# --------------------------------------------------------------------------
# GCP sets and QGIS Georeferencer .points files


@dataclass
class GCPSet:
    """Ground control points: map (x, y) beside image (col, row), with ids and flags.

    Parameters
    ----------
    map_xy : (n, 2) array_like
        Map coordinates (easting, northing) of each GCP.
    image_xy : (n, 2) array_like
        Image coordinates (col, row) of the same GCP, rows counted downwards.
    enabled : (n,) array_like of bool, optional
        False for GCPs left out of the fit (QGIS's "enable" column).
    ids : sequence of str, optional
        A name per GCP; "1", "2", ... by default.
    crs : str, optional
        The map coordinates' CRS (WKT or "EPSG:..."), written to .points files.
    notes : sequence of str, optional
        What each GCP is on the ground ("road crossing", "field corner").
    """

    map_xy: np.ndarray
    image_xy: np.ndarray
    enabled: np.ndarray = None
    ids: list = None
    crs: str = None
    notes: list = None

    def __post_init__(self):
        self.map_xy = as_points(self.map_xy, "map_xy")
        self.image_xy = as_points(self.image_xy, "image_xy")
        n = len(self.map_xy)
        if len(self.image_xy) != n:
            raise ValueError(f"map_xy and image_xy must hold the same GCPs, got {n} and {len(self.image_xy)}")
        self.enabled = np.ones(n, bool) if self.enabled is None else _as_flags(self.enabled, "enabled")
        if self.enabled.shape != (n,):
            raise ValueError(f"enabled must have one flag per GCP ({n}), got shape {self.enabled.shape}")
        self.ids = [str(i + 1) for i in range(n)] if self.ids is None else [str(i) for i in self.ids]
        self.notes = [""] * n if self.notes is None else list(self.notes)
        if len(self.ids) != n or len(self.notes) != n:
            raise ValueError(f"ids and notes must have one entry per GCP ({n})")

    def __len__(self):
        return len(self.map_xy)

    def fit(self, order):
        """Polynomial map -> image (u = f(x, y), v = g(x, y)) on the enabled GCPs.

        Parameters
        ----------
        order : {1, 2, 3}
            Degree of the polynomial.

        Returns
        -------
        PolynomialModel
            Map (x, y) -> image (col, row).

        Raises
        ------
        ValueError
            As :func:`fit_polynomial` (too few or collinear enabled GCPs).
        """
        return fit_polynomial(self.map_xy[self.enabled], self.image_xy[self.enabled], order)

    def to_crs(self, crs):
        """The same GCPs with their map coordinates transformed to ``crs`` by PROJ.

        Image coordinates, flags, ids and notes are kept. PROJ picks the datum
        transformation GDAL would (SAD69 -> SIRGAS 2000 offline: EPSG:15485).

        Parameters
        ----------
        crs : str, int or rasterio.crs.CRS
            The target CRS ("EPSG:31981", 31981, a WKT).

        Returns
        -------
        GCPSet
            With ``crs`` set to the target's WKT.

        Raises
        ------
        ValueError
            If this set has no CRS, or PROJ does not know either CRS.
        """
        from rasterio.warp import transform

        if self.crs is None:
            raise ValueError("these GCPs have no CRS (crs=None): set the CRS their map "
                             "coordinates are in before transforming them")
        source, target = _as_crs(self.crs, "the GCPs' crs"), _as_crs(crs, "crs")
        xs, ys = transform(source, target, self.map_xy[:, 0], self.map_xy[:, 1])
        return GCPSet(np.column_stack([xs, ys]), self.image_xy.copy(), self.enabled.copy(),
                      list(self.ids), target.to_wkt(), list(self.notes))

    def combine(self, other):
        """This set followed by ``other``; refuses to mix map coordinates of two CRSs.

        Parameters
        ----------
        other : GCPSet
            More GCPs of the same image, in the same CRS (or both without one).

        Returns
        -------
        GCPSet

        Raises
        ------
        ValueError
            If the CRSs differ (transform one with :meth:`to_crs` first) or
            only one of the sets has a CRS.
        """
        if not isinstance(other, GCPSet):
            raise ValueError(f"other must be a GCPSet, got {type(other).__name__}")
        if (self.crs is None) != (other.crs is None) or (
                self.crs is not None and _as_crs(self.crs) != _as_crs(other.crs)):
            names = [_crs_name(self.crs), _crs_name(other.crs)]
            raise ValueError(f"cannot mix GCPs in {names[0]} with GCPs in {names[1]}: "
                             "transform one set with .to_crs() first")
        return GCPSet(np.vstack([self.map_xy, other.map_xy]),
                      np.vstack([self.image_xy, other.image_xy]),
                      np.concatenate([self.enabled, other.enabled]),
                      list(self.ids) + list(other.ids), self.crs,
                      list(self.notes) + list(other.notes))

    def table(self, model=None):
        """The GCP table as a pandas DataFrame; with a model, residuals in pixels.

        Columns: id, map x/y, image col/row, enabled, and with a model dx, dy
        (model - GCP, pixels), residual R_i (pixels), and ``residual_map``: the
        residual of the separately fitted reverse model (image -> map), in map units.

        Parameters
        ----------
        model : PolynomialModel, optional
            A map -> image model, e.g. from :meth:`fit`.

        Returns
        -------
        pandas.DataFrame
            Indexed by id.

        Raises
        ------
        ValueError
            If the enabled GCPs cannot determine the reverse model.
        """
        import pandas as pd

        table = pd.DataFrame({
            "id": self.ids, "map_x": self.map_xy[:, 0], "map_y": self.map_xy[:, 1],
            "col": self.image_xy[:, 0], "row": self.image_xy[:, 1], "enabled": self.enabled,
        })
        if any(self.notes):
            table["note"] = self.notes
        if model is not None:
            dx, dy, distance = residuals(model, self.map_xy, self.image_xy)
            table["dx"], table["dy"], table["residual"] = dx, dy, distance
            reverse = fit_polynomial(self.image_xy[self.enabled], self.map_xy[self.enabled], model.order)
            table["residual_map"] = residuals(reverse, self.image_xy, self.map_xy)[2]
        return table.set_index("id")


def _as_crs(crs, name="crs"):
    """A rasterio CRS, or ValueError for one that PROJ does not know."""
    from rasterio.crs import CRS
    from rasterio.errors import CRSError

    if isinstance(crs, CRS):
        return crs
    try:
        return CRS.from_epsg(crs) if isinstance(crs, (int, np.integer)) else CRS.from_user_input(crs)
    except (CRSError, TypeError, ValueError) as error:
        raise ValueError(f"{name} {str(crs)[:60]!r} is not a CRS that PROJ knows ({error}); give "
                         "an EPSG code such as 'EPSG:31983', a WKT or a PROJ string") from None


def _crs_name(crs):
    """A short name for a CRS in messages: 'EPSG:29191', or 'no CRS'."""
    if crs is None:
        return "no CRS"
    value = _as_crs(crs)
    epsg = value.to_epsg()
    return f"EPSG:{epsg}" if epsg else value.to_string()[:40]


def read_points(path):
    """Read a QGIS Georeferencer ``.points`` file into a :class:`GCPSet`.

    Format (QGIS Georeferencer): an optional first line ``#CRS: <WKT>``, a
    header ``mapX,mapY,sourceX,sourceY,enable,dX,dY,residual`` (older files:
    ``mapX,mapY,pixelX,pixelY,enable``), comma- or tab-separated. ``sourceY``
    is the negative line number; rsgeo's rows count downwards, so row = -sourceY.

    Parameters
    ----------
    path : str or path-like
        The ``.points`` file.

    Returns
    -------
    GCPSet
        With ``crs`` from the ``#CRS:`` line, if any.

    Raises
    ------
    ValueError
        If the header lacks the needed columns or a value is not a number.
    """
    with open(path, encoding="utf-8") as handle:
        text = handle.read()
    lines = text.splitlines()
    crs = None
    if lines and lines[0].startswith("#CRS:"):
        crs = lines.pop(0)[len("#CRS:"):].strip() or None
    lines = [line for line in lines if line.strip() and not line.startswith("#")]
    if not lines:
        raise ValueError(f"{path}: no header and no GCPs; a .points file needs a header line")
    delimiter = "\t" if "\t" in lines[0] else ","
    reader = csv.DictReader(io.StringIO("\n".join(lines)), delimiter=delimiter)
    header = [name.strip() for name in reader.fieldnames]
    reader.fieldnames = header
    source_x = "sourceX" if "sourceX" in header else "pixelX"
    source_y = "sourceY" if "sourceY" in header else "pixelY"
    missing = {"mapX", "mapY", source_x, source_y} - set(header)
    if missing:
        raise ValueError(f"{path}: header {header} lacks {sorted(missing)}; "
                         "expected mapX,mapY,sourceX,sourceY,enable")
    map_xy, image_xy, enabled = [], [], []
    for number, row in enumerate(reader, start=2):
        try:
            map_xy.append((float(row["mapX"]), float(row["mapY"])))
            image_xy.append((float(row[source_x]), -float(row[source_y])))
        except (TypeError, ValueError):
            raise ValueError(f"{path}, line {number}: coordinates must be numbers, got {dict(row)}") from None
        enabled.append(str(row.get("enable", "1")).strip() not in ("0", "false", "False"))
    return GCPSet(np.array(map_xy), np.array(image_xy), enabled=enabled, crs=crs)


def write_points(path, gcps, model=None):
    """Write a :class:`GCPSet` as a QGIS Georeferencer ``.points`` file.

    With a model (map -> image, as :meth:`GCPSet.fit` returns), the dX, dY and
    residual columns hold its residuals in pixels; QGIS's dY, like sourceY,
    points up, so dY = -(model row - GCP row).

    Parameters
    ----------
    path : str or path-like
        The file to write.
    gcps : GCPSet
    model : callable, optional
        Map -> image model whose residuals fill dX, dY and residual.

    Returns
    -------
    None

    Raises
    ------
    ValueError
        If ``gcps`` is not a :class:`GCPSet`, or as :func:`residuals`.
    """
    if not isinstance(gcps, GCPSet):
        raise ValueError(f"gcps must be a GCPSet (map_xy, image_xy, enabled), got {type(gcps).__name__}")
    if model is not None:
        dx, dy, distance = residuals(model, gcps.map_xy, gcps.image_xy)
    else:
        dx = dy = distance = np.zeros(len(gcps))
    with open(path, "w", encoding="utf-8", newline="") as handle:
        if gcps.crs:
            handle.write(f"#CRS: {gcps.crs}\n")
        handle.write("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n")
        for i in range(len(gcps)):
            values = (gcps.map_xy[i, 0], gcps.map_xy[i, 1], gcps.image_xy[i, 0], -gcps.image_xy[i, 1])
            handle.write(",".join(repr(float(v)) for v in values)
                         + f",{int(gcps.enabled[i])},{float(dx[i])!r},{float(-dy[i])!r},{float(distance[i])!r}\n")


# --- Transformation models: QGIS's Georeferencer choices (issue 16) ---------------------------

KINDS = ("linear", "helmert", "polynomial", "projective", "tps")

_FIXED_MINIMUM = {"linear": 2, "helmert": 2, "projective": 4, "tps": 3}


def _check_kind(kind, order):
    """Check ``kind`` and ``order`` together; return the polynomial order (None otherwise)."""
    if kind not in KINDS:
        raise ValueError(f"unknown transformation kind {kind!r}; choose one of "
                         f"{', '.join(map(repr, KINDS))}")
    if kind == "polynomial":
        if order is None:
            raise ValueError("kind 'polynomial' needs an order: 1, 2 or 3")
        return _check_order(order)
    if order is not None:
        raise ValueError(f"kind {kind!r} has no order (got order={order!r}); "
                         "only 'polynomial' takes one")
    return None


def _fit_inputs(src, dst, kind, order):
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    order = _check_kind(kind, order)
    if len(src) != len(dst):
        raise ValueError(f"src and dst must hold the same GCPs, got {len(src)} and {len(dst)} points")
    needed = min_gcps(kind, order)
    if len(src) < needed:
        what = f"order-{order} polynomial" if kind == "polynomial" else f"{kind!r} model"
        raise ValueError(f"a {what} needs at least {needed} GCPs, got {len(src)}")
    return src, dst, order


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
        Free parameters: 4 (linear, Helmert) or 8 (projective).
    """

    _PARAMETERS = {"linear": 4, "helmert": 4, "projective": 8}

    def __init__(self, matrix, kind, src=None, dst=None):
        matrix = np.asarray(matrix, dtype=np.float64)
        if matrix.shape != (3, 3) or not np.isfinite(matrix).all():
            raise ValueError(f"matrix must be a finite 3×3 array, got shape {matrix.shape}")
        if kind not in self._PARAMETERS:
            raise ValueError(f"a matrix model's kind must be one of {list(self._PARAMETERS)}, "
                             f"got {kind!r}")
        self.matrix = matrix / matrix[2, 2]
        self.kind = kind
        self.n_parameters = self._PARAMETERS[kind]
        self.src, self.dst = src, dst

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
        ValueError
            If the points are not (n, 2) finite numbers, or a point lies on a
            projective model's vanishing line (it maps to infinity).
        """
        points = as_points(points)
        homogeneous = np.column_stack([points, np.ones(len(points))]) @ self.matrix.T
        w = homogeneous[:, 2]
        if (np.abs(w) < 1e-12).any():
            raise ValueError("some points lie on the projective model's vanishing line and map "
                             "to infinity; keep the points inside the GCPs' area")
        return homogeneous[:, :2] / w[:, np.newaxis]

    def inverse(self):
        """The exact inverse: the inverse matrix, same kind, src and dst swapped.

        Returns
        -------
        MatrixModel

        Raises
        ------
        ValueError
            If the matrix is singular (the model collapses the plane).
        """
        if abs(np.linalg.det(self.matrix)) < 1e-300:
            raise ValueError("the model's matrix is singular and has no inverse")
        return MatrixModel(np.linalg.inv(self.matrix), self.kind, self.dst, self.src)

    def __repr__(self):
        return f"MatrixModel(kind={self.kind!r}, matrix={self.matrix.tolist()!r})"


class TPSModel(GeometricModel):
    """Thin-plate spline through every GCP (GDAL's ``-tps``).

    u(x, y) = a0 + a1 x + a2 y + Σ w_i r_i² log r_i, the same for v, with
    r_i the distance to GCP i; the weights make it pass exactly through every
    GCP and its bending energy is the smallest that does. Evaluated with
    SciPy's ``RBFInterpolator(kernel="thin_plate_spline", degree=1)``.

    Parameters
    ----------
    src, dst : (n, 2) ndarray
        The GCPs, checked by :func:`fit_transform`.

    Attributes
    ----------
    kind : str
        "tps".
    n_parameters : int
        2 (n + 3): n weights and 3 affine coefficients per output.
    """

    kind = "tps"

    def __init__(self, src, dst):
        self.src, self.dst = src, dst
        self.n_parameters = 2 * (len(src) + 3)
        self._spline = RBFInterpolator(src, dst, kernel="thin_plate_spline", degree=1)

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
        return self._spline(as_points(points))

    def reverse(self):
        """A thin-plate spline fitted the other way round (dst -> src), as GDAL does.

        GDAL's TPS transformer fits a second spline from dst to src on the
        same GCPs (what rasterio's ``GCPTransformer(gcps, tps=True)`` returns in
        that direction). Both pass through every GCP, so they are inverse at
        the GCPs and only approximately so between them (a tenth of a pixel).

        Returns
        -------
        TPSModel

        Raises
        ------
        ValueError
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
        h = check_range(step, "step", low=1e-12, high=1e-1) * (
            float(np.abs(self.src - self.src.mean(axis=0)).max()) or 1.0)
        columns = []
        for axis in range(2):
            offset = np.zeros(2)
            offset[axis] = h
            columns.append((self(points + offset) - self(points - offset)) / (2 * h))
        return np.stack(columns, axis=-1)

    def inverse(self, tolerance=1e-10, max_iterations=30):
        """The exact inverse (dst -> src), by Newton's method on this spline.

        Each point starts from :meth:`reverse` (the spline fitted the other way
        round) and is polished until model(p) = q within ``tolerance`` times the
        dst extent. This is what GDAL's warper uses: ``gdalwarp -tps`` with a
        spline fitted image -> map maps every output cell back by inverting it.

        Parameters
        ----------
        tolerance : float
            Largest accepted ``|model(p) - q|``, relative to the extent of ``dst``.
        max_iterations : int

        Returns
        -------
        InverseModel

        Raises
        ------
        ValueError
            If the reverse spline cannot be fitted (repeated or collinear dst).
        """
        start = self.reverse()
        extent = float(np.abs(self.dst - self.dst.mean(axis=0)).max()) or 1.0
        limit = check_range(tolerance, "tolerance", low=0, why="relative to the dst extent") * extent

        def solve(targets):
            points = start(targets)
            error = np.full(len(targets), np.inf)
            for _ in range(int(max_iterations)):
                difference = self(points) - targets
                error = np.hypot(difference[:, 0], difference[:, 1])
                if not (error > limit).any():
                    break
                jacobian = self.jacobian(points)
                usable = np.abs(np.linalg.det(jacobian)) > 1e-300
                step = np.zeros_like(points)
                step[usable] = np.linalg.solve(jacobian[usable], difference[usable][..., None])[..., 0]
                points = points - step
            failed = ~(error <= limit)
            if failed.any():
                raise ValueError(
                    f"the thin-plate spline has no inverse at {failed.sum()} of {len(targets)} "
                    "points: Newton's method did not converge (the spline folds there); keep "
                    "the points inside the GCPs' area")
            return points

        return InverseModel(self, solve)

    def __repr__(self):
        return f"TPSModel(n_gcps={len(self.src)})"


def _fit_linear(src, dst):
    """Scale and offset per axis: u = a x + c, v = b y + d (QGIS's Linear, a world file)."""
    matrix = np.eye(3)
    for axis in range(2):
        x = src[:, axis] - src[:, axis].mean()
        if not np.abs(x).max() > 1e-12 * max(1.0, np.abs(src[:, axis]).max()):
            raise ValueError(f"a 'linear' model needs GCPs at two different {'xy'[axis]} "
                             "coordinates at least; spread the GCPs over the image")
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
        raise ValueError("a 'helmert' model needs at least two distinct GCPs; "
                         "these all fall on the same point")
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
            raise ValueError(f"the {name} points are collinear (or coincide): a 'projective' "
                             "model needs at least 4 GCPs, no three of them on one line, "
                             "spread over the image")
    src_norm, dst_norm = _normaliser(src), _normaliser(dst)
    s = np.column_stack([src, np.ones(len(src))]) @ src_norm.T
    d = np.column_stack([dst, np.ones(len(dst))]) @ dst_norm.T
    zero = np.zeros((len(s), 3))
    rows_u = np.hstack([s, zero, -s * d[:, :1]])
    rows_v = np.hstack([zero, s, -s * d[:, 1:2]])
    system = np.vstack([rows_u, rows_v])
    _, singular, vt = np.linalg.svd(system)
    if len(singular) >= 8 and not singular[7] > 1e-10 * singular[0]:
        raise ValueError("the GCPs do not determine a 'projective' model: three of the four "
                         "are collinear or points repeat; use 4 GCPs, no three on one line")
    h = vt[-1].reshape(3, 3)
    if abs(h[2, 2]) < 1e-12 * np.abs(h).max():
        raise ValueError("the GCPs put the projective model's vanishing line through their "
                         "centre; they are degenerate (check for swapped points)")
    matrix = np.linalg.inv(dst_norm) @ h @ src_norm
    return MatrixModel(matrix, "projective", src, dst)


def _fit_tps(src, dst):
    _, first = np.unique(src, axis=0, return_index=True)
    if len(first) < len(src):
        repeated = sorted(set(range(len(src))) - set(first.tolist()))[:5]
        raise ValueError(f"a 'tps' model needs distinct src points, but rows {repeated} repeat "
                         "an earlier point (a spline cannot pass through two targets at one "
                         "place); remove the duplicate GCPs")
    centred = (src - src.mean(axis=0)) / (np.abs(src - src.mean(axis=0)).max() or 1.0)
    if np.linalg.matrix_rank(np.column_stack([np.ones(len(src)), centred]), tol=1e-9) < 3:
        raise ValueError("a 'tps' model needs at least 3 GCPs that are not collinear (its affine "
                         "part is fixed by them); spread the GCPs over the image")
    return TPSModel(src, dst)


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
    order : {1, 2, 3} or None
        Only for ``kind="polynomial"``.

    Returns
    -------
    GeometricModel
        :class:`MatrixModel`, :class:`PolynomialModel` or :class:`TPSModel`.

    Raises
    ------
    ValueError
        Unknown kind; an order for a kind that has none (or none for a
        polynomial); fewer GCPs than ``min_gcps(kind, order)``; collinear
        points for projective, TPS or polynomial; repeated points for TPS.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> model = fit_transform(src, src * 2 + 1, "helmert")
    >>> model.kind, model.n_parameters, model([[5.0, 5.0]]).round(6).tolist()
    ('helmert', 4, [[11.0, 11.0]])
    """
    src, dst, order = _fit_inputs(src, dst, kind, order)
    if kind == "polynomial":
        return fit_polynomial(src, dst, order)
    fit = {"linear": _fit_linear, "helmert": _fit_helmert, "projective": _fit_projective,
           "tps": _fit_tps}[kind]
    return fit(src, dst)


#: The models QGIS's Georeferencer offers, as (label, kind, order).
GEOREFERENCER_MODELS = (("linear", "linear", None), ("helmert", "helmert", None),
                        ("polynomial 1", "polynomial", 1), ("polynomial 2", "polynomial", 2),
                        ("polynomial 3", "polynomial", 3), ("projective", "projective", None),
                        ("tps", "tps", None))


def transform_leave_one_out(src, dst, kind, order=None):
    """Leave-one-out error of every GCP for any model kind.

    GCP i is left out, the model is fitted on the others, and its distance
    from where that model puts it is measured: an honest error (the GCP did not
    pull the model towards itself), the only one a TPS has (its fitting
    residuals are zero).

    Parameters
    ----------
    src, dst : (n, 2) array_like
        The GCPs (src -> dst, for resampling map -> image).
    kind : str
        As :func:`fit_transform`.
    order : {1, 2, 3} or None
        For ``kind="polynomial"`` only.

    Returns
    -------
    ndarray, shape (n,)
        Distance of each GCP from the model fitted without it, in dst units.

    Raises
    ------
    ValueError
        As :func:`fit_transform`, or if there are fewer than
        ``min_gcps(kind, order) + 1`` GCPs.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> transform_leave_one_out(src, src * 2, "helmert").round(9) + 0.0
    array([0., 0., 0., 0., 0.])
    """
    src, dst, order = _fit_inputs(src, dst, kind, order)
    needed = min_gcps(kind, order) + 1
    if len(src) < needed:
        raise ValueError(f"leave-one-out needs at least {needed} GCPs for this model "
                         f"(one more than its minimum), got {len(src)}")
    errors = np.empty(len(src))
    for i in range(len(src)):
        keep = np.arange(len(src)) != i
        model = fit_transform(src[keep], dst[keep], kind, order)
        errors[i] = float(np.hypot(*(model(src[i:i + 1])[0] - dst[i])))
    return errors


def compare_models(src, dst, is_check=None, models=GEOREFERENCER_MODELS):
    """One row per model: parameters, minimum GCPs, fitting RMS, leave-one-out RMS, check RMS.

    The models are fitted on the GCPs not flagged in ``is_check``; the
    check points are only measured. Leave-one-out runs on the fitting GCPs.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        All points (src -> dst).
    is_check : (n,) array_like of bool or None
        True for check points (not used to fit). None: no check points.
    models : sequence of (label, kind, order)
        Default: :data:`GEOREFERENCER_MODELS`, QGIS's seven choices.

    Returns
    -------
    pandas.DataFrame
        Index: the labels. Columns ``parameters``, ``min GCPs``,
        ``fitting RMS (px)``, ``leave-one-out RMS (px)`` and, with check
        points, ``check RMS (px)``. A model with too few GCPs for leave-one-out
        gets NaN there.

    Raises
    ------
    ValueError
        If the points are malformed, ``is_check`` does not hold one flag per
        point, or a model cannot be fitted (too few or degenerate GCPs).

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> table = compare_models(src, src * 2, models=[("helmert", "helmert", None)])
    >>> table.columns.tolist()
    ['parameters', 'min GCPs', 'fitting RMS (px)', 'leave-one-out RMS (px)']
    """
    import pandas as pd

    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise ValueError(f"src and dst must hold the same points, got {len(src)} and {len(dst)}")
    check = np.zeros(len(src), bool) if is_check is None else _as_flags(is_check, "is_check")
    if check.shape != (len(src),):
        raise ValueError(f"is_check needs one flag per point ({len(src)}), got shape {check.shape}")
    fit_src, fit_dst = src[~check], dst[~check]
    rows = {}
    for label, kind, order in models:
        model = fit_transform(fit_src, fit_dst, kind, order)
        row = {"parameters": model.n_parameters, "min GCPs": min_gcps(kind, order),
               "fitting RMS (px)": model.rms(fit_src, fit_dst)}
        if len(fit_src) > min_gcps(kind, order):
            loo = transform_leave_one_out(fit_src, fit_dst, kind, order)
            row["leave-one-out RMS (px)"] = float(np.sqrt(np.mean(loo**2)))
        else:
            row["leave-one-out RMS (px)"] = np.nan
        if check.any():
            row["check RMS (px)"] = model.rms(src[check], dst[check])
        rows[label] = row
    return pd.DataFrame.from_dict(rows, orient="index")
