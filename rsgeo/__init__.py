"""rsgeo: geometric correction of remote-sensing images, for teaching.

One module per topic of the course:

- :mod:`rsgeo.data` - real CBERS scenes shipped with the package;
- :mod:`rsgeo.synthetic` - data with a known answer;
- :mod:`rsgeo.distortion` - systematic distortions (chapter 1);
- :mod:`rsgeo.gcp` - polynomial GCP models, residuals, RMS, and the mapping protocol every
  model follows (``model(points)``, ``model.residuals(src, dst)``, ``model.inverse()``)
  (chapters 2-3);
- :mod:`rsgeo.georef` - CRSs and datums (SAD69 -> SIRGAS 2000) through PROJ, and a complete
  georeferencing run, ``georeference`` (chapter 2b);
- :mod:`rsgeo.resample` - GDAL-exact nearest, bilinear, cubic (chapter 4);
- :mod:`rsgeo.terrain` - relief displacement, RPCs fitted to a sensor, orthorectification with a
  DEM (chapter 4b);
- :mod:`rsgeo.radiometry` - contrast matching by regression (chapter 5, the regression paper);
- :mod:`rsgeo.regions`, :mod:`rsgeo.matching` - homologous regions by a genetic algorithm (chapter 6, the GA paper);
- :mod:`rsgeo.tiepoints` - automatic tie points by correlation and by features, and the
  registration pipeline they share with the GA (chapter 6c);
- :mod:`rsgeo.experiments` - the experiment harness behind chapter 6's saved tables (success rates, certified optima);
- :mod:`rsgeo.exercises` - checks for the exercises;
- :mod:`rsgeo.plot`, :mod:`rsgeo.widgets` - figures and interactive widgets on top of the maths.
"""

import importlib
import os
import pkgutil

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


if os.environ.get("RSGEO_AUDIT_FIGURES"):
    # set by the book's build (book/_ext/offline_book.py) for its kernels: an unreadable figure
    # writes to standard error, which fails the build
    importlib.import_module(f"{__name__}.plot").audit_rendered_figures(to_stderr=True)
