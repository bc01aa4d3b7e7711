"""rsgeo's compiled internals (Numba), shared by the models and the warps; not an API.

- ``rsgeo._kernels.thin_plate`` - GDAL's thin-plate-spline solver and evaluator;
- ``rsgeo._kernels.transformer`` - every model packed as arrays and evaluated inside a
  kernel, as GDAL's transformers are;
- ``rsgeo._kernels.resampling`` - the per-pixel loops of GDAL's warp kernels.

The public verbs that use them are :mod:`rsgeo.transforms`, :mod:`rsgeo.resample` and
:mod:`rsgeo.ortho`; nothing outside rsgeo imports this package.
"""

from contextlib import contextmanager

__all__ = ["numba_threads"]


@contextmanager
def numba_threads(count):
    """``with numba_threads(n):`` Numba's parallel loops use ``n`` threads, as before after.

    The one place rsgeo sets Numba's thread count (a warp's or an orthorectification's
    ``num_threads``, already checked by :func:`rsgeo.validation.as_num_threads`).

    Parameters
    ----------
    count : int
        Threads for the loops inside the ``with`` block.

    Yields
    ------
    None
        Nothing: the count holds inside the block.
    """
    import numba

    previous = numba.get_num_threads()
    numba.set_num_threads(count)
    try:
        yield
    finally:
        numba.set_num_threads(previous)
