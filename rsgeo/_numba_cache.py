"""Numba's on-disk cache of rsgeo's kernels: kept consistent, or done without.

Numba caches a compiled function (``cache=True``) in the first writable place of its
list (``NUMBA_CACHE_DIR``, the ``__pycache__`` beside the source, the user's cache folder),
keyed on that function's source file alone: a kernel of :mod:`rsgeo.resample` that calls
``rsgeo._kernels.transformer.row_positions`` keeps the old machine code of the callee after
``transformer.py`` changes and ``resampling.py`` does not (Numba's documented limitation,
"Notes on caching"). A course updated by ``git pull`` changes files one by one, so when the
first compiled module is imported, rsgeo compares a digest of all its compiled modules'
sources with the one stored beside each cache folder they use (the package's own or the
user-wide one); if they differ, it removes those modules' cache files there and Numba
compiles afresh, once.

Where Numba has no writable place at all (a read-only install run without a writable home),
rsgeo compiles without a cache (:data:`CACHE` is False) and says so once: every session then
pays the compilation. Nothing here changes Numba's settings or the environment.

References
----------
Numba, "Notes on caching": "functions called from cached functions are not
invalidated when their source changes".
"""

import hashlib
import warnings
from pathlib import Path

from .language import _

__all__ = ["CACHE", "COMPILED_MODULES", "cache_folder", "refresh"]

#: rsgeo's modules with functions compiled by Numba, which may call each other (paths below
#: the package's folder, without ``.py``).
COMPILED_MODULES = ("_kernels/dem", "_kernels/resampling", "_kernels/rpc", "_kernels/thin_plate",
                    "_kernels/transformer", "ortho", "registration/_genetic")

_FOLDER = Path(__file__).resolve().parent
_STAMP = "rsgeo-compiled-sources.sha256"


def cache_folder(source):
    """The folder where Numba would cache the functions of ``source``, or None if none is writable.

    Numba's own choice (its list of cache locators, ``NUMBA_CACHE_DIR`` and
    ``NUMBA_CACHE_LOCATOR_CLASSES`` included), asked for a stand-in function of that file.

    Parameters
    ----------
    source : path-like
        A Python source file.

    Returns
    -------
    pathlib.Path or None
    """
    from numba.core.caching import FunctionCache

    # a function whose code says it was defined in ``source``: what Numba's locators look at
    code = compile("def stand_in():\n    pass\n", str(source), "exec").co_consts[0]
    stand_in = type(cache_folder)(code, {})
    try:
        return Path(FunctionCache(stand_in).cache_path)
    except RuntimeError:                # "cannot cache function ...: no locator available"
        return None


def _digest(folder):
    digest = hashlib.sha256()
    for name in COMPILED_MODULES:
        digest.update((folder / f"{name}.py").read_bytes())
    return digest.hexdigest()


def _places(folder):
    """{module name: the folder Numba caches it in, or None} for the compiled modules found."""
    return {name: cache_folder(folder / f"{name}.py") for name in COMPILED_MODULES
            if (folder / f"{name}.py").exists()}


def refresh(folder=_FOLDER, places=None):
    """Remove the compiled modules' cache files wherever any of their sources changed.

    Parameters
    ----------
    folder : path-like
        The package's folder.
    places : dict, optional
        Where Numba caches each module (:func:`_places`), if already asked.

    Returns
    -------
    bool
        Whether cache files were removed.
    """
    folder = Path(folder)
    try:
        digest = _digest(folder)
    except OSError:
        return False            # an unusual install (a zip): leave Numba's cache alone
    modules_in = {}
    for name, place in (_places(folder) if places is None else places).items():
        if place is not None:
            modules_in.setdefault(place, []).append(Path(name).name)
    removed = False
    for place, modules in modules_in.items():
        stamp = place / _STAMP
        try:
            if stamp.read_text() == digest:
                continue
        except OSError:
            pass
        for module in modules:
            for pattern in (f"{module}.*.nbi", f"{module}.*.nbc"):
                for path in place.glob(pattern):
                    path.unlink(missing_ok=True)
                    removed = True
        try:
            stamp.write_text(digest)
        except OSError:
            pass
    return removed


def _cache_available(places):
    """Whether Numba can cache every compiled module; warns once when it cannot."""
    missing = [name for name, place in places.items() if place is None]
    if missing:
        warnings.warn(_(
            "Numba has no writable folder to cache rsgeo's compiled kernels in (not beside "
            "rsgeo's sources, not in the user's cache folder): rsgeo compiles them in every "
            "session, which costs seconds to a minute of CPU at each first call; set "
            "NUMBA_CACHE_DIR to a writable folder to keep them"), UserWarning, stacklevel=2)
    return not missing


# Numba is asked once where each module's cache goes: the refresh and the choice below share it
_PLACES = _places(_FOLDER)
refresh(_FOLDER, _PLACES)
#: Whether rsgeo's kernels are compiled with ``cache=True`` (False when Numba has no
#: writable cache folder for them).
CACHE = _cache_available(_PLACES)
