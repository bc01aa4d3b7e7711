"""Input checks shared by every rsgeo module: one family, ``as_...`` returns the value checked.

Each helper raises an :class:`rsgeo.errors.RsgeoError` subclass (a ``ValueError``) with a
message that names the argument, what was wrong with it and what is needed, so that a student
sees the cause of an error at the line they wrote, not a traceback from deep inside NumPy.
"""

import math
import numbers
import warnings

import numpy as np

from ._proj_database import check_database
from .errors import CRSError, GCPError, GridError, ImageError, RsgeoError
from .language import N_, _

__all__ = [
    "as_points", "as_points_3d", "as_image", "as_bands_first", "as_nodata", "as_shape", "as_scale",
    "as_resolution", "as_num_threads", "as_number", "as_integer", "as_finite", "check_choice",
    "as_crs",
    "as_output_shape", "as_affine", "memory_bytes", "as_lon_lat_height", "few_values",
    "as_invertible_affine", "as_flags", "as_broadcast",
]


def as_points(points, name="points"):
    """Return ``points`` as a float64 array of shape (n, 2), finite.

    Parameters
    ----------
    points : array_like
        (n, 2) coordinates, or a single (x, y) pair.
    name : str
        Its name in the error message.

    Returns
    -------
    ndarray
        (n, 2) float64.

    Raises
    ------
    TypeError
        If the array holds complex numbers, booleans or text.
    rsgeo.errors.GCPError
        If the array is not (n, 2) or holds NaN or infinite values.
    """
    try:
        kind = np.asarray(points).dtype.kind
    except (TypeError, ValueError):
        kind = "O"                      # ragged or odd input: the conversion below says why
    if kind in "cbUS":                  # NumPy would drop an imaginary part or read True as 1
        what = {"c": "complex", "b": "bool", "U": "text", "S": "text"}[kind]
        raise TypeError(_("{name} must hold real numbers (map or image coordinates), got a "
                          "{what} array").format(name=name, what=what))
    try:
        array = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise GCPError(_("{name} must be numbers in an (n, 2) array: {error}").format(
            name=name, error=error)) from None
    if array.ndim == 1 and array.shape == (2,):
        array = array[np.newaxis, :]
    if array.ndim != 2 or array.shape[1] != 2:
        raise GCPError(_("{name} must be an (n, 2) array of (x, y) pairs, got shape {shape}")
                       .format(name=name, shape=array.shape))
    bad = ~np.isfinite(array).all(axis=1)
    if bad.any():
        rows = np.flatnonzero(bad)[:5].tolist()
        raise GCPError(_("{name} holds NaN or infinite coordinates (rows {rows}); every "
                         "coordinate must be a finite number").format(name=name, rows=rows))
    return array


def as_points_3d(points, name="points", axes="X, Y, Z"):
    """Return ``points`` as a float64 array of shape (n, 3), finite: ground or map points.

    Parameters
    ----------
    points : array_like
        (n, 3) coordinates, or a single point of three.
    name : str
        Its name in the error messages.
    axes : str
        What the three columns are, for the messages (e.g. ``"x, y, height"``); translated.

    Returns
    -------
    ndarray
        (n, 3) float64.

    Raises
    ------
    TypeError
        If the array holds complex numbers, booleans or text.
    rsgeo.errors.GCPError
        If the array is not (n, 3) or holds NaN or infinite values.
    """
    try:
        kind = np.asarray(points).dtype.kind
    except (TypeError, ValueError):
        kind = "O"                      # ragged or odd input: the conversion below says why
    if kind in "cbUS":                  # NumPy would drop an imaginary part or read True as 1
        raise TypeError(_("{name} must hold real numbers ({axes})").format(name=name,
                                                                            axes=_(axes)))
    try:
        array = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise GCPError(_("{name} must be numbers in an (n, 3) array: {error}").format(
            name=name, error=error)) from None
    if array.shape == (3,):
        array = array[np.newaxis, :]
    if array.ndim != 2 or array.shape[1] != 3:
        raise GCPError(_("{name} must be an (n, 3) array of ({axes}) points, got shape "
                         "{shape}").format(name=name, axes=_(axes), shape=array.shape))
    if not np.isfinite(array).all():
        rows = np.flatnonzero(~np.isfinite(array).all(axis=1))[:5].tolist()
        raise GCPError(_("{name} holds NaN or infinite coordinates (rows {rows}); every "
                         "coordinate must be a finite number").format(name=name, rows=rows))
    return array


def as_image(image, name="image"):
    """Return ``image`` as an array with 2 (rows, cols) or 3 (bands, rows, cols) dimensions.

    Parameters
    ----------
    image : array_like
        Integers or floats, at least one pixel.
    name : str
        Its name in the error message.

    Returns
    -------
    ndarray
        ``image`` as an array (not copied when it is one).

    Raises
    ------
    rsgeo.errors.ImageError
        If the array is not 2-D or 3-D, holds neither integers nor floats, or is empty.
    """
    array = np.asarray(image)
    if array.ndim not in (2, 3):
        raise ImageError(_("{name} must be 2-D (rows, cols) or 3-D (bands, rows, cols), got "
                           "{ndim}-D with shape {shape}").format(name=name, ndim=array.ndim,
                                                                 shape=array.shape))
    if array.dtype.kind not in "uif":
        raise ImageError(_("{name} must hold integers or floats, got dtype {dtype}").format(
            name=name, dtype=array.dtype))
    if min(array.shape[-2:]) < 1:
        raise ImageError(_("{name} is empty (shape {shape}); it needs at least one pixel").format(
            name=name, shape=array.shape))
    return array


def as_bands_first(image, name="image"):
    """Return ``image`` unchanged unless a 3-D image looks bands-last (rows, cols, 3 or 4).

    rsgeo, like rasterio and GDAL, stores several bands first: (bands, rows,
    cols). An RGB array from matplotlib, Pillow or OpenCV is (rows, cols, 3);
    read bands first, it would be 351 "bands" of 369 x 3 pixels, and a warp or
    a GeoTIFF made from it is silently wrong.

    Parameters
    ----------
    image : ndarray
        The image to check.
    name : str
        Its name in the error message.

    Returns
    -------
    ndarray
        ``image`` unchanged.

    Raises
    ------
    rsgeo.errors.ImageError
        If ``image`` is 3-D, its last axis has 3 or 4 entries and its first
        two axes are both more than four times longer.

    Examples
    --------
    >>> as_bands_first(np.zeros((3, 40, 50))).shape
    (3, 40, 50)
    >>> as_bands_first(np.zeros((40, 50, 3)))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rsgeo.errors.ImageError: image has shape (40, 50, 3), which looks like bands last ...
    """
    shape = np.shape(image)
    if len(shape) == 3 and shape[2] in (3, 4) and min(shape[0], shape[1]) > 4 * shape[2]:
        raise ImageError(_("{name} has shape {shape}, which looks like bands last "
                           "(rows, cols, bands); rsgeo needs bands first (bands, rows, "
                           "cols): pass np.moveaxis({name}, -1, 0)").format(
                name=name, shape=tuple(shape)))
    return image


def as_nodata(nodata, dtype):
    """Return ``nodata`` if it is representable in ``dtype``, else raise.

    Parameters
    ----------
    nodata : int, float or None
        The value for positions outside the image; None for none.
    dtype : numpy dtype or str
        The image's dtype.

    Returns
    -------
    int, float or None
        ``nodata`` as an int for an integer dtype, unchanged otherwise.

    Raises
    ------
    TypeError
        If ``nodata`` is not a real number (a bool, a string, a complex, an array).
    rsgeo.errors.ImageError
        If ``dtype`` is an integer type and ``nodata`` is not a finite whole
        number inside its range, or ``dtype`` is float16 or float32 and ``nodata``
        is finite but beyond its largest value (it would be stored as infinity).

    Examples
    --------
    >>> as_nodata(255.0, np.uint8)
    255
    >>> as_nodata(-1, np.uint8)
    Traceback (most recent call last):
    ...
    rsgeo.errors.ImageError: nodata=-1 does not fit dtype uint8 (needs an integer in [0, 255])
    """
    if nodata is None:
        return None
    if (np.ndim(nodata) != 0 or isinstance(nodata, (bool, np.bool_, str, bytes))
            or not isinstance(nodata, (numbers.Real, np.integer, np.floating))):
        raise TypeError(_("nodata must be a real number (or None for no nodata), got "
                          "{value!r} of type {kind}").format(value=nodata,
                                                            kind=type(nodata).__name__))
    dtype = np.dtype(dtype)
    if dtype.kind in "ui":
        info = np.iinfo(dtype)
        if not (math.isfinite(float(nodata)) and float(nodata).is_integer()
                and info.min <= nodata <= info.max):
            raise ImageError(_("nodata={nodata!r} does not fit dtype {dtype} (needs an "
                               "integer in [{info_min}, {info_max}])").format(
                    nodata=nodata, dtype=dtype, info_min=info.min, info_max=info.max))
        return int(nodata)
    # a finite nodata beyond a narrow float's range would be stored as infinity; compared as
    # Python floats, so that NumPy casts nothing (and warns of no overflow)
    if (dtype.kind == "f" and dtype.itemsize < 8 and math.isfinite(float(nodata))
            and abs(float(nodata)) > float(np.finfo(dtype).max)):
        raise ImageError(_(
            "nodata={nodata!r} does not fit dtype {dtype} (its largest finite value is "
            "{high:g}; beyond it the value becomes inf); pick a value the dtype can hold").format(
                nodata=nodata, dtype=dtype, high=float(np.finfo(dtype).max)))
    return nodata


def as_shape(shape, name="shape"):
    """Return ``shape`` as a (rows, cols) tuple of positive ints, else raise.

    Parameters
    ----------
    shape : sequence of two numbers
        A grid size, (rows, cols); whole-valued floats are accepted.
    name : str
        Its name in the error message.

    Returns
    -------
    (int, int)
        Rows and columns.

    Raises
    ------
    rsgeo.errors.GridError
        If ``shape`` is a single number, has other than two entries, or holds
        anything but positive whole numbers.

    Examples
    --------
    >>> as_shape((351.0, 369))
    (351, 369)
    >>> as_shape(351)
    Traceback (most recent call last):
    ...
    rsgeo.errors.GridError: shape must be (rows, cols), two positive integers, got 351
    """
    message = _("{name} must be (rows, cols), two positive integers, got {shape!r}").format(
        name=name, shape=shape)
    try:
        values = tuple(shape)
    except TypeError:
        raise GridError(message) from None
    if len(values) != 2:
        raise GridError(message)
    try:
        ok = all(float(n).is_integer() and n >= 1 for n in values)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise GridError(message)
    return int(values[0]), int(values[1])


def _positive_pair(value, name, meaning):
    """``value`` (one number for both, or two) as two finite floats above 0, else GridError
    naming ``name`` and saying what it means."""
    message = _("{name} must be one or two finite numbers above 0 ({meaning}), got "
                "{value!r}").format(name=name, meaning=_(meaning), value=value)
    try:
        values = np.asarray(value, dtype=np.float64).ravel()
    except (TypeError, ValueError):
        raise GridError(message) from None
    if values.size == 1:
        values = np.repeat(values, 2)
    if values.size != 2 or not (np.isfinite(values).all() and (values > 0).all()):
        raise GridError(message)
    return float(values[0]), float(values[1])


def as_scale(scale):
    """Return a kernel scale as two positive floats (xscale, yscale), else raise.

    Parameters
    ----------
    scale : float or (float, float)
        GDAL's XSCALE and YSCALE: output pixels per source pixel along the
        rows and the columns (below 1 when downsampling). One number is used
        for both.

    Returns
    -------
    (float, float)
        xscale and yscale.

    Raises
    ------
    rsgeo.errors.GridError
        If ``scale`` is not one or two finite numbers above zero.

    Examples
    --------
    >>> as_scale(0.125)
    (0.125, 0.125)
    >>> as_scale((0.5, 0))
    Traceback (most recent call last):
    ...
    rsgeo.errors.GridError: scale must be one or two finite numbers above 0 (output pixels per source pixel, xscale and yscale, e.g. 0.125 for 2.5 m taken to 20 m), got (0.5, 0)
    """  # noqa: E501  (a doctest's expected line)
    return _positive_pair(scale, "scale", N_("output pixels per source pixel, xscale and "
                                             "yscale, e.g. 0.125 for 2.5 m taken to 20 m"))


def as_resolution(resolution):
    """Return a pixel size as two positive floats (xres, yres), else raise.

    Parameters
    ----------
    resolution : float or (float, float)
        Output pixel size in map units (gdalwarp's ``-tr``); one number for both.

    Returns
    -------
    (float, float)
        xres and yres.

    Raises
    ------
    rsgeo.errors.GridError
        If ``resolution`` is not one or two finite numbers above 0.

    Examples
    --------
    >>> as_resolution(20)
    (20.0, 20.0)
    """
    return _positive_pair(resolution, "resolution", N_("the output pixel size in map units, "
                                                       "xres and yres, e.g. 20 for 20 m "
                                                       "pixels"))


def as_num_threads(num_threads):
    """Return ``num_threads`` as an int from 1 to Numba's thread count, else raise.

    Parameters
    ----------
    num_threads : int
        Threads to share a kernel's rows; a whole-valued float is accepted.

    Returns
    -------
    int
        ``num_threads`` as an int.

    Raises
    ------
    rsgeo.errors.RsgeoError
        If ``num_threads`` is not a whole number from 1 to
        ``numba.config.NUMBA_NUM_THREADS``.

    Examples
    --------
    >>> as_num_threads(1)
    1
    >>> as_num_threads(0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rsgeo.errors.RsgeoError: num_threads must be a whole number from 1 to ...
    """
    import numba  # only the kernels' callers need it: importing Numba takes a second

    most = numba.config.NUMBA_NUM_THREADS
    try:
        ok = float(num_threads).is_integer() and 1 <= num_threads <= most
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise RsgeoError(_("num_threads must be a whole number from 1 to {most} (the "
                           "threads Numba may use here, NUMBA_NUM_THREADS), got "
                           "{num_threads!r}").format(most=most, num_threads=num_threads))
    return int(num_threads)


def _bounds_text(low, high):
    if low is not None and high is not None:
        return f"[{low}, {high}]"
    return f">= {low}" if low is not None else f"<= {high}"


def as_number(value, name, low=None, high=None, why=""):
    """Return ``value`` as a float, checked to be a real, finite number within [low, high].

    A string, a bool or a complex number is not taken for a number (``float("2")`` and
    ``float(True)`` would be): it raises ``TypeError``.

    Parameters
    ----------
    value : float
        The number to check (a Python or NumPy real number, or a 0-d array of one).
    name : str
        Its name in the error message.
    low, high : float, optional
        The bounds, inclusive; None for none.
    why : str
        Said in parentheses after the bounds.

    Returns
    -------
    float
        ``value`` as a float.

    Raises
    ------
    TypeError
        If ``value`` is not a real number (a string, a bool, a complex, a sequence).
    rsgeo.errors.RsgeoError
        If ``value`` is not finite or lies outside the bounds.

    Examples
    --------
    >>> as_number(np.float32(2.5), "tolerance", low=0)
    2.5
    >>> as_number("2.5", "tolerance")
    Traceback (most recent call last):
    ...
    TypeError: tolerance must be a number, got str '2.5'
    """
    array = np.asarray(value) if not isinstance(value, (str, bytes)) else None
    if (array is None or array.ndim != 0 or isinstance(value, (bool, np.bool_))
            or not np.issubdtype(array.dtype, np.number)
            or np.issubdtype(array.dtype, np.complexfloating)):
        raise TypeError(_("{name} must be a number, got {kind} {value!r}").format(
            name=name, kind=type(value).__name__, value=value))
    number = float(array)
    if not np.isfinite(number):
        raise RsgeoError(_("{name} must be a finite number, got {value!r}").format(
            name=name, value=value))
    if (low is not None and number < low) or (high is not None and number > high):
        raise RsgeoError((_("{name} must be {bounds} ({why}), got {value!r}") if why else
                          _("{name} must be {bounds}, got {value!r}")).format(
            name=name, bounds=_bounds_text(low, high), why=_(why), value=value))
    return number


def as_finite(values, name, error=RsgeoError):
    """Return ``values`` as a float64 array, checked to hold only finite numbers.

    Parameters
    ----------
    values : array_like
        Numbers of any shape.
    name : str
        The argument's name, for the message.
    error : type
        The :class:`rsgeo.errors.RsgeoError` subclass to raise (a sensor model raises
        ``ModelError``).

    Returns
    -------
    ndarray
        ``values`` as float64.

    Raises
    ------
    TypeError
        If ``values`` are booleans, text or complex numbers: ``float(True)`` and
        ``float("30")`` would read them as numbers, and a complex would lose its imaginary part.
    RsgeoError
        ``error``: if ``values`` are not numbers, or hold NaN or infinite values.

    Examples
    --------
    >>> as_finite([1, 2.5], "height").tolist()
    [1.0, 2.5]
    >>> as_finite("30", "view_zenith_deg")
    Traceback (most recent call last):
    ...
    TypeError: view_zenith_deg must be a number or numbers, got str '30'
    """
    _refuse_non_numbers(values, name)
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise error(_("{name} must be numbers, got {value!r}").format(
            name=name, value=values)) from None
    if not np.isfinite(array).all():
        raise error(_("{name} holds NaN or infinite values; every value must be finite")
                    .format(name=name))
    return array


def _refuse_non_numbers(values, name):
    """TypeError for booleans, text and complex numbers, which NumPy would take as numbers."""
    try:
        array = np.asarray(values)
    except (TypeError, ValueError):
        return                          # ragged: the float conversion says why
    kind = array.dtype.kind
    if kind == "O":
        odd = any(isinstance(v, (bool, np.bool_, str, bytes, complex)) for v in array.flat)
    else:
        odd = kind in "bcUS"
    if odd:
        raise TypeError(_("{name} must be a number or numbers, got {kind} {value!r}").format(
            name=name, kind=type(values).__name__, value=values))


def as_integer(value, name, low=None, high=None, why=""):
    """Return ``value`` as an int, checked to be a whole number within [low, high].

    Parameters
    ----------
    value : int
        The integer to check (a Python or NumPy integer, or a float with no fractional part,
        such as 3.0); not a bool, a string, or a float such as 2.5.
    name : str
        Its name in the error message.
    low, high : int, optional
        The bounds, inclusive; None for none.
    why : str
        Said in parentheses after the bounds.

    Returns
    -------
    int
        ``value`` as an int.

    Raises
    ------
    TypeError
        If ``value`` is not a real number (see :func:`as_number`).
    rsgeo.errors.RsgeoError
        If ``value`` has a fractional part or lies outside the bounds.

    Examples
    --------
    >>> as_integer(np.int64(3), "iterations", low=1)
    3
    >>> as_integer(2.5, "iterations", low=1)
    Traceback (most recent call last):
    ...
    rsgeo.errors.RsgeoError: iterations must be a whole number, got 2.5
    """
    number = as_number(value, name)
    if number != int(number):
        raise RsgeoError(_("{name} must be a whole number, got {value!r}").format(
            name=name, value=value))
    return int(as_number(int(number), name, low, high, why))


def check_choice(value, name, choices):
    """Return ``value`` if it is one of ``choices``, else raise naming the options.

    Parameters
    ----------
    value : object
        The choice made.
    name : str
        What is chosen, in the error message.
    choices : sequence
        The options.

    Returns
    -------
    object
        ``value``.

    Raises
    ------
    rsgeo.errors.RsgeoError
        If ``value`` is not one of ``choices``.
    """
    if value not in choices:
        raise RsgeoError(_("unknown {name} {value!r}; choose one of {choices}").format(
            name=name, value=value, choices=", ".join(map(repr, choices))))
    return value


def memory_bytes():
    """The machine's physical memory in bytes, or None where the OS does not say.

    Returns
    -------
    int or None
        ``SC_PAGE_SIZE`` times ``SC_PHYS_PAGES`` (POSIX ``sysconf``).
    """
    import os

    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return None


def as_output_shape(shape, dtype, bands=1, name="shape", limit=None):
    """Return an output grid's (rows, cols), refused before allocating if it cannot fit.

    An output array is allocated whole (a warp keeps input + output + one
    strip), so a grid whose array alone is larger than the machine's physical
    memory can only end in a MemoryError after minutes of swapping, or in
    the operating system killing Python. The limit is that memory (not a
    fixed count of pixels: 2**31 float64 pixels need 16 GiB, which some
    machines have and others do not).

    Parameters
    ----------
    shape : (rows, cols)
        The output grid size, as :func:`as_shape` takes it.
    dtype : numpy dtype or str
        The output's dtype.
    bands : int
        Bands of the output.
    name : str
        Its name in the error message.
    limit : int, optional
        Largest output in bytes; the machine's physical memory by default
        (no limit where the OS does not say).

    Returns
    -------
    (int, int)
        Rows and columns.

    Raises
    ------
    rsgeo.errors.GridError
        If ``shape`` is not two positive integers, or the output would take
        more bytes than ``limit``; the message gives its size in GiB and the
        fix (a coarser resolution, or a window of the grid).

    Examples
    --------
    >>> as_output_shape((351, 369), np.uint8)
    (351, 369)
    >>> as_output_shape((10**6, 10**6), np.float32)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rsgeo.errors.GridError: the output (shape=(1000000, 1000000), 1 band(s) of float32) ...
    """
    rows, cols = as_shape(shape, name)
    dtype = np.dtype(dtype)
    limit = memory_bytes() if limit is None else limit
    needed = float(rows) * float(cols) * bands * dtype.itemsize
    if limit is not None and needed > limit:
        raise GridError(_(
            "the output ({name}=({rows}, {cols}), {bands} band(s) of {dtype}) would take "
            "{gib:.1f} GiB, more than the {limit:.1f} GiB this machine has; choose a coarser "
            "resolution (fewer, larger pixels) or warp a window of the grid at a time"
        ).format(name=name, rows=rows, cols=cols, bands=bands, dtype=dtype,
                 gib=needed / 2 ** 30, limit=limit / 2 ** 30))
    return rows, cols


def as_affine(transform, name="transform", gdal_tuple=False):
    """Return ``transform`` if it is a finite ``affine.Affine``, else raise.

    rsgeo's one geotransform rule: a geotransform is an ``affine.Affine``. A GDAL geotransform,
    a 6-tuple (c, a, b, f, d, e), is not taken for one: ``affine.Affine(*t)`` would read it in
    another order without a word; ``affine.Affine.from_gdal(*t)`` converts it. The verbs that
    read a GDAL 6-tuple before this rule (``data.save``, ``dem.dem_height``,
    ``ortho.orthorectify``, ``heights.geoid_on_grid``) still do for one release
    (``gdal_tuple=True``), with a ``DeprecationWarning``.

    Parameters
    ----------
    transform : affine.Affine
        A geotransform (pixel corner -> map) or its inverse.
    name : str
        Its name in the error message.
    gdal_tuple : bool, optional
        Also read a sequence of 6 numbers in GDAL's order (deprecated, with a warning), as
        the verbs that read one before the rule still do.

    Returns
    -------
    affine.Affine
        ``transform``.

    Raises
    ------
    TypeError
        If ``transform`` is not an ``affine.Affine`` (the message says how to
        convert a GDAL 6-tuple: ``affine.Affine.from_gdal(*t)``).
    rsgeo.errors.GridError
        If it holds NaN or infinity, or is singular (its determinant a e - b d is 0
        to rounding: every cell would land on one line or point).

    Examples
    --------
    >>> import affine
    >>> as_affine(affine.Affine.identity()) == affine.Affine.identity()
    True
    >>> as_affine((0.0, 1.0, 0.0, 0.0, 0.0, -1.0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    TypeError: transform must be an affine.Affine, got tuple ...
    """
    import affine

    if gdal_tuple:
        return _from_gdal_sequence(transform, name)
    if not isinstance(transform, affine.Affine):
        raise TypeError(_(
            "{name} must be an affine.Affine, got {kind} {value!r}; for a GDAL geotransform "
            "(c, a, b, f, d, e) use affine.Affine.from_gdal(*{name}), for rasterio's order "
            "(a, b, c, d, e, f) affine.Affine(*{name})").format(
                name=name, kind=type(transform).__name__, value=transform))
    if not np.isfinite(np.asarray(transform[:6], dtype=np.float64)).all():
        raise GridError(_("{name} holds NaN or infinity: {value!r}; every coefficient of a "
                          "geotransform must be finite").format(name=name, value=transform))
    a, b, _c, d, e, _f = transform[:6]
    # rank-deficient to rounding: all cells of a grid would fall on one line (or point)
    if abs(a * e - b * d) <= 1e-12 * (abs(a * e) + abs(b * d)):
        raise GridError(_("{name} {value!r} is singular (its determinant a e - b d is 0): it "
                          "maps every cell onto one line or point; a geotransform or mapping "
                          "needs a nonzero pixel width and height").format(
                              name=name, value=transform))
    return transform


def as_crs(crs, name="crs"):
    """A rasterio CRS from a code, a string or a CRS, refusing one PROJ does not know.

    Parameters
    ----------
    crs : str, int or rasterio.crs.CRS
        ``"EPSG:29193"``, ``29193``, a WKT or PROJ string, or a CRS.
    name : str
        The argument's name, for the error message.

    Returns
    -------
    rasterio.crs.CRS

    Raises
    ------
    rsgeo.errors.CRSError
        If ``crs`` is None or PROJ does not recognise it; if PROJ's database is not found (a
        broken install: ``PROJ_DATA`` pointing elsewhere), that is what the message says.

    Examples
    --------
    >>> as_crs(31983).to_epsg()
    31983
    """
    from rasterio.crs import CRS
    from rasterio.errors import CRSError as RasterioCRSError

    if crs is None:
        raise CRSError(_("{name} is None; a CRS is needed, e.g. 'EPSG:31983' (SIRGAS "
                         "2000 / UTM zone 23S)").format(name=name))
    if isinstance(crs, CRS):
        return crs
    try:
        value = (CRS.from_epsg(crs) if isinstance(crs, (int, np.integer))
                 else CRS.from_user_input(crs))
    except (RasterioCRSError, TypeError, ValueError) as error:
        # "not a CRS that PROJ knows" is every CRS when PROJ has no database: say that instead
        check_database()
        raise CRSError(_("{name} {crs!r} is not a CRS that PROJ knows ({error}); give "
                         "an EPSG code such as 'EPSG:31983', a WKT or a PROJ string").format(
                name=name, crs=crs, error=error)) from None
    return value


def few_values(values):
    """The first values of an array for an error message: ``"1, 2, 3 ... (8 values)"``.

    Parameters
    ----------
    values : array_like
        The values a message quotes (the ones that were wrong).

    Returns
    -------
    str
        At most five values, then how many there were.

    Examples
    --------
    >>> few_values([91.0, 95.5])
    '91, 95.5'
    """
    values = np.ravel(values)
    shown = ", ".join(f"{v:g}" for v in values[:5])
    return shown + (f" ... ({values.size} values)" if values.size > 5 else "")


def as_broadcast(arrays, names, error=RsgeoError):
    """Arrays broadcast to one shape, or an error naming each argument's shape.

    Parameters
    ----------
    arrays : sequence of ndarray
        Already checked (e.g. by :func:`as_finite`).
    names : sequence of str
        Their names, for the message.
    error : type
        The :class:`rsgeo.errors.RsgeoError` subclass to raise.

    Returns
    -------
    list of ndarray
        ``np.broadcast_arrays(*arrays)``.

    Raises
    ------
    RsgeoError
        ``error``: if the shapes do not broadcast (one value, or one per point, for each).

    Examples
    --------
    >>> as_broadcast([np.zeros(3), np.zeros(2)], ["lon", "lat"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rsgeo.errors.RsgeoError: lon and lat must have one shape (or be single values), got ...
    """
    arrays = [np.asarray(a) for a in arrays]
    try:
        return np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = ", ".join(f"{name} {array.shape}" for name, array in zip(names, arrays))
        raise error(_("{names} must have one shape (or be single values), got {shapes}")
                    .format(names=" and ".join([", ".join(names[:-1]), names[-1]]
                                               if len(names) > 1 else names),
                            shapes=shapes)) from None


def as_lon_lat_height(lon, lat, height, west=-180.0):
    """Longitudes, latitudes and heights checked (degrees, metres) and broadcast together.

    Parameters
    ----------
    lon, lat : array_like
        Degrees: longitude in [west, 360], latitude in [-90, 90].
    height : array_like
        Metres.
    west : float
        The westernmost longitude accepted: -180, or -360 where a model folds longitudes
        around its own centre (an RPC near the antimeridian reaches a little west of -180).

    Returns
    -------
    tuple of ndarray
        ``lon, lat, height`` broadcast to one shape.

    Raises
    ------
    CRSError
        If a latitude or longitude is out of its range (swapped, or projected metres).
    ValueError
        If a value is not finite.
    """
    lon = as_finite(lon, "lon")
    lat = as_finite(lat, "lat")
    height = as_finite(height, "height")
    if np.any(np.abs(lat) > 90):
        raise CRSError(_("lat must be in [-90, 90] degrees, got {few} (longitude and "
                         "latitude swapped?)").format(few=few_values(lat[np.abs(lat) > 90])))
    if np.any((lon < west) | (lon > 360)):
        raise CRSError(_("lon must be in [{west:g}, 360] degrees, got {few} (projected "
                         "metres given instead of degrees?)").format(
                west=west, few=few_values(lon[(lon < west) | (lon > 360)])))
    return as_broadcast([lon, lat, height], ["lon", "lat", "height"])


def as_invertible_affine(transform, name):
    """Return ``transform``, an affine geotransform that can be inverted, else raise.

    Parameters
    ----------
    transform : affine.Affine
        A geotransform (pixel -> map).
    name : str
        Its name in the error message.

    Returns
    -------
    affine.Affine
        ``transform``.

    Raises
    ------
    GridError
        If it is not an affine transform, or its pixel axes are degenerate (no inverse).
    """
    try:
        determinant = transform.a * transform.e - transform.b * transform.d
    except AttributeError:
        raise GridError(_("{name} must be an affine.Affine geotransform (pixel -> map), "
                          "got {kind}").format(name=name, kind=type(transform).__name__)) from None
    if not np.isfinite(determinant) or determinant == 0:
        raise GridError(_("{name} cannot be inverted (its pixel axes are degenerate): "
                          "{transform!r}").format(name=name, transform=transform))
    return transform


def _from_gdal_sequence(transform, name):
    """``as_affine(..., gdal_tuple=True)``: an Affine as it is, a GDAL-ordered 6-sequence
    (x0, pixel width, row rotation, y0, column rotation, pixel height) converted with a
    DeprecationWarning. One whose pixel width or height is 0 while the other is not is
    affine.Affine's order read the wrong way: refused, as is any transform whose pixels have
    no area."""
    import affine

    if isinstance(transform, affine.Affine):
        gt = transform.to_gdal()
    else:
        if isinstance(transform, (str, bytes)) or not hasattr(transform, "__len__"):
            raise TypeError(_(
                "{name} must be an affine.Affine or 6 finite numbers in GDAL's order (x0, "
                "pixel width, row rotation, y0, column rotation, pixel height), got "
                "{kind}").format(
                    name=name, kind=type(transform).__name__))
        try:
            gt = tuple(float(v) for v in transform)
        except (TypeError, ValueError):
            gt = None
        if gt is None or len(gt) != 6 or not np.isfinite(gt).all():
            raise GridError(_(
                "{name} must be an affine.Affine or 6 finite numbers in GDAL's order (x0, "
                "pixel width, row rotation, y0, column rotation, pixel height), got "
                "{value!r}").format(name=name, value=transform))
        warnings.warn(f"{name} as a GDAL 6-tuple is deprecated (rsgeo reads a geotransform "
                      f"as an affine.Affine); pass affine.Affine.from_gdal(*{name})",
                      DeprecationWarning, stacklevel=4)
        if (gt[1] == 0) != (gt[5] == 0):
            raise GridError(_(
                "{name} {value!r} read in GDAL's order (x0, pixel width, row rotation, y0, "
                "column rotation, pixel height) has pixel width {width:g} and pixel height "
                "{height:g}: it looks like affine.Affine's order (a, b, c, d, e, f); give "
                "affine.Affine(*{name}) for that order, or affine.Affine.from_gdal(*{name}) "
                "for GDAL's").format(name=name, value=tuple(transform), width=gt[1],
                                  height=gt[5]))
    if not np.isfinite(gt).all():
        raise GridError(_("{name} must be an affine.Affine or 6 finite numbers, got "
                          "{value!r}").format(name=name, value=transform))
    determinant = gt[1] * gt[5] - gt[2] * gt[4]
    if determinant == 0:
        raise GridError(_(
            "{name} {value!r} (GDAL's order) has pixels with no area (pixel width x height "
            "- rotations = 0); a geotransform needs a nonzero pixel width and height").format(
                name=name, value=tuple(gt)))
    return transform if isinstance(transform, affine.Affine) else affine.Affine.from_gdal(*gt)


def as_flags(flags, name):
    """``flags`` as a bool array: only booleans or 0/1 (0.5 or NaN would read as True).

    Parameters
    ----------
    flags : array_like
        One flag per item (a GCP enabled, a point a check point).
    name : str
        Their name in the error message.

    Returns
    -------
    ndarray of bool
        The flags.

    Raises
    ------
    GCPError
        If a flag is not True/False or 1/0.
    """
    array = np.asarray(flags)
    if array.dtype != bool:
        try:
            numbers = array.astype(np.float64)
        except (TypeError, ValueError):
            raise GCPError(_("{name} must hold True/False (or 1/0) flags, got {flags!r}").format(
                    name=name, flags=flags)) from None
        if not np.isin(numbers, (0.0, 1.0)).all():
            raise GCPError(_("{name} must hold True/False (or 1/0) flags, got values "
                             "{tolist}").format(
                    name=name,
                    tolist=np.unique(numbers[~np.isin(numbers, (0.0, 1.0))])[:5].tolist()))
        array = numbers.astype(bool)
    return array
