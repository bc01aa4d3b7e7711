"""Old homes of moved public names: they keep working for one release, with a warning.

A module that moved (``rsgeo.exercises`` to ``rsgeo_course.exercises``) or a name that moved
(``rsgeo.ortho.orthorectify`` to ``rsgeo.ortho.orthorectify``) stays importable from its old
home; each use warns with a ``DeprecationWarning`` naming the new home (scikit-image's policy).
"""

import importlib
import warnings

__all__ = ["moved_names", "moved_module", "renamed_arguments"]

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
        ``(__getattr__, __dir__)`` to assign in the old module; ``__getattr__.homes`` is
        ``homes``.
    """
    def __getattr__(name):
        if name not in homes:
            raise AttributeError(f"module {old_module!r} has no attribute {name!r}")
        _warn(f"{old_module}.{name}", f"{homes[name]}.{name}")
        return getattr(importlib.import_module(homes[name]), name)

    def __dir__():
        return sorted(homes)

    __getattr__.homes = dict(homes)
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
        if not hasattr(module, name):
            raise AttributeError(f"module {old_module!r} (now {new_module}) has no attribute "
                                 f"{name!r}")
        _warn(f"{old_module}.{name}", f"{new_module}.{name}")
        return getattr(module, name)

    def __dir__():
        return sorted(getattr(importlib.import_module(new_module), "__all__", []))

    return __getattr__, __dir__


def renamed_arguments(old_order, renamed):
    """Decorate a function whose arguments were renamed or made keyword-only.

    A call in the old form keeps working for one release, with a ``DeprecationWarning``: an
    old keyword (``nodata=``) is passed as its new name (``dst_nodata=``), and arguments
    given by position beyond the new positional ones are passed by their old names.

    Parameters
    ----------
    old_order : sequence of str
        The function's parameters in their old order (for arguments given by position).
    renamed : dict
        ``{old name: new name}``.

    Returns
    -------
    callable
        The decorator.
    """
    import functools
    import inspect

    def decorate(function):
        parameters = inspect.signature(function).parameters.values()
        positional = sum(parameter.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD
                         for parameter in parameters)
        where = f"{function.__module__.split('._')[0]}.{function.__name__}"

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            if len(args) > positional:
                extra = old_order[positional:len(args)]
                if len(extra) < len(args) - positional:
                    raise TypeError(f"{where} takes {positional} positional arguments, got "
                                    f"{len(args)}")
                warnings.warn(f"{where}: passing {', '.join(extra)} by position is deprecated; "
                              f"pass {', '.join(renamed.get(name, name) for name in extra)} "
                              "by keyword", DeprecationWarning, stacklevel=2)
                for name, value in zip(extra, args[positional:], strict=True):
                    if renamed.get(name, name) in kwargs or name in kwargs:
                        raise TypeError(f"{where} got {name} twice")
                    kwargs[renamed.get(name, name)] = value
                args = args[:positional]
            for old, new in renamed.items():
                if old in kwargs:
                    if new in kwargs:
                        raise TypeError(f"{where} got both {old}= (its old name) and {new}=")
                    warnings.warn(f"{where}: {old}= is now {new}=", DeprecationWarning,
                                  stacklevel=2)
                    kwargs[new] = kwargs.pop(old)
            return function(*args, **kwargs)

        return wrapper

    return decorate
