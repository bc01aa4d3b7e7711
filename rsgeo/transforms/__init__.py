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


from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..errors import GCPError
from ..language import _
from ..validation import as_points
from ._base import GeometricModel, InverseModel, newton_inverse, outside_hull
from ._matrix import N_PARAMETERS, MatrixModel, fit_helmert, fit_linear, fit_projective
from ._polynomial import (
    ORDERS,
    PolynomialModel,
    check_order,
    design_matrix,
    fit_polynomial,
    n_terms,
    term_names,
)
from ._tps import TPSModel, fit_tps

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
    ModelKind("linear", "linear", None, fit_linear, 2, N_PARAMETERS["linear"]),
    ModelKind("helmert", "helmert", None, fit_helmert, 2, N_PARAMETERS["helmert"]),
    *(ModelKind(f"polynomial {n}", "polynomial", n,
                lambda src, dst, n=n: fit_polynomial(src, dst, n), n_terms(n), 2 * n_terms(n))
      for n in ORDERS),
    ModelKind("projective", "projective", None, fit_projective, 4, N_PARAMETERS["projective"]),
    ModelKind("tps", "tps", None, fit_tps, 3, None),
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
        order = check_order(order)
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


#: Largest |coordinate| a model is fitted to: least squares square the coordinates, and a
#: spline's collinearity test multiplies two sums of squares (x**4 for 2,000 GCPs overflows
#: float64 beyond about 1e76); a linear fit at 1e198 returned one point for every GCP, a
#: polynomial NaN.
MAX_COORDINATE = 1e75


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
    for name, points in (("src", src), ("dst", dst)):
        largest = float(np.abs(points).max(initial=0.0))
        if largest > MAX_COORDINATE:
            raise GCPError(_(
                "a {kind!r} model cannot be fitted to {name} coordinates as large as "
                "{largest:.3g}: its fit squares them (or their distances), which overflows "
                "float64; coordinates must lie within +/-{bound:g} (map metres or degrees, "
                "image pixels)").format(kind=entry.kind, name=name, largest=largest,
                                        bound=MAX_COORDINATE))
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
        polynomial); for TPS, src points repeated with different dst points
        (exact duplicates, same src and same dst, are skipped as GDAL does and
        listed in ``model.skipped``), neighbouring GCPs whose dst points are
        more than 40 times further apart than the GCPs' typical slope allows
        for their distance in src (the spline would fold between them); for
        every kind, coordinates beyond +/-1e75 (``MAX_COORDINATE``).
    TypeError
        If an array is complex, bool or text, or the order is not a number.

    Examples
    --------
    >>> import numpy as np
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> model = fit_transform(src, src * 2 + 1, "helmert")
    >>> model.kind, model.n_parameters, model([[5.0, 5.0]]).round(6).tolist()
    ('helmert', 4, [[11.0, 11.0]])
    """
    src, dst, entry = _fit_inputs(src, dst, kind, order)
    return entry.fit(src, dst)
