"""GDAL's own warp tests, ported: rsgeo and GDAL on the same inputs.

Each test names the GDAL autotest it comes from (``autotest/alg/warp.py`` in
github.com/OSGeo/gdal, and its ``autotest/alg/data`` files). The original tests
compare GDAL with checksums or reference images stored in GDAL's repository;
here rsgeo's output is compared with GDAL's (the one inside the locked rasterio
wheel, 3.10.3) on the same input, and with what the original test expects.

Ported are the cases whose inputs are small and defined in the test or in a text
file: the binary reference images (``utmsmall*.tif``, ``test3658.tif``,
``byte.tif``) are not, and the resampling methods rsgeo does not have (cubic
spline, Lanczos, mode, sum, alpha bands) are not ported either.
"""

import affine
import numpy as np
import pytest

from rsgeo.resample import WARP_METHODS, warp

from gdal_reference import affine_source, gdal_warp, gdalwarp_reproject

# -- autotest/alg/warp.py::test_warp_19 ------------------------------------------
# "Test all data types and resampling methods for very small images to test edge
# behaviour": a size x size image filled with 10.1, geotransform (10, 5, 0, 30, 0, -5),
# warped by gdalwarp onto its own grid; the checksum must be the source's.

SMALL_TRANSFORM = affine.Affine(5.0, 0, 10.0, 0, -5.0, 30.0)


@pytest.mark.parametrize("size", [1, 2, 3, 7])
@pytest.mark.parametrize("method", WARP_METHODS)
@pytest.mark.parametrize("dtype", ["uint8", "int16", "uint16", "int32", "float32", "float64"])
def test_warp_19_tiny_images_onto_their_own_grid(size, method, dtype):
    image = np.full((size, size), 10.1).astype(dtype)
    shape = (size, size)
    got = warp(image, ~SMALL_TRANSFORM, shape, SMALL_TRANSFORM, method=method, dst_nodata=None)
    gdal = gdalwarp_reproject(image, SMALL_TRANSFORM, SMALL_TRANSFORM, shape, method, None)
    assert np.array_equal(gdal, image)      # what GDAL's test checks
    assert np.array_equal(got, gdal)


# -- autotest/alg/warp.py::test_warp_22 ------------------------------------------
# "Test warping with datasets which are 'bigger' than the wm parameter" (GDAL #3458):
# a 1001 x 1001 image of non-uniform values warped onto its own grid with a warp memory
# far below its size, so that gdalwarp cuts it into many chunks; the checksum must be the
# source's. Onto its own grid every chunk's scale is 1: the chunks cannot change a pixel.


def warp_22_image(size=1001):
    i = np.arange(size, dtype=np.float64)[np.newaxis, :]      # column
    j = np.arange(size, dtype=np.float64)[:, np.newaxis]      # row
    return ((i * i + size * j / (i + 1)) % 256).astype(np.uint8)


@pytest.mark.parametrize("method", ["nearest", "bilinear", "cubic"])
def test_warp_22_many_chunks_onto_the_own_grid(method):
    image = warp_22_image()
    transform = affine.Affine(0.01, 0, 2.0, 0, -0.01, 49.0)
    got = warp(image, ~transform, image.shape, transform, method=method, dst_nodata=None)
    gdal = gdalwarp_reproject(image, transform, transform, image.shape, method, None,
                              crs="EPSG:4326", warp_mem_limit=1)
    assert np.array_equal(gdal, image)
    assert np.array_equal(got, gdal)


# -- autotest/alg/warp.py::test_warp_weighted_average and
#    test_warp_weighted_average_with_srcoffset (data/3by3_average.vrt,
#    data/3by3_average_with_srcoffset.vrt) --------------------------------------------
# A 4 x 4 Float64 source (geotransform 0, 0.25, 0, 1, 0, -0.25) averaged onto a 3 x 3 grid of
# 1/3 pixels, and onto one 1/3 pixel at (1/3, 2/3). The source, 4by4.tif, is binary and not
# ported; it is taken here as the values 1 to 16 row by row, which gives the 8.5 the second
# test expects (the mean of 6, 7, 10 and 11, each a quarter of the cell).

FOUR_BY_FOUR = affine.Affine(0.25, 0, 0.0, 0, -0.25, 1.0)
THIRDS = {"3by3_average": (affine.Affine(1 / 3, 0, 0.0, 0, -1 / 3, 1.0), (3, 3)),
          "3by3_average_with_srcoffset": (affine.Affine(1 / 3, 0, 1 / 3, 0, -1 / 3, 2 / 3),
                                          (1, 1))}


@pytest.mark.parametrize("case", THIRDS)
def test_warp_weighted_average(case):
    image = np.arange(1.0, 17.0).reshape(4, 4)
    dst_transform, shape = THIRDS[case]
    got = warp(image, ~FOUR_BY_FOUR, shape, dst_transform, method="average", dst_nodata=-1.7e308)
    gdal = gdal_warp(image, affine_source(FOUR_BY_FOUR), dst_transform, shape, "average",
                     -1.7e308)
    np.testing.assert_array_equal(got, gdal)
    if case == "3by3_average_with_srcoffset":
        assert got[0, 0] == pytest.approx(8.5, abs=1e-5)      # GDAL's expected value
    else:
        # every cell is a weighted mean of the pixels it covers: the centre one, of the
        # four central pixels equally
        assert got[1, 1] == pytest.approx(8.5)
