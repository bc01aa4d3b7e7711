"""Sensor models: where a sensor puts the ground in its image, and back.

- :class:`SystematicDistortion` - chapter 1's systematic distortions (Earth rotation,
  attitude, view angle, curvature) combined into one model between pixel grids, with
  :func:`simulate`, :func:`correct` and :func:`distorted_grid`;
- :class:`RawSensor` - the geometry of a raw (level 1A) pushbroom scene placed on a map, over a
  DEM;
- :class:`PushbroomSensor` - a pushbroom scanner over a flat map plane, with
  :func:`fit_rpc_to_sensor`;
- :class:`FrameCamera` - a frame camera's collinearity equations, and :func:`resect` (space
  resection from GCPs);
- :class:`RPCModel` - rational polynomial camera models (RPC00B) as GDAL reads them,
  :func:`fit_rpc` (terrain independent, as vendors fit them) and :func:`refine_rpc` (bias
  compensation with GCPs).

Orthorectification with a DEM is :func:`rsgeo.ortho.orthorectify`.
"""

from ._frame import (
    PARAMETERS,
    UNITS,
    ExteriorOrientation,
    FrameCamera,
    InteriorOrientation,
    Resection,
    angles_from_rotation,
    resect,
    rotation_matrix,
)
from ._pushbroom import PushbroomSensor, fit_rpc_to_sensor
from ._raw import RawSensor
from ._rpc import BIAS_KINDS, RPC_TERMS, RefinedRPC, RPCModel, fit_rpc, refine_rpc, simple_rpc_dict
from ._systematic import SystematicDistortion, correct, distorted_grid, simulate

__all__ = [
    "SystematicDistortion", "simulate", "correct", "distorted_grid",
    "RawSensor",
    "PushbroomSensor", "fit_rpc_to_sensor",
    "PARAMETERS", "UNITS", "InteriorOrientation", "ExteriorOrientation", "FrameCamera",
    "Resection", "rotation_matrix", "angles_from_rotation", "resect",
    "RPC_TERMS", "RPCModel", "simple_rpc_dict", "fit_rpc", "BIAS_KINDS", "RefinedRPC",
    "refine_rpc",
]
