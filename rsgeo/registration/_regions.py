"""Forest segments and their relational mesh, from an image (the GA paper, steps 2-3).

The GA paper: *Homologous regions by genetic algorithms for the registration of
multi-sensor images* (see the book's bibliography and chapter 6).

The paper segmented and classified its images in eCognition and kept only the
forest segments. This module does the same with a short, documented
scikit-image pipeline: smooth, threshold the vegetation signal, clean up with
morphology, label connected components; then each segment's centroid and
area, and an optional grouping of contiguous segments into a few regions
(the paper grouped into 5 or 8).
"""

from dataclasses import dataclass

import numpy as np

from ..errors import GridError, ImageError, RsgeoError
from ..language import _, prose_number
from ..validation import as_image

__all__ = [
    "Segments", "centroids_and_areas", "forest_segments", "group_segments", "keep_largest",
    "ndvi",
]


@dataclass
class Segments:
    """Labelled segments and their measurements.

    Attributes
    ----------
    labels : ndarray of int
        0 = background, 1..n = segments, same shape as the image.
    centroids : ndarray, shape (n, 2)
        (col, row) of each segment's centroid, GDAL's continuous pixel coordinates.
    areas : ndarray, shape (n,)
        Pixels in each segment.
    """

    labels: np.ndarray
    centroids: np.ndarray
    areas: np.ndarray

    def __len__(self):
        return len(self.areas)

    def map_centroids(self, transform):
        """Centroids in map coordinates through a geotransform (affine.Affine).

        Parameters
        ----------
        transform : affine.Affine
            Pixel (col, row) -> map (x, y).

        Returns
        -------
        ndarray, shape (n, 2)
            Map (x, y) of each centroid.

        Raises
        ------
        ValueError
            If ``transform`` is not an affine.Affine.
        """
        if not all(hasattr(transform, key) for key in "abcdef"):
            raise GridError(_("transform must be an affine.Affine geotransform (pixel "
                              "-> map), got {kind}").format(kind=type(transform).__name__))
        x, y = transform @ (self.centroids[:, 0], self.centroids[:, 1])
        return np.column_stack([x, y])


def centroids_and_areas(labels):
    """Centroid and area of every labelled segment 1..n of a label image.

    A centroid is the mean of the segment's pixel centres in GDAL's continuous
    (col, row) coordinates (the centre of ``labels[r, c]`` is (c + 0.5, r + 0.5)).

    Parameters
    ----------
    labels : ndarray of int
        0 = background, 1..n = segments, every label present.

    Returns
    -------
    centroids : ndarray, shape (n, 2)
        (col, row) of each segment's centroid.
    areas : ndarray, shape (n,)
        Pixels in each segment.

    Raises
    ------
    ValueError
        If the labels are not integers, are negative, or skip a number.

    Examples
    --------
    >>> centroids, areas = centroids_and_areas(np.array([[1, 1, 0], [0, 0, 2]]))
    >>> centroids.tolist(), areas.tolist()
    ([[1.0, 0.5], [2.5, 1.5]], [2.0, 1.0])
    """
    labels = np.asarray(labels)
    if labels.dtype.kind not in "ui" or labels.size == 0 or labels.min() < 0:
        raise ImageError(_("labels must be a non-empty image of non-negative integers "
                           "(0 = background, 1..n = segments), got dtype {labels_dtype} "
                           "and shape {labels_shape}").format(
                labels_dtype=labels.dtype, labels_shape=labels.shape))
    count = int(labels.max())
    rows, cols = np.indices(labels.shape)
    flat = labels.ravel()
    areas = np.bincount(flat, minlength=count + 1)[1:].astype(np.float64)
    if (areas == 0).any():
        raise ImageError(_("labels must be consecutive 1..n with every label present"))
    sum_cols = np.bincount(flat, weights=cols.ravel() + 0.5, minlength=count + 1)[1:]
    sum_rows = np.bincount(flat, weights=rows.ravel() + 0.5, minlength=count + 1)[1:]
    return np.column_stack([sum_cols / areas, sum_rows / areas]), areas


def forest_segments(image, threshold=None, min_area=30, smooth_sigma=1.0, opening_radius=1):
    """Segments of the bright class of a vegetation image (forest), as the paper's step 2.

    Pipeline: Gaussian smoothing (sigma ``smooth_sigma`` pixels) to calm the
    texture; a threshold (Otsu's when None) keeping the pixels above it; a
    morphological opening with a disk of ``opening_radius`` to cut thin links
    and specks; removal of segments under ``min_area`` pixels; connected
    components (8-connectivity) numbered 1..n.

    Parameters
    ----------
    image : ndarray, 2-D
        A band where forest is brighter than everything else (e.g. a
        vegetation index, or the near infrared of a dry-season scene).
    threshold : float, optional
    min_area : int
    smooth_sigma : float
    opening_radius : int

    Returns
    -------
    Segments

    Raises
    ------
    ValueError
        If the image is not 2-D or no segment survives.
    """
    from scipy import ndimage
    from skimage.filters import threshold_otsu
    from skimage.morphology import disk

    image = as_image(image)
    if image.ndim != 2:
        raise ImageError(_("forest_segments needs one band (2-D), got shape "
                           "{image_shape}").format(image_shape=image.shape))
    smooth = (ndimage.gaussian_filter(image.astype(np.float64), smooth_sigma) if smooth_sigma
              else image)
    if threshold is None:
        threshold = threshold_otsu(smooth)
    mask = smooth > threshold
    if opening_radius:
        mask = ndimage.binary_opening(mask, structure=disk(opening_radius))
    labels, count = ndimage.label(mask, structure=np.ones((3, 3)))
    sizes = np.bincount(labels.ravel(), minlength=count + 1)
    keep = sizes >= min_area
    keep[0] = False
    relabel = np.zeros(count + 1, dtype=np.int32)
    relabel[keep] = np.arange(1, keep.sum() + 1)
    labels = relabel[labels]
    if labels.max() == 0:
        raise RsgeoError(_("no forest segment of at least {min_area} pixels above "
                           "threshold {threshold:.3g}").format(
                min_area=min_area, threshold=prose_number(threshold)))
    centroids, areas = centroids_and_areas(labels)
    return Segments(labels, centroids, areas)


def group_segments(segments, n_groups):
    """Merge neighbouring segments into ``n_groups`` regions (the paper's 5 or 8).

    Ward clustering of the centroids (area-weighted by repetition is not
    needed: nearby segments merge first), then each region's centroid is the
    area-weighted mean of its members' and its area their sum.

    Parameters
    ----------
    segments : Segments
    n_groups : int
        Regions wanted, 1 to ``len(segments)``.

    Returns
    -------
    Segments
        Labels 1..n_groups over the same image.

    Raises
    ------
    ValueError
        If ``n_groups`` is outside 1 to ``len(segments)``.

    References
    ----------
    Ward, J. H. (1963), "Hierarchical grouping to optimize an objective
    function", Journal of the American Statistical Association 58, 236-244.
    """
    from scipy.cluster.hierarchy import fcluster, linkage

    if not 1 <= n_groups <= len(segments):
        raise RsgeoError(_("n_groups must be between 1 and the number of segments "
                           "({n_segments}), got {n_groups}").format(
                n_segments=len(segments), n_groups=n_groups))
    if n_groups == len(segments):
        return segments
    groups = fcluster(linkage(segments.centroids, method="ward"), n_groups, criterion="maxclust")
    # number the regions by position (top to bottom) so labels are reproducible
    order = np.argsort([segments.centroids[groups == g, 1].mean() for g in range(1, n_groups + 1)])
    renumber = np.zeros(n_groups + 1, dtype=np.int32)
    renumber[order + 1] = np.arange(1, n_groups + 1)
    lookup = np.zeros(len(segments) + 1, dtype=np.int32)
    lookup[1:] = renumber[groups]
    labels = lookup[segments.labels]
    centroids, areas = centroids_and_areas(labels)
    return Segments(labels, centroids, areas)


def keep_largest(segments, count):
    """The ``count`` largest segments (centroids and areas; labels renumbered by size).

    Small segments are the least stable across dates, sensors and
    resolutions: keeping the largest is a simple alternative to grouping.

    Parameters
    ----------
    segments : Segments
    count : int
        Segments kept, 1 to ``len(segments)``.

    Returns
    -------
    Segments
        Largest first.

    Raises
    ------
    ValueError
        If ``count`` is outside 1 to ``len(segments)``.
    """
    if not 1 <= count <= len(segments):
        raise RsgeoError(_("count must be between 1 and the number of segments "
                           "({n_segments}), got {count}").format(
                n_segments=len(segments), count=count))
    order = np.argsort(-segments.areas, kind="stable")[:count]
    lookup = np.zeros(len(segments) + 1, dtype=np.int32)
    lookup[order + 1] = np.arange(1, count + 1)
    return Segments(lookup[segments.labels], segments.centroids[order], segments.areas[order])


def ndvi(red, nir):
    """Normalised difference vegetation index (NIR − red) / (NIR + red); 0 where both are 0.

    Parameters
    ----------
    red, nir : array_like
        Red and near-infrared bands, same shape.

    Returns
    -------
    ndarray of float64
        -1 to 1.

    Raises
    ------
    ValueError
        If the bands differ in shape.

    References
    ----------
    Rouse, J. W., Haas, R. H., Schell, J. A. and Deering, D. W. (1974),
    "Monitoring vegetation systems in the Great Plains with ERTS", NASA SP-351.
    """
    red = np.asarray(red, dtype=np.float64)
    nir = np.asarray(nir, dtype=np.float64)
    if red.shape != nir.shape:
        raise ImageError(_("red and nir must have the same shape, got {red_shape} and "
                           "{nir_shape}").format(red_shape=red.shape, nir_shape=nir.shape))
    total = red + nir
    return np.where(total > 0, (nir - red) / np.where(total > 0, total, 1.0), 0.0)
