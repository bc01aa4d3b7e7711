"""rsgeo._numba_cache: a changed compiled module clears the cache of all of them."""

import pytest

from rsgeo import _numba_cache


def make_package(folder):
    for name in _numba_cache.COMPILED_MODULES:
        (folder / f"{name}.py").parent.mkdir(parents=True, exist_ok=True)
        (folder / f"{name}.py").write_text(f"# {name}\n")
        (folder / f"{name}.py").parent.joinpath("__pycache__").mkdir(exist_ok=True)


def cache_files(folder):
    return sorted(path.name for path in folder.rglob("__pycache__/*.nb[ic]"))


@pytest.fixture(autouse=True)
def numba_chooses_its_own_folders(monkeypatch):
    """Numba's choice without NUMBA_CACHE_DIR (which a user, or a benchmark, may have set):
    the folder beside the sources, else the user-wide one."""
    import numba

    monkeypatch.setattr(numba.config, "CACHE_DIR", "")


def test_a_changed_callee_clears_its_callers_cache(tmp_path):
    make_package(tmp_path)
    assert _numba_cache.refresh(tmp_path) is False          # nothing cached yet
    kernel = tmp_path / "_kernels" / "__pycache__" / "resampling._bilinear_loop-808.py311.nbi"
    kernel.write_bytes(b"old machine code")
    assert _numba_cache.refresh(tmp_path) is False          # same sources: kept
    assert cache_files(tmp_path) == [kernel.name]
    (tmp_path / "_kernels" / "transformer.py").write_text("# a new row_positions\n")
    assert _numba_cache.refresh(tmp_path) is True           # the callee changed: all go
    assert cache_files(tmp_path) == []
    kernel.write_bytes(b"new machine code")
    assert _numba_cache.refresh(tmp_path) is False


def test_other_caches_are_left_alone(tmp_path):
    make_package(tmp_path)
    _numba_cache.refresh(tmp_path)
    other = tmp_path / "__pycache__" / "plot.cpython-311.pyc"
    other.write_bytes(b"bytecode")
    (tmp_path / "_kernels" / "thin_plate.py").write_text("# changed\n")
    _numba_cache.refresh(tmp_path)
    assert other.exists()


def make_read_only_package(folder):
    """A package whose folders cannot hold a ``__pycache__`` (a file already has that name):
    Numba's in-tree cache is impossible there, as in a read-only install (the tests run as
    root, who may write anywhere else)."""
    make_package(folder)
    for cache in folder.rglob("__pycache__"):
        cache.rmdir()
        cache.write_text("")


def test_a_user_wide_cache_is_cleared_when_a_callee_changes(tmp_path, monkeypatch):
    package, user_cache = tmp_path / "package", tmp_path / "user-cache"
    make_read_only_package(package)
    monkeypatch.setenv("XDG_CACHE_HOME", str(user_cache))     # Numba's user-wide folder
    place = _numba_cache.cache_folder(package / "_kernels" / "resampling.py")
    assert user_cache in place.parents                           # Numba's own choice
    assert _numba_cache.refresh(package) is False
    kernel = place / "resampling._bilinear_loop-808.py311.nbi"
    kernel.write_bytes(b"old machine code")
    assert _numba_cache.refresh(package) is False                # same sources: kept
    (package / "_kernels" / "transformer.py").write_text("# a new row_positions\n")
    assert _numba_cache.refresh(package) is True                 # the callee changed
    assert not kernel.exists()


def test_no_writable_cache_folder_compiles_without_a_cache_and_says_so(tmp_path):
    import os
    import shutil
    import subprocess
    import sys
    from pathlib import Path

    import rsgeo

    copy = tmp_path / "install"
    shutil.copytree(Path(rsgeo.__file__).parent, copy / "rsgeo",
                    ignore=shutil.ignore_patterns("__pycache__"))
    for folder in [copy / "rsgeo", *(copy / "rsgeo").rglob("*")]:
        if folder.is_dir():
            (folder / "__pycache__").write_text("")
    # no writable home either: /sys/kernel refuses even root's writes
    environment = {**os.environ, "HOME": "/sys/kernel", "XDG_CACHE_HOME": "/sys/kernel/cache",
                   "PYTHONPATH": str(copy), "PYTHONDONTWRITEBYTECODE": "1"}
    environment.pop("NUMBA_CACHE_DIR", None)
    code = ("import warnings; warnings.simplefilter('always')\n"
            "from rsgeo._kernels import resampling\n"
            "print(resampling.__file__, resampling.CACHE)\n"
            "print(resampling.keys_weights(0.5).tolist())\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=environment, cwd=tmp_path, timeout=3600)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0] == f"{copy / 'rsgeo' / '_kernels' / 'resampling.py'} False", lines
    assert lines[1] == "[-0.0625, 0.5625, 0.5625, -0.0625]", lines
    assert run.stderr.count("no writable folder to cache rsgeo's compiled kernels") == 1, \
        run.stderr
