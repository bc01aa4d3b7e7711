"""The mapping protocol every model follows, its exact inverse, and Newton's method that inverts a
model fitted map -> image (after scikit-image's ``transform/_geometric.py``).
"""


import importlib

import numpy as np

from ..errors import GCPError, ModelError
from ..language import N_, _
from ..validation import as_number, as_points

__all__ = [
    "compiled", "GeometricModel", "same_points", "residual_vectors", "rms_of", "outside_hull",
    "InverseModel", "newton_inverse",
]


def compiled(name):
    """One of rsgeo's compiled modules (Numba), imported when a model is first evaluated, so
    that reading GCPs (rsgeo.gcp, rsgeo.data) does not load the compiler."""
    return importlib.import_module(f"rsgeo._kernels.{name}")


# --- The protocol --------------------------------------------------------------------------------


class GeometricModel:
    """The mapping protocol every rsgeo model and distortion follows (after scikit-image).

    A geometric model maps points of one coordinate system (``src``) to
    another (``dst``). Subclasses define ``__call__`` and
    :meth:`inverse`; :meth:`~rsgeo.accuracy.residuals` and :meth:`rms` come with the protocol.

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
        >>> from rsgeo.transforms import fit_polynomial
        >>> model = fit_polynomial(src, src + 1, 1)
        >>> model.residuals(src, src + [[1, 1], [1, 1], [4, 5]]).round(6) + 0.0
        array([0., 0., 5.])
        """
        return residual_vectors(self, src, dst)[1]

    def rms(self, src, dst):
        """The lecture's RMS of :meth:`~rsgeo.accuracy.residuals`: sqrt(Σ R_i² / n).

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
            As :meth:`~rsgeo.accuracy.residuals`, or when there is no point.

        Examples
        --------
        >>> src = np.array([[0, 0], [10, 0], [0, 10]], dtype=float)
        >>> from rsgeo.transforms import fit_polynomial
        >>> round(fit_polynomial(src, src, 1).rms(src, src + [[3, 4], [0, 0], [0, 0]]), 4)
        2.8868
        """
        predicted, _ = residual_vectors(self, src, dst)
        return rms_of(predicted - as_points(dst, "dst"))


def same_points(src, dst):
    """src and dst as (n, 2) arrays holding the same number of points."""
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    if len(src) != len(dst):
        raise GCPError(_("src and dst must hold the same points, got {n_src} and {n_dst}").format(
                n_src=len(src), n_dst=len(dst)))
    return src, dst


def residual_vectors(model, src, dst):
    """model(src) and |model(src) - dst|, with the inputs checked."""
    src, dst = same_points(src, dst)
    predicted = np.asarray(model(src), dtype=np.float64)
    if predicted.shape != dst.shape:
        raise GCPError(_("the model must return an (n, 2) array, got shape "
                         "{predicted_shape}").format(predicted_shape=predicted.shape))
    return predicted, np.hypot(*(predicted - dst).T)


def rms_of(difference):
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
    >>> from rsgeo.transforms import fit_polynomial
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
            # a step where the model folds can throw a point to infinity: it has failed, and
            # the model is not evaluated there (its own check would blame the caller's points)
            finite = np.isfinite(points).all(axis=1)
            difference = np.full_like(points, np.inf)
            if finite.any():
                difference[finite] = model(points[finite]) - targets[finite]
            with np.errstate(over="ignore", invalid="ignore"):
                error = np.hypot(difference[:, 0], difference[:, 1])
            active = finite & (error > limit) & np.isfinite(error)
            if not active.any():
                break
            jacobian = model.jacobian(points[active])
            usable = np.abs(np.linalg.det(jacobian)) > 1e-300
            step = np.zeros((int(active.sum()), 2))
            step[usable] = np.linalg.solve(jacobian[usable],
                                           difference[active][usable][..., None])[..., 0]
            points = points.copy()
            points[active] = points[active] - step
        failed = ~(error <= limit)
        if failed.any():
            raise ModelError(failure(failed, targets))
        return points

    return InverseModel(model, solve)

