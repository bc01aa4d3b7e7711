"""Automatic image-to-image registration: tie points by correlation and by features.

Two ways to find GCPs without a human, both on scikit-image, both returning a
:class:`rsgeo.gcp.GCPSet` (map coordinates through the reference's
geotransform, image coordinates (col, row) in the moving image), so that the
fitting, refinement and evaluation of chapters 2-4 apply unchanged:

* :func:`correlation_tiepoints` - a grid of windows, each one's sub-pixel
  shift by phase correlation (``skimage.registration.phase_cross_correlation``,
  upsampled; Guizar-Sicairos et al. 2008), as AROSICS (Scheffler et al. 2017)
  co-registers Landsat and Sentinel-2 scenes: the moving image is first
  resampled onto the reference grid through a global estimate, the windows are
  correlated there, the shifts are composed with the estimate, and this is
  repeated. Unreliable windows are rejected (constant or masked, low contrast,
  a weak correlation peak, outliers to a robust global fit).
* :func:`feature_tiepoints` - SIFT (Lowe 2004) or ORB (Rublee et al. 2011)
  keypoints, matched by their descriptors (``skimage.feature.match_descriptors``),
  then RANSAC (Fischler and Bolles 1981; ``skimage.measure.ransac``) with any
  model of :func:`rsgeo.transforms.fit_transform`, keeping the inliers.

:func:`rsgeo.registration.register` is the step every automatic method shares with the GA
paper's (:func:`rsgeo.registration.register_by_regions`): tie points -> GCPSet ->
model -> refinement (``gdalwarp -refine_gcps``) -> check points.
"""


import numpy as np
from threadpoolctl import threadpool_limits

from .. import gcp, resample, transforms
from ..errors import GCPError, GridError, ImageError
from ..language import N_, _
from ..validation import as_image, as_integer, as_invertible_affine, as_number, check_choice

__all__ = [
    "DETECTORS", "MIN_WINDOW", "MAX_EDGE_SHARE", "MAX_UPSAMPLE", "measure_shifts", "edge_share",
    "offsets_against_reference", "ransac_model", "robust_fit", "correlation_tiepoints",
    "feature_tiepoints", "one_blas_thread", "to_map", "apply_model",
]

#: Largest ``upsample`` the correlation takes (measure_shifts, correlation_tiepoints,
#: band_misregistration): 1/1000 px is ten times finer than a window's shift is known, and the
#: upsampled correlation of a window holds (1.5 upsample)² complex numbers (36 MB at 1000; at
#: 10**6, 36 TB).
MAX_UPSAMPLE = 1000
UPSAMPLE_NEEDED = N_("1 / the sub-pixel precision; the upsampled correlation takes "
                     "(1.5 upsample)² complex numbers per window, and a window's shift "
                     "is not known to better than a hundredth of a pixel")




DETECTORS = ("sift", "orb")
#: Smallest correlation window, pixels: below it a window's spectrum has too few frequencies to
#: locate a peak (and SciPy's FFT refuses a side of 1).
MIN_WINDOW = 8
#: Largest :func:`edge_share` of a window :func:`correlation_tiepoints` trusts by default.
MAX_EDGE_SHARE = 0.4


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
        :func:`rsgeo.registration.correlation_tiepoints` filters on); then every
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
        (the smaller standard deviation of the two windows), ``skipped``
        ("" or why the window was not correlated: "constant", "invalid") and
        ``edge_share`` (:func:`edge_share` of the two windows: how smooth they
        are for phase correlation).

    Raises
    ------
    ValueError
        If the images differ in shape, are not 2-D or hold NaN, or step
        or upsample is not a positive whole number, the window is not a whole
        number from ``MIN_WINDOW`` to the images' smaller side, or
        ``valid`` is not a mask of their shape.

    References
    ----------
    Guizar-Sicairos, M., Thurman, S. T. and Fienup, J. R. (2008),
    "Efficient subpixel image registration algorithms", Optics Letters 33(2).
    """
    from skimage.registration import phase_cross_correlation

    reference = np.asarray(reference, dtype=np.float64)
    moving = np.asarray(moving, dtype=np.float64)
    if reference.shape != moving.shape or reference.ndim != 2:
        raise ImageError(_("reference and moving must be 2-D images of the same shape, "
                           "got {reference_shape} and {moving_shape}").format(
                reference_shape=reference.shape, moving_shape=moving.shape))
    if not (np.isfinite(reference).all() and np.isfinite(moving).all()):
        raise ImageError(_("reference and moving hold NaN or infinite values; crop or fill them "
                           "first"))
    step = as_integer(step, "step", 1, None, _("a whole number of pixels"))
    upsample = as_integer(upsample, "upsample", 1, MAX_UPSAMPLE, UPSAMPLE_NEEDED)
    window = as_integer(window, "window", MIN_WINDOW, None,
                        _("a correlation window needs at least {n} × {n} pixels").format(
                            n=MIN_WINDOW))
    if window > min(reference.shape):
        raise GridError(_("window ({window} px) is larger than the images "
                          "{reference_shape}; use a window no larger than the smaller "
                          "side").format(window=window, reference_shape=reference.shape))
    if valid is not None:
        valid = np.asarray(valid)
        if valid.shape != reference.shape or valid.dtype != bool:
            raise ImageError(_("valid must be a boolean mask of the images' shape "
                               "{reference_shape}, got {valid_dtype} of shape "
                               "{valid_shape}").format(
                    reference_shape=reference.shape, valid_dtype=valid.dtype,
                    valid_shape=valid.shape))
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
                shift, error, _phase = phase_cross_correlation(
                    a, b, upsample_factor=upsample, normalization=None)
            else:
                shift, error, _phase = phase_cross_correlation(a, b, upsample_factor=upsample)
            points.append((col, row))
            shifts.append((shift[1], shift[0]))
            if details:
                rows.append({**_correlation_peak(a, b), "error": error, "contrast": contrast,
                             "skipped": "", "edge_share": edge_share(a, b)})
    points = np.array(points, dtype=float).reshape(-1, 2)
    shifts = np.array(shifts, dtype=float).reshape(-1, 2)
    if not details:
        return points, shifts
    import pandas as pd

    columns = ["peak", "reliability", "error", "contrast", "skipped", "edge_share"]
    return points, shifts, pd.DataFrame(rows, columns=columns)


def edge_share(window, other=None):
    """Share of a window's frequencies where its cut edges outweigh its content.

    Phase correlation weights every frequency alike. A window cut out of an
    image is, to the FFT, periodic, with jumps where its opposite edges meet;
    two windows taken at the same place share those jumps, and they correlate
    best at zero shift. On a textured window the content outweighs the jumps
    at most frequencies; on a smooth one the jumps do, and phase correlation
    reports (nearly) zero whatever the content's shift: 16 of 16 windows of a
    smooth scene were called reliable while 2.3 px off. Moisan's (2011)
    periodic-plus-smooth decomposition separates the two: the smooth
    component is what the jumps contribute, the periodic one the content.

    Parameters
    ----------
    window : (rows, cols) array_like
        One window, at least 2 × 2 pixels.
    other : (rows, cols) array_like, optional
        The window it is correlated with: then the share of the frequencies
        where the edges outweigh the content in both (those vote for zero
        shift in the cross-power spectrum).

    Returns
    -------
    float
        From 0 (content everywhere) to 1 (the edges everywhere). For one
        64 × 64 window: 0.02 for white noise, at most 0.54 on the course's
        CBERS, nat1 and synthetic landscape windows, 0.56 to 0.87 for noise
        blurred by a Gaussian of 2 px, 0.96 to 1 of 8 px.

    Raises
    ------
    ValueError
        If a window is not a finite 2-D array of at least 2 × 2 pixels, or
        the two differ in shape.

    References
    ----------
    Moisan, L. (2011), "Periodic plus smooth image decomposition", Journal of
    Mathematical Imaging and Vision 39(2), 161-179.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> bool(edge_share(rng.normal(size=(32, 32))) < 0.1)
    True
    >>> from scipy.ndimage import gaussian_filter
    >>> bool(edge_share(gaussian_filter(rng.normal(size=(64, 64)), 8)) > 0.9)   # smooth
    True
    """
    dominated = _edge_dominated(window, "window")
    if other is not None:
        second = _edge_dominated(other, "other")
        if second.shape != dominated.shape:
            raise ImageError(_("window and other must have the same shape, got {a} and "
                               "{b}").format(a=dominated.shape, b=second.shape))
        dominated &= second
    return float(dominated.mean())


def _edge_dominated(window, name):
    """Frequencies where the window's periodic-plus-smooth decomposition's smooth part (the
    edges' jumps) is larger than its periodic part (the content)."""
    u = np.asarray(window, dtype=np.float64)
    if u.ndim != 2 or min(u.shape) < 2 or not np.isfinite(u).all():
        raise ImageError(_("{name} must be a finite 2-D array of at least 2 × 2 pixels, got "
                           "shape {shape}").format(name=name, shape=u.shape))
    rows, cols = u.shape
    jumps = np.zeros_like(u)
    jumps[0, :] += u[-1, :] - u[0, :]
    jumps[-1, :] += u[0, :] - u[-1, :]
    jumps[:, 0] += u[:, -1] - u[:, 0]
    jumps[:, -1] += u[:, 0] - u[:, -1]
    laplacian = (2 * np.cos(2 * np.pi * np.arange(rows) / rows)[:, np.newaxis]
                 + 2 * np.cos(2 * np.pi * np.arange(cols) / cols)[np.newaxis] - 4)
    laplacian[0, 0] = 1.0
    smooth = np.fft.fft2(jumps) / laplacian
    smooth[0, 0] = 0.0
    return np.abs(smooth) > np.abs(np.fft.fft2(u) - smooth)


def _correlation_peak(a, b):
    """Height of the phase-correlation surface's peak, and its distance from the rest in standard
    deviations (a sharp, lone peak is a reliable match; a peak among many is not)."""
    spectrum = np.fft.fft2(a) * np.conj(np.fft.fft2(b))
    floor = 1e-12 * np.abs(spectrum).max()
    surface = np.abs(np.fft.ifft2(spectrum / np.maximum(np.abs(spectrum), floor)))
    flat = surface.ravel()
    top = int(np.argmax(flat))
    rest = np.delete(flat, top)
    return {"peak": float(flat[top]),
            "reliability": float((flat[top] - rest.mean()) / (rest.std() or 1.0))}


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
        raise ImageError(_("image and reference must be single bands (2-D), got shapes "
                           "{image_shape} and {reference_shape}").format(
                image_shape=image.shape, reference_shape=reference.shape))
    for name, t in (("transform", transform), ("reference_transform", reference_transform)):
        as_invertible_affine(t, name)
        if t.b != 0 or t.d != 0 or t.a <= 0 or t.e >= 0:
            raise GridError(_("{name} must be north-up (no rotation terms), got {t!r}").format(
                    name=name, t=t))
    ratio = transform.a / reference_transform.a
    factor = int(round(ratio))
    if (factor < 1 or abs(ratio - factor) > 1e-6
            or abs(-transform.e / -reference_transform.e - factor) > 1e-6):
        raise GridError(_("the image's pixel ({transform_a}, {value}) must be a whole "
                          "multiple of the reference's ({reference_transform_a}, "
                          "{value2})").format(
                transform_a=transform.a, value=-transform.e,
                reference_transform_a=reference_transform.a, value2=-reference_transform.e))
    rows, cols = (n // factor * factor for n in reference.shape)
    blocks = reference[:rows, :cols].reshape(rows // factor, factor, cols // factor,
                                             factor).mean(axis=(1, 3))
    block_transform = reference_transform @ reference_transform.scale(factor)
    grid_rows, grid_cols = np.mgrid[0:image.shape[0], 0:image.shape[1]] + 0.5
    x, y = transform @ (grid_cols, grid_rows)
    block_cols, block_rows = ~block_transform @ (x, y)
    inside = ((block_cols >= 0.5) & (block_rows >= 0.5) & (block_cols <= blocks.shape[1] - 0.5)
              & (block_rows <= blocks.shape[0] - 0.5))
    if not inside.any():
        raise GridError(_("the image and the reference do not overlap"))
    used_rows, used_cols = np.flatnonzero(inside.any(axis=1)), np.flatnonzero(inside.any(axis=0))
    box = np.s_[used_rows[0]:used_rows[-1] + 1, used_cols[0]:used_cols[-1] + 1]
    if not inside[box].all() or min(inside[box].shape) < window:
        raise GridError(_("the overlap {shape} must be a full rectangle of at least "
                          "{window} × {window} image pixels").format(
                shape=inside[box].shape, window=window))
    sampled = map_coordinates(blocks, [block_rows[box] - 0.5, block_cols[box] - 0.5], order=1)
    points, shifts = measure_shifts(sampled, image[box], step=step, window=window, taper=True)
    return points + [used_cols[0], used_rows[0]], -shifts


def ransac_model(kind="polynomial", order=1):
    """A model class for ``skimage.measure.ransac`` fitting :func:`rsgeo.transforms.fit_transform`.

    scikit-image's RANSAC asks a class for ``from_estimate(src, dst)`` (a
    fitted model, or a false value when the sample cannot determine one) and
    the model for ``residuals(src, dst)``; rsgeo's models already follow that
    protocol, so the class only wraps the fit.

    Parameters
    ----------
    kind : {"linear", "helmert", "polynomial", "projective", "tps"}
        As :func:`rsgeo.transforms.fit_transform`.
    order : {1, 2, 3} or None
        Polynomial order (only for ``kind="polynomial"``).

    Returns
    -------
    type
        A class with ``from_estimate`` and the attribute ``min_samples``
        (:func:`rsgeo.transforms.min_gcps` of the kind).

    Raises
    ------
    ValueError
        For an unknown kind or an order that does not fit it.

    Examples
    --------
    >>> Model = ransac_model("polynomial", 1)
    >>> Model.min_samples
    3
    >>> src = np.array([[0, 0], [10, 0], [0, 10]], dtype=float)
    >>> Model.from_estimate(src, src + 2)(np.array([[5.0, 5.0]])).round(6).tolist()
    [[7.0, 7.0]]
    """
    order = None if kind != "polynomial" else order
    needed = transforms.min_gcps(kind, order)

    class RsgeoModel:
        min_samples = needed
        # the fitted models' own, named for the protocol
        residuals = transforms.GeometricModel.residuals

        @classmethod
        def from_estimate(cls, src, dst):
            try:
                return transforms.fit_transform(src, dst, kind, order)
            except (ValueError, np.linalg.LinAlgError):
                return None

    RsgeoModel.__name__ = f"RansacModel_{kind}{order or ''}"
    return RsgeoModel


def robust_fit(src, dst, kind="polynomial", order=1, threshold=1.0, max_trials=1000, seed=0):
    """RANSAC fit of an rsgeo model: the model of the largest consistent subset, and that subset.

    Parameters
    ----------
    src, dst : (n, 2) array_like
        Point pairs (for GCPs: map x, y and image col, row).
    kind, order
        As :func:`rsgeo.transforms.fit_transform`.
    threshold : float
        Largest residual of an inlier, in dst units.
    max_trials : int
        Random samples RANSAC draws.
    seed : int
        Seed of RANSAC's sampling.

    Returns
    -------
    model : GeometricModel
        Refitted on all inliers.
    inliers : ndarray of bool, shape (n,)

    Raises
    ------
    ValueError
        If there are fewer pairs than the model needs, or no sample gives a
        model (all points collinear).

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [5, 5]], dtype=float)
    >>> dst = src + 1.0
    >>> dst[4] += 30                                   # one blunder
    >>> model, inliers = robust_fit(src, dst, threshold=0.5)
    >>> inliers.tolist()
    [True, True, True, True, False]
    """
    from skimage.measure import ransac

    src = np.asarray(src, dtype=np.float64)
    dst = np.asarray(dst, dtype=np.float64)
    model_class = ransac_model(kind, order)
    if len(src) < model_class.min_samples:
        raise GCPError((_("an order-{order} polynomial needs at least {min_samples} tie points, "
                          "got {n_src}") if kind == "polynomial" else
                        _("a {kind!r} model needs at least {min_samples} tie points, got "
                          "{n_src}")).format(order=order, kind=kind,
                                             min_samples=model_class.min_samples,
                                             n_src=len(src)))
    as_number(threshold, "threshold", 0, None, N_("a residual in dst units"))
    model, inliers = ransac((src, dst), model_class, model_class.min_samples, threshold,
                            max_trials=int(max_trials), rng=np.random.default_rng(seed))
    if not model or inliers is None or inliers.sum() < model_class.min_samples:
        raise GCPError(_("RANSAC found no {kind} model supported by "
                         "{model_class_min_samples} or more of the {n_src} tie points "
                         "(collinear or all inconsistent); more, better spread tie "
                         "points are needed").format(
                kind=kind, model_class_min_samples=model_class.min_samples, n_src=len(src)))
    return transforms.fit_transform(src[inliers], dst[inliers], kind, order), inliers


def one_blas_thread():
    """A context in which NumPy's BLAS runs on one thread (restored after), via threadpoolctl.

    phase_cross_correlation's upsampled DFT multiplies matrices of a few dozen rows: with several
    BLAS threads on a busy machine each product waits for a core (25 ms instead of 1 ms here).
    """
    return threadpool_limits(limits=1, user_api="blas")


def _transform(transform):
    import affine

    if transform is None:
        return affine.Affine.identity()
    return as_invertible_affine(transform, "reference_transform")


def to_map(transform, col_row):
    return np.column_stack(transform @ (col_row[:, 0], col_row[:, 1]))


def apply_model(mapping, points):
    """``mapping`` (a model, a function or an affine.Affine) on (n, 2) points."""
    import affine

    if isinstance(mapping, affine.Affine):
        return to_map(mapping, points)
    return np.asarray(mapping(points), dtype=np.float64)


def correlation_tiepoints(reference, moving, spacing, window, reference_transform=None,
                          initial=None, kind="polynomial", order=1, iterations=3, upsample=20,
                          min_contrast=2.0, min_reliability=8.0, tolerance=1.0, valid=None,
                          method="cubic", taper=False, seed=0, max_edge_share=MAX_EDGE_SHARE):
    """Tie points on a grid of windows by phase correlation, AROSICS-style, reliability-filtered.

    Each pass: resample ``moving`` onto the reference grid through the
    current estimate (map -> moving image; ``initial`` the first time), find
    every window's sub-pixel shift by phase correlation, and compose: the
    feature at reference position p is at p - shift on the resampled grid,
    hence at ``estimate(map(p - shift))`` in the moving image. A window
    measures a translation only, so with a rotation or scale change left in
    the estimate one pass is biased; the next pass starts from the model the
    reliable tie points give, until the shifts are (almost) zero.

    A window is rejected (its GCP disabled, the reason in ``notes``) when it
    is outside the moving image or masked by ``valid`` ("invalid"), constant
    ("constant"), of low contrast ("low contrast": water, cloud, a
    featureless field), has a weak correlation peak ("weak peak"), is too
    smooth for phase correlation ("smooth": :func:`edge_share` over
    ``max_edge_share``) or disagrees with a RANSAC fit of ``kind`` to the
    others by more than ``tolerance`` pixels ("outlier"): the idea of
    AROSICS's tie-point filters, from the correlation peak's reliability to
    RANSAC outlier detection.

    Smooth scenes: phase correlation of two windows cut at the same place is
    pulled towards zero shift by their cut edges, and on a smooth scene that
    pull wins (a blurred scene shifted by 2.3 px gave 16 of 16 "reliable"
    windows measuring about zero). Such windows are rejected as "smooth";
    ``taper=True`` (Hann-tapered cross-correlation, which has no cut edges)
    measures them, and is then the choice. It is not the default: on the
    course's CBERS-2B CCD/HRC pair the tapered correlation agrees less with
    the hand-made GCPs (0.84 px against 0.69 px in the red band, 0.89 against
    0.75 px in the near infrared with 36 windows kept instead of 84).

    Parameters
    ----------
    reference : (rows, cols) array_like
        The reference image, on the grid of ``reference_transform``.
    moving : (rows, cols) array_like
        The image to register (any size and pixel size).
    spacing, window : int
        Distance between window centres and side of each window, reference
        pixels.
    reference_transform : affine.Affine, optional
        Reference pixel -> map; by default map coordinates are the
        reference's pixel coordinates.
    initial : callable or affine.Affine, optional
        First estimate, map -> moving (col, row), e.g. ``~moving_transform``
        from the moving file's own (approximate) georeferencing; by default
        the moving image is taken to be on the reference grid.
    kind, order
        The global model (:func:`rsgeo.transforms.fit_transform`) of the outlier
        test and of each pass's estimate.
    iterations : int
        Passes at most (1 = a single pass on the first estimate).
    upsample : int
        Sub-pixel precision of each shift: 1 / upsample pixel.
    min_contrast : float
        Smallest standard deviation of a window (DN).
    min_reliability : float
        Smallest height of the correlation peak above the rest of the
        correlation surface, in its standard deviations.
    tolerance : float
        Outlier threshold, moving-image pixels.
    valid : (rows, cols) array_like of bool, optional
        False for reference pixels not to use (clouds, water).
    method : {"nearest", "bilinear", "cubic"}
        Resampling of the moving image.
    taper : bool
        Hann-tapered cross-correlation (:func:`measure_shifts`'s
        ``taper``): no pull towards zero shift from the windows' cut edges.
    seed : int
        Seed of the RANSAC outlier test.
    max_edge_share : float
        Largest :func:`edge_share` of a window pair phase correlation trusts
        (0 to 1; 1 keeps every window). The default, 0.4, is above every window
        of the course's CBERS and synthetic pairs (at most 0.34) and below
        most windows of noise blurred by 1.5 px or more. Not used with
        ``taper=True``.

    Returns
    -------
    GCPSet
        One GCP per window (map x, y of the window centre; its position in
        the moving image), ``enabled`` for the reliable ones, ``notes`` with
        each rejection's reason. Extra attributes: ``reliability`` (a table
        of peak, reliability, error, contrast and the shift of the last pass
        per window) and ``passes`` (per pass: reliable points and median
        length of the shifts, in pixels).

    Raises
    ------
    ValueError
        If an image is not 2-D, holds NaN, the window is smaller than
        ``MIN_WINDOW`` or larger than the reference, ``iterations`` is not a
        whole number from 1, ``spacing``, ``upsample`` or ``seed`` is not a
        whole number (a bool is not one: ``TypeError``) in its range,
        ``min_contrast``, ``min_reliability`` or ``tolerance`` is not a finite
        number from 0 (NaN would disable a filter), the
        first estimate puts the moving image nowhere on the
        reference grid (no overlap), or fewer reliable tie points remain
        than the model needs (the message counts each rejection reason).
    """
    reference = as_image(reference, "reference").astype(np.float64)
    moving = as_image(moving, "moving").astype(np.float64)
    for name, image in (("reference", reference), ("moving", moving)):
        if image.ndim != 2:
            raise ImageError(_("{name} must be one band (2-D), got shape {image_shape}").format(
                    name=name, image_shape=image.shape))
        if not np.isfinite(image).all():
            raise ImageError(_("{name} holds NaN or infinite values; fill them and mark "
                               "them with valid=False").format(name=name))
    check_choice(method, "method", ("nearest", "bilinear", "cubic"))
    iterations = as_integer(iterations, "iterations", 1, None, _("a number of passes"))
    spacing = as_integer(spacing, "spacing", 1, None, _("a whole number of pixels"))
    seed = as_integer(seed, "seed", 0, None, _("the seed of the RANSAC outlier test"))
    upsample = as_integer(upsample, "upsample", 1, MAX_UPSAMPLE, UPSAMPLE_NEEDED)
    window = as_integer(window, "window", MIN_WINDOW, None,
                        _("a correlation window needs at least {n} × {n} pixels").format(
                            n=MIN_WINDOW))
    min_contrast = as_number(min_contrast, "min_contrast", 0, None,
                             _("a standard deviation in DN; 0 keeps every window"))
    min_reliability = as_number(min_reliability, "min_reliability", 0, None,
                                _("a peak height in standard deviations; 0 keeps every window"))
    tolerance = as_number(tolerance, "tolerance", 0, None, _("an outlier threshold in pixels"))
    max_edge_share = as_number(max_edge_share, "max_edge_share", 0, 1,
                               _("a share of the window's frequencies"))
    transform = _transform(reference_transform)
    estimate = ~transform if initial is None else initial
    if valid is None:
        valid = np.ones(reference.shape, bool)
    else:
        valid = np.asarray(valid, dtype=bool)
        if valid.shape != reference.shape:
            raise ImageError(_("valid must have the reference's shape "
                               "{reference_shape}, got {valid_shape}").format(
                    reference_shape=reference.shape, valid_shape=valid.shape))
    needed = ransac_model(kind, order).min_samples
    passes = []
    for _pass in range(iterations):
        try:
            resampled = resample.warp(moving, estimate, reference.shape, transform,
                                      method=method, dst_nodata=np.nan)
        except ValueError as error:
            if "lands inside" not in str(error):
                raise
            resampled = np.full(reference.shape, np.nan)
        inside = np.isfinite(resampled)
        if not inside.any():
            raise GridError(_("the images do not overlap: the estimate puts no reference pixel "
                              "inside the moving image; give an initial estimate (map -> moving "
                              "image) that roughly aligns them"))
        with one_blas_thread():
            points, shifts, table = measure_shifts(
                reference, np.where(inside, resampled, 0.0), spacing, window, upsample, taper,
                valid=valid & inside, details=True)
        table["dcol"], table["drow"] = shifts[:, 0], shifts[:, 1]
        reason = table["skipped"].to_numpy(dtype=object)
        reason[(reason == "") & (table["contrast"] < min_contrast)] = "low contrast"
        reason[(reason == "") & (table["reliability"] < min_reliability)] = "weak peak"
        if not taper:
            reason[(reason == "") & (table["edge_share"] > max_edge_share)] = "smooth"
        map_xy = to_map(transform, points)
        image_xy = np.full(points.shape, np.nan)
        good = reason == ""
        if good.any():
            image_xy[good] = apply_model(estimate, to_map(transform, points[good] - shifts[good]))
        if good.sum() >= needed:
            model, inliers = robust_fit(map_xy[good], image_xy[good], kind, order, tolerance,
                                        seed=seed)
            outliers = np.flatnonzero(good)[~inliers]
            reason[outliers] = "outlier"
            good = reason == ""
        passes.append({"reliable": int(good.sum()),
                       "median shift (px)": float(np.median(np.hypot(*shifts[good].T)))
                       if good.any() else np.nan})
        if good.sum() < needed:
            counts = ", ".join(f"{n} {r}" for r, n in zip(*np.unique(
                reason[reason != ""].astype(str), return_counts=True)))
            hint = (_("smooth windows pull phase correlation towards zero shift; use "
                      "taper=True") if (reason == "smooth").any() else
                    _("use smaller spacing, larger windows or a better initial estimate"))
            raise GCPError((_("{good} reliable tie points of {total} windows ({counts}); an "
                              "order-{order} polynomial needs at least {needed}: {hint}")
                            if kind == "polynomial" else
                            _("{good} reliable tie points of {total} windows ({counts}); a "
                              "{kind!r} model needs at least {needed}: {hint}")).format(
                good=good.sum(), total=len(points), counts=counts or _("none rejected"),
                order=order, kind=kind, needed=needed, hint=hint))
        estimate = transforms.fit_transform(map_xy[good], image_xy[good], kind, order)
        if passes[-1]["median shift (px)"] < 0.5 / upsample:
            break
    table["reason"] = reason
    image_xy[~good] = np.nan_to_num(image_xy[~good], nan=-1.0)
    return gcp.GCPSet(map_xy, image_xy, enabled=good,
                      ids=[f"W{k + 1:02d}" for k in range(len(points))],
                      notes=[r or "reliable" for r in reason], reliability=table, passes=passes)


def _keypoints(image, detector, n_keypoints, seed):
    from skimage.feature import ORB, SIFT

    scaled = (image - image.min()) / ((image.max() - image.min()) or 1.0)
    if detector == "sift":
        extractor = SIFT()
    else:
        extractor = ORB(n_keypoints=n_keypoints, fast_threshold=0.05)
    extractor.detect_and_extract(scaled)
    # scikit-image's (row, col) has pixel centres at whole numbers; GDAL's at halves
    return extractor.keypoints[:, ::-1] + 0.5, extractor.descriptors


def feature_tiepoints(reference, moving, detector="sift", reference_transform=None,
                      kind="polynomial", order=1, threshold=1.0, max_ratio=0.8, n_keypoints=2000,
                      max_trials=2000, seed=0):
    """Tie points from keypoints: detect, match descriptors, keep the RANSAC inliers.

    Keypoints and descriptors by scikit-image's ``SIFT`` (Lowe 2004; scale-
    and rotation-invariant) or ``ORB`` (Rublee et al. 2011; binary, fast);
    matches by ``match_descriptors`` (mutual nearest neighbours with Lowe's
    ratio test); then ``skimage.measure.ransac`` with an rsgeo model
    (:func:`ransac_model`) from the reference's map coordinates to the moving
    image. No initial estimate is needed.

    Parameters
    ----------
    reference, moving : (rows, cols) array_like
        The two images (any sizes and pixel sizes).
    detector : {"sift", "orb"}
    reference_transform : affine.Affine, optional
        Reference pixel -> map; by default the reference's pixel coordinates.
    kind, order
        The model RANSAC fits (:func:`rsgeo.transforms.fit_transform`).
    threshold : float
        RANSAC's inlier threshold, moving-image pixels.
    max_ratio : float
        Lowe's ratio test: a match is kept if its distance is under this
        fraction of the second best's.
    n_keypoints : int
        Keypoints ORB keeps (SIFT keeps all it finds).
    max_trials : int
        RANSAC's random samples.
    seed : int
        Seed of RANSAC's sampling.

    Returns
    -------
    GCPSet
        The inliers: map (x, y) of the reference keypoint, (col, row) of the
        moving one. Extra attributes: ``n_keypoints`` (reference, moving),
        ``n_matches`` (before RANSAC) and ``candidates`` (every match, as a
        GCPSet whose ``enabled`` flags the inliers).

    Raises
    ------
    ValueError
        If an image is not 2-D or is constant (no keypoint), the detector is
        unknown, or fewer matches than the model needs survive (the message
        says how many keypoints and matches were found).
    """
    from skimage.feature import match_descriptors

    check_choice(detector, "detector", DETECTORS)
    images = []
    for name, image in (("reference", reference), ("moving", moving)):
        image = as_image(image, name).astype(np.float64)
        if image.ndim != 2:
            raise ImageError(_("{name} must be one band (2-D), got shape {image_shape}").format(
                    name=name, image_shape=image.shape))
        if not np.isfinite(image).all() or image.std() == 0:
            raise ImageError(_("{name} is constant or holds NaN: no keypoint can be "
                               "found in it").format(name=name))
        images.append(image)
    as_number(max_ratio, "max_ratio", 0, 1, N_("a ratio of descriptor distances"))
    transform = _transform(reference_transform)
    found = []
    for image in images:
        try:
            found.append(_keypoints(image, detector, int(n_keypoints), seed))
        except RuntimeError:   # ORB: too few keypoints
            found.append((np.empty((0, 2)), np.empty((0, 32), bool)))
    (ref_xy, ref_desc), (mov_xy, mov_desc) = found
    needed = ransac_model(kind, order).min_samples
    if len(ref_xy) and len(mov_xy):
        matches = match_descriptors(ref_desc, mov_desc, cross_check=True, max_ratio=max_ratio)
    else:
        matches = np.empty((0, 2), int)
    if len(matches) < needed:
        raise GCPError(_("{upper} found {n_ref_xy} and {n_mov_xy} keypoints and "
                         "{n_matches} matches; the {kind} model needs at least "
                         "{needed}: the images may not overlap or may look too different").format(
                upper=detector.upper(), n_ref_xy=len(ref_xy), n_mov_xy=len(mov_xy),
                n_matches=len(matches), kind=kind, needed=needed))
    map_xy = to_map(transform, ref_xy[matches[:, 0]])
    image_xy = mov_xy[matches[:, 1]]
    inliers = robust_fit(map_xy, image_xy, kind, order, threshold, max_trials, seed)[1]
    return gcp.GCPSet(map_xy[inliers], image_xy[inliers],
                      ids=[f"{detector.upper()}{k + 1:03d}" for k in range(int(inliers.sum()))],
                      n_keypoints=(len(ref_xy), len(mov_xy)), n_matches=len(matches),
                      candidates=gcp.GCPSet(map_xy, image_xy, enabled=inliers))
