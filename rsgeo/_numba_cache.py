"""Numba's on-disk cache, kept consistent across rsgeo's compiled modules.

Numba caches a compiled function (``cache=True``) beside its source, keyed on
that source file alone: a kernel of :mod:`rsgeo.resample` that calls
``rsgeo._kernels.transformer.row_positions`` keeps the old machine code of
the callee after ``transformer.py`` changes and ``resampling.py`` does not (Numba's
documented limitation, "Notes on caching"). A course updated by ``git pull``
into an editable install changes files one by one, so at import rsgeo
compares a fingerprint of its compiled modules' sources with the one stored
beside the cache; if they differ, it removes those modules' cache files and
Numba compiles afresh, once.

References
----------
Numba, "Notes on caching": "functions called from cached functions are not
invalidated when their source changes".
"""

import hashlib
from pathlib import Path

__all__ = ["COMPILED_MODULES", "refresh"]

#: rsgeo's modules with functions compiled by Numba, which may call each other (paths below
#: the package's folder, without ``.py``; Numba caches each in its folder's ``__pycache__``).
COMPILED_MODULES = ("_kernels/dem", "_kernels/resampling", "_kernels/rpc", "_kernels/thin_plate",
                    "_kernels/transformer", "ortho", "registration/_genetic")

_FOLDER = Path(__file__).resolve().parent
_STAMP = "rsgeo-compiled-sources.sha256"


def refresh(folder=_FOLDER):
    """Remove the compiled modules' cache files if any of their sources changed.

    Parameters
    ----------
    folder : path-like
        The package's folder (its ``__pycache__`` holds Numba's cache).

    Returns
    -------
    bool
        Whether cache files were removed.
    """
    folder = Path(folder)
    digest = hashlib.sha256()
    for name in COMPILED_MODULES:
        try:
            digest.update((folder / f"{name}.py").read_bytes())
        except OSError:
            return False            # an unusual install (a zip): leave Numba's cache alone
    cache = folder / "__pycache__"
    stamp = cache / _STAMP
    try:
        if stamp.read_text() == digest.hexdigest():
            return False
    except OSError:
        pass
    removed = False
    for name in COMPILED_MODULES:
        module = folder / name
        for pattern in (f"{module.name}.*.nbi", f"{module.name}.*.nbc"):
            for path in (module.parent / "__pycache__").glob(pattern):
                path.unlink(missing_ok=True)
                removed = True
    try:
        cache.mkdir(exist_ok=True)
        stamp.write_text(digest.hexdigest())
    except OSError:
        pass                        # a read-only install: Numba uses its user-wide cache
    return removed
