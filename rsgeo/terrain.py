"""Deprecated: this module's names moved to relief displacement (:mod:`rsgeo.relief`), RPCs and
sensors (:mod:`rsgeo.sensors`), DEM sampling (:mod:`rsgeo.dem`) and orthorectification
(:mod:`rsgeo.ortho`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("dem_height", "line_of_sight_on_dem"), "rsgeo.dem"),
    **dict.fromkeys(("map_on_grid", "orthorectify", "positional_error"), "rsgeo.ortho"),
    **dict.fromkeys(("height_error_budget", "occluded", "relief_displacement",
                     "relief_displacement_photo"), "rsgeo.relief"),
    **dict.fromkeys(("BIAS_KINDS", "PushbroomSensor", "RPCModel", "RPC_TERMS", "RefinedRPC",
                     "fit_rpc", "fit_rpc_to_sensor", "refine_rpc", "simple_rpc_dict"),
                    "rsgeo.sensors"),
})
