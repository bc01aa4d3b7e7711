"""GCP sets the model tests share (imported by name from tests/, like notebook_runner)."""

import numpy as np


def utm_gcps(n, seed, blunders=0):
    """Random GCPs over a 1000 x 800 image, UTM-sized map coordinates, a gentle curvature."""
    rng = np.random.default_rng(seed)
    image_xy = np.column_stack([rng.uniform(0, 1000, n), rng.uniform(0, 800, n)])
    c, r = image_xy[:, 0], image_xy[:, 1]
    map_xy = np.column_stack([500_000 + 20 * c + 0.01 * r**1.5 + rng.normal(0, 15, n),
                              7_400_000 - 20 * r + 3 * c + 2e-5 * c * c + rng.normal(0, 15, n)])
    for k in range(blunders):
        image_xy[3 * k + 1] += (25 + 10 * k, -30)
    return image_xy, map_xy
