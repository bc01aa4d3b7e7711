"""The errors rsgeo raises, after rasterio's ``errors.py``: one small hierarchy.

Every error rsgeo raises for a value a user passed is an :class:`RsgeoError`, which is a
``ValueError``, so code written before these types existed (``except ValueError``) keeps working.
Its message says what was wrong and what is needed ("order 2 needs at least 6 GCPs, got 4").
A value of the wrong type (a string where a number is needed) raises ``TypeError``.

Which subclass to raise: the one that names what the user must change. ``GCPError`` for control
points and the models fitted to them, ``ImageError`` for image arrays and their bands,
``GridError`` for output grids, geotransforms, shapes and resolutions, ``CRSError`` for
coordinate reference systems, datums and heights, ``ModelError`` for a model that cannot be
evaluated or inverted where asked, ``DataError`` for shipped data and files that cannot be read.
Anything else is a plain :class:`RsgeoError`.

A result that rsgeo computes but does not trust comes with a warning, not an error:
:class:`ExtrapolationWarning` when a model is used far from the GCPs that control it.

Examples
--------
>>> from rsgeo import errors
>>> issubclass(errors.GCPError, ValueError)
True
>>> try:
...     raise errors.GCPError("order 2 needs at least 6 GCPs, got 4")
... except ValueError as error:
...     print(type(error).__name__, error)
GCPError order 2 needs at least 6 GCPs, got 4
"""

__all__ = ["RsgeoError", "GCPError", "ImageError", "GridError", "CRSError", "ModelError",
           "DataError", "ExtrapolationWarning"]


class RsgeoError(ValueError):
    """A value passed to rsgeo cannot be used; the message says what is needed."""


class GCPError(RsgeoError):
    """Control points (too few, collinear, duplicated, not finite) or a model fitted to them."""


class ImageError(RsgeoError):
    """An image array: its dimensions, bands, dtype, values or nodata."""


class GridError(RsgeoError):
    """An output grid, geotransform, shape, resolution, window or kernel scale."""


class CRSError(RsgeoError):
    """A coordinate reference system, datum, vertical datum or the units they imply."""


class ModelError(RsgeoError):
    """A model evaluated or inverted where it cannot be (no convergence, outside its domain)."""


class DataError(RsgeoError):
    """A shipped data set that does not exist, or a file that cannot be read as expected."""


class ExtrapolationWarning(UserWarning):
    """A model used beyond its GCPs, where its error is not controlled (a polynomial of degree
    2 or 3, or a projective model, grows fast with the distance from them)."""
