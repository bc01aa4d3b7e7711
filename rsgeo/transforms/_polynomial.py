"""GDAL's centred, normalised polynomials of degree 1 to 3, in the lecture's term order.
"""


from dataclasses import dataclass, field
from math import comb

import numpy as np

from ..errors import GCPError, ModelError
from ..language import N_, _
from ..validation import as_integer, as_number, as_points
from ._base import GeometricModel, InverseModel, compiled, newton_inverse

__all__ = [
    "ORDERS", "check_order", "n_terms", "term_names", "design_matrix", "normalised_design",
    "PolynomialModel", "fit_polynomial",
]

# --- Polynomials (GDAL's centred, normalised least squares) --------------------------------------

ORDERS = (1, 2, 3)

# (power of x, power of y) of every term, in the lecture's order:
# 1, x, y, xy, x², y², then the cubic terms.
_TERMS = ((0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2), (2, 1), (1, 2), (3, 0), (0, 3))


def check_order(order):
    order = as_integer(order, "order", why=N_("a polynomial's degree: 1, 2 or 3"))
    if order not in ORDERS:
        raise GCPError(_("polynomial order must be 1, 2 or 3 (the lecture's degrees), "
                         "got {order!r}").format(order=order))
    return int(order)


def n_terms(order):
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
    for px, py in _TERMS[:n_terms(check_order(order))]:
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
    order = check_order(order)
    x, y = points[:, 0], points[:, 1]
    return np.column_stack([x**px * y**py for px, py in _TERMS[:n_terms(order)]])


def normalised_design(points, order, origin=None, scale=None):
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
        return compiled("transformer").polynomial_many(self.kernel_form()[1],
                                                          as_points(points))

    def kernel_form(self):
        """The model packed for the warp kernels (see ``rsgeo._kernels.transformer``).

        Returns
        -------
        (str, ndarray)
            ``("polynomial", parameters)``.
        """
        return "polynomial", compiled("transformer").polynomial_parameters(
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
        (:func:`~rsgeo.transforms.outside_hull`) or where the polynomial's Jacobian has the
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
        matrix = normalised_design(self.src, self.order, self.origin, self.scale)[0]
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
    order = check_order(order)
    if len(src) != len(dst):
        raise GCPError(_("src and dst must hold the same GCPs, got {n_src} and {n_dst} points")
                       .format(n_src=len(src), n_dst=len(dst)))
    needed = n_terms(order)
    if len(src) < needed:
        raise GCPError(_("order {order} needs at least {n} GCPs, got {got}").format(
            order=order, n=needed, got=len(src)))
    matrix, origin, scale = normalised_design(src, order)
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
