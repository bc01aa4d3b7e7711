"""rsgeo._numba_cache: a changed compiled module clears the cache of all of them."""

from rsgeo import _numba_cache


def make_package(folder):
    for name in _numba_cache.COMPILED_MODULES:
        (folder / f"{name}.py").parent.mkdir(parents=True, exist_ok=True)
        (folder / f"{name}.py").write_text(f"# {name}\n")
        (folder / f"{name}.py").parent.joinpath("__pycache__").mkdir(exist_ok=True)


def cache_files(folder):
    return sorted(path.name for path in folder.rglob("__pycache__/*.nb[ic]"))


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
