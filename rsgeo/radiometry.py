"""Contrast matching of overlapping images by linear regression (the regression paper, chapter 5).

The paper's recipe: regress photo B (Y) on photo A (X) over their common
area; the raw correlation is low (r = 0.4495) because noise and slight
misregistration scatter the pixels, so low-pass both with a mean filter first
(r = 0.8037, Y = 0.885 X + 27.107); apply that gain and offset to the
*original* A (IDRISI's SCALAR), truncate to integers, and the seam of the
mosaic disappears.

How well it disappears is measured by :func:`seam_metrics` over the whole
common ground (the brightness step is the difference of the means, the
contrast mismatch the difference of the spreads), not by the step across one
seam, which the noise of a few columns dominates. With noise in X, the OLS
gain is diluted (too small) even after the paper's 3 × 3 filter: the mean is
matched but the corrected image has less contrast than the reference; the
reduced major axis (``method="rma"``) is not diluted. Truncating instead of
rounding lowers the mean by about 0.5 DN.
"""

from dataclasses import dataclass

import numpy as np

from .errors import CRSError, GridError, ImageError, RsgeoError
from .language import _
from .resample import interpolate
from .validation import as_integer, as_number, check_choice

__all__ = [
    "FIT_METHODS", "GainOffsetFit", "mean_filter", "fit_gain_offset", "apply_gain_offset",
    "minmax_stretch", "match_histograms", "overlap", "concatenate_halves", "seam_step",
    "seam_metrics",
]

FIT_METHODS = ("ols", "rma", "orthogonal", "theil_sen")


@dataclass
class GainOffsetFit:
    """Result of :func:`fit_gain_offset`: Y ≈ gain·X + offset.

    Attributes
    ----------
    gain, offset : float
    r : float
        Pearson's correlation between X and Y (of the filtered images when smoothed).
    r2 : float
    residual_std : float
        Standard deviation of Y − (gain·X + offset), in DN.
    n : int
        Number of pixel pairs used.
    method : str
    """

    gain: float
    offset: float
    r: float
    r2: float
    residual_std: float
    n: int
    method: str = "ols"

    def predict(self, x):
        """gain·x + offset, as floats.

        Parameters
        ----------
        x : array_like
            DN of the image the fit corrects.

        Returns
        -------
        ndarray of float64

        Raises
        ------
        ValueError
            If ``x`` is not numbers.
        """
        try:
            values = np.asarray(x, dtype=np.float64)
        except (TypeError, ValueError):
            raise ImageError(_("x must be numbers (DN of the image to correct), got "
                               "{x!r}").format(x=x)) from None
        return self.gain * values + self.offset


def _pair(x_image, y_image):
    x = np.asarray(x_image)
    y = np.asarray(y_image)
    for name, values in (("x_image", x), ("y_image", y)):
        # bool is refused as every image check of rsgeo does: a regression of a mask is a slip
        if values.dtype.kind not in "uif":
            raise TypeError(_("{name} must hold real numbers (integers or floats), got dtype "
                              "{dtype}; for a complex image regress its real part, imaginary "
                              "part or modulus (np.abs); a bool array is a mask: regress the "
                              "pixels it keeps, e.g. x_image[mask]").format(
                                  name=name, dtype=values.dtype))
    if x.shape != y.shape:
        raise ImageError(_("x_image and y_image must cover the same pixels (same "
                           "shape), got {x_shape} and {y_shape}; cut both to their "
                           "overlap first").format(x_shape=x.shape, y_shape=y.shape))
    if x.size < 3:
        raise ImageError(_("a regression needs at least 3 pixel pairs, got {x_size}").format(
                x_size=x.size))
    x, y = x.astype(np.float64), y.astype(np.float64)
    for name, values in (("x_image", x), ("y_image", y)):
        bad = int(np.count_nonzero(~np.isfinite(values)))
        if bad:
            raise ImageError(
                _("{name} holds {bad} NaN or infinite value(s) of {values_size}: every "
                  "pixel pair must be finite. Mask them first, e.g. keep = "
                  "np.isfinite(x_image) & np.isfinite(y_image), then fit x_image[keep], "
                  "y_image[keep] (without smooth, which needs a full grid), or fill the "
                  "gaps before filtering").format(name=name, bad=bad, values_size=values.size))
    return x, y


def mean_filter(image, size=3):
    """The paper's low-pass filter: the mean of a size × size window (edges replicate).

    Parameters
    ----------
    image : array_like
        2-D image.
    size : int
        Odd window size.

    Returns
    -------
    ndarray of float64
        Same shape.

    Raises
    ------
    ValueError
        If ``size`` is not an odd positive whole number.
    """
    from scipy.ndimage import uniform_filter

    size = as_integer(size, "size", 1, None, _("an odd window size: 3, 5, 7 ..."))
    if size % 2 == 0:
        raise RsgeoError(_("filter size must be an odd positive integer (3, 5, 7 ...), "
                           "got {size!r}").format(size=size))
    return uniform_filter(np.asarray(image, dtype=np.float64), size=int(size), mode="nearest")


def fit_gain_offset(x_image, y_image, smooth=None, method="ols"):
    """Fit Y = gain·X + offset between co-registered images (chapter 5's paper, IDRISI REGRESS).

    Parameters
    ----------
    x_image, y_image : ndarray
        The independent (X, the image to correct) and dependent (Y, the
        reference) images over the same ground, same shape.
    smooth : int, optional
        Size of the mean filter applied to both before fitting (the paper used
        a low-pass mean filter); None fits the raw pixels. Only for one band
        (2-D images): a band stack is refused, since a 2-D filter would not
        run along a band and a 3-D one would mix bands.
    method : {"ols", "rma", "orthogonal", "theil_sen"}
        "ols" is ordinary least squares as in the paper; it assumes X has no
        noise, and noise in X biases its gain towards zero. "rma" (reduced
        major axis, gain = sign(r)·σy/σx) and "orthogonal" (total least
        squares) treat X and Y alike; "theil_sen" is the median of pairwise
        slopes, robust to outliers (on a fixed sample of 2000 pixels).

    Returns
    -------
    GainOffsetFit

    Raises
    ------
    ValueError
        If the shapes differ, there are fewer than 3 pixels, either image holds
        NaN or infinite values (mask them first: the message says how),
        either image is constant or the two do not vary together (no
        regression possible), their spread overflows float64, or ``smooth``
        is given with a band stack (3-D: fit each band separately).
    TypeError
        If either image holds complex, bool (a mask) or non-numeric values.

    Examples
    --------
    >>> x = np.arange(100.0).reshape(10, 10)
    >>> fit = fit_gain_offset(x, 0.885 * x + 27.107)
    >>> round(fit.gain, 3), round(fit.offset, 3), round(fit.r, 3)
    (0.885, 27.107, 1.0)
    >>> fit_gain_offset(np.where(x == 5, np.nan, x), x)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rsgeo.errors.ImageError: x_image holds 1 NaN or infinite value(s) of 100: ... before filtering
    """
    check_choice(method, "method", FIT_METHODS)
    x, y = _pair(x_image, y_image)
    if smooth is not None:
        if x.ndim != 2:
            raise ImageError(_("smooth filters one band (a 2-D image), got shape {shape}; fit "
                               "each band separately (fit_gain_offset(x_image[b], y_image[b], "
                               "smooth=...)), or pass smooth=None").format(shape=x.shape))
        smooth = as_integer(smooth, "smooth", 1, None, _("an odd window size: 3, 5, 7 ..."))
        x, y = mean_filter(x, smooth), mean_filter(y, smooth)
    x, y = x.ravel(), y.ravel()
    # centred in float64 (the images are float64 from _pair): no integer wrap, no overflow
    with np.errstate(over="ignore"):
        sx, sy = x.std(), y.std()
    for name, spread in (("x_image", sx), ("y_image", sy)):
        if not np.isfinite(spread):
            raise ImageError(_("{name}'s values are too large to regress in float64 (their "
                               "spread overflows); scale both images down first").format(
                                   name=name))
        if spread == 0:
            raise ImageError(_("{name} is constant over the overlap: a constant image cannot "
                               "be regressed (no gain fits it); use an overlap where both "
                               "images vary").format(name=name))
    covariance = float(np.mean((x - x.mean()) * (y - y.mean())))
    if method != "theil_sen" and (covariance == 0 or not np.isfinite(covariance)):
        raise ImageError(_("x_image and y_image do not vary together (covariance {cov}): no "
                           "gain can be fitted; check that they cover the same ground").format(
                               cov=covariance))
    r = float(np.corrcoef(x, y)[0, 1])
    if method == "ols":
        gain = r * sy / sx
    elif method == "rma":
        gain = np.sign(r) * sy / sx
    elif method == "orthogonal":
        cov = np.cov(x, y)
        spread = cov[1, 1] - cov[0, 0]
        gain = (spread + np.sqrt(spread ** 2 + 4 * cov[0, 1] ** 2)) / (2 * cov[0, 1])
    else:
        from scipy.stats import theilslopes

        sample = np.random.default_rng(0).choice(x.size, size=min(2000, x.size), replace=False)
        gain = theilslopes(y[sample], x[sample])[0]
    offset = (float(y.mean() - gain * x.mean()) if method != "theil_sen"
              else float(np.median(y - gain * x)))
    residual = y - (gain * x + offset)
    return GainOffsetFit(float(gain), offset, r, r * r, float(residual.std()), int(x.size), method)


def apply_gain_offset(image, gain, offset, rounding="truncate"):
    """gain·image + offset, truncated to integers and clipped to the dtype (IDRISI SCALAR).

    Paper 000, step 5: the gain and offset fitted on the filtered images are
    applied to the original image, and the result is truncated to integers.
    Values beyond the dtype's range are clipped, never wrapped around.

    Truncation drops the fractional part, about 0.5 DN on average: the
    truncated image's mean is about 0.5 DN below gain·mean + offset.
    ``rounding="nearest"`` rounds as GDAL does, floor(v + 0.5), without that bias.

    Parameters
    ----------
    image : ndarray of an integer dtype
    gain, offset : float
    rounding : {"truncate", "nearest"}
        "truncate" (the paper's, IDRISI's and the default) or "nearest".

    Returns
    -------
    ndarray
        Same shape and dtype as ``image``.

    Raises
    ------
    TypeError
        If ``gain`` or ``offset`` is not a real number (a string, a bool, an array).
    ValueError
        If the image is not of an integer dtype, gain/offset are not finite,
        or ``rounding`` is unknown; if a 64-bit image holds values beyond
        +-2**53 (float64, in which the stretch is computed, cannot hold
        them exactly). Results beyond the dtype's range are clipped to it,
        exactly for 64-bit types too (2**62 * 4 in int64 is 2**63 - 1).

    Examples
    --------
    >>> apply_gain_offset(np.array([0, 100, 255], dtype=np.uint8), 0.885, 27.107)
    array([ 27, 115, 252], dtype=uint8)
    >>> apply_gain_offset(np.array([0, 100, 255], dtype=np.uint8), 0.885, 27.107, "nearest")
    array([ 27, 116, 253], dtype=uint8)
    >>> apply_gain_offset(np.array([250], dtype=np.uint8), 2.0, 0.0)
    array([255], dtype=uint8)
    """
    check_choice(rounding, "rounding", ("truncate", "nearest"))
    image = np.asarray(image)
    if image.dtype.kind not in "ui":
        raise ImageError(_("apply_gain_offset truncates to integers: the image must "
                           "have an integer dtype, got {image_dtype}").format(
                image_dtype=image.dtype))
    gain = as_number(gain, "gain")
    offset = as_number(offset, "offset")
    info = np.iinfo(image.dtype)
    if image.dtype.itemsize == 8 and image.size and (int(image.max()) > 2 ** 53
                                                     or int(image.min()) < -(2 ** 53)):
        raise ImageError(_(
            "image ({dtype}) holds values from {low} to {high}, beyond +-2**53: gain * image "
            "+ offset is computed in float64, whose integers stop being exact at 2**53, so "
            "their last bits would be lost; subtract an offset first so that the values "
            "fit").format(dtype=image.dtype, low=int(image.min()), high=int(image.max())))
    exact = gain * image.astype(np.float64) + offset
    stretched = np.trunc(exact) if rounding == "truncate" else np.floor(exact + 0.5)
    # clip in float64, then set the values above the top exactly: a 64-bit maximum has no
    # float64 (2**63 - 1 rounds up to 2**63, whose cast wraps around to -2**63)
    top = float(info.max)
    above = stretched >= top if int(top) > info.max else stretched > top
    result = np.clip(stretched, info.min, np.nextafter(top, 0) if int(top) > info.max
                     else top).astype(image.dtype)
    result[above] = info.max
    return result


def minmax_stretch(x_image, y_image):
    """Gain and offset of a plain linear stretch mapping X's min-max onto Y's min-max.

    The ordinary contrast stretch the paper criticises: it has no control of
    gain and offset beyond the two extremes, which a few odd pixels decide.

    Parameters
    ----------
    x_image, y_image : ndarray
        The image to stretch and the reference, same shape.

    Returns
    -------
    gain, offset : float

    Raises
    ------
    ValueError
        As :func:`fit_gain_offset`'s input checks, or if ``x_image`` is constant.
    """
    x, y = _pair(x_image, y_image)
    if x.max() == x.min():
        raise ImageError(_("x_image is constant: a min-max stretch is undefined"))
    gain = (y.max() - y.min()) / (x.max() - x.min())
    return float(gain), float(y.min() - gain * x.min())


def match_histograms(image, reference):
    """Histogram matching (scikit-image): the values remapped to the reference's distribution.

    Parameters
    ----------
    image : ndarray
        The image to change, 2-D or bands first, integer or float, finite.
    reference : ndarray
        The image whose histogram it should take (any shape).

    Returns
    -------
    ndarray
        Same shape and dtype as ``image``: integer images are rounded to the
        nearest integer and clipped to the dtype's range; float images keep
        the matched values.

    Raises
    ------
    ValueError
        If either image is not numeric, is empty, or holds NaN or infinity.

    References
    ----------
    Gonzalez, R. C. and Woods, R. E., *Digital Image Processing*,
    section "Histogram matching (specification)".

    Examples
    --------
    >>> reference = np.array([[10, 20], [30, 40]], dtype=np.uint8)
    >>> match_histograms(np.array([[0, 1], [2, 3]], dtype=np.uint8), reference)
    array([[10, 20],
           [30, 40]], dtype=uint8)
    >>> match_histograms(np.array([[0.0, 0.1], [0.2, 0.3]]), reference)
    array([[10., 20.],
           [30., 40.]])
    """
    from skimage.exposure import match_histograms as skimage_match

    arrays = []
    for name, values in (("image", image), ("reference", reference)):
        values = np.asarray(values)
        if values.dtype.kind not in "uif" or values.size == 0:
            raise ImageError(_("{name} must be a non-empty array of integers or floats, "
                               "got dtype {values_dtype} and shape {values_shape}").format(
                    name=name, values_dtype=values.dtype, values_shape=values.shape))
        if not np.isfinite(values).all():
            raise ImageError(_("{name} holds NaN or infinite values; mask or fill them "
                               "before matching histograms").format(name=name))
        arrays.append(values)
    image, reference = arrays
    # scikit-image's fast path for unsigned images needs an unsigned reference too
    source = image if reference.dtype.kind == "u" else image.astype(np.float64)
    matched = skimage_match(source, reference)
    if image.dtype.kind == "f":
        return matched.astype(image.dtype)
    info = np.iinfo(image.dtype)
    return np.clip(np.round(matched), info.min, info.max).astype(image.dtype)


def overlap(raster_a, raster_b):
    """The common ground of two georeferenced rasters, as two arrays on A's grid.

    B is sampled at the centres of A's pixels (nearest neighbour: where the
    grids are aligned it is an exact cut; where they are offset, the shift is
    under half a pixel).

    Parameters
    ----------
    raster_a, raster_b : rsgeo.data.Raster
        Single-band rasters in the same CRS, north-up.

    Returns
    -------
    a_part, b_part : ndarray
        Same shape, same ground.
    window : (row_start, row_stop, col_start, col_stop)
        The overlap's place in A.

    Raises
    ------
    ValueError
        If the CRSs differ or the rasters do not overlap.
    """
    if raster_a.crs != raster_b.crs:
        raise CRSError(_("the rasters are in different CRSs ({value} and {value2}); "
                         "pairing them pixel by pixel would mix two datums or "
                         "projections: reproject one first with "
                         "rsgeo.resample.reproject(raster, dst_crs)").format(
                value=raster_a.crs or 'no CRS', value2=raster_b.crs or 'no CRS'))
    west_a, south_a, east_a, north_a = raster_a.bounds
    west_b, south_b, east_b, north_b = raster_b.bounds
    west, east = max(west_a, west_b), min(east_a, east_b)
    south, north = max(south_a, south_b), min(north_a, north_b)
    inverse_a = ~raster_a.transform
    col_start, row_start = inverse_a @ (west, north)
    col_stop, row_stop = inverse_a @ (east, south)
    col_start, row_start = int(np.ceil(col_start - 1e-6)), int(np.ceil(row_start - 1e-6))
    col_stop, row_stop = int(np.floor(col_stop + 1e-6)), int(np.floor(row_stop + 1e-6))
    if col_stop - col_start < 1 or row_stop - row_start < 1:
        raise GridError(_("the rasters {value} and {value2} do not overlap on the ground").format(
                value=raster_a.name or 'A', value2=raster_b.name or 'B'))
    a_part = raster_a.array[row_start:row_stop, col_start:col_stop]
    rows, cols = np.mgrid[row_start:row_stop, col_start:col_stop] + 0.5
    x, y = raster_a.transform @ (cols, rows)
    b_cols, b_rows = ~raster_b.transform @ (x, y)
    b_part = interpolate(raster_b.array, b_cols, b_rows, "nearest")
    return a_part, b_part, (row_start, row_stop, col_start, col_stop)


def concatenate_halves(left_image, right_image, split=None):
    """The paper's test mosaic: the left part of one image beside the right part of the other.

    Both images cover the same ground; columns before ``split`` (default: the
    middle) come from ``left_image``, the rest from ``right_image``.

    Parameters
    ----------
    left_image, right_image : ndarray
        Same shape, same ground.
    split : int, optional
        First column taken from ``right_image``.

    Returns
    -------
    mosaic : ndarray
        Same shape as the inputs.
    split : int
        The column of the seam.

    Raises
    ------
    ValueError
        If the shapes differ or ``split`` is outside 1 to (columns - 1).
    """
    left_image, right_image = np.asarray(left_image), np.asarray(right_image)
    if left_image.shape != right_image.shape:
        raise ImageError(_("both images must cover the same ground (same shape), got "
                           "{left_image_shape} and {right_image_shape}").format(
                left_image_shape=left_image.shape, right_image_shape=right_image.shape))
    split = left_image.shape[-1] // 2 if split is None else int(split)
    if not 1 <= split <= left_image.shape[-1] - 1:
        raise RsgeoError(_("split must leave at least one column on each side (1 to "
                           "{value}), got {split}").format(
                value=left_image.shape[-1] - 1, split=split))
    return np.concatenate([left_image[..., :split], right_image[..., split:]], axis=-1), split


def seam_step(mosaic, split, width=3):
    """Brightness step across a vertical seam: ``|mean of width columns right − left|``, in DN.

    Over ground that continues across the seam, a step means the two halves
    have different contrast; after a good correction it is near the natural
    variation between neighbouring columns. On one noisy seam that variation
    dominates (a few hundred pixels per side): prefer :func:`seam_metrics`,
    which compares the two images over their whole common ground.

    Parameters
    ----------
    mosaic : array_like
        The mosaic, 2-D or bands first.
    split : int
        The seam's column.
    width : int
        Columns averaged on each side.

    Returns
    -------
    float
        DN, ≥ 0.

    Raises
    ------
    ValueError
        If the seam leaves fewer than ``width`` columns on one side.
    """
    mosaic = np.asarray(mosaic, dtype=np.float64)
    if not width <= split <= mosaic.shape[-1] - width:
        raise RsgeoError(_("split {split} leaves fewer than {width} columns on one side").format(
                split=split, width=width))
    right, left = mosaic[..., split:split + width], mosaic[..., split - width:split]
    return float(abs(right.mean() - left.mean()))


def seam_metrics(corrected, reference):
    """How alike the two sides of a seam are: means and spreads over the common ground.

    Both images cover the same ground (the overlap), so every difference is
    radiometric. Over all the overlap's pixels the noise averages out, which
    the step across a single seam (:func:`seam_step`) does not.

    Parameters
    ----------
    corrected, reference : ndarray
        The (corrected) image and the reference, same shape, finite.

    Returns
    -------
    dict
        ``mean_difference`` (DN): mean(corrected) − mean(reference), the
        brightness step a seam shows (negative: the corrected side is darker).
        ``std_difference`` (DN): std(corrected) − std(reference), the contrast
        mismatch (positive: the corrected side has more contrast; negative:
        less, e.g. after a gain shrunk by noise in X).
        ``std_ratio`` (×): std(corrected) / std(reference), 1 when the
        contrasts match.
        ``histogram_distance`` (DN): the Wasserstein, or earth mover's,
        distance between the two value distributions (0: same histogram).

    Raises
    ------
    ValueError
        If the shapes differ, an image holds NaN, or the reference is constant.

    Examples
    --------
    >>> reference = np.arange(100.0).reshape(10, 10)
    >>> metrics = seam_metrics(2 * reference + 3, reference)
    >>> round(metrics["mean_difference"], 2), round(metrics["std_ratio"], 2)
    (52.5, 2.0)
    """
    from scipy.stats import wasserstein_distance

    a, b = _pair(corrected, reference)
    if b.std() == 0:
        raise ImageError(_("reference is constant: its spread is 0 and no contrast ratio exists"))
    return {"mean_difference": float(a.mean() - b.mean()),
            "std_difference": float(a.std() - b.std()),
            "std_ratio": float(a.std() / b.std()),
            "histogram_distance": float(wasserstein_distance(a.ravel(), b.ravel()))}
