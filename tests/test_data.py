"""rsgeo.data: every shipped file opens offline with the metadata its README states."""

import subprocess
import sys

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


def test_path_of_every_shipped_file():
    for name in data.available():
        assert data.path(name).suffix == ".tif" and data.path(name).is_file()
    points = data.path("cbers2b_ccd_hrc")
    assert points.suffix == ".points" and points.is_file()
    assert data.path("cbers2b_ccd_hrc.points") == points
    from rsgeo.gcp import read_points

    np.testing.assert_array_equal(read_points(points).map_xy,
                                  data.load_gcps("cbers2b_ccd_hrc").map_xy)
    with pytest.raises(ValueError, match=r"'landsat'.*nat2.*GCP sets: cbers2b_ccd_hrc.*\.points"):
        data.path("landsat")
    with pytest.raises(ValueError, match="unknown dataset 'cbers2b_ccd_hrc'"):
        data.load("cbers2b_ccd_hrc")        # a GCP set is not a raster


def test_raster_repr_is_one_short_line():
    assert repr(data.load("cbers2b_hrc")) == (
        "Raster('cbers2b_hrc', 2810 × 2954, uint8, 2.5 m pixels, EPSG:29191)")
    assert repr(data.load("cbers2b_rgb342")) == (
        "Raster('cbers2b_rgb342', 3 bands × 351 × 369, uint8, 20 m pixels, EPSG:29191)")
    assert str(data.load("nat1")) == "Raster('nat1', 1105 × 1102, uint8, 25 m pixels, EPSG:29193)"


def test_descriptions_name_the_sensor_only_where_it_is_known():
    for name in data.available():
        description = data.load(name).description
        if name.startswith("cbers"):
            assert "CBERS" in description
        else:
            assert "CBERS" not in description and "undocumented" in description


@pytest.mark.parametrize("transform", [
    (500_000.0, 10.0, 0.0, 7_400_000.0, 0.0, -10.0),          # GDAL's order, a tuple
    [500_000, 10, 0, 7_400_000, 0, -10],                      # or a list
])
def test_save_accepts_a_gdal_ordered_transform(tmp_path, transform):
    import affine
    import rasterio

    array = np.arange(12, dtype=np.uint8).reshape(3, 4)
    written = data.save(tmp_path / "ramp.tif", array, transform=transform, crs="EPSG:31983")
    with rasterio.open(written) as dataset:
        assert dataset.transform == affine.Affine(10.0, 0, 500_000.0, 0, -10.0, 7_400_000.0)
        assert np.array_equal(dataset.read(1), array)


def test_save_round_trips_a_raster(tmp_path):
    import rasterio

    ccd = data.load("cbers2b_rgb342")
    with rasterio.open(data.save(tmp_path / "ccd.tif", ccd)) as dataset:
        assert dataset.transform == ccd.transform and dataset.crs == ccd.crs
        assert np.array_equal(dataset.read(), ccd.array)


@pytest.mark.parametrize("transform", [(1.0, 2.0), (1, 2, 3, 4, 5, float("nan")),
                                       ("a", 1, 0, 2, 0, -1), tuple(range(9))])
def test_save_refuses_a_transform_it_cannot_read(tmp_path, transform):
    with pytest.raises(ValueError, match="transform must be an affine.Affine or 6 finite numbers"):
        data.save(tmp_path / "x.tif", np.zeros((3, 4), np.uint8), transform=transform)
    with pytest.raises(TypeError, match="transform must be an affine.Affine .* got str"):
        data.save(tmp_path / "x.tif", np.zeros((3, 4), np.uint8), transform="EPSG:4326")
    assert not (tmp_path / "x.tif").exists()


def test_save_refuses_a_tuple_in_affine_order_and_names_from_gdal(tmp_path):
    # Affine's order (a, b, c, d, e, f) read as GDAL's wrote a pixel width of 0
    import affine
    import rasterio

    affine_order = (20.0, 0.0, 500_000.0, 0.0, -20.0, 7_400_000.0)
    array = np.arange(12, dtype=np.uint8).reshape(3, 4)
    with pytest.raises(ValueError, match=r"pixel width 0 .*affine.Affine's order.*"
                                         r"affine.Affine\(\*transform\).*Affine.from_gdal"):
        data.save(tmp_path / "x.tif", array, transform=affine_order)
    with pytest.raises(ValueError, match="pixels with no area"):
        data.save(tmp_path / "x.tif", array, transform=affine.Affine(20, 0, 0, 0, 0, 0))
    assert not (tmp_path / "x.tif").exists()
    # the same grid as an Affine, and in GDAL's order: one file, pixel width 20
    for transform in (affine.Affine(*affine_order), affine.Affine(*affine_order).to_gdal()):
        with rasterio.open(data.save(tmp_path / "ok.tif", array, transform=transform)) as dataset:
            assert dataset.transform == affine.Affine(*affine_order)
            assert dataset.res == (20.0, 20.0)


def test_save_refuses_settings_beside_a_raster(tmp_path):
    # transform= was ignored without a word when a Raster was given
    import affine

    ccd = data.load("cbers2b_rgb342")
    for given in ({"transform": affine.Affine.identity()}, {"crs": "EPSG:31981"},
                  {"nodata": 0}):
        with pytest.raises(ValueError, match=f"{next(iter(given))} given with a Raster.*"
                                             "dataclasses.replace"):
            data.save(tmp_path / "x.tif", ccd, **given)
    assert not (tmp_path / "x.tif").exists()


def test_save_gives_clear_errors_for_a_crs_or_a_folder(tmp_path):
    array = np.zeros((3, 4), np.uint8)
    with pytest.raises(ValueError, match="crs 'EPSG:999999' is not a CRS that PROJ knows"):
        data.save(tmp_path / "x.tif", array, crs="EPSG:999999")
    with pytest.raises(ValueError, match=r"folder of file .* does not exist.*mkdir"):
        data.save(tmp_path / "missing" / "x.tif", array)
    with pytest.raises(TypeError, match="file must be a path"):
        data.save(3, array)


def test_save_refuses_to_write_over_the_shipped_data(tmp_path):
    shipped = data.path("nat1")
    before = shipped.read_bytes()
    with pytest.raises(ValueError, match="inside rsgeo's data folder"):
        data.save(shipped, np.zeros((3, 4), np.uint8))
    with pytest.raises(ValueError, match="inside rsgeo's data folder"):
        data.save(shipped.parent / "new.tif", np.zeros((3, 4), np.uint8))
    assert shipped.read_bytes() == before and not (shipped.parent / "new.tif").exists()


@pytest.mark.parametrize("dtype, written", [(np.float16, "float32"), (">i2", "int16"),
                                            (">f8", "float64"), ("<u2", "uint16")])
def test_save_writes_float16_and_big_endian_arrays_without_changing_a_value(tmp_path, dtype,
                                                                           written):
    import rasterio

    array = (np.arange(12).reshape(3, 4) * 3 - 7 * (np.dtype(dtype).kind != "u")).astype(dtype)
    array[0, 0] = 7 if np.dtype(dtype).kind == "u" else -2.5 if array.dtype.kind == "f" else -2
    with rasterio.open(data.save(tmp_path / "x.tif", array)) as dataset:
        back = dataset.read(1)
    assert back.dtype == np.dtype(written)
    np.testing.assert_array_equal(back, array.astype(np.float64))


def test_save_does_not_load_numba(tmp_path):
    code = ("import sys, numpy as np, rsgeo.data as d; "
            f"d.save({str(tmp_path / 'a.tif')!r}, np.zeros((2, 2), np.uint8), crs=31983); "
            "print('numba' in sys.modules)")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "False"


def test_save_refuses_a_bands_last_rgb_array(tmp_path):
    rgb = np.moveaxis(data.load("cbers2b_rgb342").array, 0, -1)      # (351, 369, 3)
    with pytest.raises(ValueError, match=r"bands last.*np\.moveaxis\(array, -1, 0\)"):
        data.save(tmp_path / "rgb.tif", rgb)
    assert not (tmp_path / "rgb.tif").exists()


def test_import_does_not_load_numba():
    # reading a shipped scene needs no compiler: Numba (a second or more) loads with resampling
    code = "import sys, rsgeo.data; print('numba' in sys.modules)"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "False"


def test_every_proj_grid_is_documented_with_its_checksum():
    # rsgeo/data/README.md, "PROJ grids": each shipped grid's SHA-256, as copied from its source
    import hashlib
    import re
    from pathlib import Path

    folder = Path(data.__file__).parent
    readme = (folder / "README.md").read_text(encoding="utf-8")
    documented = dict(re.findall(r"^\| `([\w.]+)` \|.*\| `([0-9a-f]{64})` \|$", readme, re.M))
    shipped = {path.name: hashlib.sha256(path.read_bytes()).hexdigest()
               for path in sorted((folder / "proj").iterdir()) if path.is_file()}
    assert shipped == documented
    assert set(shipped) == {"br_ibge_SAD69_003.tif", "br_ibge_SAD96_003.tif", "egm96_15.gtx"}


def test_save_keeps_a_good_nodata_and_a_float16_one_that_fits(tmp_path):
    import rasterio

    ramp = np.arange(12, dtype=np.uint8).reshape(3, 4)
    for array, nodata in ((ramp, 255), (ramp.astype(np.float16), 65504.0),
                          (ramp.astype(np.float32), float("nan"))):
        with rasterio.open(data.save(tmp_path / "x.tif", array, nodata=nodata)) as dataset:
            assert dataset.nodata == nodata or (np.isnan(nodata) and np.isnan(dataset.nodata))


def test_save_names_the_band_count_a_geotiff_cannot_hold(tmp_path):
    # rasterio's own error was "Attempt to create 1x1x70000 TIFF file"; count=0 was GDAL's
    from rsgeo.errors import ImageError

    for bands in (0, 65536):
        with pytest.raises(ImageError, match=f"array has {bands} bands .*from 1 to 65535"):
            data.save(tmp_path / "x.tif", np.zeros((bands, 1, 1), np.uint8))
    assert not (tmp_path / "x.tif").exists()
