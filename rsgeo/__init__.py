"""rsgeo: geometric correction of remote-sensing images, for teaching.

One module per topic of the course:

- :mod:`rsgeo.data` - real CBERS scenes shipped with the package;
- :mod:`rsgeo.synthetic` - data with a known answer;
- :mod:`rsgeo.distortion` - systematic distortions (chapter 1);
- :mod:`rsgeo.transforms` - the mapping protocol every model follows (``model(points)``,
  ``model.residuals(src, dst)``, ``model.inverse()``), one registry of model kinds (linear,
  Helmert, polynomial 1-3, projective, TPS) and ``fit_transform`` (chapters 2, 3b);
- :mod:`rsgeo.accuracy` - residuals, RMS, leave-one-out, check points, ``refine_gcps`` for any
  kind (chapter 3);
- :mod:`rsgeo.gcp` - GCP sets, their CRS and QGIS ``.points`` files (chapter 2);
- :mod:`rsgeo.georef` - CRSs and datums (SAD69 -> SIRGAS 2000) through PROJ, and a complete
  georeferencing run, ``georeference`` (chapter 2b);
- :mod:`rsgeo.resample` - GDAL-exact nearest, bilinear, cubic (chapter 4), with the models
  evaluated inside the kernels (:mod:`rsgeo.transformer`, GDAL's thin-plate spline in
  :mod:`rsgeo.thin_plate`) and scenes warped tile by tile (:mod:`rsgeo.tiling`);
- :mod:`rsgeo.terrain` - relief displacement, RPCs fitted to a sensor, orthorectification with a
  DEM (chapter 4b);
- :mod:`rsgeo.radiometry` - contrast matching by regression (chapter 5, the regression paper);
- :mod:`rsgeo.regions`, :mod:`rsgeo.matching` - homologous regions by a genetic algorithm
  (chapter 6, the GA paper);
- :mod:`rsgeo.tiepoints` - local shifts by correlation (``measure_shifts``), automatic tie
  points by correlation and by features, and the registration pipeline they share with the GA
  (chapter 6c);
- :mod:`rsgeo_course.exercises` - the exercises' checks, declared per exercise notebook;
- :mod:`rsgeo.errors` - the errors rsgeo raises, every one a ``ValueError``;
- :mod:`rsgeo.plot`, :mod:`rsgeo.widgets` - figures and interactive widgets on top of the maths.
"""

import importlib
import pkgutil

from . import _numba_cache

# before any compiled module is imported: Numba's cache must not outlive a changed callee
_numba_cache.refresh()

__version__ = "0.1.0"

# Every public module, imported on first use: ``import rsgeo; rsgeo.gcp`` works without
# loading Numba or matplotlib for a script that needs only one topic.
_MODULES = tuple(sorted(module.name for module in pkgutil.iter_modules(__path__)
                        if not module.name.startswith("_")))

__all__ = ["__version__", *_MODULES]


def __getattr__(name):
    if name in _MODULES:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module 'rsgeo' has no attribute {name!r}; its modules are "
                         f"{', '.join(_MODULES)}")


def __dir__():
    return sorted(set(globals()) | set(_MODULES))

