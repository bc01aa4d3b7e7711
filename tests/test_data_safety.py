"""Nothing lost: rsgeo's writers replace a file whole or leave it as it was.

``rsgeo.data.save`` and ``rsgeo.gcp.write_points`` write a hidden temporary file beside the
target and rename it onto the target (``rsgeo._atomic.replacing``). Checked here with real
processes: a writer killed mid-write leaves the old file, two writers of one file leave one
complete file, and a refused call leaves an existing file byte for byte.

The subprocesses have a generous ``timeout=`` as a guard against a hang only: nothing here
measures time, since the machines that run the tests are shared and loaded.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from rsgeo import _atomic, data, gcp
from rsgeo.errors import DataError, GCPError, ImageError

HANG_GUARD = 600                      # seconds; only a guard, never a measure


def _temporaries(folder):
    """The writers' hidden temporary files left in ``folder``."""
    return sorted(path for path in Path(folder).iterdir()
                  if path.name.startswith(".") and path.name.endswith(".tmp"))


def _gcps(n, seed, offset=0.0, tag="g"):
    rng = np.random.default_rng(seed)
    return gcp.GCPSet(rng.uniform(0, 1e5, (n, 2)) + offset, rng.uniform(0, 1e3, (n, 2)),
                      ids=[f"{tag}{i}" for i in range(n)], crs="EPSG:31983")


def _same_gcps(a, b):
    return (len(a) == len(b) and np.array_equal(a.map_xy, b.map_xy)
            and np.array_equal(a.image_xy, b.image_xy) and a.ids == b.ids)


def _kill_mid_write(code, folder, *args):
    """Run ``code`` in a new Python; SIGKILL it once its temporary file holds a megabyte."""
    writer = subprocess.Popen([sys.executable, "-c", code, *map(str, args)],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        # wait for the temporary file to hold data: the kill then lands mid-write, when an
        # in-place writer would have left a partial file under the final name
        while writer.poll() is None:
            if any(path.stat().st_size > 2**20 for path in _temporaries(folder)):
                break
            time.sleep(0.005)              # poll gently: the writer needs the CPU
        else:
            pytest.fail(f"the writer ended before it was killed: {writer.communicate()}")
        writer.send_signal(signal.SIGKILL)
        writer.communicate(timeout=HANG_GUARD)
    finally:
        if writer.poll() is None:
            writer.kill()
            writer.communicate()
    assert writer.returncode == -signal.SIGKILL, "the writer was not killed mid-write"
    leftover = _temporaries(folder)
    assert len(leftover) == 1 and leftover[0].stat().st_size > 2**20, (
        "the kill did not land while the temporary file was being written")


SAVE_BIG = """
import sys, warnings
import numpy as np
from rsgeo import data
warnings.simplefilter("ignore")        # no transform: rasterio's NotGeoreferencedWarning
array = np.random.default_rng(1).integers(0, 256, (4, 6000, 6000), dtype=np.uint8)
data.save(sys.argv[1], array)
"""


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="SIGKILL is POSIX")
def test_save_killed_mid_write_leaves_the_old_file(tmp_path):
    import rasterio

    target = tmp_path / "scene.tif"
    old = np.random.default_rng(0).integers(1, 256, (3, 40, 50), dtype=np.uint8)
    data.save(target, old, crs="EPSG:31983")
    before = target.read_bytes()
    _kill_mid_write(SAVE_BIG, tmp_path, target)
    assert target.read_bytes() == before
    with rasterio.open(target) as dataset:
        assert np.array_equal(dataset.read(), old)
    # the next save is not hindered by a dead writer's temporary file
    data.save(target, old[:1])
    with rasterio.open(target) as dataset:
        assert np.array_equal(dataset.read(), old[:1])


WRITE_MANY_POINTS = """
import sys
import numpy as np
from rsgeo import gcp
n = 2_000_000
rng = np.random.default_rng(2)
gcps = gcp.GCPSet(rng.uniform(0, 1e5, (n, 2)), rng.uniform(0, 1e3, (n, 2)))
gcp.write_points(sys.argv[1], gcps)
"""


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="SIGKILL is POSIX")
def test_write_points_killed_mid_write_leaves_the_old_file(tmp_path):
    target = tmp_path / "scene.points"
    old = _gcps(200, seed=3)
    gcp.write_points(target, old)
    before = target.read_bytes()
    _kill_mid_write(WRITE_MANY_POINTS, tmp_path, target)
    assert target.read_bytes() == before
    assert _same_gcps(gcp.read_points(target), old)


WRITE_ONE_SET_REPEATEDLY = """
import sys, time
from pathlib import Path
import numpy as np
from rsgeo import gcp
target, seed, offset, tag, go = sys.argv[1:]
rng = np.random.default_rng(int(seed))
gcps = gcp.GCPSet(rng.uniform(0, 1e5, (5000, 2)) + float(offset), rng.uniform(0, 1e3, (5000, 2)),
                  ids=[f"{tag}{i}" for i in range(5000)], crs="EPSG:31983")
while not Path(go).exists():           # both writers start together, once both are ready
    time.sleep(0.01)
for _ in range(20):
    gcp.write_points(target, gcps)
"""


def test_two_writers_of_one_points_file_leave_one_complete_set(tmp_path):
    target, go = tmp_path / "shared.points", tmp_path / "go"
    first, second = _gcps(5000, seed=11, tag="a"), _gcps(5000, seed=12, offset=5e5, tag="b")
    initial = _gcps(10, seed=13, tag="c")
    gcp.write_points(target, initial)
    writers = [subprocess.Popen([sys.executable, "-c", WRITE_ONE_SET_REPEATEDLY, str(target),
                                 str(seed), str(offset), tag, str(go)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
               for seed, offset, tag in ((11, 0.0, "a"), (12, 5e5, "b"))]
    reads = []
    try:
        go.touch()
        # a reader meanwhile sees one whole set each time: the old one or either writer's
        while any(writer.poll() is None for writer in writers):
            reads.append(gcp.read_points(target))
            assert any(_same_gcps(reads[-1], each) for each in (initial, first, second))
            time.sleep(0.01)               # leave the writers most of the CPU
        outputs = [writer.communicate(timeout=HANG_GUARD) for writer in writers]
    finally:
        for writer in writers:
            if writer.poll() is None:
                writer.kill()
                writer.communicate()
    assert [writer.returncode for writer in writers] == [0, 0], outputs
    final = gcp.read_points(target)
    assert _same_gcps(final, first) or _same_gcps(final, second)
    assert sorted(path.name for path in tmp_path.iterdir()) == ["go", "shared.points"]


# -- refused calls: every argument is checked before the existing file is touched ------------

UINT8 = np.arange(12, dtype=np.uint8).reshape(3, 4)


@pytest.mark.parametrize("array, settings, error, message", [
    (UINT8, {"nodata": -1}, ImageError, r"nodata=-1 does not fit dtype uint8 .*\[0, 255\]"),
    (UINT8, {"nodata": 300}, ImageError, r"nodata=300 does not fit dtype uint8 .*\[0, 255\]"),
    (UINT8, {"nodata": 0.5}, ImageError, r"nodata=0.5 does not fit dtype uint8"),
    (UINT8, {"nodata": float("nan")}, ImageError, r"nodata=nan does not fit dtype uint8"),
    (UINT8.astype(np.float16), {"nodata": 1e6}, ImageError,
     r"nodata=1000000.0 does not fit dtype float16 \(its largest finite value is 65504.*inf"),
    (UINT8.astype(np.float32), {"nodata": 1e39}, ImageError, r"nodata=1e\+39 .*float32"),
    (UINT8, {"nodata": True}, TypeError, r"nodata must be a real number .*True of type bool"),
    (UINT8, {"nodata": "0"}, TypeError, r"nodata must be a real number .*'0' of type str"),
    (np.zeros((0, 3, 4), np.uint8), {}, ImageError,
     r"array has 0 bands \(shape \(0, 3, 4\)\); a GeoTIFF holds from 1 to 65535 bands"),
    (np.zeros((3, 4, 5, 6), np.uint8), {}, ImageError, r"array must be 2-D .* got 4-D"),
    (UINT8, {"crs": "EPSG:999999"}, ValueError, r"crs 'EPSG:999999' is not a CRS"),
    (UINT8, {"transform": (1.0, 2.0)}, ValueError, r"transform must be an affine.Affine"),
])
def test_a_refused_save_leaves_the_existing_file_byte_for_byte(tmp_path, array, settings, error,
                                                               message):
    target = tmp_path / "kept.tif"
    data.save(target, np.full((3, 4), 7, np.uint8), crs="EPSG:31983")
    before = target.read_bytes()
    with pytest.raises(error, match=message):
        data.save(target, array, **settings)
    assert target.read_bytes() == before
    assert sorted(tmp_path.iterdir()) == [target]


def _model(output):
    return lambda points: output(np.asarray(points))


@pytest.mark.parametrize("model, error, message", [
    (_model(lambda p: p[:, 0]), GCPError,
     r"model returned shape \(3,\) for the 3 GCPs' map \(x, y\); .*shape \(3, 2\)"),
    (_model(lambda p: p.T), GCPError, r"model returned shape \(2, 3\) .*shape \(3, 2\)"),
    (_model(lambda p: p[:1]), GCPError, r"model returned shape \(1, 2\) .*shape \(3, 2\)"),
    (_model(lambda p: np.full(p.shape, "x")), GCPError,
     r"model returned values that are not numbers"),
    (3, TypeError, r"model must be a map -> image model .*got int"),
])
def test_a_refused_write_points_leaves_the_existing_file_byte_for_byte(tmp_path, model, error,
                                                                       message):
    target = tmp_path / "kept.points"
    gcp.write_points(target, _gcps(3, seed=4))
    before = target.read_bytes()
    gcps = gcp.GCPSet([[0, 0], [1, 0], [0, 1]], [[0, 0], [1, 0], [0, 1]])
    with pytest.raises(error, match=message):
        gcp.write_points(target, gcps, model)
    with pytest.raises(GCPError, match=r"ids\[0\] .* line break"):
        gcp.write_points(target, gcp.GCPSet([[0, 0]], [[0, 0]], ids=["a\nb"]))
    assert target.read_bytes() == before
    assert sorted(tmp_path.iterdir()) == [target]


# -- folders and files that cannot be written -------------------------------------------------

def _can_create_in(folder):
    probe = Path(folder) / ".rsgeo-probe.tmp"
    try:
        os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
    except OSError:
        return False
    probe.unlink()
    return True


@pytest.fixture
def read_only_folder(tmp_path):
    """A folder in which no file can be created, for this user (root writes anywhere)."""
    folder = tmp_path / "read-only"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        if not _can_create_in(folder):
            yield folder
        elif Path("/sys/kernel").is_dir() and not _can_create_in("/sys/kernel"):
            yield Path("/sys/kernel")          # sysfs refuses new files, to root too
        else:
            pytest.skip("no folder here refuses new files to this user")
    finally:
        folder.chmod(0o700)


def test_writers_refuse_a_read_only_folder_with_an_rsgeo_error(read_only_folder):
    with pytest.raises(DataError, match=r"cannot write file '.*x\.tif': no file can be created "
                                        r"in its folder .*\(.+\); write to a folder"):
        data.save(read_only_folder / "x.tif", UINT8)
    with pytest.raises(DataError, match=r"cannot write file '.*x\.points': no file can be"):
        gcp.write_points(read_only_folder / "x.points", _gcps(3, seed=5))
    assert not (read_only_folder / "x.tif").exists()


def test_writers_refuse_a_read_only_file_and_a_folder(tmp_path, monkeypatch):
    target = tmp_path / "kept.points"
    gcp.write_points(target, _gcps(3, seed=6))
    data.save(tmp_path / "kept.tif", UINT8)
    before = {path: path.read_bytes() for path in (target, tmp_path / "kept.tif")}
    for path in before:
        path.chmod(0o444)
    if os.access(target, os.W_OK):      # root may write a read-only file: say it cannot
        access = os.access
        monkeypatch.setattr(_atomic.os, "access", lambda path, mode, **options: (
            Path(path) not in before and access(path, mode, **options)))
    with pytest.raises(DataError, match=r"file '.*kept\.points' is read-only, so it is left"):
        gcp.write_points(target, _gcps(4, seed=7))
    with pytest.raises(DataError, match=r"file '.*kept\.tif' is read-only"):
        data.save(tmp_path / "kept.tif", UINT8 + 1)
    monkeypatch.undo()
    with pytest.raises(DataError, match=r"file '.*' is a folder; give the name of a file"):
        data.save(tmp_path, UINT8)
    with pytest.raises(DataError, match=r"is a folder"):
        gcp.write_points(tmp_path, _gcps(3, seed=8))
    assert {path: path.read_bytes() for path in before} == before
    assert sorted(tmp_path.iterdir()) == sorted(before)


def test_written_files_get_the_modes_a_plain_open_gives(tmp_path):
    umask = os.umask(0o022)
    os.umask(umask)
    fresh = tmp_path / "fresh.points"
    gcp.write_points(fresh, _gcps(3, seed=9))
    data.save(tmp_path / "fresh.tif", UINT8)
    for path in (fresh, tmp_path / "fresh.tif"):
        assert path.stat().st_mode & 0o777 == 0o666 & ~umask        # not mkstemp's 0o600
    # a file written again keeps its mode, as when it is opened for writing
    fresh.chmod(0o640)
    gcp.write_points(fresh, _gcps(4, seed=10))
    assert fresh.stat().st_mode & 0o777 == 0o640 and len(gcp.read_points(fresh)) == 4


@pytest.mark.skipif(not hasattr(os, "symlink"), reason="no symbolic links")
def test_a_symbolic_link_is_followed_like_a_plain_open(tmp_path):
    real, link = tmp_path / "real.points", tmp_path / "link.points"
    gcp.write_points(real, _gcps(3, seed=14))
    link.symlink_to(real)
    gcp.write_points(link, _gcps(5, seed=15))
    assert link.is_symlink() and len(gcp.read_points(real)) == 5


def test_a_failing_writer_leaves_no_temporary_file(tmp_path):
    target = tmp_path / "kept.txt"
    target.write_text("old")
    with pytest.raises(KeyboardInterrupt):
        with _atomic.replacing(target) as temporary:
            temporary.write_text("half")
            raise KeyboardInterrupt
    assert target.read_text() == "old" and sorted(tmp_path.iterdir()) == [target]
