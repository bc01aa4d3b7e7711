"""GDAL as the reference: warps through a hand-written VRTWarpedDataset.

The VRT names GDAL's transformer directly, with no approximate transformer
around it (its default 0.125-pixel error threshold would move sample positions
and change values), so GDAL computes every output pixel's source position
exactly, like rsgeo does by default. ``gdal_warp(..., max_error=0.125)`` wraps
it in GDAL's approximate transformer instead, as gdalwarp does by default, to
check rsgeo's ``warp(..., error_threshold=0.125)``.
"""

import os
import tempfile
from xml.sax.saxutils import quoteattr

import numpy as np
import rasterio

_RESAMPLING = {"nearest": "NearestNeighbour", "bilinear": "Bilinear", "cubic": "Cubic",
              "average": "Average"}
_GDAL_TYPES = {"uint8": "Byte", "uint16": "UInt16", "int16": "Int16", "int32": "Int32",
               "float32": "Float32", "float64": "Float64", "int64": "Int64", "uint64": "UInt64"}


def _geotransform(transform):
    return ",".join(repr(float(v)) for v in transform.to_gdal())


def _write_source(folder, image):
    bands = image if image.ndim == 3 else image[np.newaxis]
    path = os.path.join(folder, "source.tif")
    with rasterio.open(path, "w", driver="GTiff", width=bands.shape[2], height=bands.shape[1],
                       count=bands.shape[0], dtype=bands.dtype) as dataset:
        dataset.write(bands)
    return path, bands.shape[0]


def gdal_warp(image, source_transformer_xml, dst_transform, shape, method, nodata,
              plain_kernels=False, scale=None, block=256, src_nodata=None, options=None,
              max_error=None):
    """Warp ``image`` with GDAL; ``source_transformer_xml`` places the source on the map.

    ``nodata``: the destination nodata, or None for none (gdalwarp without
    ``-dstnodata``: the output starts at 0).
    ``plain_kernels``: set GDAL's XSCALE and YSCALE warp options to 1, so that it
    never widens its kernels (it otherwise does where the bounding box of a
    chunk's source window makes the scale look below 0.95).
    ``scale``: (xscale, yscale) to force as XSCALE and YSCALE instead.
    ``block``: the VRT's block size, GDAL's chunk of output.
    ``src_nodata``: the source nodata (gdalwarp's ``-srcnodata``), or None for none.
    ``options``: more warp options, a dict of name -> value (e.g. UNIFIED_SRC_NODATA).
    ``max_error``: wrap the transformer in GDAL's approximate transformer with this
    error threshold in pixels (gdalwarp's ``-et``), or None for the exact transformer.
    """
    dtype = _GDAL_TYPES[np.dtype(image.dtype).name]
    with tempfile.TemporaryDirectory() as folder:
        source, count = _write_source(folder, np.asarray(image))
        band_nodata = f"<NoDataValue>{nodata}</NoDataValue>" if nodata is not None else ""
        bands = "".join(
            f'<VRTRasterBand dataType="{dtype}" band="{b}" subClass="VRTWarpedRasterBand">'
            f"{band_nodata}</VRTRasterBand>" for b in range(1, count + 1))
        dst_nodata = (f"<DstNoDataReal>{nodata}</DstNoDataReal><DstNoDataImag>0</DstNoDataImag>"
                      if nodata is not None else "")
        src_nodata_xml = (f"<SrcNoDataReal>{src_nodata!r}</SrcNoDataReal>"
                          f"<SrcNoDataImag>0</SrcNoDataImag>" if src_nodata is not None else "")
        mapping = "".join(f'<BandMapping src="{b}" dst="{b}">{src_nodata_xml}{dst_nodata}'
                          "</BandMapping>" for b in range(1, count + 1))
        init = "NO_DATA" if nodata is not None else "0"
        inverse = ~dst_transform
        if plain_kernels:
            scale = (1, 1)
        scale_options = (f'<Option name="XSCALE">{scale[0]!r}</Option>'
                         f'<Option name="YSCALE">{scale[1]!r}</Option>'
                         if scale is not None else "")
        scale_options += "".join(f'<Option name="{key}">{value}</Option>'
                                 for key, value in (options or {}).items())
        transformer = f"""<GenImgProjTransformer>
      {source_transformer_xml}
      <DstGeoTransform>{_geotransform(dst_transform)}</DstGeoTransform>
      <DstInvGeoTransform>{_geotransform(inverse)}</DstInvGeoTransform>
    </GenImgProjTransformer>"""
        if max_error is not None:
            transformer = (f"<ApproxTransformer><MaxError>{max_error!r}</MaxError>"
                           f"<BaseTransformer>{transformer}</BaseTransformer></ApproxTransformer>")
        xml = f"""<VRTDataset rasterXSize="{shape[1]}" rasterYSize="{shape[0]}" \
subClass="VRTWarpedDataset">
  <GeoTransform>{_geotransform(dst_transform)}</GeoTransform>
  {bands}
  <BlockXSize>{block}</BlockXSize><BlockYSize>{block}</BlockYSize>
  <GDALWarpOptions>
    <WarpMemoryLimit>67108864</WarpMemoryLimit>
    <ResampleAlg>{_RESAMPLING[method]}</ResampleAlg>
    <WorkingDataType>{dtype}</WorkingDataType>
    <Option name="INIT_DEST">{init}</Option>{scale_options}
    <SourceDataset relativeToVRT="0">{source}</SourceDataset>
    <Transformer>{transformer}</Transformer>
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


def gdalwarp_reproject(image, src_transform, dst_transform, shape, method, nodata,
                       crs="EPSG:29191", **warp_options):
    """What gdalwarp itself gives: rasterio.warp.reproject, GDAL's chunked warp operation.

    Unlike :func:`gdal_warp` (a VRTWarpedDataset, which computes the scale of
    each chunk from its padded source window), this is the path of
    ``gdalwarp``: GDALWarpOperation::ChunkAndWarpImage, the scale from the
    unpadded source window (``dfSrcXSizeRaw``). Two things make it differ
    from :func:`gdal_warp` beyond the scale (checked with rasterio 1.4.4,
    GDAL 3.10.3):

    * rasterio's ``_reproject`` always wraps GDAL's transformer in the
      approximate transformer with a 0.125-pixel threshold (gdalwarp's
      default ``-et 0.125``; its ``tolerance`` argument is ignored). For an
      affine map the linear interpolation along each output row is exact in
      real numbers but not in floating point: positions move in the last
      bits, so exact .5 ties (an enlargement such as 10 m -> 4 m) round the
      other way for about 0.5 % of bilinear pixels. rsgeo follows the exact
      transformer (``gdalwarp -et 0``), not this.
    * given an array, ``_reproject`` replaces ``dst_nodata`` by
      ``dst_nodata or src_nodata``, so a destination nodata of 0 is silently
      dropped. The destination here is therefore a dataset band carrying
      ``nodata``, which keeps it (GDAL's DstValid mask, GWKRealCase).

    ``nodata`` None: no destination nodata, the output starts at 0.
    ``warp_options``, e.g. ``XSCALE="0.5"``, are passed to GDAL as warp options.
    """
    from rasterio.warp import Resampling, reproject

    image = np.asarray(image)
    bands = image if image.ndim == 3 else image[np.newaxis]
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "destination.tif")
        with rasterio.open(path, "w+", driver="GTiff", width=shape[1], height=shape[0],
                           count=bands.shape[0], dtype=bands.dtype, crs=crs,
                           transform=dst_transform, nodata=nodata) as dataset:
            reproject(bands, rasterio.band(dataset, list(range(1, bands.shape[0] + 1))),
                      src_transform=src_transform, src_crs=crs,
                      resampling=getattr(Resampling, method), src_nodata=None,
                      dst_nodata=nodata, init_dest_nodata=True, **warp_options)
            out = dataset.read()
    return out if image.ndim == 3 else out[0]


def gdal_suggested_grid(shape, transform=None, gcps=None, crs="EPSG:29191"):
    """GDAL's GDALSuggestedWarpOutput2 for a source of ``shape`` (rows, cols).

    The source is placed by its geotransform or by ``gcps`` ((col, row, x, y)
    rows, for GDAL's GCP polynomial); a WarpedVRT into the same CRS with no
    grid given takes GDAL's suggested transform and size.
    """
    from rasterio.control import GroundControlPoint
    from rasterio.vrt import WarpedVRT

    rows, cols = shape
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "source.tif")
        options = dict(driver="GTiff", width=cols, height=rows, count=1, dtype="uint8", crs=crs)
        if gcps is None:
            options["transform"] = transform
        with rasterio.open(path, "w", **options) as dataset:
            if gcps is not None:
                dataset.gcps = ([GroundControlPoint(row=r, col=c, x=x, y=y, z=0.0)
                                 for c, r, x, y in gcps], rasterio.crs.CRS.from_user_input(crs))
        with rasterio.open(path) as source, WarpedVRT(source, crs=source.crs) as vrt:
            return vrt.transform, (vrt.height, vrt.width)
