"""The thin-plate spline through every GCP, GDAL's (``gdalwarp -tps``).
"""



import numpy as np

from ..errors import GCPError
from ..language import N_, _
from ..validation import as_number, as_points
from ._base import GeometricModel, InverseModel, compiled, newton_inverse

__all__ = [
    "TPSModel", "fit_tps",
]

# --- Thin-plate spline ---------------------------------------------------------------------------


class TPSModel(GeometricModel):
    """Thin-plate spline through every GCP, GDAL's (``gdalwarp -tps``), bit for bit.

    u(x, y) = a0 + a1 x + a2 y + Σ w_i r_i² log r_i², the same for v, with
    r_i the distance to GCP i (x and y measured from the GCPs' mean); the
    weights make it pass through every GCP and its bending energy is the
    smallest that does. Solved and evaluated as GDAL's ``VizGeorefSpline2D``
    does (``rsgeo._kernels.thin_plate``): the same LU decomposition, the same
    order of operations, GDAL's faster logarithm for the grouped terms, so
    its values equal GDAL's to the last bit. It therefore misses its GCPs by
    GDAL's rounding (about 1e-11 px with tens of GCPs, 1e-7 px with
    thousands), and GCPs nearly on one line (r² of their x and y above 0.99,
    or one extent under a thousandth of the other) give GDAL's
    piecewise-linear interpolation along that line instead of a spline.

    Parameters
    ----------
    src, dst : (n, 2) ndarray
        The GCPs, checked by :func:`~rsgeo.transforms.fit_transform`.

    skipped : sequence of int
        Rows of the GCPs given to :func:`~rsgeo.transforms.fit_transform` that repeated an
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
        The solved spline, read-only, for ``rsgeo._kernels.thin_plate.evaluate``
        (its layout is in that module's docstring).
    """

    kind = "tps"

    def __init__(self, src, dst, skipped=()):
        self.src = np.array(src, dtype=np.float64)
        self.dst = np.array(dst, dtype=np.float64)
        self.skipped = tuple(skipped)
        self.n_parameters = 2 * (len(self.src) + 3)      # the spline's weights and affine part
        self.packed = compiled("thin_plate").solve(self.src, self.dst)
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
        """The model packed for the warp kernels (see ``rsgeo._kernels.transformer``).

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
        return fit_tps(self.dst, self.src)

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
            ``rsgeo._kernels.thin_plate.GDAL_STEPS``) and again as many for the
            points they leave short.

        Returns
        -------
        InverseModel
            Raises ``ModelError`` at points where the refinement does not
            converge (the spline folds there); its ``packed`` attribute is
            ``rsgeo._kernels.thin_plate.pack_inverse`` of this spline and its reverse.

        Raises
        ------
        GCPError
            If the reverse spline cannot be fitted (repeated or collinear dst).
        ValueError
            If ``tolerance`` is negative or ``max_iterations`` not an integer >= 0.
        """
        if max_iterations is None:
            max_iterations = compiled("thin_plate").GDAL_STEPS
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
    compiled("thin_plate").evaluate_many(packed, points, out)
    return out


class _TPSInverse(InverseModel):
    """A :class:`TPSModel` inverted as GDAL's TPS transformer does (:meth:`TPSModel.inverse`)."""

    def __init__(self, forward, reverse, tolerance, max_iterations):
        self.packed = compiled("thin_plate").pack_inverse(forward.packed, reverse.packed,
                                                            max_iterations)
        self.packed.flags.writeable = False
        self._tolerance = as_number(tolerance, "tolerance", low=0,
                                    why=N_("relative to the dst extent"))
        self._max_iterations = int(self.packed[1])
        super().__init__(forward, self._solve_points)

    def kernel_form(self):
        """The inversion packed for the warp kernels (see ``rsgeo._kernels.transformer``).

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
        compiled("thin_plate").invert_many(self.packed, targets, points, converged)
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


#: How many times steeper than the GCPs' typical slope the line between two neighbouring GCPs
#: may be before the spline is refused. A spline through two GCPs d apart in src whose dst
#: points are g apart must climb g / d between them; far beyond the set's own slope it folds
#: there and bends the whole surface to do so (14 CBERS GCPs and one more 0.2 m from a GCP with
#: its pixel 0.8 px away, 80 times the slope: the scene's centre moves by 30 px). GCPs measured
#: twice with a little noise are fitted: GDAL autotest's 2,115 GCPs (gcps_2115.vrt), which GDAL
#: fits to 1e-3, reach 19.5 times their slope (two GCPs 4.5 cm apart, 0.88 m apart in dst).
TPS_MAX_SLOPE_RATIO = 40.0

#: Neighbours of each GCP whose slope is checked: a GCP with more neighbours closer than a
#: partner is held by them, and the check stays O(n log n) for tens of thousands of GCPs.
_TPS_NEIGHBOURS = 8

def _typical_slope(src, dst):
    """The GCPs' typical |d dst| / |d src|: the RMS singular value of their least-squares
    affine map's linear part (0 where every dst point is the same)."""
    centred = src - src.mean(axis=0)
    design = np.column_stack([np.ones(len(src)), centred])
    coefficients = np.linalg.lstsq(design, dst - dst.mean(axis=0), rcond=None)[0]
    return float(np.linalg.norm(coefficients[1:]) / np.sqrt(2.0))


def _check_slopes(src, dst, keep):
    """Refuse neighbouring GCPs whose dst points are far further apart than the set's typical
    slope allows for their distance in src: the spline folds between them."""
    from scipy.spatial import cKDTree

    typical = _typical_slope(src, dst)
    if not typical > 0:
        return
    k = min(_TPS_NEIGHBOURS, len(src) - 1)
    distance, neighbour = cKDTree(src).query(src, k=k + 1)
    distance, neighbour = distance[:, 1:], neighbour[:, 1:]
    gap = np.hypot(*(dst[neighbour] - dst[:, np.newaxis, :]).transpose(2, 0, 1))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(distance > 0, gap / distance, np.inf) / typical
    steep = ratio > TPS_MAX_SLOPE_RATIO
    if not steep.any():
        return
    rows, columns = np.nonzero(steep)
    pairs = {tuple(sorted((int(keep[i]), int(keep[neighbour[i, j]])))) for i, j in
             zip(rows, columns)}
    worst = np.unravel_index(np.argmax(np.where(steep, ratio, -np.inf)), ratio.shape)
    i, j = int(worst[0]), int(neighbour[worst])
    a, b = sorted((int(keep[i]), int(keep[j])))
    raise GCPError(_(
        "a 'tps' model cannot pass through GCPs {count} pair(s) of which are close in src but "
        "far apart in dst (worst: rows {a} and {b}, {distance:.3g} apart in src and {gap:.3g} "
        "in dst, a slope {ratio:.0f} times the GCPs' typical {typical:.3g}; the spline would "
        "fold between them and bend the whole surface); remove or correct one of each pair "
        "(neighbouring GCPs may be at most {bound:g} times steeper than the set)").format(
            count=len(pairs), a=a, b=b, distance=float(distance[worst]),
            gap=float(gap[worst]), ratio=float(ratio[worst]), typical=typical,
            bound=TPS_MAX_SLOPE_RATIO))


def fit_tps(src, dst):
    """The spline through every GCP; exact duplicates skipped (as GDAL does); src points
    repeated with different dst, or neighbours far steeper than the set, refused."""
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
    centred = (src - src.mean(axis=0)) / (np.abs(src - src.mean(axis=0)).max() or 1.0)
    if np.linalg.matrix_rank(np.column_stack([np.ones(len(src)), centred]), tol=1e-9) < 3:
        raise GCPError(_("a 'tps' model needs at least 3 GCPs that are not collinear (its "
                         "affine part is fixed by them); spread the GCPs over the image"))
    _check_slopes(src, dst, keep)
    return TPSModel(src, dst, skipped)


