"""rsgeo's declared API: every module says what it exports, every public module is on the API
page, docstring cross-references resolve, every geometric model follows one mapping protocol,
and importing rsgeo changes nothing.

Import layers and cycles are import-linter's job, docstring sections numpydoc's (both run by
pre-commit, configured in pyproject.toml)."""

import importlib
import inspect
import os
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import rsgeo

PACKAGE = Path(__file__).resolve().parents[1] / "rsgeo"
ALL_MODULES = sorted(info.name for info in pkgutil.walk_packages(rsgeo.__path__, prefix="rsgeo."))


def is_old_home(name):
    """A module that only forwards moved names (rsgeo._deprecated), with no code of its own."""
    source = (PACKAGE.parent / f"{name.replace('.', '/')}.py")
    if not source.exists():
        return False
    text = source.read_text(encoding="utf-8")
    return "moved_" in text and not re.search(r"^(def|class) ", text, flags=re.M)


# the old homes of moved names: they forward, with a DeprecationWarning, for one release
DEPRECATED = [name for name in ALL_MODULES if is_old_home(name)]
MODULES = [name for name in ALL_MODULES if name not in DEPRECATED]


def test_import_rsgeo_reaches_every_module():
    code = ("import rsgeo; rsgeo.transforms.fit_polynomial; rsgeo.data.load; "
            "print(sorted(set(rsgeo.__all__) - {'__version__'}))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    public = sorted({name.split(".")[1] for name in ALL_MODULES
                     if not name.split(".")[1].startswith("_")})
    assert run.stdout.strip() == str(public)
    with pytest.raises(AttributeError, match="its modules are"):
        rsgeo.not_a_module  # noqa: B018  (the attribute access is the test)


def test_import_rsgeo_changes_nothing():
    # no submodule, no matplotlib, no patching, whatever the environment says (the book's build
    # audits figures in its own kernels, book/_ext/figure_audit.py); the guard of Numba's cache
    # (rsgeo._numba_cache) runs when the first compiled module is imported, not before
    code = ("import sys, rsgeo; "
            "print(sorted(m for m in sys.modules if m.startswith(('rsgeo.', 'matplotlib'))))")
    environment = {**os.environ, "RSGEO_AUDIT_FIGURES": "1"}
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=300, env=environment)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "[]", run.stdout


@pytest.mark.parametrize("name", MODULES)
def test_every_module_declares_what_it_exports(name):
    module = importlib.import_module(name)
    assert hasattr(module, "__all__"), f"{name} has no __all__"
    missing = [item for item in module.__all__ if not hasattr(module, item)]
    assert not missing, f"{name}.__all__ names what it does not define: {missing}"
    defined = [item for item, value in vars(module).items()
               if not item.startswith("_")
               and (inspect.isfunction(value) or inspect.isclass(value))
               and value.__module__ == name]
    undeclared = sorted(set(defined) - set(module.__all__))
    assert not undeclared, (f"{name} defines public {undeclared} outside __all__ "
                            "(add them or rename _x)")


def polynomial():
    src = np.array([[0, 0], [100, 0], [0, 100], [100, 100], [50, 50], [50, 0], [0, 50]], float)
    model = rsgeo.transforms.fit_polynomial(src, src * [1.1, 0.9] + 0.001 * src**2 + [3, -2], 2)
    return model, src


def systematic():
    grid = np.array([[10.0, 20.0], [150.0, 150.0], [290.0, 280.0]])
    return rsgeo.sensors.SystematicDistortion(skew_per_line=0.1, yaw_rate_deg_per_line=0.02,
                                                 scale=1.05, shape=(300, 300)), grid


@pytest.mark.parametrize("make", [polynomial, systematic], ids=["polynomial", "systematic"])
def test_every_model_follows_the_mapping_protocol(make):
    model, points = make()
    assert isinstance(model, rsgeo.transforms.GeometricModel)
    mapped = model(points)
    assert mapped.shape == points.shape and not np.allclose(mapped, points)
    np.testing.assert_allclose(model.residuals(points, mapped), 0, atol=1e-9)
    moved = mapped + [[3.0, 4.0]] + 0 * mapped
    np.testing.assert_allclose(model.residuals(points, moved), 5.0, rtol=1e-9)
    assert model.rms(points, moved) == pytest.approx(5.0)
    inverse = model.inverse()
    assert isinstance(inverse, rsgeo.transforms.GeometricModel) and inverse.inverse() is model
    np.testing.assert_allclose(inverse(mapped), points, atol=1e-6)
    np.testing.assert_allclose(inverse.residuals(mapped, points), 0, atol=1e-6)
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        model(np.zeros((3, 3)))


def test_the_api_page_documents_every_public_module():
    page = (PACKAGE.parent / "book" / "api.md").read_text()
    # rsgeo's own modules (a package's modules are documented as its page says)
    public = [name for name in MODULES
              if name.count(".") == 1 and not name.split(".")[1].startswith("_")]
    missing = [name for name in public if f".. automodule:: {name}\n" not in page]
    assert not missing, f"book/api.md lacks an automodule for {missing}"
    # an old home is not documented: each name is listed once, at its home
    old = [name for name in DEPRECATED if f"automodule:: {name}\n" in page]
    assert not old, f"book/api.md documents old homes {old}"
    toc = (PACKAGE.parent / "_toc.yml").read_text()
    assert "file: book/api" in toc


@pytest.mark.parametrize("name", MODULES)
def test_docstring_cross_references_resolve(name):
    # the API page is built with -n: a :func:`name` that names nothing fails the book's build
    module = importlib.import_module(name)
    text = Path(module.__file__).read_text()
    missing = []
    for target in re.findall(r":(?:func|class|data|mod):`~?([A-Za-z_][\w.]*)`", text):
        if target.startswith("rsgeo."):
            parts, obj = target.split("."), None
            try:
                obj = importlib.import_module(".".join(parts[:2]))
                for part in parts[2:]:
                    obj = getattr(obj, part)
            except (ImportError, AttributeError):
                missing.append(target)
        elif not hasattr(module, target.split(".")[0]):
            missing.append(target)
    assert not missing, f"{name}: cross-references to nothing: {missing}"
