"""Deprecated: this module's names moved to the frame camera (:mod:`rsgeo.sensors`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("ExteriorOrientation", "FrameCamera", "InteriorOrientation", "PARAMETERS",
                     "Resection", "UNITS", "angles_from_rotation", "resect", "rotation_matrix"),
                    "rsgeo.sensors"),
})
