"""GDAL as the reference: warps through a hand-written VRTWarpedDataset.

The VRT names GDAL's transformer directly, with no approximate transformer
around it (its default 0.125-pixel error threshold would move sample positions
and change values), so GDAL computes every output pixel's source position
exactly, like rsgeo does.
"""

import os
import tempfile
from xml.sax.saxutils import quoteattr

import numpy as np
import rasterio

_RESAMPLING = {"nearest": "NearestNeighbour", "bilinear": "Bilinear", "cubic": "Cubic"}
_GDAL_TYPES = {"uint8": "Byte", "uint16": "UInt16", "int16": "Int16", "int32": "Int32",
               "float32": "Float32", "float64": "Float64"}


def _geotransform(transform):
    return ",".join(repr(float(v)) for v in transform.to_gdal())


def _write_source(folder, image):
    bands = image if image.ndim == 3 else image[np.newaxis]
    path = os.path.join(folder, "source.tif")
    with rasterio.open(path, "w", driver="GTiff", width=bands.shape[2], height=bands.shape[1],
                       count=bands.shape[0], dtype=bands.dtype) as dataset:
        dataset.write(bands)
    return path, bands.shape[0]


def gdal_warp(image, source_transformer_xml, dst_transform, shape, method, nodata, plain_kernels=False):
    """Warp ``image`` with GDAL; ``source_transformer_xml`` places the source on the map.

    ``plain_kernels``: set GDAL's XSCALE and YSCALE warp options to 1, so that it
    never widens its kernels (it otherwise does where the bounding box of a
    chunk's source window makes the scale look below 0.95).
    """
    dtype = _GDAL_TYPES[np.dtype(image.dtype).name]
    with tempfile.TemporaryDirectory() as folder:
        source, count = _write_source(folder, np.asarray(image))
        bands = "".join(
            f'<VRTRasterBand dataType="{dtype}" band="{b}" subClass="VRTWarpedRasterBand">'
            f"<NoDataValue>{nodata}</NoDataValue></VRTRasterBand>" for b in range(1, count + 1))
        mapping = "".join(f'<BandMapping src="{b}" dst="{b}"><DstNoDataReal>{nodata}</DstNoDataReal>'
                          f"<DstNoDataImag>0</DstNoDataImag></BandMapping>" for b in range(1, count + 1))
        inverse = ~dst_transform
        scale_options = ('<Option name="XSCALE">1</Option><Option name="YSCALE">1</Option>'
                         if plain_kernels else "")
        xml = f"""<VRTDataset rasterXSize="{shape[1]}" rasterYSize="{shape[0]}" subClass="VRTWarpedDataset">
  <GeoTransform>{_geotransform(dst_transform)}</GeoTransform>
  {bands}
  <BlockXSize>256</BlockXSize><BlockYSize>256</BlockYSize>
  <GDALWarpOptions>
    <WarpMemoryLimit>67108864</WarpMemoryLimit>
    <ResampleAlg>{_RESAMPLING[method]}</ResampleAlg>
    <WorkingDataType>{dtype}</WorkingDataType>
    <Option name="INIT_DEST">NO_DATA</Option>{scale_options}
    <SourceDataset relativeToVRT="0">{source}</SourceDataset>
    <Transformer><GenImgProjTransformer>
      {source_transformer_xml}
      <DstGeoTransform>{_geotransform(dst_transform)}</DstGeoTransform>
      <DstInvGeoTransform>{_geotransform(inverse)}</DstInvGeoTransform>
    </GenImgProjTransformer></Transformer>
    <BandList>{mapping}</BandList>
  </GDALWarpOptions>
</VRTDataset>"""
        vrt = os.path.join(folder, "warped.vrt")
        with open(vrt, "w") as handle:
            handle.write(xml)
        with rasterio.open(vrt) as dataset:
            out = dataset.read()
    return out if np.asarray(image).ndim == 3 else out[0]


def affine_source(src_transform):
    """Transformer XML for a source placed on the map by an affine geotransform."""
    return (f"<SrcGeoTransform>{_geotransform(src_transform)}</SrcGeoTransform>"
            f"<SrcInvGeoTransform>{_geotransform(~src_transform)}</SrcInvGeoTransform>")


def gcp_source(image_xy, map_xy, order, refine=None):
    """Transformer XML for a source placed by GCPs and GDAL's polynomial of ``order``.

    ``refine``: (tolerance, min_gcps) to have GDAL drop outliers like
    ``gdalwarp -refine_gcps``.
    """
    points = "".join(
        f'<GCP Id="{i}" Pixel={quoteattr(repr(float(c)))} Line={quoteattr(repr(float(r)))} '
        f'X={quoteattr(repr(float(x)))} Y={quoteattr(repr(float(y)))}/>'
        for i, ((c, r), (x, y)) in enumerate(zip(image_xy, map_xy)))
    refinement = ""
    if refine is not None:
        refinement = (f"<Refine>1</Refine><MinimumGcps>{refine[1]}</MinimumGcps>"
                      f"<Tolerance>{refine[0]!r}</Tolerance>")
    return (f"<SrcGCPTransformer><GCPTransformer><Order>{order}</Order><Reversed>0</Reversed>"
            f"{refinement}<GCPList>{points}</GCPList></GCPTransformer></SrcGCPTransformer>")


def gdal_map_to_image(image_xy, map_xy, order, dst_transform, shape, refine=None):
    """GDAL's map -> image prediction at the centres of an output grid.

    Warps two ramps whose pixel values are their own centre coordinates; bilinear
    interpolation is exact on a ramp, so each output pixel holds the (col, row)
    GDAL computed for it. Positions within one pixel of the source edge are NaN.
    """
    width = int(np.ceil(np.max(image_xy[:, 0]))) + 2
    height = int(np.ceil(np.max(image_xy[:, 1]))) + 2
    cols, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    ramps = np.stack([cols, rows])
    out = gdal_warp(ramps, gcp_source(image_xy, map_xy, order, refine), dst_transform, shape,
                    "bilinear", -1e9, plain_kernels=True)
    inside = ((out[0] > 1) & (out[0] < width - 1) & (out[1] > 1) & (out[1] < height - 1))
    return np.where(inside, out[0], np.nan), np.where(inside, out[1], np.nan)
