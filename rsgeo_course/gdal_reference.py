"""GDAL as the reference: the warps the book, the tests and the benchmarks compare rsgeo with.

Written once, here, in two paths:

- :func:`gdal_warp` (and :func:`warped_vrt`, its XML): a hand-written VRTWarpedDataset that
  names GDAL's transformer directly (:func:`affine_source`, :func:`gcp_source` or any other
  transformer's XML inside :func:`gen_img_proj`), with no approximate transformer around it,
  so that GDAL computes every output pixel's source position exactly, like rsgeo does by
  default; ``max_error`` wraps it in GDAL's approximate transformer, as gdalwarp does by
  default (``-et``). The benchmarks time the same VRT on read.
- :func:`gdalwarp_reproject`: what ``gdalwarp`` itself gives, through
  ``rasterio.warp.reproject`` (GDAL's chunked warp operation, ``ChunkAndWarpImage``): its
  approximate transformer with a 0.125-pixel threshold (rasterio 1.4 uses it between two grids
  and has no ``tolerance`` argument; with RPCs and ``RPC_DEM`` it is exact) and its kernel
  scale computed per chunk, from the unpadded source window.
  Checked with rasterio 1.4.4 and GDAL 3.10.3: given an array, rasterio's ``_reproject``
  replaces ``dst_nodata`` by ``dst_nodata or src_nodata``, so a destination nodata of 0 would be
  dropped; the destination here is therefore a dataset band carrying ``nodata``, which keeps it
  (GDAL's DstValid mask, GWKRealCase).

Examples
--------
>>> import affine
>>> import numpy as np
>>> image = np.arange(16, dtype=np.uint8).reshape(4, 4)
>>> grid = affine.Affine(1, 0, 0, 0, -1, 4)
>>> on_map = affine.Affine(1, 0, 0, 0, -1, 4)
>>> out = gdal_warp(image, affine_source(on_map), grid, (4, 4), "nearest", 0)
>>> bool((out == image).all())
True
"""

import os
import tempfile
import warnings
from xml.sax.saxutils import quoteattr

import numpy as np

__all__ = ["GDAL_RESAMPLING", "GDAL_TYPES", "geotransform", "affine_source", "gcp_source",
           "gen_img_proj", "warped_vrt", "gdal_warp", "gdalwarp_reproject"]

#: rsgeo's method names -> GDAL's resampling names in a VRT.
GDAL_RESAMPLING = {"nearest": "NearestNeighbour", "bilinear": "Bilinear", "cubic": "Cubic",
                   "average": "Average"}
#: NumPy dtypes -> GDAL's data types.
GDAL_TYPES = {"int8": "Int8", "uint8": "Byte", "uint16": "UInt16", "int16": "Int16",
              "uint32": "UInt32", "int32": "Int32", "float32": "Float32", "float64": "Float64",
              "int64": "Int64", "uint64": "UInt64"}


def geotransform(transform):
    """An affine.Affine as GDAL's six numbers, comma-separated, exactly (repr).

    Parameters
    ----------
    transform : affine.Affine
        A geotransform.

    Returns
    -------
    str
        ``"x0,a,b,y0,d,e"`` in GDAL's order.
    """
    return ",".join(repr(float(v)) for v in transform.to_gdal())


def affine_source(src_transform):
    """Transformer XML for a source placed on the map by an affine geotransform.

    Parameters
    ----------
    src_transform : affine.Affine
        The source's geotransform.

    Returns
    -------
    str
        The ``SrcGeoTransform`` and its inverse, for :func:`gen_img_proj`.
    """
    return (f"<SrcGeoTransform>{geotransform(src_transform)}</SrcGeoTransform>"
            f"<SrcInvGeoTransform>{geotransform(~src_transform)}</SrcInvGeoTransform>")


def gcp_source(image_xy, map_xy, order, refine=None):
    """Transformer XML for a source placed by GCPs and GDAL's polynomial of ``order``.

    Parameters
    ----------
    image_xy, map_xy : ndarray
        (n, 2) GCPs: (col, row) and (x, y).
    order : int
        The polynomial's degree.
    refine : tuple, optional
        (tolerance, min_gcps) to have GDAL drop outliers like ``gdalwarp -refine_gcps``.

    Returns
    -------
    str
        A ``SrcGCPTransformer``, for :func:`gen_img_proj`.
    """
    points = "".join(
        f'<GCP Id="{i}" Pixel={quoteattr(repr(float(c)))} Line={quoteattr(repr(float(r)))} '
        f'X={quoteattr(repr(float(x)))} Y={quoteattr(repr(float(y)))}/>'
        for i, ((c, r), (x, y)) in enumerate(zip(image_xy, map_xy, strict=True)))
    refinement = ""
    if refine is not None:
        refinement = (f"<Refine>1</Refine><MinimumGcps>{refine[1]}</MinimumGcps>"
                      f"<Tolerance>{refine[0]!r}</Tolerance>")
    return (f"<SrcGCPTransformer><GCPTransformer><Order>{order}</Order><Reversed>0</Reversed>"
            f"{refinement}<GCPList>{points}</GCPList></GCPTransformer></SrcGCPTransformer>")


def gen_img_proj(source_xml, dst_transform, reproject_xml=""):
    """GDAL's GenImgProjTransformer: the source's transformer, a reprojection, the output grid.

    Parameters
    ----------
    source_xml : str
        The source's transformer (:func:`affine_source`, :func:`gcp_source`, an RPC's).
    dst_transform : affine.Affine
        The output grid's geotransform.
    reproject_xml : str, optional
        A ``ReprojectTransformer`` between the two CRSs, if they differ.

    Returns
    -------
    str
        The transformer's XML.
    """
    return (f"<GenImgProjTransformer>{source_xml}{reproject_xml}"
            f"<DstGeoTransform>{geotransform(dst_transform)}</DstGeoTransform>"
            f"<DstInvGeoTransform>{geotransform(~dst_transform)}</DstInvGeoTransform>"
            "</GenImgProjTransformer>")


def warped_vrt(source_path, dst_transform, shape, transformer, method, dtype, count=1,
               nodata=0, src_nodata=None, block=None, max_error=None, scale=None,
               options=None, memory_limit=64 << 20):
    """The XML of a VRTWarpedDataset: ``source_path`` warped onto a grid by ``transformer``.

    Parameters
    ----------
    source_path : str
        The source GeoTIFF.
    dst_transform : affine.Affine
        The output grid's geotransform.
    shape : (rows, cols)
        The output grid's shape.
    transformer : str
        The transformer's XML (:func:`gen_img_proj`).
    method : {"nearest", "bilinear", "cubic", "average"}
        The resampling.
    dtype : str
        The source's and output's dtype name (``"uint8"``, ...).
    count : int, optional
        The number of bands.
    nodata : number or None, optional
        The destination nodata (``-dstnodata``); None for none (the output starts at 0).
    src_nodata : number or None, optional
        The source nodata (``-srcnodata``).
    block : (rows, cols) or int or None, optional
        The VRT's block, GDAL's chunk of output: one side, both, or None for the whole grid.
    max_error : float or None, optional
        None for GDAL's exact transformer, else its approximate transformer's threshold in
        pixels (gdalwarp's ``-et``).
    scale : (float, float) or None, optional
        The XSCALE and YSCALE warp options to force (1, 1: never widen the kernels); None to
        let GDAL compute them for each chunk.
    options : dict, optional
        More warp options (``NUM_THREADS``, ``UNIFIED_SRC_NODATA``, ...).
    memory_limit : int, optional
        GDAL's warp memory limit in bytes.

    Returns
    -------
    str
        The VRT's XML.
    """
    gdal_type = GDAL_TYPES[np.dtype(dtype).name]
    if max_error is not None:
        transformer = (f"<ApproxTransformer><MaxError>{max_error!r}</MaxError>"
                       f"<BaseTransformer>{transformer}</BaseTransformer></ApproxTransformer>")
    if block is None:
        block = shape
    elif np.ndim(block) == 0:
        block = (block, block)
    band_nodata = f"<NoDataValue>{nodata}</NoDataValue>" if nodata is not None else ""
    bands = "".join(
        f'<VRTRasterBand dataType="{gdal_type}" band="{b}" subClass="VRTWarpedRasterBand">'
        f"{band_nodata}</VRTRasterBand>" for b in range(1, count + 1))
    dst_nodata = (f"<DstNoDataReal>{nodata}</DstNoDataReal><DstNoDataImag>0</DstNoDataImag>"
                  if nodata is not None else "")
    src_nodata_xml = (f"<SrcNoDataReal>{src_nodata!r}</SrcNoDataReal>"
                      f"<SrcNoDataImag>0</SrcNoDataImag>" if src_nodata is not None else "")
    mapping = "".join(f'<BandMapping src="{b}" dst="{b}">{src_nodata_xml}{dst_nodata}'
                      "</BandMapping>" for b in range(1, count + 1))
    warp_options = {"INIT_DEST": "NO_DATA" if nodata is not None else "0"}
    if scale is not None:
        warp_options.update(XSCALE=repr(scale[0]), YSCALE=repr(scale[1]))
    warp_options.update(options or {})
    warp_options = "".join(f'<Option name="{key}">{value}</Option>'
                           for key, value in warp_options.items())
    return f"""<VRTDataset rasterXSize="{shape[1]}" rasterYSize="{shape[0]}" \
subClass="VRTWarpedDataset">
  <GeoTransform>{geotransform(dst_transform)}</GeoTransform>
  {bands}
  <BlockXSize>{block[1]}</BlockXSize><BlockYSize>{block[0]}</BlockYSize>
  <GDALWarpOptions>
    <WarpMemoryLimit>{memory_limit}</WarpMemoryLimit>
    <ResampleAlg>{GDAL_RESAMPLING[method]}</ResampleAlg>
    <WorkingDataType>{gdal_type}</WorkingDataType>{warp_options}
    <SourceDataset relativeToVRT="0">{source_path}</SourceDataset>
    <Transformer>{transformer}</Transformer>
    <BandList>{mapping}</BandList>
  </GDALWarpOptions>
</VRTDataset>"""


def _write_source(folder, bands):
    import rasterio

    path = os.path.join(folder, "source.tif")
    with warnings.catch_warnings():
        # no geotransform: the VRT's transformer places the source
        warnings.simplefilter("ignore", rasterio.errors.NotGeoreferencedWarning)
        with rasterio.open(path, "w", driver="GTiff", width=bands.shape[2],
                           height=bands.shape[1], count=bands.shape[0],
                           dtype=bands.dtype) as dataset:
            dataset.write(bands)
    return path


def gdal_warp(image, source_transformer_xml, dst_transform, shape, method, nodata,
              plain_kernels=False, scale=None, block=256, src_nodata=None, options=None,
              max_error=None):
    """Warp ``image`` with GDAL through a VRT; ``source_transformer_xml`` places it on the map.

    Parameters
    ----------
    image : ndarray
        2-D, or 3-D bands first.
    source_transformer_xml : str
        :func:`affine_source`, :func:`gcp_source` or another source transformer's XML.
    dst_transform : affine.Affine
        The output grid's geotransform.
    shape : (rows, cols)
        The output grid's shape.
    method : {"nearest", "bilinear", "cubic", "average"}
        The resampling.
    nodata : number or None
        The destination nodata, or None for none (gdalwarp without ``-dstnodata``: the output
        starts at 0).
    plain_kernels : bool, optional
        Set GDAL's XSCALE and YSCALE warp options to 1, so that it never widens its kernels (it
        otherwise does where the bounding box of a chunk's source window makes the scale look
        below 0.95).
    scale : (float, float), optional
        XSCALE and YSCALE to force instead.
    block : int, optional
        The VRT's block size, GDAL's chunk of output.
    src_nodata : number or None, optional
        The source nodata (gdalwarp's ``-srcnodata``), or None for none.
    options : dict, optional
        More warp options, name -> value (e.g. UNIFIED_SRC_NODATA).
    max_error : float or None, optional
        Wrap the transformer in GDAL's approximate transformer with this error threshold in
        pixels (gdalwarp's ``-et``), or None for the exact transformer.

    Returns
    -------
    ndarray
        GDAL's output, 2-D or bands first as ``image``.
    """
    import rasterio

    image = np.asarray(image)
    bands = image if image.ndim == 3 else image[np.newaxis]
    with tempfile.TemporaryDirectory() as folder:
        source = _write_source(folder, bands)
        xml = warped_vrt(source, dst_transform, shape,
                         gen_img_proj(source_transformer_xml, dst_transform), method,
                         bands.dtype, count=bands.shape[0], nodata=nodata,
                         src_nodata=src_nodata, block=block, max_error=max_error,
                         scale=(1, 1) if plain_kernels else scale, options=options)
        vrt = os.path.join(folder, "warped.vrt")
        with open(vrt, "w") as handle:
            handle.write(xml)
        with rasterio.open(vrt) as dataset:
            out = dataset.read()
    return out if image.ndim == 3 else out[0]


def gdalwarp_reproject(image, dst_transform, shape, method, nodata, crs, src_transform=None,
                       gcps=None, **warp_options):
    """What ``gdalwarp`` itself gives: ``rasterio.warp.reproject``, GDAL's chunked warp.

    Parameters
    ----------
    image : ndarray
        2-D, or 3-D bands first.
    dst_transform : affine.Affine
        The output grid's geotransform.
    shape : (rows, cols)
        The output grid's shape.
    method : {"nearest", "bilinear", "cubic", "average"}
        The resampling.
    nodata : number or None
        The destination nodata (kept: the destination is a band carrying it); None for none.
    crs : str or rasterio.crs.CRS
        The source's and the output's CRS.
    src_transform : affine.Affine, optional
        The source's geotransform (an image placed by it)...
    gcps : rsgeo.gcp.GCPSet, optional
        ... or its GCPs (GDAL's GCP transformer; ``MAX_GCP_ORDER`` or ``SRC_METHOD`` in
        ``warp_options`` choose the model).
    **warp_options
        GDAL warp or transformer options, e.g. ``XSCALE="0.5"``.

    Returns
    -------
    ndarray
        gdalwarp's output, 2-D or bands first as ``image``.
    """
    import rasterio
    from rasterio.control import GroundControlPoint
    from rasterio.io import MemoryFile
    from rasterio.warp import Resampling, reproject

    image = np.asarray(image)
    bands = image if image.ndim == 3 else image[np.newaxis]
    placed = {"src_transform": src_transform}
    if gcps is not None:
        placed = {"gcps": [GroundControlPoint(row=row, col=col, x=x, y=y)
                           for (col, row), (x, y) in zip(gcps.image_xy, gcps.map_xy,
                                                         strict=True)]}
    profile = dict(driver="GTiff", width=shape[1], height=shape[0], count=len(bands),
                   dtype=bands.dtype, crs=crs, transform=dst_transform, nodata=nodata)
    with MemoryFile() as memory, memory.open(**profile) as out:
        reproject(bands, rasterio.band(out, list(range(1, len(bands) + 1))), src_crs=crs,
                  src_nodata=None, dst_nodata=nodata, init_dest_nodata=True,
                  resampling=Resampling[method], num_threads=1, **placed, **warp_options)
        return out.read() if image.ndim == 3 else out.read(1)
