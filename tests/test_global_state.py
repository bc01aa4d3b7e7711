"""rsgeo leaves the process as it found it: PROJ's search path, its network switch, the user's
own pyproj transformations and the environment are the same after every verb that uses PROJ.

A library that put its grid folder on pyproj's process-wide search path would change what its
user's own ``pyproj.Transformer.from_crs(4618, 4674)`` gives (metres, by IBGE's grid instead of
EPSG:15485); one that switched the network off would undo the user's ``PROJ_NETWORK=ON``.
"""

import os
import subprocess
import sys

import affine
import numpy as np
import pyproj
import pyproj.datadir
import pyproj.network
import pytest
import rasterio  # noqa: F401  (rasterio sets its CA-bundle variables when imported)

import rsgeo.resample  # noqa: F401  (imported before the snapshots, which compare verbs)
from rsgeo import crs, data, heights, resample
from rsgeo.ortho import orthorectify
from rsgeo.sensors import RPCModel, simple_rpc_dict


def _user_points():
    """What the user's own pyproj gives: SAD69 -> SIRGAS 2000, and a geoid height."""
    shift = pyproj.Transformer.from_crs(4618, 4674, always_xy=True)
    geoid = pyproj.Transformer.from_crs("EPSG:4979", "EPSG:4326+5773", always_xy=True)
    return (np.array(shift.transform([-47.0, -51.2], [-15.0, -23.3])),
            np.array(geoid.transform([-47.0], [-15.0], [0.0])))


def _state():
    return {"points": _user_points(), "data_dir": pyproj.datadir.get_data_dir(),
            "user_data_dir": pyproj.datadir.get_user_data_dir(),
            "network": pyproj.network.is_network_enabled(), "environ": dict(os.environ)}


def _same(before, after):
    for key in ("data_dir", "user_data_dir", "network", "environ"):
        assert after[key] == before[key], key
    for was, now in zip(before["points"], after["points"]):
        np.testing.assert_array_equal(now, was)


def _ortho():
    rpc = RPCModel.from_dict(simple_rpc_dict())
    image = np.arange(1000 * 1000, dtype=np.float32).reshape(1000, 1000)
    return orthorectify(image, rpc, np.zeros((10, 10)),
                        affine.Affine(0.01, 0, -34.95, 0, -0.01, -7.95),
                        affine.Affine(0.001, 0, -34.91, 0, -0.001, -7.99), (20, 20), "nearest",
                        dem_vertical="EGM96")


def _georeference():
    raster, gcps = data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc")
    return resample.georeference(raster, gcps, order=1, resolution=40.0)


VERBS = {
    "datum_shift": lambda: crs.datum_shift([[775445.0, 7369105.0]], "EPSG:29191",
                                           "EPSG:31981"),
    "datum_shift SAD69(96)": lambda: crs.datum_shift([[-47.0, -15.0]], "EPSG:5527",
                                                     "EPSG:4674"),
    "transform_points forced": lambda: crs.transform_points(
        [[775445.0, 7369105.0]], "EPSG:29191", "EPSG:31981", transformation="EPSG:15485"),
    "transformations": lambda: crs.transformations("EPSG:4618", "EPSG:4674"),
    "geocentric_translation": lambda: crs.geocentric_translation(
        [[775445.0, 7369105.0]], "EPSG:29191", "EPSG:31981"),
    "grid_shift": lambda: crs.grid_shift([[-57.0, -23.0]], "SAD69"),
    "geoid_undulation": lambda: heights.geoid_undulation([-47.0], [-15.0]),
    "geoid_on_grid projected": lambda: heights.geoid_on_grid(
        affine.Affine(90.0, 0, 280000.0, 0, -90.0, 9120000.0), (4, 5), crs="EPSG:31985"),
    "to_ellipsoidal": lambda: heights.to_ellipsoidal([10.0], [-34.85], [-8.0], "EGM96"),
    "reproject": lambda: resample.reproject(data.load("cbers2b_rgb342"), "EPSG:31983",
                                            resolution=200.0),
    "georeference": _georeference,
    "orthorectify EGM96": _ortho,
}


@pytest.mark.parametrize("verb", sorted(VERBS))
def test_a_verb_leaves_proj_and_the_environment_as_it_found_them(verb):
    before = _state()
    VERBS[verb]()
    _same(before, _state())


def test_the_users_own_sad69_transformation_does_not_move():
    # the finding this guards: after a datum_shift the user's 4618 -> 4674 moved 2.46 m
    # (rsgeo's grid folder on pyproj's search path); now 0
    shift = pyproj.Transformer.from_crs(4618, 4674, always_xy=True)
    before = np.array(shift.transform(-47.0, -15.0))
    crs.datum_shift([[-47.0, -15.0]], "EPSG:4618", "EPSG:4674")
    after = np.array(pyproj.Transformer.from_crs(4618, 4674, always_xy=True).transform(
        -47.0, -15.0))
    assert np.array_equal(before, after)


def test_a_users_network_switch_stays_on():
    was = pyproj.network.is_network_enabled()
    pyproj.network.set_network_enabled(True)
    try:
        # rsgeo reads its own grids, downloads nothing, and leaves the switch on
        n = heights.geoid_undulation([-47.0], [-15.0])
        shift = crs.datum_shift([[-47.0, -15.0]], "EPSG:4618", "EPSG:4674")
        assert pyproj.network.is_network_enabled()
    finally:
        pyproj.network.set_network_enabled(was)
    assert round(float(n[0]), 2) == -15.03
    assert shift.transformation.codes == ("EPSG:5528",)


def _run(code, **environment):
    env = {**os.environ, **environment}
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)


def test_import_alone_writes_only_what_rasterio_writes():
    # rasterio sets GDAL_CURL_CA_BUNDLE and PROJ_CURL_CA_BUNDLE when imported (its own doing);
    # rsgeo's PROJ modules add nothing (the compiled kernels' modules are another matter,
    # as is threadpoolctl's KMP_DUPLICATE_LIB_OK when something imports it)
    code = ("import os; before = dict(os.environ); import rasterio; after_rasterio = "
            "dict(os.environ); import rsgeo, rsgeo.crs, rsgeo.heights; "
            "print(sorted(k for k in set(os.environ) | set(after_rasterio) "
            "if os.environ.get(k) != after_rasterio.get(k)))")
    run = _run(code)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "[]"


def test_proj_network_on_is_kept_and_gives_rsgeos_numbers():
    # PROJ_NETWORK=ON without a network gave "longitude nan" (GDAL's PROJ could not fetch a
    # grid); rsgeo now asks its own offline PROJ there, and leaves the switch on
    code = ("import pyproj.network; from rsgeo import crs, heights; "
            "s = crs.datum_shift([[775445.0, 7369105.0]], 'EPSG:29191', 'EPSG:31981'); "
            "n = heights.geoid_undulation([-47.0], [-15.0]); "
            "print(pyproj.network.is_network_enabled(), s.transformation.codes, "
            "round(float(n[0]), 2), round(float(s.distance[0]), 2))")
    on, off = _run(code, PROJ_NETWORK="ON"), _run(code, PROJ_NETWORK="OFF")
    assert on.returncode == 0 and off.returncode == 0, on.stderr + off.stderr
    assert on.stdout.split()[0] == "True" and off.stdout.split()[0] == "False"
    assert on.stdout.split()[1:] == off.stdout.split()[1:]


def test_a_proj_install_without_its_database_is_named():
    code = ("from rsgeo import crs, errors\n"
            "try:\n"
            "    crs.transform_points([[0.0, 0.0]], 'EPSG:4326', 'EPSG:3857')\n"
            "except errors.CRSError as error:\n"
            "    print(error)\n")
    run = _run(code, PROJ_DATA="/nonexistent")
    assert run.returncode == 0, run.stderr
    assert "PROJ's database is not found at /nonexistent/proj.db" in run.stdout
    assert "PROJ_DATA" in run.stdout and "not a CRS that PROJ knows" not in run.stdout


# -- RSGEO_LANG rsgeo does not speak: a warning, then English (pt_BR for a Portuguese) ----------
# (here, not in test_i18n.py, which runs with the book's tests)

LANGUAGE_CASE = """
import warnings
import numpy as np
from rsgeo import registration
from rsgeo.language import _, get_language, prose_number
from rsgeo.sensors import FrameCamera, resect
from rsgeo.sensors import ExteriorOrientation, InteriorOrientation

with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    language = get_language()
    play = _("Play")
    number = "{:.1f}".format(prose_number(22.5))
    # verbs that failed on valid input when every message raised: they run
    rng = np.random.default_rng(0)
    base = rng.random((192, 192))
    registration.band_misregistration(np.stack([base, np.roll(base, 1, axis=1)]), window=32)
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000))
    camera = FrameCamera(interior, ExteriorOrientation(5000.0, 8000.0, 3000.0, 2.0, -1.5, 30.0))
    ground = np.column_stack([rng.uniform(4000, 6000, 8), rng.uniform(7000, 9000, 8),
                              rng.uniform(0, 150, 8)])
    resect(ground, camera.project(ground), interior)
    _("Pause", "xx_YY")
ours = [str(w.message) for w in caught if "rsgeo does not speak" in str(w.message)]
print(language, play, number, len(ours), "|", " || ".join(ours))
"""


@pytest.mark.parametrize("value, language, play, number, warned", [
    ("fr", "en", "Play", "22.5", True),
    ("de_DE.UTF-8", "en", "Play", "22.5", True),
    ("pt_PT", "pt_BR", "Reproduzir", "22,5", True),
    ("pt_BR.UTF-8", "pt_BR", "Reproduzir", "22,5", False),
    ("C.UTF-8", "en", "Play", "22.5", False),
])
def test_an_rsgeo_lang_rsgeo_does_not_speak_warns_once_and_falls_back(value, language, play,
                                                                      number, warned):
    env = {**os.environ, "RSGEO_LANG": value}
    run = subprocess.run([sys.executable, "-c", LANGUAGE_CASE], capture_output=True, text=True,
                         env=env)
    assert run.returncode == 0, run.stderr
    head, messages = run.stdout.split("|", 1)
    got_language, got_play, got_number, count = head.split()
    assert (got_language, got_play, got_number) == (language, play, number)
    # once for RSGEO_LANG (however many messages), once for the language asked of _()
    assert int(count) == (2 if warned else 1)
    if warned:
        assert f"RSGEO_LANG is {value!r}" in messages and "en, pt_BR" in messages
