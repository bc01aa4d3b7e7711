"""The two homes: rsgeo, the library, and rsgeo_course, the course built on it.

- every name that moved keeps working from its old home for one release, with a
  DeprecationWarning that names the new home (scikit-image's policy), and is the same object;
- rsgeo imports, and each of its modules works, without the course installed;
- no module of either package is over 1,200 lines, and no module imports another module's
  private (underscore) names;
- no source cites a file outside the repository or an issue number (this project's or another's).

Import layers and cycles are import-linter's contracts (pyproject.toml), run by pre-commit.
"""

import ast
import importlib
import re
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from rsgeo import _deprecated

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("rsgeo", "rsgeo_course")
MAX_LINES = 1200

# old home -> {name: new home}, read from the old homes themselves
OLD_HOMES = ("terrain", "georef", "tiepoints", "matching", "regions", "camera", "tiling",
             "transformer", "thin_plate", "distortion", "synthetic")
MOVED_MODULES = {"rsgeo.exercises": "rsgeo_course.exercises",
                 "rsgeo.alt_text": "rsgeo_course.alt_text",
                 "rsgeo.figure_language": "rsgeo_course.figure_language"}


def moved_names():
    cases = []
    for old in OLD_HOMES:
        module = importlib.import_module(f"rsgeo.{old}")
        homes = module.__dict__["__getattr__"].homes
        cases += [(f"rsgeo.{old}", name, home) for name, home in sorted(homes.items())]
    return cases


MOVED = moved_names()


def test_every_old_home_forwards_something():
    assert {old for old, _name, _home in MOVED} == {f"rsgeo.{old}" for old in OLD_HOMES}
    assert len(MOVED) > 100


@pytest.mark.parametrize("old, name, home", MOVED, ids=[f"{o}.{n}" for o, n, _h in MOVED])
def test_a_moved_name_warns_and_is_the_same_object(old, name, home):
    module = importlib.import_module(old)
    with pytest.warns(DeprecationWarning, match=rf"{re.escape(old)}\.{name} moved to "
                                                rf"{re.escape(home)}\.{name}"):
        value = getattr(module, name)
    assert value is getattr(importlib.import_module(home), name)


@pytest.mark.parametrize("old, new", sorted(MOVED_MODULES.items()))
def test_a_moved_module_forwards_every_public_name(old, new):
    module, target = importlib.import_module(old), importlib.import_module(new)
    assert sorted(dir(module)) == sorted(target.__all__)
    for name in target.__all__:
        with pytest.warns(DeprecationWarning, match=f"moved to {re.escape(new)}"):
            assert getattr(module, name) is getattr(target, name)


def test_from_import_of_an_old_home_still_works():
    with pytest.warns(DeprecationWarning, match="rsgeo.ortho.orthorectify"):
        from rsgeo.terrain import orthorectify
    from rsgeo.ortho import orthorectify as new

    assert orthorectify is new
    with pytest.raises(AttributeError, match="has no attribute 'nothing'"):
        _deprecated.moved_names("rsgeo.old", {})[0]("nothing")


def test_the_library_works_without_the_course():
    # the course's package hidden, as in an install of rsgeo alone: every module of rsgeo
    # imports, a figure is still described (by its titles), and an old home of the course's
    # names says what to install
    code = """
import sys, importlib, pkgutil
class NoCourse:
    def find_spec(self, name, path=None, target=None):
        if name == "rsgeo_course" or name.startswith("rsgeo_course."):
            raise ImportError("no rsgeo_course here")
sys.meta_path.insert(0, NoCourse())
import rsgeo
for info in pkgutil.walk_packages(rsgeo.__path__, prefix="rsgeo."):
    importlib.import_module(info.name)
import matplotlib
matplotlib.use("Agg")
from matplotlib.figure import Figure
from rsgeo import plot
figure = Figure()
figure.subplots().set_title("slope")
assert plot.figure_description(figure) == "Figure “slope”.", plot.figure_description(figure)
import rsgeo.exercises
try:
    rsgeo.exercises.check_rms
except ImportError as error:
    assert "install the course" in str(error)
else:
    raise AssertionError("rsgeo.exercises answered without the course")
assert not any(name.startswith("rsgeo_course") for name in sys.modules)
print("ok")
"""
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=600, cwd=ROOT)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stderr[-2000:]


def sources(*folders, suffixes=(".py",)):
    for folder in folders:
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix in suffixes and "_build" not in path.parts \
                    and "__pycache__" not in path.parts and "_vendor" not in path.parts:
                yield path


@pytest.mark.parametrize("package", PACKAGES)
def test_no_module_is_over_1200_lines(package):
    long = {str(path.relative_to(ROOT)): n for path in sources(package)
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
    assert not long, f"split these modules, one topic each: {long}"


def private_imports(path, package):
    """``from X import _name`` where X is another module of the package (not a private module
    of the same package folder: a package's __init__ and its private modules share names)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.module is None:         # from . import _proj: a private module, not a name
                continue
            # ``_`` is gettext's translate, every module's; dunder names are Python's
            private = [alias.name for alias in node.names if alias.name.startswith("_")
                       and alias.name != "_" and not alias.name.startswith("__")]
            if private and node.level:
                found.append((node.lineno, node.module, private))
            elif private and (node.module or "").startswith(PACKAGES):
                found.append((node.lineno, node.module, private))
    return found


@pytest.mark.parametrize("package", PACKAGES)
def test_no_module_imports_another_modules_private_names(package):
    found = {str(path.relative_to(ROOT)): hits for path in sources(package)
             if (hits := private_imports(path, package))}
    assert not found, found


# the design notes kept outside the repository, or an issue number, this project's or
# another's: a reader of the repository can follow neither
_CITED_FILE = re.compile(r"\bDESIGN\.md\b|\.\./shared/")
_ISSUE_NUMBER = re.compile(r"\b[Ii]ssues? #?\d+\b|\bpull request #?\d+\b")


def test_no_source_cites_a_file_outside_the_repository_or_an_issue_number():
    cited = []
    for path in sources("rsgeo", "rsgeo_course", "tests", "benchmarks", "exercises", "book",
                        "locales", suffixes=(".py", ".ipynb", ".md")):
        if path.name == "test_layout.py":
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if _CITED_FILE.search(line) or _ISSUE_NUMBER.search(line):
                cited.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()[:90]}")
    assert not cited, "\n".join(cited[:20])


def test_importing_rsgeo_warns_about_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in ("rsgeo.ortho", "rsgeo.sensors", "rsgeo.registration", "rsgeo.resample",
                     "rsgeo.crs", "rsgeo.synthetic", "rsgeo.widgets", "rsgeo_course.exercises"):
            importlib.import_module(name)


def test_warps_take_one_convention_and_the_old_one_warns():
    # warp(image, mapping, dst_shape, dst_transform, *, method, src_nodata, dst_nodata, ...):
    # rasterio's src_/dst_ pairing; the old keywords and positions work for one release
    import inspect

    import affine
    import numpy as np

    from rsgeo import resample

    for verb in (resample.warp, resample.warp_tiled, resample.warp_dask):
        parameters = inspect.signature(verb).parameters
        assert list(parameters)[2:4] == ["dst_shape", "dst_transform"], verb.__name__
        assert parameters["dst_nodata"].kind is inspect.Parameter.KEYWORD_ONLY
        assert parameters["method"].kind is inspect.Parameter.KEYWORD_ONLY
        assert "src_nodata" in parameters and "nodata" not in parameters
    image = np.arange(20, dtype=np.uint8).reshape(4, 5)
    grid = affine.Affine.identity()
    new = resample.warp(image, grid, (4, 5), grid, method="bilinear", dst_nodata=255)
    with pytest.warns(DeprecationWarning, match=r"nodata= is now dst_nodata="):
        old = resample.warp(image, grid, shape=(4, 5), transform=grid, method="bilinear",
                            nodata=255)
    np.testing.assert_array_equal(old, new)
    with pytest.warns(DeprecationWarning, match=r"passing method, nodata by position"):
        positional = resample.warp(image, grid, (4, 5), grid, "bilinear", 255)
    np.testing.assert_array_equal(positional, new)
    with pytest.raises(TypeError, match="both nodata="):
        resample.warp(image, grid, (4, 5), grid, nodata=0, dst_nodata=0)


def test_a_gdal_six_tuple_is_read_for_one_release_with_a_warning():
    import affine

    from rsgeo.validation import as_affine

    gdal = (500000.0, 20.0, 0.0, 7400000.0, 0.0, -20.0)
    with pytest.warns(DeprecationWarning, match=r"affine.Affine.from_gdal\(\*dem_transform\)"):
        read = as_affine(gdal, "dem_transform", gdal_tuple=True)
    assert read == affine.Affine.from_gdal(*gdal)
    with pytest.raises(TypeError, match=r"from_gdal"):
        as_affine(gdal, "dst_transform")
