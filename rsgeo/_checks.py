"""Input checks shared by every rsgeo module.

Each helper raises ``ValueError`` with a message that names the argument, what
was wrong with it and what is needed, so that a student sees the cause of an
error at the line they wrote, not a traceback from deep inside NumPy.
"""

import numpy as np

from ._i18n import _

__all__ = [
    "as_points", "as_image", "as_shape", "check_range", "check_choice",
]


def as_points(points, name="points"):
    """Return ``points`` as a float64 array of shape (n, 2), finite.

    Raises
    ------
    ValueError
        If the array is not (n, 2) or holds NaN or infinite values.
    """
    try:
        array = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ValueError(_("{name} must be numbers in an (n, 2) array: {error}").format(
            name=name, error=error)) from None
    if array.ndim == 1 and array.shape == (2,):
        array = array[np.newaxis, :]
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(_("{name} must be an (n, 2) array of (x, y) pairs, got shape {shape}")
                         .format(name=name, shape=array.shape))
    bad = ~np.isfinite(array).all(axis=1)
    if bad.any():
        rows = np.flatnonzero(bad)[:5].tolist()
        raise ValueError(_("{name} holds NaN or infinite coordinates (rows {rows}); every "
                           "coordinate must be a finite number").format(name=name, rows=rows))
    return array


def as_image(image, name="image"):
    """Return ``image`` as an array with 2 (rows, cols) or 3 (bands, rows, cols) dimensions."""
    array = np.asarray(image)
    if array.ndim not in (2, 3):
        raise ValueError(_("{name} must be 2-D (rows, cols) or 3-D (bands, rows, cols), got "
                           "{ndim}-D with shape {shape}").format(name=name, ndim=array.ndim,
                                                                 shape=array.shape))
    if array.dtype.kind not in "uif":
        raise ValueError(_("{name} must hold integers or floats, got dtype {dtype}").format(
            name=name, dtype=array.dtype))
    if min(array.shape[-2:]) < 1:
        raise ValueError(_("{name} is empty (shape {shape}); it needs at least one pixel").format(
            name=name, shape=array.shape))
    return array


def check_range(value, name, low=None, high=None, why=""):
    """Return ``value`` as a float, checked to be finite and within [low, high]."""
    number = float(value)
    if not np.isfinite(number):
        raise ValueError(_("{name} must be a finite number, got {value!r}").format(
            name=name, value=value))
    if (low is not None and number < low) or (high is not None and number > high):
        bounds = f"[{low}, {high}]" if low is not None and high is not None else (
            f">= {low}" if low is not None else f"<= {high}")
        reason = f" ({why})" if why else ""
        raise ValueError(_("{name} must be {bounds}{reason}, got {value!r}").format(
            name=name, bounds=bounds, reason=reason, value=value))
    return number


def check_choice(value, name, choices):
    """Return ``value`` if it is one of ``choices``, else raise naming the options."""
    if value not in choices:
        raise ValueError(_("unknown {name} {value!r}; choose one of {choices}").format(
            name=name, value=value, choices=", ".join(map(repr, choices))))
    return value


def as_shape(shape, name="shape"):
    """Return ``shape`` as a (rows, cols) tuple of positive ints, else raise ValueError.

    Parameters
    ----------
    shape : sequence of two numbers
        A grid size, (rows, cols); whole-valued floats are accepted.
    name : str
        Its name in the error message.

    Returns
    -------
    (int, int)

    Raises
    ------
    ValueError
        If ``shape`` is a single number, has other than two entries, or holds
        anything but positive whole numbers.

    Examples
    --------
    >>> as_shape((351.0, 369))
    (351, 369)
    >>> as_shape(351)
    Traceback (most recent call last):
    ...
    ValueError: shape must be (rows, cols), two positive integers, got 351
    """
    message = _("{name} must be (rows, cols), two positive integers, got {shape!r}").format(
        name=name, shape=shape)
    try:
        values = tuple(shape)
    except TypeError:
        raise ValueError(message) from None
    if len(values) != 2:
        raise ValueError(message)
    try:
        ok = all(float(n).is_integer() and n >= 1 for n in values)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ValueError(message)
    return int(values[0]), int(values[1])
