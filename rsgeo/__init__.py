"""rsgeo: geometric correction of remote-sensing images.

The maths of the course on geometric correction, usable without it, one topic per module:

- :mod:`rsgeo.data` - real scenes (CBERS, Landsat, a DEM) and grids shipped with the package;
  :mod:`rsgeo.synthetic` - data with a known answer;
- :mod:`rsgeo.distortion` - systematic distortions' formulas (chapter 1);
- :mod:`rsgeo.transforms` - the mapping protocol every model follows (``model(points)``,
  ``model.residuals(src, dst)``, ``model.inverse()``), one registry of model kinds (linear,
  Helmert, polynomial 1-3, projective, TPS) and ``fit_transform`` (chapters 2, 3b);
- :mod:`rsgeo.accuracy` - residuals, RMS, leave-one-out, check points, ``refine_gcps`` for any
  kind; the PEC-PCD, ASPRS and CE90 standards (chapter 3);
- :mod:`rsgeo.gcp` - GCP sets, their CRS and QGIS ``.points`` files (chapter 2);
- :mod:`rsgeo.crs`, :mod:`rsgeo.heights` - CRSs and datums (SAD69 -> SIRGAS 2000) through PROJ;
  the geoid and ellipsoidal heights (chapters 2b, 4b);
- :mod:`rsgeo.resample` - GDAL-exact nearest, bilinear, cubic and average, ``warp`` with the
  models evaluated inside the kernels, ``reproject``, ``georeference``, tiled warps (chapter 4);
- :mod:`rsgeo.relief`, :mod:`rsgeo.dem`, :mod:`rsgeo.ortho` - relief displacement, a DEM's
  heights, orthorectification (chapter 4b);
- :mod:`rsgeo.sensors` - sensor models: systematic distortion, raw scene, pushbroom, frame
  camera, RPCs fitted and refined (chapters 1, 4b-4d);
- :mod:`rsgeo.radiometry` - contrast matching by regression (chapter 5, the regression paper);
- :mod:`rsgeo.registration` - tie points by correlation and by features, the registration
  pipeline, band-to-band registration, and the GA paper's homologous regions (chapters 6, 6c);
- :mod:`rsgeo.plot`, :mod:`rsgeo.widgets` - figures and interactive widgets of those results;
- :mod:`rsgeo.validation`, :mod:`rsgeo.language`, :mod:`rsgeo.errors` - input checks, the
  language of messages, the errors rsgeo raises (every one a ``ValueError``).

The course's own machinery (exercise checks, figure descriptions and translations) is the
package ``rsgeo_course``, built on this one; rsgeo imports nothing of it. Names that moved keep
working from their old homes for one release, with a ``DeprecationWarning``.
"""

import importlib
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

