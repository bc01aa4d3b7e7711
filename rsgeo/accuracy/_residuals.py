"""Residuals, RMS, leave-one-out errors, check points, ``gdalwarp -refine_gcps``, and the
diagnostics of a fitted model (standard errors, condition number, hull coverage, predicted error,
one table of every model).
"""

from dataclasses import dataclass, field

import numpy as np

from ..errors import GCPError, GridError, ModelError
from ..language import N_, _
from ..transforms import GEOREFERENCER_MODELS, PolynomialModel, fit_transform, registered
from ..transforms._base import rms_of, same_points
from ..transforms._polynomial import normalised_design
from ..validation import as_flags, as_integer, as_invertible_affine, as_number, as_points, as_shape

__all__ = [
    "residuals", "rms_error", "mean_error", "leave_one_out_errors",
    "leave_one_out_residuals", "fit_with_check_points", "refine_gcps",
    "coefficient_standard_errors", "condition_number", "hull_coverage", "predicted_error_map",
    "compare_models", "GeotransformCheck", "compare_with_geotransform",
]


def _pair(src, dst):
    """src and dst as (n, 2) arrays of the same length."""
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise GCPError(_("src and dst must hold the same GCPs, got {n_src} and {n_dst} "
                         "points").format(n_src=len(src), n_dst=len(dst)))
    return src, dst


def _predicted_observed(predicted, observed, per_gcp=False):
    """predicted and observed as (n, 2) arrays of the same shape (``per_gcp``: the message says
    one row per GCP)."""
    predicted = as_points(predicted, "predicted")
    observed = as_points(observed, "observed")
    if predicted.shape != observed.shape:
        raise GCPError((_("predicted and observed must have the same shape (one row per GCP), "
                          "got {predicted_shape} and {observed_shape}") if per_gcp else
                        _("predicted and observed must have the same shape, got "
                          "{predicted_shape} and {observed_shape}")).format(
                predicted_shape=predicted.shape, observed_shape=observed.shape))
    return predicted, observed


# --- Residuals and RMS ---------------------------------------------------------------------------


def residuals(model, src, dst):
    """Per-GCP residuals of a model: dx, dy and R_i = sqrt(dx² + dy²).

    Lecture, slide "Avaliação da transformação": R_i is the distance between
    the position the model gives and the GCP's own position, in dst units
    (pixels when the model goes map -> image).

    Parameters
    ----------
    model : callable
        A model on (n, 2) arrays (e.g. a :class:`~rsgeo.transforms.PolynomialModel`).
    src, dst : (n, 2) array_like
        The GCPs in the model's input and output coordinates.

    Returns
    -------
    dx, dy, distance : ndarray
        ``model(src) - dst`` split in its two components, and its length.

    Raises
    ------
    GCPError
        If src and dst are not (n, 2) of the same length or hold NaN.
    """
    src, dst = _pair(src, dst)
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
    GCPError
        If the arrays differ in shape, are empty or hold NaN or infinity.

    Examples
    --------
    >>> rms_error([[0, 0], [3, 4]], [[0, 0], [0, 0]])
    3.5355339059327378
    """
    predicted, observed = _predicted_observed(predicted, observed)
    return rms_of(predicted - observed)


def mean_error(predicted, observed, order, kind=None):
    """QGIS Georeferencer's "mean error": sqrt(Σ R_i² / (n - m)), m = min_gcps(kind, order).

    Dividing by the degrees of freedom rather than n makes it an unbiased
    estimate of the GCPs' error, where the lecture's RMS flatters a model that
    has nearly as many coefficients as GCPs. m is the model's parameters per
    output coordinate: its minimum number of GCPs.

    Parameters
    ----------
    predicted, observed : (n, 2) array_like
        Where the model puts the GCPs and where they are.
    order : {1, 2, 3} or str
        Degree of the polynomial, or the name of another kind ("helmert").
    kind : str, optional
        A kind of :data:`rsgeo.transforms.REGISTRY`; then ``order`` is only
        for ``kind="polynomial"``.

    Returns
    -------
    float
        In the points' units.

    Raises
    ------
    GCPError
        If the arrays differ in shape or hold NaN, or n <= m: with no
        redundant GCP the error cannot be estimated.

    Examples
    --------
    >>> mean_error([[0, 0], [3, 4], [0, 0], [0, 0]], np.zeros((4, 2)), 1)
    5.0
    """
    predicted, observed = _predicted_observed(predicted, observed, per_gcp=True)
    entry = _registered(order, kind, "mean_error")
    n, m = len(predicted), entry.min_gcps
    if n <= m:
        raise GCPError(_("the mean error of {describe} needs more than {m} GCPs, got {n}").format(
                describe=_describe(entry), m=m, n=n))
    return float(np.sqrt(np.sum((predicted - observed) ** 2) / (n - m)))


def _registered(order, kind, caller):
    """The registry entry of ``order`` (a degree or a kind's name), or of ``kind`` and ``order``.
    """
    if kind is None:
        return registered(order, None, caller)
    return registered(kind, order, caller)


def _describe(entry):
    """'order 2' for a polynomial, "'helmert'" for the other kinds, as the messages name them."""
    return (_("order {order}").format(order=entry.order) if entry.kind == "polynomial"
            else repr(entry.kind))


# --- Errors of GCPs the model was not fitted to --------------------------------------------------


def leave_one_out_errors(src, dst, order, kind=None):
    """Each GCP's error when the model is fitted on all the others, for any model kind.

    GCP i is left out, the model is fitted on the others, and its distance
    from where that model puts it is measured: an honest error (the GCP did not
    pull the model towards itself), the only one a TPS has (its fitting
    residuals are zero).

    Parameters
    ----------
    src, dst : (n, 2) array_like
        The GCPs (src -> dst, for resampling map -> image).
    order : {1, 2, 3} or str or None
        Degree of the polynomial, or the name of another kind ("tps").
    kind : str, optional
        As :func:`rsgeo.transforms.fit_transform`; then ``order`` is only for
        ``kind="polynomial"``.

    Returns
    -------
    ndarray, shape (n,)
        Distance between GCP i's dst and the prediction of the model fitted
        without GCP i, in dst units. Needs ``min_gcps(kind, order) + 1`` GCPs.

    Raises
    ------
    GCPError
        As :func:`rsgeo.transforms.fit_transform`, or if there are fewer than
        ``min_gcps(kind, order) + 1`` GCPs.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> leave_one_out_errors(src, src * 2, "helmert").round(9) + 0.0
    array([0., 0., 0., 0., 0.])
    """
    difference = _left_out_differences(src, dst, order, kind, "leave_one_out_errors")
    return np.hypot(difference[:, 0], difference[:, 1])


def leave_one_out_residuals(src, dst, order, kind=None):
    """Each GCP's (dx, dy) when the model is fitted on all the others: leave-one-out, per axis.

    As :func:`leave_one_out_errors`, whose distances are the lengths of these
    vectors; the two components are what an accuracy standard reports per
    axis (ASPRS's RMSE_x and RMSE_y, :func:`~rsgeo.accuracy.asprs_horizontal`). Fitted image ->
    map, they are the check-point discrepancies on the ground, in map units.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        The GCPs (src -> dst).
    order : {1, 2, 3} or str or None
        Degree of the polynomial, or the name of another kind ("helmert").
    kind : str, optional
        As :func:`rsgeo.transforms.fit_transform`; then ``order`` is only for
        ``kind="polynomial"``.

    Returns
    -------
    ndarray, shape (n, 2)
        Row i: the prediction at GCP i's src of the model fitted without GCP i,
        minus GCP i's dst, in dst units.

    Raises
    ------
    GCPError
        As :func:`leave_one_out_errors`.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> dst = src * 2
    >>> dst[4] += [1.0, 0.0]                          # one GCP 1 unit east of the rest's fit
    >>> (leave_one_out_residuals(src, dst, "helmert")[4] + 0.0).tolist()
    [-1.0, 0.0]
    """
    return _left_out_differences(src, dst, order, kind, "leave_one_out_residuals")


def _left_out_differences(src, dst, order, kind, caller, fit=None):
    """(n, 2): the model fitted without GCP i at GCP i's src, minus GCP i's dst; ``fit(src, dst,
    entry)`` fits it (default: the registry's fit, src -> dst)."""
    src, dst = _pair(src, dst)
    entry = _registered(order, kind, caller)
    needed = entry.min_gcps + 1
    if len(src) < needed:
        if entry.kind == "polynomial":
            raise GCPError(_("leave-one-out for order {entry_order} needs at least "
                             "{needed} GCPs (the minimum {value} once one is left out), "
                             "got {n_src}").format(
                    entry_order=entry.order, needed=needed, value=needed - 1, n_src=len(src)))
        raise GCPError(_("leave-one-out needs at least {needed} GCPs for this model "
                         "(one more than its minimum), got {n_src}").format(
                needed=needed, n_src=len(src)))
    difference = np.empty((len(src), 2))
    for index in range(len(src)):
        others = np.arange(len(src)) != index
        model = (entry.fit(src[others], dst[others]) if fit is None
                 else fit(src[others], dst[others], entry))
        difference[index] = model(src[index:index + 1])[0] - dst[index]
    return difference


def fit_with_check_points(src, dst, order, is_check, kind=None):
    """Fit on the GCPs not marked as check points; RMS on the GCPs and on the check points.

    The RMS on the fitting GCPs flatters high degrees (with the minimum number
    of GCPs it is zero whatever the model's quality); check points that were
    not used in the fit tell the truth.

    Parameters
    ----------
    src, dst : (n, 2) array_like
    order : {1, 2, 3} or str or None
        Degree of the polynomial, or the name of another kind ("projective").
    is_check : (n,) array_like of bool
        True for the check points, False for the GCPs used in the fit.
    kind : str, optional
        As :func:`rsgeo.transforms.fit_transform`; then ``order`` is only for
        ``kind="polynomial"``.

    Returns
    -------
    model : GeometricModel
        Fitted on the GCPs.
    fit_rms, check_rms : float
        Lecture's RMS on the fitting GCPs and on the check points.

    Raises
    ------
    GCPError
        If ``is_check`` is not one True/False flag per GCP or marks none,
        or as :func:`rsgeo.transforms.fit_transform` for the remaining GCPs.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> dst = src * 2
    >>> dst[4] += 1
    >>> _, fit_rms, check_rms = fit_with_check_points(src, dst, 1, [0, 0, 0, 0, 1])
    >>> round(fit_rms, 6), round(check_rms, 6)
    (0.0, 1.414214)
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    is_check = as_flags(is_check, "is_check")
    if is_check.shape != (len(src),):
        raise GCPError(_("is_check must have one flag per GCP ({n_src}), got shape "
                         "{is_check_shape}").format(
                n_src=len(src), is_check_shape=is_check.shape))
    if not is_check.any():
        raise GCPError(_("is_check marks no check point; mark at least one GCP as a check point"))
    entry = _registered(order, kind, "fit_with_check_points")
    model = fit_transform(src[~is_check], dst[~is_check], entry.kind, entry.order)
    fit_rms = model.rms(src[~is_check], dst[~is_check])
    check_rms = model.rms(src[is_check], dst[is_check])
    return model, fit_rms, check_rms


def refine_gcps(src, dst, order, tolerance, min_gcps=None, kind=None):
    """Drop bad GCPs one by one, like ``gdalwarp -refine_gcps tolerance min_gcps``, any kind.

    GDAL's ``remove_outliers`` (alg/gdal_crs.cpp): fit, find the single GCP
    with the largest residual ``|model(src) - dst|``; if it is at least
    ``tolerance``, drop it and refit; stop when none is, or when only
    ``min_gcps`` remain. GDAL does it for polynomials; the same loop serves
    every kind of the registry.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        GCPs; GDAL fits pixel -> map here, so its tolerance is in map units.
    order : {1, 2, 3} or str or None
        Degree of the polynomial (``refine_gcps(src, dst, 1, tolerance)``,
        GDAL's case), or the name of another kind ("helmert").
    tolerance : float
        Residual, in dst units, from which a GCP counts as an outlier.
    min_gcps : int, optional
        Never go below this many GCPs; default the kind's minimum.
    kind : str, optional
        As :func:`rsgeo.transforms.fit_transform`; then ``order`` is only for
        ``kind="polynomial"``.

    Returns
    -------
    model : GeometricModel
        Fitted on the kept GCPs.
    kept : ndarray of bool, shape (n,)
        True for the GCPs that survived.

    Raises
    ------
    GCPError
        As :func:`rsgeo.transforms.fit_transform`, or for a ``min_gcps`` below
        the kind's minimum or above the number of GCPs.
    rsgeo.errors.RsgeoError
        For a negative, NaN or infinite tolerance, or a ``min_gcps`` that is
        not a whole number.
    TypeError
        If ``tolerance`` or ``min_gcps`` is not a number (a string, a bool).

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> dst = src / 2
    >>> dst[4] += 3                                   # one bad GCP
    >>> model, kept = refine_gcps(src, dst, "helmert", 1.0)
    >>> kept.tolist()
    [True, True, True, True, False]
    """
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    entry = _registered(order, kind, "refine_gcps")
    floor = entry.min_gcps
    tolerance = as_number(tolerance, "tolerance", low=0,
                          why=N_("the residual, in dst units, from which a GCP is dropped"))
    min_gcps = floor if min_gcps is None else as_integer(min_gcps, "min_gcps")
    if min_gcps < floor:
        raise GCPError(_("min_gcps must be at least {floor} for {describe}, got "
                         "{min_gcps}").format(
                floor=floor, describe=_describe(entry), min_gcps=min_gcps))
    if min_gcps > len(src):
        raise GCPError(_("min_gcps ({min_gcps}) exceeds the number of GCPs ({n_src}); "
                         "it must be between the order's minimum and the number of GCPs").format(
                min_gcps=min_gcps, n_src=len(src)))
    kept = np.ones(len(src), dtype=bool)
    model = fit_transform(src, dst, entry.kind, entry.order)
    while kept.sum() > min_gcps:
        distance = residuals(model, src[kept], dst[kept])[2]
        # Residuals below float32's epsilon count as zero, as in GDAL.
        distance = np.where(distance < np.finfo(np.float32).eps, 0.0, distance)
        worst = int(np.argmax(distance))
        if distance[worst] < tolerance:
            break
        kept[np.flatnonzero(kept)[worst]] = False
        model = fit_transform(src[kept], dst[kept], entry.kind, entry.order)
    return model, kept


# --- The polynomial's statistics -----------------------------------------------------------------


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
        As :func:`rsgeo.transforms.fit_polynomial` returns; its ``src`` and
        ``dst`` are the GCPs.

    Returns
    -------
    ndarray, shape (2, m)
        Row 0 the standard errors of the a_i, row 1 those of the b_i, in the
        order of ``model.coefficients``.

    Raises
    ------
    GCPError
        If the model has no redundant GCP (n <= m): s² cannot be estimated.
    TypeError
        If ``model`` is not a :class:`~rsgeo.transforms.PolynomialModel`.

    Examples
    --------
    >>> from rsgeo.transforms import fit_polynomial
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> dst = src * 2 + [[0, 0], [0, 0], [0, 0], [0, 0], [1, -1]]
    >>> coefficient_standard_errors(fit_polynomial(src, dst, 1)).round(3)
    array([[0.283, 0.063, 0.063],
           [0.283, 0.063, 0.063]])
    """
    if not isinstance(model, PolynomialModel):
        raise TypeError(_("model must be a PolynomialModel (from fit_polynomial), got "
                          "{kind}").format(kind=type(model).__name__))
    return model.standard_errors()


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
    GCPError
        If src is not (n, 2) finite numbers or the order is not 1-3.
    """
    matrix, _, _ = normalised_design(as_points(src, "src"), order)
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
    GCPError
        If the points are not (n, 2) finite numbers or the size is not positive.
    """
    from scipy.spatial import ConvexHull, QhullError

    points = as_points(points)
    width = as_number(width, "width", low=0, why=N_("the image's width in pixels"))
    height = as_number(height, "height", low=0, why=N_("the image's height in pixels"))
    if width == 0 or height == 0:
        raise GridError(_("width and height must be positive (pixels), got {width} and "
                          "{height}").format(width=width, height=height))
    clipped = np.clip(points, [0, 0], [width, height])
    try:
        area = ConvexHull(clipped).volume
    except QhullError:
        return 0.0  # collinear or too few points: no area at all
    return float(area / (width * height))


def predicted_error_map(src, order, x, y, gcp_error=1.0, kind=None, dst=None):
    """Standard deviation of the model's prediction over a grid, for GCP errors of ``gcp_error``.

    For least squares with independent GCP errors of standard deviation σ, a
    polynomial's prediction at a point with terms a(x, y) has variance
    σ² a(x, y)ᵀ (AᵀA)⁻¹ a(x, y): small among the GCPs, growing fast away
    from them, faster for higher degrees. Any other kind is propagated the same
    way through its fit: the prediction at a point responds to each GCP's dst
    coordinate with a weight w_i (the fit of a unit error at that GCP alone),
    and its variance is σ² Σ w_i². That is exact for the kinds whose fit is
    linear in dst (linear, Helmert, thin-plate spline; for polynomials it equals
    the formula above) and first order for a projective model, whose weights
    depend on ``dst`` (given).

    Parameters
    ----------
    src : (n, 2) array_like
        GCP positions in the model's input coordinates.
    order : {1, 2, 3} or str or None
        Degree of the polynomial, or the name of another kind ("tps").
    x, y : ndarray
        Grid of positions (same units as src), any shape.
    gcp_error : float
        σ, the standard deviation of one GCP's error (dst units), on each axis.
    kind : str, optional
        As :func:`rsgeo.transforms.fit_transform`; then ``order`` is only for
        ``kind="polynomial"``.
    dst : (n, 2) array_like, optional
        The GCPs' dst positions: needed by a projective model only.

    Returns
    -------
    ndarray, shape of x
        Predicted standard deviation of the model at each position, per axis
        (the root mean of the two axes' variances; for a polynomial both are
        equal).

    Raises
    ------
    GCPError
        If x and y differ in shape, gcp_error is negative, the GCPs do not
        determine the model, or a projective model is given no ``dst``.

    References
    ----------
    Draper, N. R. and Smith, H., *Applied Regression Analysis*, the
    variance of a predicted mean response, Var(ŷ₀) = σ² x₀ᵀ(XᵀX)⁻¹x₀.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> x, y = np.array([5.0, 20.0]), np.array([5.0, 20.0])
    >>> predicted_error_map(src, 1, x, y).round(3)      # centre, then far outside
    array([0.5  , 2.179])
    >>> predicted_error_map(src, "helmert", x, y).round(3)
    array([0.5  , 1.581])
    """
    gcp_error = as_number(gcp_error, "gcp_error", low=0,
                          why=N_("a standard deviation in dst units"))
    if np.shape(x) != np.shape(y):
        raise GridError(_("x and y must have the same shape, got {x_shape} and {y_shape}").format(
                x_shape=np.shape(x), y_shape=np.shape(y)))
    src = as_points(src, "src")
    entry = _registered(order, kind, "predicted_error_map")
    grid = np.column_stack([np.ravel(x), np.ravel(y)])
    if entry.kind != "polynomial":
        if entry.kind == "projective" and dst is None:
            raise GCPError(_("a 'projective' model's predicted error depends on where its GCPs "
                             "go: pass dst, the GCPs' dst positions"))
        dst = None if dst is None else _pair(src, dst)[1]
        deviation = _propagated_deviation(entry.fit, src, grid, dst)
        return (gcp_error * deviation).reshape(np.shape(x))
    order = entry.order
    matrix, origin, scale = normalised_design(src, order)
    if np.linalg.matrix_rank(matrix) < matrix.shape[1]:
        raise GCPError(_("the GCPs do not determine an order-{order} polynomial "
                         "(collinear or too few)").format(order=order))
    normal_inverse = np.linalg.inv(matrix.T @ matrix)
    terms = normalised_design(grid, order, origin, scale)[0]
    variance = np.einsum("ij,jk,ik->i", terms, normal_inverse, terms)
    return (gcp_error * np.sqrt(variance)).reshape(np.shape(x))


def _propagated_deviation(fit, src, grid, dst=None):
    """Per-axis standard deviation at ``grid`` of the model ``fit`` makes of ``src``, for unit
    GCP errors: the root mean over both axes of Σ_i w_i², w_i the prediction's response to GCP
    i's dst coordinate. Without ``dst`` the fit must be linear in dst: w_i is the model fitted to
    a unit error at that coordinate alone. With ``dst``, w_i is a finite difference around it."""
    if dst is None:
        base, step = np.zeros_like(src), 1.0
        at_base = np.zeros_like(grid)
    else:
        base = dst
        step = 1e-6 * max(1.0, float(np.abs(dst - dst.mean(axis=0)).max()))
        at_base = fit(src, base)(grid)
    variance = np.zeros(len(grid))
    for i in range(len(src)):
        for axis in (0, 1):
            moved = base.copy()
            moved[i, axis] += step
            response = (fit(src, moved)(grid) - at_base) / step
            variance += np.sum(response**2, axis=1)
    return np.sqrt(variance / 2)


# --- Every model at once -------------------------------------------------------------------------


def _georeferencer_model(map_xy, image_xy, entry):
    """A registry entry's model map -> image as gdalwarp and QGIS's Georeferencer make it.

    Every kind is fitted map -> image, except the thin-plate spline: GDAL's TPS transformer
    (which ``gdalwarp -tps`` and QGIS use) fits it image -> map and inverts it point by point,
    :meth:`~rsgeo.transforms.TPSModel.inverse` (as :func:`rsgeo.resample.georeference` does).
    """
    if entry.kind == "tps":
        return fit_transform(image_xy, map_xy, "tps").inverse()
    return fit_transform(map_xy, image_xy, entry.kind, entry.order)


def compare_models(src, dst, is_check=None, models=GEOREFERENCER_MODELS):
    """One row per model: parameters, minimum GCPs, fitting RMS, leave-one-out RMS, check RMS.

    The models are fitted on the GCPs not flagged in ``is_check``; the
    check points are only measured. Leave-one-out runs on the fitting GCPs.
    Every model maps map -> image and every error is measured there, in
    pixels: ``model(src) - dst``.

    The thin-plate spline is GDAL's, the one ``gdalwarp -tps`` and QGIS's
    Georeferencer use: fitted image -> map (dst -> src: pixel/line ->
    georeferenced x/y, GDAL's TPS transformer with the GCPs as given) and
    inverted point by point where a map -> image position is needed
    (:meth:`rsgeo.transforms.TPSModel.inverse`, GDAL's ``GDALTPSTransform``
    from dst to src: a start from a second spline fitted map -> image,
    refined by Newton's method on the first; what
    :func:`rsgeo.resample.georeference` warps with). A spline fitted map ->
    image directly, ``fit_transform(src, dst, "tps")``, passes through the
    same GCPs but is another surface between them (on chapter 3b's CBERS
    GCPs, blunder G10 included, more than half a pixel away), so its
    leave-one-out and check-point errors are not those of the image
    gdalwarp or QGIS makes. (Before GDAL 3.8, gdalwarp used that second
    spline alone as its map -> image mapping.)

    Parameters
    ----------
    src, dst : (n, 2) array_like
        All points: map (x, y) -> image (col, row).
    is_check : (n,) array_like of bool or None
        True for check points (not used to fit). None: no check points.
    models : sequence of (label, kind, order)
        Default: :data:`rsgeo.transforms.GEOREFERENCER_MODELS`, QGIS's seven choices.

    Returns
    -------
    pandas.DataFrame
        Index: the labels. Columns ``parameters``, ``min GCPs``,
        ``fitting RMS (px)``, ``leave-one-out RMS (px)`` and, with check
        points, ``check RMS (px)``. A model with too few GCPs for leave-one-out
        gets NaN there.

    Raises
    ------
    GCPError
        If the points are malformed, ``is_check`` does not hold one flag per
        point, or a model cannot be fitted (too few or degenerate GCPs).
    ModelError
        Where the thin-plate spline has no inverse at a GCP left out or a
        check point (the spline fitted image -> map folds there).

    References
    ----------
    GDAL, ``alg/gdal_tps.cpp`` (``GDALCreateTPSTransformer``,
    ``GDALTPSTransform``); QGIS's Georeferencer, ``QgsGDALGeorefTransform``
    (its thin-plate spline is GDAL's TPS transformer, pixel -> map) and
    ``QgsGCPListModel`` (its residuals in pixels are that transformer's map
    -> pixel inversion).

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> table = compare_models(src, src * 2, models=[("helmert", "helmert", None)])
    >>> table.columns.tolist()
    ['parameters', 'min GCPs', 'fitting RMS (px)', 'leave-one-out RMS (px)']
    """
    import pandas as pd

    src, dst = same_points(src, dst)
    check = np.zeros(len(src), bool) if is_check is None else as_flags(is_check, "is_check")
    if check.shape != (len(src),):
        raise GCPError(_("is_check needs one flag per point ({n_src}), got shape "
                         "{check_shape}").format(n_src=len(src), check_shape=check.shape))
    fit_src, fit_dst = src[~check], dst[~check]
    rows = {}
    for label, kind, order in models:
        entry = registered(kind, order)
        model = _georeferencer_model(fit_src, fit_dst, entry)
        fitted = model.inverse() if entry.kind == "tps" else model   # the spline image -> map
        row = {"parameters": fitted.n_parameters, "min GCPs": entry.min_gcps,
               "fitting RMS (px)": model.rms(fit_src, fit_dst)}
        if len(fit_src) > entry.min_gcps:
            loo = np.hypot(*_left_out_differences(fit_src, fit_dst, order, kind,
                                                  "compare_models", _georeferencer_model).T)
            row["leave-one-out RMS (px)"] = float(np.sqrt(np.mean(loo**2)))
        else:
            row["leave-one-out RMS (px)"] = np.nan
        if check.any():
            row["check RMS (px)"] = model.rms(src[check], dst[check])
        rows[label] = row
    return pd.DataFrame.from_dict(rows, orient="index")


# --- Against an image's own geotransform ---------------------------------------------------------


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
        :class:`~rsgeo.transforms.PolynomialModel` from :meth:`rsgeo.gcp.GCPSet.fit`.
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
    GridError
        If the transform is not an invertible affine.Affine, the shape is not
        two positive integers or the step is not a positive integer.
    ModelError
        If the model gives NaN or the wrong shape.

    Examples
    --------
    >>> import affine
    >>> from rsgeo.transforms import fit_polynomial
    >>> transform = affine.Affine(20, 0, 1000, 0, -20, 5000)
    >>> cols_rows = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> map_xy = np.column_stack(transform @ cols_rows.T)
    >>> model = fit_polynomial(map_xy, cols_rows + [0.0, 1.5], 1)   # 1.5 rows off
    >>> check = compare_with_geotransform(model, transform, (10, 10))
    >>> round(check.rms, 6), (check.mean_offset.round(6) + 0.0).tolist()
    (1.5, [0.0, 1.5])
    """
    transform = as_invertible_affine(transform, "transform")
    rows, cols = as_shape(shape)
    if int(step) != step or step < 1:
        raise GridError(_("step must be a positive whole number of pixels, got {step!r}").format(
                step=step))
    grid_rows, grid_cols = np.mgrid[0:rows:int(step), 0:cols:int(step)] + 0.5
    points = np.column_stack([grid_cols.ravel(), grid_rows.ravel()])
    map_xy = np.column_stack(transform @ (points[:, 0], points[:, 1]))
    predicted = np.asarray(model(map_xy), dtype=np.float64)
    if predicted.shape != points.shape or not np.isfinite(predicted).all():
        raise ModelError(_("model must return finite (n, 2) image positions, got shape "
                           "{predicted_shape}").format(predicted_shape=predicted.shape))
    differences = predicted - points
    lengths = np.hypot(differences[:, 0], differences[:, 1])
    mean_offset = differences.mean(axis=0)
    centred = differences - mean_offset
    return GeotransformCheck(points, differences, float(np.sqrt(np.mean(lengths**2))),
                             mean_offset, float(np.sqrt(np.mean(np.sum(centred**2, axis=1)))),
                             float(lengths.max()))


