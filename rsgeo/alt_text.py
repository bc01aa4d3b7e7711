"""Moved to :mod:`rsgeo_course.alt_text`, the course's own package: this old home forwards.

Deprecated: import from ``rsgeo_course.alt_text``. This module goes in rsgeo 0.3.
"""

from ._deprecated import moved_module

__getattr__, __dir__ = moved_module(__name__, "rsgeo_course.alt_text")
