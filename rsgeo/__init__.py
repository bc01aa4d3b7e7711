"""rsgeo: geometric correction of remote-sensing images, for teaching.

One module per topic of the course:

- :mod:`rsgeo.data` - real CBERS scenes shipped with the package;
- :mod:`rsgeo.synthetic` - data with a known answer;
- :mod:`rsgeo.distortion` - systematic distortions (chapter 1);
- :mod:`rsgeo.gcp` - polynomial GCP models, residuals, RMS (chapters 2-3);
- :mod:`rsgeo.resample` - GDAL-exact nearest, bilinear, cubic (chapter 4);
- :mod:`rsgeo.radiometry` - contrast matching by regression (chapter 5, the regression paper);
- :mod:`rsgeo.regions`, :mod:`rsgeo.matching` - homologous regions by a genetic algorithm (chapter 6, the GA paper);
- :mod:`rsgeo.exercises` - checks for the exercises;
- :mod:`rsgeo.plot`, :mod:`rsgeo.widgets` - figures and interactive widgets on top of the maths.
"""

__version__ = "0.1.0"
