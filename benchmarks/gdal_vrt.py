"""GDAL's warper for the benchmarks: a VRTWarpedDataset around a GDAL transformer, timed on read.

``benchmarks/resample.py`` (affine, GCP polynomials, thin-plate splines) and
``benchmarks/orthorectify.py`` (RPC + DEM) time GDAL the same way: the source
written once as a GeoTIFF, one VRT per case whose block is the whole grid
(one GDAL chunk, so that GDAL's approximation runs along whole rows, as
rsgeo's does), destination nodata 0, the warp option ``NUM_THREADS``, and
the opening and reading of the VRT timed (the warp happens on read). The
transformer is GDAL's exact one, or wrapped in its approximate transformer
(gdalwarp's ``-et``). tests/gdal_reference.py builds the same VRT for the
cross-checks.
"""

import warnings
from pathlib import Path

GDAL_RESAMPLING = {"nearest": "NearestNeighbour", "bilinear": "Bilinear", "cubic": "Cubic",
                   "average": "Average"}
GDAL_TYPES = {"uint8": "Byte", "int16": "Int16", "uint16": "UInt16", "float32": "Float32"}


def geotransform(transform):
    """An affine.Affine as GDAL's six numbers, comma-separated, exactly (repr)."""
    return ",".join(repr(float(v)) for v in transform.to_gdal())


def gen_img_proj(source_xml, dst_transform, reproject_xml=""):
    """GDAL's GenImgProjTransformer: the source's transformer, a reprojection, the output grid."""
    return (f"<GenImgProjTransformer>{source_xml}{reproject_xml}"
            f"<DstGeoTransform>{geotransform(dst_transform)}</DstGeoTransform>"
            f"<DstInvGeoTransform>{geotransform(~dst_transform)}</DstInvGeoTransform>"
            "</GenImgProjTransformer>")


def warped_vrt(source_path, dst_transform, shape, transformer, method, dtype, threads,
               max_error=None, scale=(1, 1)):
    """The VRT's XML: one band, one block for the grid, destination nodata 0.

    ``max_error`` None for the exact transformer, else GDAL's approximate
    transformer's threshold; ``scale`` the XSCALE and YSCALE warp options, or
    None to let GDAL compute them for the chunk.
    """
    if max_error is not None:
        transformer = (f"<ApproxTransformer><MaxError>{max_error!r}</MaxError>"
                       f"<BaseTransformer>{transformer}</BaseTransformer></ApproxTransformer>")
    options = {"INIT_DEST": "NO_DATA", "NUM_THREADS": threads}
    if scale is not None:
        options.update(XSCALE=scale[0], YSCALE=scale[1])
    options = "".join(f'<Option name="{key}">{value}</Option>' for key, value in options.items())
    gdal_type = GDAL_TYPES[dtype]
    return f"""<VRTDataset rasterXSize="{shape[1]}" rasterYSize="{shape[0]}" \
subClass="VRTWarpedDataset">
  <GeoTransform>{geotransform(dst_transform)}</GeoTransform>
  <VRTRasterBand dataType="{gdal_type}" band="1" subClass="VRTWarpedRasterBand">\
<NoDataValue>0</NoDataValue></VRTRasterBand>
  <BlockXSize>{shape[1]}</BlockXSize><BlockYSize>{shape[0]}</BlockYSize>
  <GDALWarpOptions>
    <WarpMemoryLimit>{1 << 30}</WarpMemoryLimit>
    <ResampleAlg>{GDAL_RESAMPLING[method]}</ResampleAlg>
    <WorkingDataType>{gdal_type}</WorkingDataType>{options}
    <SourceDataset relativeToVRT="0">{source_path}</SourceDataset>
    <Transformer>{transformer}</Transformer>
    <BandList><BandMapping src="1" dst="1"><DstNoDataReal>0</DstNoDataReal>\
<DstNoDataImag>0</DstNoDataImag></BandMapping></BandList>
  </GDALWarpOptions>
</VRTDataset>"""


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
