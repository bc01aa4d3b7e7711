"""GDAL's warper for the benchmarks: a VRTWarpedDataset around a GDAL transformer, timed on read.

``benchmarks/resample.py`` (affine, GCP polynomials, thin-plate splines) and
``benchmarks/orthorectify.py`` (RPC + DEM) time GDAL the same way: the source
written once as a GeoTIFF, one VRT per case whose block is the whole grid
(one GDAL chunk, so that GDAL's approximation runs along whole rows, as
rsgeo's does), destination nodata 0, the warp option ``NUM_THREADS``, and
the opening and reading of the VRT timed (the warp happens on read). The
transformer is GDAL's exact one, or wrapped in its approximate transformer
(gdalwarp's ``-et``). The VRT is rsgeo_course.gdal_reference's, the one the
cross-checks warp with.
"""

import warnings
from pathlib import Path

from rsgeo_course import gdal_reference
from rsgeo_course.gdal_reference import gen_img_proj

__all__ = ["gen_img_proj", "warped_vrt", "GdalWarps"]


def warped_vrt(source_path, dst_transform, shape, transformer, method, dtype, threads,
               max_error=None, scale=(1, 1)):
    """The benchmarks' VRT (rsgeo_course.gdal_reference.warped_vrt): one band, one block for
    the grid, destination nodata 0, ``threads`` warp threads; ``scale`` the XSCALE and YSCALE
    warp options, or None to let GDAL compute them for the chunk."""
    return gdal_reference.warped_vrt(source_path, dst_transform, shape, transformer, method,
                                     dtype, nodata=0, block=None, max_error=max_error,
                                     scale=scale, options={"NUM_THREADS": threads},
                                     memory_limit=1 << 30)


class GdalWarps:
    """The source written once as a GeoTIFF; :meth:`runner` gives a warp through a VRT."""

    def __init__(self, folder, image):
        import rasterio

        self.folder = Path(folder)
        self.dtype = image.dtype.name
        self.source = str(self.folder / f"source_{image.shape[0]}_{self.dtype}.tif")
        with warnings.catch_warnings():
            # no geotransform: the VRT's transformer places the source
            warnings.simplefilter("ignore", rasterio.errors.NotGeoreferencedWarning)
            with rasterio.open(self.source, "w", driver="GTiff", width=image.shape[1],
                               height=image.shape[0], count=1, dtype=image.dtype) as dataset:
                dataset.write(image, 1)
        self._count = 0

    def runner(self, xml):
        """A function that warps with GDAL (opening and reading the VRT ``xml``) and returns
        the array."""
        import rasterio

        self._count += 1
        vrt = self.folder / f"warp_{self._count}.vrt"
        vrt.write_text(xml)

        def run():
            # a new dataset each time: a second read of the same one would come from its cache
            with rasterio.open(vrt) as dataset:
                return dataset.read(1)
        return run
