"""Input checks shared by every rsgeo module.

Each helper raises ``ValueError`` with a message that names the argument, what
was wrong with it and what is needed, so that a student sees the cause of an
error at the line they wrote, not a traceback from deep inside NumPy.
"""

import numpy as np

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
        raise ValueError(f"{name} must be numbers in an (n, 2) array: {error}") from None
    if array.ndim == 1 and array.shape == (2,):
        array = array[np.newaxis, :]
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(
            f"{name} must be an (n, 2) array of (x, y) pairs, got shape {array.shape}"
        )
    bad = ~np.isfinite(array).all(axis=1)
    if bad.any():
        rows = np.flatnonzero(bad)[:5].tolist()
        raise ValueError(
            f"{name} holds NaN or infinite coordinates (rows {rows}); "
            "every coordinate must be a finite number"
        )
    return array


def as_image(image, name="image"):
    """Return ``image`` as an array with 2 (rows, cols) or 3 (bands, rows, cols) dimensions."""
    array = np.asarray(image)
    if array.ndim not in (2, 3):
        raise ValueError(
            f"{name} must be 2-D (rows, cols) or 3-D (bands, rows, cols), "
            f"got {array.ndim}-D with shape {array.shape}"
        )
    if array.dtype.kind not in "uif":
        raise ValueError(f"{name} must hold integers or floats, got dtype {array.dtype}")
    if min(array.shape[-2:]) < 1:
        raise ValueError(f"{name} is empty (shape {array.shape}); it needs at least one pixel")
    return array


def check_range(value, name, low=None, high=None, why=""):
    """Return ``value`` as a float, checked to be finite and within [low, high]."""
    number = float(value)
    if not np.isfinite(number):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    if (low is not None and number < low) or (high is not None and number > high):
        bounds = f"[{low}, {high}]" if low is not None and high is not None else (
            f">= {low}" if low is not None else f"<= {high}")
        reason = f" ({why})" if why else ""
        raise ValueError(f"{name} must be {bounds}{reason}, got {value!r}")
    return number


def check_choice(value, name, choices):
    """Return ``value`` if it is one of ``choices``, else raise naming the options."""
    if value not in choices:
        raise ValueError(f"unknown {name} {value!r}; choose one of {', '.join(map(repr, choices))}")
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
    message = f"{name} must be (rows, cols), two positive integers, got {shape!r}"
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
