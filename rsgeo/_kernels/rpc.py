"""The RPC evaluated inside compiled code: GDAL's ``RPCEvaluate`` and ``RPCTransformPoint``
(``alg/gdal_rpc.cpp``), operation by operation, on the packed model
(:class:`rsgeo.sensors.RPCModel`'s ``_packed``).
"""

from numba import njit

from .._numba_cache import CACHE

__all__ = ["PACKED_SCALARS", "RPC_PACKED_SIZE", "rpc_sum", "rpc_point", "project_points"]



# The packed RPC the compiled code reads (RPCModel._packed): 10 scalars, then 4 x 20
# coefficients in GDAL's padfCoeffs order (LINE_NUM, LINE_DEN, SAMP_NUM, SAMP_DEN)
PACKED_SCALARS = (("LONG", "OFF"), ("LONG", "SCALE"), ("LAT", "OFF"), ("LAT", "SCALE"),
                   ("HEIGHT", "OFF"), ("HEIGHT", "SCALE"), ("SAMP", "OFF"), ("SAMP", "SCALE"),
                   ("LINE", "OFF"), ("LINE", "SCALE"))
RPC_PACKED_SIZE = 10 + 4 * 20


@njit(cache=CACHE, inline="always")
def rpc_sum(p, o, L, P, H, LP, LH, PH, LL, PP, HH):
    """GDAL's RPCEvaluate of one cubic (coefficients p[o:o + 20]): the even terms and the odd
    terms summed apart, in index order, then added (GDAL's two SSE2 lanes)."""
    even = 0.0
    odd = 0.0
    even += 1.0 * p[o]
    odd += L * p[o + 1]
    even += P * p[o + 2]
    odd += H * p[o + 3]
    even += LP * p[o + 4]
    odd += LH * p[o + 5]
    even += PH * p[o + 6]
    odd += LL * p[o + 7]
    even += PP * p[o + 8]
    odd += HH * p[o + 9]
    # the cubic terms as RPCComputeTerms multiplies them, left to right: L * P * H is
    # (L * P) * H = LP * H, and so on
    even += LP * H * p[o + 10]
    odd += LL * L * p[o + 11]
    even += LP * P * p[o + 12]
    odd += LH * H * p[o + 13]
    even += LL * P * p[o + 14]
    odd += PP * P * p[o + 15]
    even += PH * H * p[o + 16]
    odd += LL * H * p[o + 17]
    even += PP * H * p[o + 18]
    odd += HH * H * p[o + 19]
    return even + odd


@njit(cache=CACHE, inline="always")
def rpc_point(p, o, lon, lat, height):
    """GDAL's RPCTransformPoint: (col, row) of one ground point, the packed RPC at p[o:]."""
    diff = lon - p[o]
    if diff < -270:                   # GDAL's dateline fold
        diff += 360
    elif diff > 270:
        diff -= 360
    L = diff / p[o + 1]
    P = (lat - p[o + 2]) / p[o + 3]
    H = (height - p[o + 4]) / p[o + 5]
    LP = L * P
    LH = L * H
    PH = P * H
    LL = L * L
    PP = P * P
    HH = H * H
    line_num = rpc_sum(p, o + 10, L, P, H, LP, LH, PH, LL, PP, HH)
    line_den = rpc_sum(p, o + 30, L, P, H, LP, LH, PH, LL, PP, HH)
    samp_num = rpc_sum(p, o + 50, L, P, H, LP, LH, PH, LL, PP, HH)
    samp_den = rpc_sum(p, o + 70, L, P, H, LP, LH, PH, LL, PP, HH)
    # RPC line and sample count from the first pixel's centre, GDAL from its corner: + 0.5
    col = samp_num / samp_den * p[o + 7] + p[o + 6] + 0.5
    row = line_num / line_den * p[o + 9] + p[o + 8] + 0.5
    return col, row


@njit(cache=CACHE, error_model="numpy")
def project_points(p, lon, lat, height, cols, rows):
    """rpc_point for every point of 1-D arrays, into cols and rows (in vector instructions:
    error_model="numpy" lets a division by zero give infinity, as in GDAL's C)."""
    for k in range(lon.size):
        cols[k], rows[k] = rpc_point(p, 0, lon[k], lat[k], height[k])


