"""Tests of rsgeo.synthetic's two-date landscape: its images sit where their geotransforms say."""
import numpy as np
import pytest
from scipy import ndimage

from rsgeo import synthetic


def forest_offsets(image, transform, truth, threshold=185):
    """(dx, dy) in metres from each true forest centroid to the nearest image forest centroid."""
    labels, n = ndimage.label(image > threshold)
    found = np.array(ndimage.center_of_mass(np.ones_like(image), labels, range(1, n + 1)))
    xy = np.column_stack(transform @ (found[:, 1] + 0.5, found[:, 0] + 0.5))
    nearest = np.argmin(np.hypot(*(xy[:, None] - truth[None]).transpose(2, 0, 1)), axis=0)
    return xy[nearest] - truth


@pytest.fixture(scope="module")
def still():
    # no rotation and no shift: both images see the ground where their geotransforms say
    return synthetic.two_date_landscape(rotation_deg=0.0, shift=(0.0, 0.0))


def test_reference_content_is_where_its_geotransform_says(still):
    # the 20 m reference is smoothed by a 2 x 2 box (even): the old code left its content
    # 5 m east and 5 m south (dx = +5, dy = -5) of the fine scene's forests
    offsets = forest_offsets(still.reference, still.reference_transform,
                             still.forest_centroids_map)
    assert len(offsets) == 8
    mean = offsets.mean(axis=0)
    assert np.all(np.abs(mean) < 1.5), mean


def test_adjustment_content_is_where_its_geotransform_says(still):
    # the 30 m adjustment (odd 3 x 3 box) was centred already and must stay so
    offsets = forest_offsets(still.adjustment, still.adjustment_transform,
                             still.forest_centroids_map)
    assert len(offsets) == 8
    assert np.all(np.abs(offsets.mean(axis=0)) < 1.5)


def test_even_pixel_ratio_other_than_two_is_centred():
    # a 40 m reference (4 x 4 box) follows the same rule (old code: (+6.7, -5.4) m)
    land = synthetic.two_date_landscape(reference_pixel=40.0, rotation_deg=0.0,
                                        shift=(0.0, 0.0))
    offsets = forest_offsets(land.reference, land.reference_transform,
                             land.forest_centroids_map)
    assert len(offsets) == 8 and np.all(np.abs(offsets.mean(axis=0)) < 2.5)
