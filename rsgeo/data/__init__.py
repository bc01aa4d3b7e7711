"""Real imagery shipped with rsgeo, read with rasterio: CBERS-2/2B scenes and two 25 m scenes.

Every file comes from the Debian package ``libterralib-doc`` (TerraLib 4.3
examples, INPE and Tecgraf/PUC-Rio, LGPL-2.1+); see ``README.md`` beside this
file for provenance, sizes and licence. Five scenes are CBERS-2/2B (their
TerraLib file names say so); ``nat1`` and ``nat2`` are 25 m scenes whose
sensor neither TerraLib nor the files' metadata documents. Nothing is
downloaded: the files are inside the package; :func:`path` gives their paths.

Examples
--------
>>> from rsgeo import data
>>> "nat1" in data.available()
True
>>> scene = data.load("cbers_b2_A")
>>> scene.array.shape, scene.array.dtype.name, scene.pixel_size
((604, 568), 'uint8', (20.0, 20.0))
>>> scene
Raster('cbers_b2_A', 604 × 568, uint8, 20 m pixels, EPSG:29192)
>>> data.path("cbers2b_ccd_hrc").name
'cbers2b_ccd_hrc.points'
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._atomic import replacing
from ..errors import DataError, ImageError
from ..gcp import read_points
from ..language import _
from ..validation import as_affine, as_bands_first, as_crs, as_image, as_nodata

__all__ = ["Raster", "available", "path", "load", "available_gcps", "load_gcps", "save",
           "available_terrain"]

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
        "Scene 1 of an overlapping pair, 25 m, one band, 8 bit (SAD69 / UTM 23S); overlaps "
        "nat2. Sensor and date undocumented (TerraLib's mosaic example)."),
    "nat2": (
        "nat2.tif",
        "Scene 2 of an overlapping pair, 25 m, one band, 8 bit (SAD69 / UTM 23S); overlaps "
        "nat1. Sensor and date undocumented (TerraLib's mosaic example)."),
}


# Terrain: a DEM and a Landsat 7 band of the same ground (Olinda, Pernambuco), from the Debian
# package r-cran-stars (Apache-2.0); see README.md. load() and path() read them like the scenes.
_TERRAIN = {
    "olinda_dem": (
        "olinda_dem.tif",
        "Digital elevation model of Olinda, Pernambuco, 90 m, float32 heights in metres "
        "(-1 to 88; UTM 25S, GRS80). From the R package stars (Apache-2.0)."),
    "olinda_l7_b4": (
        "olinda_l7_b4.tif",
        "Landsat 7 ETM+ band 4 (near infrared) of Olinda, 28.5 m, the same ground as "
        "olinda_dem (SIRGAS 2000 / UTM 25S). From the R package stars (Apache-2.0)."),
}
# every raster load() reads: the scenes (available()) and the terrain (available_terrain())
_RASTERS = {**_DATASETS, **_TERRAIN}


# GCPs collected between two shipped scenes, as QGIS Georeferencer .points files.
# Map coordinates were read on the HRC scene (aggregated to 20 m), image
# coordinates on the CCD scene (red band) by template matching to a tenth of a
# pixel; each point was then checked by eye on both images.
_GCP_FILES = {
    "cbers2b_ccd_hrc": (
        "cbers2b_ccd_hrc.points",
        ["bend of a riparian forest strip at a field corner",
         "isolated clump of trees in a pasture",
         "small clump of trees (faint in the CCD)", "farm building in a fenced lot",
         "street crossing in the town", "north-east corner of a forest plot",
         "north-east corner of a forest plot", "tip of a bright field at a road",
         "corner of a bright field in dark vegetation",
         "small dark plot (low contrast in the CCD)",
         "farmstead trees", "road at the corner of a forest remnant",
         "farmstead at a road crossing", "farm buildings on a track"]),
}


@dataclass(repr=False)
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

    def __repr__(self):
        """One line: name, shape, dtype, pixel size and CRS code (not the pixels nor the WKT).

        Examples
        --------
        >>> import affine
        >>> Raster(np.zeros((3, 4, 5), np.uint8), affine.Affine(2.5, 0, 0, 0, -2.5, 0),
        ...        None, None, "", "test")
        Raster('test', 3 bands × 4 × 5, uint8, 2.5 pixels, no CRS)
        """
        shape = " × ".join(str(n) for n in self.array.shape[-2:])
        if self.array.ndim == 3:
            shape = f"{self.array.shape[0]} bands × {shape}"
        try:
            x_size, y_size = self.pixel_size
            size = f"{x_size:g}" if x_size == y_size else f"{x_size:g} × {y_size:g}"
        except (AttributeError, TypeError):
            size = "?"
        if self.crs is None:
            crs, units = "no CRS", "pixels"
        else:
            epsg = self.crs.to_epsg()
            crs = f"EPSG:{epsg}" if epsg else (self.crs.to_string()[:40] or "CRS")
            units = "m pixels" if self.crs.linear_units in ("metre", "meter") else "pixels"
            units = units if self.crs.is_projected else "° pixels"
        return f"Raster({self.name!r}, {shape}, {self.array.dtype}, {size} {units}, {crs})"

    @property
    def pixel_size(self):
        """(x, y) size of a pixel in map units, both positive.

        Returns
        -------
        (float, float)
        """
        return (abs(self.transform.a), abs(self.transform.e))

    @property
    def shape(self):
        """(rows, cols).

        Returns
        -------
        (int, int)
        """
        return self.array.shape[-2:]

    @property
    def bounds(self):
        """(left, bottom, right, top) in map units.

        Returns
        -------
        (float, float, float, float)
        """
        from rasterio.transform import array_bounds

        west, south, east, north = array_bounds(self.shape[0], self.shape[1], self.transform)
        return (west, south, east, north)


def available():
    """Names of the shipped datasets, for :func:`load`.

    Returns
    -------
    list of str
        Sorted.
    """
    return sorted(_DATASETS)


def path(name):
    """Path of a shipped file: a dataset's GeoTIFF or a GCP set's .points file.

    To open a scene in QGIS or with rasterio, or a GCP set in QGIS's
    Georeferencer (Settings → Load GCP points).

    Parameters
    ----------
    name : str
        A dataset name (:func:`available`), a GCP set name
        (:func:`available_gcps`), or a shipped file's name
        (``"nat1.tif"``, ``"cbers2b_ccd_hrc.points"``).

    Returns
    -------
    pathlib.Path
        The file inside the installed package.

    Raises
    ------
    ValueError
        For an unknown name; the message lists every shipped dataset, GCP set
        and file.

    Examples
    --------
    >>> path("nat1").name, path("cbers2b_ccd_hrc").suffix, path("nat2.tif").name
    ('nat1.tif', '.points', 'nat2.tif')
    """
    files = {key: entry[0] for key, entry in {**_RASTERS, **_GCP_FILES}.items()}
    if name in files:
        return _FOLDER / files[name]
    if name in files.values():
        return _FOLDER / name
    raise DataError(_("no shipped file named {name!r}; datasets: {listed}; GCP sets: "
                      "{listed2}; files: {listed3}").format(
            name=name, listed=', '.join(available()), listed2=', '.join(available_gcps()),
            listed3=', '.join(sorted(files.values()))))


def load(name):
    """Read a shipped dataset.

    Parameters
    ----------
    name : str
        One of :func:`available` or :func:`available_terrain`.

    Returns
    -------
    Raster

    Raises
    ------
    ValueError
        For an unknown name; the message lists the available ones.
    """
    import rasterio

    if name not in _RASTERS:
        raise DataError(_("unknown dataset {name!r}; available: {listed}; terrain: "
                          "{listed2}").format(
                name=name, listed=', '.join(available()),
                listed2=', '.join(available_terrain())))
    file = _FOLDER / _RASTERS[name][0]
    with rasterio.open(file) as dataset:
        array = dataset.read()
        raster = Raster(array[0] if dataset.count == 1 else array, dataset.transform,
                        dataset.crs, dataset.nodata, _RASTERS[name][1], name)
    return raster


def available_terrain():
    """Names of the shipped terrain datasets (a DEM and an image of its ground), for :func:`load`.

    Returns
    -------
    list of str
        Sorted: ``["olinda_dem", "olinda_l7_b4"]``.

    Raises
    ------
    ValueError
        Never.

    Examples
    --------
    >>> available_terrain()
    ['olinda_dem', 'olinda_l7_b4']
    >>> load("olinda_dem").array.dtype.name
    'float32'
    """
    return sorted(_TERRAIN)


def available_gcps():
    """Names of the shipped GCP sets, for :func:`load_gcps`.

    Returns
    -------
    list of str
        Sorted.
    """
    return sorted(_GCP_FILES)


def load_gcps(name):
    """A shipped GCP set (rsgeo.gcp.GCPSet) with a note saying what each point is on the ground.

    ``"cbers2b_ccd_hrc"``: 14 GCPs of the CCD scene ``cbers2b_rgb342`` (image
    col, row) against the HRC scene ``cbers2b_hrc`` used as the map.

    Parameters
    ----------
    name : str
        One of :func:`available_gcps`.

    Returns
    -------
    GCPSet
        With ids "G01", "G02", ... and a note per GCP.

    Raises
    ------
    ValueError
        For an unknown name; the message lists the available ones.
    """
    if name not in _GCP_FILES:
        raise DataError(_("unknown GCP set {name!r}; available: {listed}").format(
                name=name, listed=', '.join(available_gcps())))
    file, notes = _GCP_FILES[name]
    gcps = read_points(_FOLDER / file)
    gcps.notes = list(notes)
    gcps.ids = [f"G{k + 1:02d}" for k in range(len(gcps))]
    return gcps


def save(file, raster_or_array, transform=None, crs=None, nodata=None):
    """Write an array (or a :class:`Raster`) as a GeoTIFF, to open it in QGIS.

    Parameters
    ----------
    file : str or path-like
        The GeoTIFF to write (DEFLATE-compressed), in a folder that exists
        and outside rsgeo's own data folder (the shipped files).
    raster_or_array : Raster or ndarray
        A :class:`Raster` (its own transform, CRS and nodata are written:
        ``transform``, ``crs`` and ``nodata`` must then be left out), or an
        array: (rows, cols) for one band, (bands, rows, cols) for several.
        Float16 is written as float32 (GeoTIFF through GDAL 3.10 has no
        float16) and a big-endian array in the machine's byte order, both
        without changing a value.
    transform : affine.Affine, optional
        Pixel corner (col, row) → map (x, y). A GDAL 6-tuple (x0, pixel width,
        row rotation, y0, column rotation, pixel height), as
        ``dataset.GetGeoTransform()`` and ``gdalinfo`` give it, is still read,
        with a DeprecationWarning (``affine.Affine.from_gdal(*t)`` converts
        it); one in affine.Affine's order (pixel width first) is refused.
    crs : str, int or rasterio CRS, optional
        E.g. ``"EPSG:29191"`` (see :func:`rsgeo.crs.as_crs`).
    nodata : number, optional
        A value the array's dtype holds (0 to 255 for uint8; a finite
        float16 for float16, although it is written as float32).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    TypeError
        If ``file`` is not a path, or ``nodata`` is not a number (a bool, a
        string).
    rsgeo.errors.ImageError
        If the array is not 2-D or 3-D bands first (a (rows, cols, 3) RGB
        array is refused with the fix), has no band or more than 65,535, or
        ``nodata`` does not fit its dtype.
    ValueError
        If ``transform`` is neither an Affine nor 6 numbers in GDAL's order,
        or its pixels have no area; ``crs`` is not a CRS PROJ knows; a Raster
        comes with ``transform``, ``crs`` or ``nodata``.
    rsgeo.errors.DataError
        If the folder does not exist or no file can be created in it, ``file``
        is a folder or a read-only file, or ``file`` is inside rsgeo's data
        folder.

    Notes
    -----
    Nothing is lost: every argument is checked first, and the GeoTIFF is
    written whole to a hidden temporary file beside ``file`` and then
    renamed onto it in one atomic step (``os.replace``). A refused call, a
    failure or an interrupted process leaves an existing ``file`` as it
    was; two processes saving to one name leave one of their files,
    complete.

    Examples
    --------
    >>> import tempfile, affine, rasterio
    >>> folder = tempfile.mkdtemp()
    >>> written = save(f"{folder}/ramp.tif", np.arange(12, dtype=np.uint8).reshape(3, 4),
    ...                transform=affine.Affine(10.0, 0.0, 500000.0, 0.0, -10.0, 7400000.0),
    ...                crs="EPSG:31983")
    >>> with rasterio.open(written) as dataset:
    ...     dataset.transform.c, dataset.transform.a, dataset.crs.to_epsg()
    (500000.0, 10.0, 31983)
    """
    import rasterio

    if isinstance(raster_or_array, Raster):
        given = [name for name, value in (("transform", transform), ("crs", crs),
                                          ("nodata", nodata)) if value is not None]
        if given:
            raise DataError(_(
                "{given} given with a Raster, which carries its own; save the Raster alone, or "
                "dataclasses.replace(raster, {first}=...) to change it, or save raster.array "
                "with transform=, crs=, nodata=").format(given=", ".join(given), first=given[0]))
        array, transform, crs, nodata = (raster_or_array.array, raster_or_array.transform,
                                         raster_or_array.crs, raster_or_array.nodata)
    else:
        array = np.asarray(raster_or_array)
    # every argument is checked before a file is created: a refusal leaves the disk as it was
    array = _as_bands(as_bands_first(as_image(array, "array"), "array"))
    nodata = as_nodata(nodata, array.dtype)
    if array.dtype == np.float16:
        array = array.astype(np.float32)                  # exact: every float16 is a float32
    if not array.dtype.isnative:
        array = array.astype(array.dtype.newbyteorder("="))
    transform = None if transform is None else as_affine(transform, "transform",
                                                         gdal_tuple=True)
    crs = None if crs is None else as_crs(crs, "crs")
    target = _writable(file)
    bands = array if array.ndim == 3 else array[np.newaxis]
    # written whole beside the target, then renamed onto it: a failed or killed writer leaves
    # the old file (or none), never a partial GeoTIFF that opens as zeros
    with replacing(target) as temporary, rasterio.open(
            temporary, "w", driver="GTiff", width=bands.shape[2], height=bands.shape[1],
            count=bands.shape[0], dtype=bands.dtype, transform=transform, crs=crs,
            nodata=nodata, compress="deflate") as dataset:
        dataset.write(bands)
    return Path(file)


# a GeoTIFF's band count is a 16-bit number (GDAL refuses more)
_MAX_BANDS = 65535


def _as_bands(array):
    """``array`` if it has from 1 to 65,535 bands, as a GeoTIFF holds; else an ImageError."""
    bands = array.shape[0] if array.ndim == 3 else 1
    if not 1 <= bands <= _MAX_BANDS:
        raise ImageError(_(
            "array has {bands} bands (shape {shape}); a GeoTIFF holds from 1 to {most} bands: "
            "give (rows, cols) for one band or (bands, rows, cols)").format(
                bands=bands, shape=array.shape, most=_MAX_BANDS))
    return array


def _writable(file):
    """``file`` as a Path in an existing folder outside the shipped data; else a DataError."""
    import os

    if not isinstance(file, (str, os.PathLike)):
        raise TypeError(_("file must be a path (str or pathlib.Path), got {kind}").format(
            kind=type(file).__name__))
    target = Path(file)
    folder = target.resolve().parent
    if folder == _FOLDER.resolve() or _FOLDER.resolve() in folder.parents:
        raise DataError(_(
            "file {file!r} is inside rsgeo's data folder ({folder}), whose files are the "
            "shipped datasets; write to a folder of your own (e.g. tempfile.mkdtemp())").format(
                file=str(file), folder=str(_FOLDER)))
    if not folder.is_dir():
        raise DataError(_(
            "the folder of file {file!r} does not exist ({folder}); create it first, e.g. "
            "Path({folder_text!r}).mkdir(parents=True)").format(
                file=str(file), folder=str(folder), folder_text=str(target.parent)))
    return target


