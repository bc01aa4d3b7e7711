"""Band-to-band registration: how far each band of a multispectral image is shifted from a
reference band, by phase correlation of their gradients.
"""


import numpy as np

from ..errors import GCPError, ImageError
from ..language import _
from ..validation import as_image, as_integer, as_number, check_choice
from ._tiepoints import (
    MAX_EDGE_SHARE,
    MAX_UPSAMPLE,
    MIN_WINDOW,
    UPSAMPLE_NEEDED,
    measure_shifts,
    one_blas_thread,
)

__all__ = [
    "BAND_FEATURES", "band_misregistration",
]





#: What :func:`band_misregistration` correlates: each band's gradient magnitude, or the band.
BAND_FEATURES = ("gradient", "intensity")


def band_misregistration(bands, window=64, spacing=None, upsample=100, feature="gradient",
                         names=None, iterations=10, min_reliability=8.0,
                         max_edge_share=MAX_EDGE_SHARE, tolerance=0.5, valid=None,
                         details=False):
    """Sub-pixel misregistration between the bands of one multispectral image, pair by pair.

    For every pair of bands (reference = the earlier band, moving = the later
    one), correlation tie points on a grid of windows (:func:`measure_shifts`)
    give each window's shift; the windows' mean is the pair's misregistration,
    their standard deviation its spread over the scene, and the standard
    deviation over the square root of their number its standard error.

    Two choices make it precise to a few hundredths of a pixel, measured on
    bands with a known shift (``tests/test_tiepoints.py``):

    * ``feature="gradient"`` correlates each band's gradient magnitude (Sobel),
      not its brightness. A near-infrared band is bright over vegetation where
      a red band is dark, and bright or dark with it over soil: inside one
      window some edges are inverted and others not. scikit-image takes the
      magnitude of the correlation peak, which survives a window whose contrast
      is inverted everywhere, but the inverted and the kept edges of a mixed
      window pull the peak in opposite directions; an edge's gradient
      magnitude is the same whichever side is bright. The gradient also
      removes the smooth part of the scene, whose windows' cut edges pull
      phase correlation towards zero shift (:func:`~rsgeo.registration.edge_share`).
    * Iterations as :func:`~rsgeo.registration.correlation_tiepoints` does them, but for a
      translation only and with a Fourier shift: the moving band is moved back
      by the current estimate with the Fourier shift theorem (mirrored at its
      borders; exact only for a band-limited, periodic signal, so sharp edges
      ring a little), its feature recomputed and the windows correlated again, until
      the mean shift left is under half the sub-pixel step. On the test bands
      this recovers every pair's shift to better than 0.02 px; moving the band
      by cubic convolution instead (what :func:`~rsgeo.registration.correlation_tiepoints`
      resamples with) leaves errors of 0.03 to 0.04 px.

    Window shifts are quantised to 1 / ``upsample`` pixel, so a spread or a
    standard error under about that step means "smaller than the step".

    A window is not used when it is skipped by :func:`measure_shifts`
    ("constant", "invalid"), its correlation peak is weak ("weak peak", below
    ``min_reliability``), it is too smooth for phase correlation ("smooth",
    :func:`~rsgeo.registration.edge_share` over ``max_edge_share``), or its shift is more than
    ``tolerance`` pixels from the median of the others in either direction
    ("outlier").

    Parameters
    ----------
    bands : (bands, rows, cols) array_like
        Two or more co-registered bands of one image, bands first.
    window : int
        Side of the correlation windows, pixels.
    spacing : int, optional
        Distance between window centres, pixels; by default ``window``, so that
        no two windows share a pixel and their errors are independent, which
        the standard error assumes (overlapping windows make it too small).
    upsample : int
        Sub-pixel step of each window's shift: 1 / upsample pixel; 1 to
        ``MAX_UPSAMPLE`` (1000).
    feature : {"gradient", "intensity"}
        What is correlated (see above).
    names : sequence of str, optional
        The bands' names in the table; by default "band 1", "band 2", ...
    iterations : int
        Passes at most per pair.
    min_reliability : float
        Smallest height of a window's correlation peak above the rest of the
        correlation surface, in its standard deviations.
    max_edge_share : float
        Largest :func:`~rsgeo.registration.edge_share` of a window pair, 0 to 1.
    tolerance : float
        Largest distance of a window's shift from the pair's median, pixels.
    valid : (rows, cols) array_like of bool, optional
        False where a pixel must not be used (saturated, cloud): a window with
        any such pixel is skipped.
    details : bool
        Also return every window of every pair.

    Returns
    -------
    table : pandas.DataFrame
        One row per pair, indexed "reference → moving": ``reference`` and
        ``moving`` (names), ``dx (px)`` and ``dy (px)`` (where a feature is in
        the moving band minus where it is in the reference, columns and rows;
        moving the moving band by (-dx, -dy) registers it), ``shift (px)``
        (their length), ``sd dx (px)``, ``sd dy (px)`` (spread over the
        windows), ``se dx (px)``, ``se dy (px)`` (standard errors of the
        means), ``tie points`` (windows used), ``windows`` (windows on the grid)
        and ``passes`` (``iterations`` when the shift left never fell under half
        a step).
    windows : pandas.DataFrame
        Only with ``details=True``, one row per window and pair: ``pair``,
        ``col``, ``row`` (window centre), ``dx (px)``, ``dy (px)`` (its shift
        after the last pass; NaN where it was skipped), ``reliability``,
        ``edge_share`` and ``reason`` ("reliable" or why it was not used).

    Raises
    ------
    ValueError
        If ``bands`` is not 3-D with at least two bands or holds NaN, the
        window is not a whole number from ``MIN_WINDOW`` to the bands'
        smaller side, a count or threshold is out of its range, ``names`` or
        ``valid`` does not fit the bands, the feature is unknown, or fewer
        than two windows of a pair are usable (the message counts each
        reason).
    TypeError
        If a number is not a number.

    Notes
    -----
    The standard error covers the windows' random errors only. Bands whose
    content differs (a near-infrared band against a visible one) are measured
    with a systematic error it does not show. Three bands a, b, c give a check
    that needs no truth: (a → b) + (b → c) - (a → c) is zero for any true
    offsets, so what it measures is error; on the CBERS-2B CCD of chapter 6c it
    is 0.3 px where the standard errors are hundredths of a pixel.

    References
    ----------
    Guizar-Sicairos, M., Thurman, S. T. and Fienup, J. R. (2008),
    "Efficient subpixel image registration algorithms", Optics Letters 33(2).

    Scheffler, D., Hollstein, A., Diedrich, H., Segl, K. and Hostert, P.
    (2017), "AROSICS: an automated and robust open-source image
    co-registration software for multi-sensor satellite data", Remote Sensing
    9(7), 676.

    Examples
    --------
    >>> from scipy.ndimage import fourier_shift, gaussian_filter
    >>> rng = np.random.default_rng(0)
    >>> scene = gaussian_filter(rng.normal(size=(128, 128)), 2, mode="wrap")
    >>> moved = np.fft.ifft2(fourier_shift(np.fft.fft2(scene), (0.3, -0.4))).real  # (rows, cols)
    >>> table = band_misregistration([scene, -moved], names=["red", "nir"])   # inverted
    >>> table.index.tolist(), table[["dx (px)", "dy (px)"]].round(1).values.tolist()
    (['red → nir'], [[-0.4, 0.3]])
    """
    import pandas as pd

    bands = as_image(bands, "bands")
    if bands.ndim != 3 or bands.shape[0] < 2:
        raise ImageError(_("bands must be 3-D (bands, rows, cols) with at least two bands, got "
                           "shape {shape}").format(shape=bands.shape))
    bands = bands.astype(np.float64)
    if not np.isfinite(bands).all():
        raise ImageError(_("bands hold NaN or infinite values; fill them and mark them with "
                           "valid=False"))
    check_choice(feature, "feature", BAND_FEATURES)
    window = as_integer(window, "window", MIN_WINDOW, min(bands.shape[1:]),
                        _("a correlation window of at least {n} × {n} pixels that fits the "
                          "bands").format(n=MIN_WINDOW))
    spacing = window if spacing is None else as_integer(spacing, "spacing", 1, None,
                                                        _("a whole number of pixels"))
    upsample = as_integer(upsample, "upsample", 1, MAX_UPSAMPLE, UPSAMPLE_NEEDED)
    iterations = as_integer(iterations, "iterations", 1, None, _("a number of passes"))
    min_reliability = as_number(min_reliability, "min_reliability", 0, None,
                                _("a peak height in standard deviations; 0 keeps every window"))
    max_edge_share = as_number(max_edge_share, "max_edge_share", 0, 1,
                               _("a share of the window's frequencies"))
    tolerance = as_number(tolerance, "tolerance", 0, None, _("an outlier threshold in pixels"))
    if tolerance == 0:
        raise GCPError(_("tolerance must be more than 0 pixels (the largest distance of a "
                         "window's shift from the median), got 0"))
    if names is None:
        names = [f"band {k + 1}" for k in range(bands.shape[0])]
    names = [str(name) for name in names]
    if len(names) != bands.shape[0]:
        raise ImageError(_("names must give one name per band ({n}), got {m}").format(
            n=bands.shape[0], m=len(names)))
    if valid is not None:
        valid = np.asarray(valid)
        if valid.shape != bands.shape[1:] or valid.dtype != bool:
            raise ImageError(_("valid must be a boolean mask of the bands' shape {shape}, got "
                               "{dtype} of shape {got}").format(
                shape=bands.shape[1:], dtype=valid.dtype, got=valid.shape))
    features = [_band_feature(band, feature) for band in bands]
    rows, tables = [], []
    for i in range(len(bands)):
        for j in range(i + 1, len(bands)):
            label = f"{names[i]} → {names[j]}"
            offsets, reason, table, passes = _pair_offsets(
                features[i], bands[j], feature, window, spacing, upsample, iterations,
                min_reliability, max_edge_share, tolerance, valid, label)
            used = offsets[reason == ""]
            mean, sd = used.mean(axis=0), used.std(axis=0, ddof=1)
            rows.append({"pair": label, "reference": names[i], "moving": names[j],
                         "dx (px)": mean[0], "dy (px)": mean[1],
                         "shift (px)": float(np.hypot(*mean)),
                         "sd dx (px)": sd[0], "sd dy (px)": sd[1],
                         "se dx (px)": sd[0] / np.sqrt(len(used)),
                         "se dy (px)": sd[1] / np.sqrt(len(used)),
                         "tie points": len(used), "windows": len(offsets), "passes": passes})
            if details:
                table.insert(0, "pair", label)
                table["dx (px)"], table["dy (px)"] = offsets[:, 0], offsets[:, 1]
                table["reason"] = np.where(reason == "", "reliable", reason)
                tables.append(table)
    result = pd.DataFrame(rows).set_index("pair")
    if not details:
        return result
    return result, pd.concat(tables, ignore_index=True)


def _band_feature(band, feature):
    """What :func:`band_misregistration` correlates of one band."""
    if feature == "intensity":
        return band
    from scipy.ndimage import sobel

    return np.hypot(sobel(band, axis=0), sobel(band, axis=1))


def _fourier_shift(image, dx, dy, pad):
    """``image`` with its content moved by (dx, dy) pixels (the value at (c, r) is the input's at
    (c - dx, r - dy)), by the Fourier shift theorem on the image mirrored ``pad`` pixels beyond
    each border, so that its borders do not wrap around."""
    from scipy import fft
    from scipy.ndimage import fourier_shift

    # mirrored up to a size the FFT factors well (a prime side is several times slower)
    sizes = [fft.next_fast_len(n + 2 * pad, real=True) for n in image.shape]
    padded = np.pad(image, [(pad, size - n - pad) for size, n in zip(sizes, image.shape)],
                    mode="symmetric")
    moved = fft.ifft2(fourier_shift(fft.fft2(padded, workers=1), (dy, dx)), workers=1).real
    return moved[pad:pad + image.shape[0], pad:pad + image.shape[1]]


def _pair_offsets(reference, moving_band, feature, window, spacing, upsample, iterations,
                  min_reliability, max_edge_share, tolerance, valid, label):
    """Per-window offsets (moving minus reference, pixels) of one band pair, iterated until the
    mean shift left is under half the sub-pixel step; with why each unused window is unused."""
    estimate = np.zeros(2)
    for passes in range(1, iterations + 1):
        moved = (moving_band if passes == 1
                 else _fourier_shift(moving_band, -estimate[0], -estimate[1], window))
        with one_blas_thread():
            points, shifts, table = measure_shifts(
                reference, _band_feature(moved, feature), spacing, window, upsample,
                valid=valid, details=True)
        left = -shifts        # where a feature is in the moved band minus in the reference
        reason = table["skipped"].to_numpy(dtype=object)
        reason[(reason == "") & (table["reliability"] < min_reliability)] = "weak peak"
        reason[(reason == "") & (table["edge_share"] > max_edge_share)] = "smooth"
        usable = reason == ""
        if usable.sum() >= 2:
            median = np.median(left[usable], axis=0)
            far = np.zeros(len(left), bool)
            far[usable] = (np.abs(left[usable] - median) > tolerance).any(axis=1)
            reason[far] = "outlier"
            usable = reason == ""
        if usable.sum() < 2:
            found, counts = np.unique(reason[reason != ""].astype(str), return_counts=True)
            raise GCPError(_("{pair}: {good} usable windows of {total} ({counts}); the mean "
                             "shift needs at least 2: use smaller windows or spacing, or "
                             "lower min_reliability").format(
                pair=label, good=int(usable.sum()), total=len(left),
                counts=", ".join(f"{n} {r}" for r, n in zip(found, counts))))
        offsets = estimate + left
        step = left[usable].mean(axis=0)
        estimate = estimate + step
        if np.abs(step).max() < 0.5 / upsample:
            break
    table = table.drop(columns=["peak", "error", "contrast", "skipped"])
    table.insert(0, "col", points[:, 0])
    table.insert(1, "row", points[:, 1])
    return offsets, reason, table, passes
