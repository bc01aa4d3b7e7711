"""rsgeo's compiled internals (Numba), shared by the models and the warps; not an API.

- ``rsgeo._kernels.thin_plate`` - GDAL's thin-plate-spline solver and evaluator;
- ``rsgeo._kernels.transformer`` - every model packed as arrays and evaluated inside a
  kernel, as GDAL's transformers are;
- ``rsgeo._kernels.resampling`` - the per-pixel loops of GDAL's warp kernels;
- ``rsgeo._kernels.rpc`` and ``rsgeo._kernels.dem`` - the RPC model and a DEM's heights;
- ``rsgeo._kernels._rows`` - threads sharing a loop's rows (no loop is compiled parallel).

The public verbs that use them are :mod:`rsgeo.transforms`, :mod:`rsgeo.resample` and
:mod:`rsgeo.ortho`; nothing outside rsgeo imports this package.
"""

__all__ = []
