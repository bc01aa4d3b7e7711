"""Old homes of moved public names: they keep working for one release, with a warning.

A module that moved (``rsgeo.exercises`` to ``rsgeo_course.exercises``) or a name that moved
(``rsgeo.ortho.orthorectify`` to ``rsgeo.ortho.orthorectify``) stays importable from its old
home; each use warns with a ``DeprecationWarning`` naming the new home (scikit-image's policy).
"""

import importlib
import warnings

__all__ = ["moved_names", "moved_module"]

#: The release after which the old homes go.
REMOVED_IN = "0.3"


def _warn(old, new):
    warnings.warn(f"{old} moved to {new}; import it from there ({old} goes in rsgeo "
                  f"{REMOVED_IN})", DeprecationWarning, stacklevel=3)


def moved_names(old_module, homes):
    """Module ``__getattr__`` and ``__dir__`` for an old module whose names moved.

    Parameters
    ----------
    old_module : str
        The old module's name (``__name__``).
    homes : dict
        ``{name: new module name}`` for every public name the old module had.

    Returns
    -------
    tuple
        ``(__getattr__, __dir__)`` to assign in the old module.
    """
    def __getattr__(name):
        if name not in homes:
            raise AttributeError(f"module {old_module!r} has no attribute {name!r}")
        _warn(f"{old_module}.{name}", f"{homes[name]}.{name}")
        return getattr(importlib.import_module(homes[name]), name)

    def __dir__():
        return sorted(homes)

    return __getattr__, __dir__


def moved_module(old_module, new_module):
    """Module ``__getattr__`` and ``__dir__`` for an old module that moved whole.

    Parameters
    ----------
    old_module : str
        The old module's name (``__name__``).
    new_module : str
        Where it lives now; every public name of it is forwarded.

    Returns
    -------
    tuple
        ``(__getattr__, __dir__)`` to assign in the old module.
    """
    def __getattr__(name):
        if name.startswith("__"):
            raise AttributeError(name)
        try:
            module = importlib.import_module(new_module)
        except ImportError as error:
            raise ImportError(f"{old_module} moved to {new_module}, which is not installed "
                              f"({error}); install the course beside rsgeo") from error
        _warn(f"{old_module}.{name}", f"{new_module}.{name}")
        return getattr(module, name)

    def __dir__():
        return sorted(getattr(importlib.import_module(new_module), "__all__", []))

    return __getattr__, __dir__
