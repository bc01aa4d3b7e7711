"""Real CBERS-2/2B imagery shipped with rsgeo, read with rasterio.

Every file comes from the Debian package ``libterralib-doc`` (TerraLib 4.3
examples, INPE and Tecgraf/PUC-Rio, LGPL-2.1+); see ``README.md`` beside this
file for provenance, sizes and licence. Nothing is downloaded: the files are
inside the package.

Examples
--------
>>> from rsgeo import data
>>> "nat1" in data.available()
True
>>> scene = data.load("cbers_b2_A")
>>> scene.array.shape, scene.array.dtype.name, scene.pixel_size
((604, 568), 'uint8', (20.0, 20.0))
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

_FOLDER = Path(__file__).parent

# name: (file, description)
_DATASETS = {
    "cbers2b_hrc": (
        "cbers2b_hrc.tif",
        "CBERS-2B HRC panchromatic, 2.5 m: crop fields, roads and forest remnants "
        "(SAD69 / UTM 21S). The same ground as cbers2b_rgb342, eight times finer."),
    "cbers2b_rgb342": (
        "cbers2b_rgb342.tif",
        "CBERS-2B CCD bands 3, 4, 2 (red, near infrared, green) as R, G, B, 20 m: "
        "the same fields and forest as cbers2b_hrc (SAD69 / UTM 21S)."),
    "cbers_b2_A": (
        "cbers_b2_A.tif",
        "CBERS-2 CCD band 2 (green), 20 m, crop A of three overlapping crops (SAD69 / UTM 22S)."),
    "cbers_b2_B_contraste": (
        "cbers_b2_B_contraste.tif",
        "CBERS-2 CCD band 2, 20 m, crop B: overlaps A and C, with its contrast changed "
        "(the case the regression paper corrects; SAD69 / UTM 22S)."),
    "cbers_b2_C": (
        "cbers_b2_C.tif",
        "CBERS-2 CCD band 2, 20 m, crop C, overlapping A and B (SAD69 / UTM 22S)."),
    "nat1": (
        "nat1.tif",
        "Scene 1 of an overlapping pair, 25 m, one band (SAD69 / UTM 23S); overlaps nat2."),
    "nat2": (
        "nat2.tif",
        "Scene 2 of an overlapping pair, 25 m, one band (SAD69 / UTM 23S); overlaps nat1."),
}


# GCPs collected between two shipped scenes, as QGIS Georeferencer .points files.
# Map coordinates were read on the HRC scene (aggregated to 20 m), image
# coordinates on the CCD scene (red band) by template matching to a tenth of a
# pixel; each point was then checked by eye on both images.
_GCP_FILES = {
    "cbers2b_ccd_hrc": (
        "cbers2b_ccd_hrc.points",
        ["bend of a riparian forest strip at a field corner", "isolated clump of trees in a pasture",
         "small clump of trees (faint in the CCD)", "farm building in a fenced lot",
         "street crossing in the town", "north-east corner of a forest plot",
         "north-east corner of a forest plot", "tip of a bright field at a road",
         "corner of a bright field in dark vegetation", "small dark plot (low contrast in the CCD)",
         "farmstead trees", "road at the corner of a forest remnant",
         "farmstead at a road crossing", "farm buildings on a track"]),
}


@dataclass
class Raster:
    """Pixels with their georeferencing.

    Attributes
    ----------
    array : ndarray
        (rows, cols) for one band, (bands, rows, cols) for several, as rasterio reads them.
    transform : affine.Affine
        Pixel corner (col, row) -> map (x, y).
    crs : rasterio.crs.CRS or None
    nodata : number or None
    description : str
    name : str
    """

    array: np.ndarray
    transform: object
    crs: object
    nodata: object
    description: str
    name: str = ""

    @property
    def pixel_size(self):
        """(x, y) size of a pixel in map units, both positive."""
        return (abs(self.transform.a), abs(self.transform.e))

    @property
    def shape(self):
        """(rows, cols)."""
        return self.array.shape[-2:]

    @property
    def bounds(self):
        """(left, bottom, right, top) in map units."""
        from rasterio.transform import array_bounds

        west, south, east, north = array_bounds(self.shape[0], self.shape[1], self.transform)
        return (west, south, east, north)


def available():
    """Names of the shipped datasets, for :func:`load`."""
    return sorted(_DATASETS)


def path(name):
    """Path of a shipped dataset's GeoTIFF (to open it with rasterio or QGIS)."""
    if name not in _DATASETS:
        raise ValueError(f"unknown dataset {name!r}; available: {', '.join(available())}")
    return _FOLDER / _DATASETS[name][0]


def load(name):
    """Read a shipped dataset.

    Parameters
    ----------
    name : str
        One of :func:`available`.

    Returns
    -------
    Raster

    Raises
    ------
    ValueError
        For an unknown name; the message lists the available ones.
    """
    import rasterio

    file = path(name)
    with rasterio.open(file) as dataset:
        array = dataset.read()
        raster = Raster(array[0] if dataset.count == 1 else array, dataset.transform,
                        dataset.crs, dataset.nodata, _DATASETS[name][1], name)
    return raster


def available_gcps():
    """Names of the shipped GCP sets, for :func:`load_gcps`."""
    return sorted(_GCP_FILES)


def load_gcps(name):
    """A shipped GCP set (rsgeo.gcp.GCPSet) with a note saying what each point is on the ground.

    ``"cbers2b_ccd_hrc"``: 14 GCPs of the CCD scene ``cbers2b_rgb342`` (image
    col, row) against the HRC scene ``cbers2b_hrc`` used as the map.
    """
    from ..gcp import read_points

    if name not in _GCP_FILES:
        raise ValueError(f"unknown GCP set {name!r}; available: {', '.join(available_gcps())}")
    file, notes = _GCP_FILES[name]
    gcps = read_points(_FOLDER / file)
    gcps.notes = list(notes)
    gcps.ids = [f"G{k + 1:02d}" for k in range(len(gcps))]
    return gcps


def save(file, raster_or_array, transform=None, crs=None, nodata=None):
    """Write an array (or a :class:`Raster`) as a GeoTIFF, to open it in QGIS."""
    import rasterio

    if isinstance(raster_or_array, Raster):
        array, transform, crs, nodata = (raster_or_array.array, raster_or_array.transform,
                                         raster_or_array.crs, raster_or_array.nodata)
    else:
        array = np.asarray(raster_or_array)
    bands = array if array.ndim == 3 else array[np.newaxis]
    with rasterio.open(file, "w", driver="GTiff", width=bands.shape[2], height=bands.shape[1],
                       count=bands.shape[0], dtype=bands.dtype, transform=transform, crs=crs,
                       nodata=nodata, compress="deflate") as dataset:
        dataset.write(bands)
