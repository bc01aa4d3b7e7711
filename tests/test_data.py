"""rsgeo.data: every shipped file opens offline with the metadata its README states."""

import numpy as np
import pytest

from rsgeo import data

EXPECTED = {  # name: (shape, EPSG, pixel size)
    "cbers2b_hrc": ((2810, 2954), 29191, 2.5),
    "cbers2b_rgb342": ((3, 351, 369), 29191, 20.0),
    "cbers_b2_A": ((604, 568), 29192, 20.0),
    "cbers_b2_B_contraste": ((563, 599), 29192, 20.0),
    "cbers_b2_C": ((442, 373), 29192, 20.0),
    "nat1": ((1105, 1102), 29193, 25.0),
    "nat2": ((980, 1126), 29193, 25.0),
}


def test_available_lists_every_file():
    assert data.available() == sorted(EXPECTED)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_every_file(name):
    raster = data.load(name)
    shape, epsg, pixel = EXPECTED[name]
    assert raster.array.shape == shape
    assert raster.array.dtype == np.uint8
    assert raster.crs.to_epsg() == epsg
    assert raster.pixel_size == (pixel, pixel)
    assert raster.description and raster.array.std() > 5


def overlap(a, b):
    west_a, south_a, east_a, north_a = data.load(a).bounds
    west_b, south_b, east_b, north_b = data.load(b).bounds
    return max(west_a, west_b), max(south_a, south_b), min(east_a, east_b), min(north_a, north_b)


@pytest.mark.parametrize("a, b, expected", [
    ("cbers_b2_A", "cbers_b2_B_contraste", (545_080, 7_894_300, 552_160, 7_901_740)),
    ("cbers_b2_B_contraste", "cbers_b2_C", (549_260, 7_897_160, 556_720, 7_901_740)),
    ("cbers_b2_A", "cbers_b2_C", (549_260, 7_897_160, 552_160, 7_906_000)),
    ("nat1", "nat2", (474_364, 7_407_165, 483_501, 7_431_665)),
    ("cbers2b_hrc", "cbers2b_rgb342", (770_597, 7_363_093, 777_977, 7_370_113)),
])
def test_overlaps_stated_in_the_readme(a, b, expected):
    np.testing.assert_allclose(overlap(a, b), expected, atol=1.0)


def test_unknown_name_lists_what_is_available():
    with pytest.raises(ValueError, match="unknown dataset 'landsat'.*cbers2b_hrc.*nat2"):
        data.load("landsat")


def test_gcp_set_has_a_note_per_point():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    assert len(gcps) == 14 and all(gcps.notes)
    assert gcps.crs.startswith("PROJCS[\"SAD69 / UTM zone 21S\"")
