"""rsgeo_course: the course built on rsgeo, kept beside the library.

What the course needs and a user of :mod:`rsgeo` does not:

- :mod:`rsgeo_course.exercises` - the exercises' checks (a verdict that teaches), declared per
  exercise notebook, and their engine;
- :mod:`rsgeo_course.alt_text` - what a figure shows, in words, for a reader who cannot see it
  (installed as :func:`rsgeo.plot.set_figure_describer` when this package is imported, so that
  the widgets' frames and animation players say it too);
- :mod:`rsgeo_course.figure_language` - the figures' and tables' texts in the book's language,
  from the course's figure catalogue (extracted from the chapters' code);
- the course's messages in Portuguese (``locale/``), in the language :mod:`rsgeo.language`
  speaks.

The instructors' tools (grading, the student edition, the printed course) are the scripts in
the repository's ``exercises/`` folder; they use this package.
"""

from rsgeo import plot as _plot

from .alt_text import describe_figure

__version__ = "0.1.0"
__all__ = ["__version__", "alt_text", "exercises", "figure_language"]

# the widgets' frames and animation players rsgeo draws say what they show
_plot.set_figure_describer(describe_figure)


def __getattr__(name):
    if name in ("exercises", "figure_language", "alt_text"):
        import importlib

        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module 'rsgeo_course' has no attribute {name!r}")
