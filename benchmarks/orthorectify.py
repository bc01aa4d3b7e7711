"""Orthorectification speed and memory: rsgeo's RPC + DEM beside GDAL's, in the same run.

    python benchmarks/orthorectify.py [--sizes 2048 4096] [--dtypes uint8 int16]
                                      [--grids lonlat utm] [--methods nearest bilinear cubic]
                                      [--threads 1 2] [--repeat 3] [--once-above 2]
                                      [--no-memory] [--output FILE]

One row per (grid, method, size, dtype): the seconds of one orthorectification
of a ``size`` x ``size`` random image (covering the dtype's range) onto a
``size`` x ``size`` output grid, best of ``--repeat`` runs, for

* rsgeo's ``terrain.orthorectify(image, rpc, dem, ...)`` (exact: every cell's
  longitude, latitude, DEM height and RPC position computed, as
  ``gdalwarp -et 0``), with ``num_threads`` of each ``--threads``;
* GDAL through a VRTWarpedDataset naming its transformer (a
  GenImgProjTransformer around GDAL's RPCTransformer with ``RPC_DEM`` and
  bilinear DEM interpolation, as tests/gdal_reference.py builds them for the
  other models): exactly (``gdalwarp -et 0``, which is also gdalwarp's default
  when ``RPC_DEM`` is given) and wrapped in its approximate transformer with a
  0.125-pixel threshold (``gdalwarp -et 0.125``, the default of every other
  transformer), with the warp option ``NUM_THREADS`` of each ``--threads``.
  The warp happens when the VRT is read: the time is opening it (GDAL opens
  the DEM and sets up its transformers there) and reading it, from an
  uncompressed GeoTIFF source in a temporary folder; nothing is subtracted.

The scene (``--grids``): a pushbroom image looking 20 degrees off nadir over
Olinda (lon -34.9, lat -8.0), ``size`` pixels of 8.8 km / ``size`` each way,
its RPC fitted to the sensor model as vendors do (``terrain.fit_rpc``, a 3-D
grid), a DEM of smooth hills up to a few hundred metres on a 0.001-degree grid
in EPSG:4326, and the output grid over the same ground:

=======  ===========================================================================
lonlat   the grid in EPSG:4326, the RPC's own CRS (the usual orthoimage product):
         no PROJ at all
utm      the grid in SIRGAS 2000 / UTM 25S (EPSG:31985), the DEM in EPSG:4326:
         PROJ takes every cell to longitude and latitude (in both libraries)
utm_dem  the grid and the DEM in UTM 25S (chapter 4b's case): PROJ twice per cell
=======  ===========================================================================

Both libraries use their plain 1 x 1, 2 x 2 and 4 x 4 kernels (GDAL's XSCALE
= YSCALE = 1), destination nodata 0, and one GDAL chunk for the whole grid (the
VRT's block), so that they do the same work: the columns ``differing_exact``
and ``differing_approx`` count the output pixels where rsgeo (exact) and GDAL
disagree (0 expected for the exact transformer).

Ratios are GDAL's time over rsgeo's, measured in the same run (> 1: rsgeo is
faster): ``x_gdal_exact_1t`` compares both exact with one thread,
``x_gdal_approx_1t`` rsgeo exact with GDAL approximated (rsgeo's
orthorectify has no approximation), ``..._2t`` the same with two threads;
``speedup_2t`` is rsgeo's one-thread time over its two-thread time. The peers of
a row run in turn, repeat after repeat, so that a busy machine slows them
alike; rsgeo is run once on a small grid before it is timed (Numba compiles
there). Numba's compile time is measured apart, in a fresh process with an
empty cache, and is in no time of the table.

Memory (bilinear rows, unless ``--no-memory``): each of rsgeo (one thread) and
GDAL exact (one thread) orthorectifies once in a fresh process that has
built the scene and warmed up; the peak resident set size of the call beyond
what the process held before it (Linux's VmHWM, reset through
/proc/self/clear_refs), divided by the output pixels:
``rsgeo_peak_bytes_per_px`` and ``gdal_peak_bytes_per_px``. It includes the
output array itself (1 byte per pixel for uint8, 2 for int16).

The table is printed and saved as CSV (default
``benchmarks/results/orthorectify.csv``), with the machine and the compile
times as ``# key: value`` lines above the header (read it with
``pandas.read_csv(file, comment="#")``). Rows that miss the speed goals
(>= 1.0x GDAL exact single-threaded, >= 1.7x rsgeo's own time with two
threads) are listed at the end.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import affine
import numpy as np

from rsgeo.ortho import orthorectify
from rsgeo.resample import METHODS
from rsgeo.sensors import PushbroomSensor, fit_rpc

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
from gdal_vrt import GdalWarps, gen_img_proj, warped_vrt  # noqa: E402  (benchmarks/)
from machine import describe, save_table  # noqa: E402  (benchmarks/machine.py)
from timing import time_in_turn  # noqa: E402  (benchmarks/timing.py)

#: GDAL's approximation threshold (gdalwarp -et), in source pixels
ERROR_THRESHOLD = 0.125
GRIDS = ("lonlat", "utm", "utm_dem")
UTM = "EPSG:31985"                    # SIRGAS 2000 / UTM zone 25S
LON0, LAT0 = -34.9, -8.0              # the scene's centre (Olinda)
HALF = 0.04                           # degrees: the output grid spans LON0 +- HALF, LAT0 +- HALF
KX, KY = 111320.0 * np.cos(np.radians(LAT0)), 110574.0   # metres per degree, locally
ANGLE, ALTITUDE = 20.0, 700e3         # view angle (degrees off nadir) and orbit height (m)
_DTYPES = ("uint8", "int16", "uint16")


# --- The scene --------------------------------------------------------------------------------


def test_image(size, dtype):
    """A random image covering the dtype's whole range (the same in every run)."""
    info = np.iinfo(dtype)
    return np.random.default_rng(0).integers(info.min, int(info.max) + 1, (size, size),
                                             dtype=dtype)


def pixel_metres(size):
    """The image's (and the output grid's) pixel: the scene's 2 * HALF degrees over ``size``."""
    return 2 * HALF * KY / size


def fitted_rpc(size):
    """The RPC of a ``size`` x ``size`` pushbroom image 20 degrees off nadir over the scene.

    The sensor works in local metres, x = (lon - LON0) * KX, y = (lat - LAT0) * KY;
    its middle column sees (LON0, LAT0) at height 0. The RPC is fitted to a
    15 x 15 x 5 grid of it (0 to 600 m), as vendors do.
    """
    pixel = pixel_metres(size)
    ifov = np.degrees(pixel / ALTITUDE * np.cos(np.radians(ANGLE)) ** 2)
    sensor = PushbroomSensor(-ALTITUDE * np.tan(np.radians(ANGLE)), size * pixel / 2, ALTITUDE,
                             ANGLE, ifov, size, pixel)
    margin = 1.15 * HALF
    grid = np.meshgrid(np.linspace(LON0 - margin, LON0 + margin, 15),
                       np.linspace(LAT0 - margin, LAT0 + margin, 15),
                       np.linspace(0, 600, 5), indexing="ij")
    lon, lat, h = (a.ravel() for a in grid)
    col, row = sensor.project((lon - LON0) * KX, (lat - LAT0) * KY, h)
    return fit_rpc(lon, lat, h, col, row)


def hills(lon, lat):
    """Smooth hills up to a few hundred metres (the same in every run)."""
    rng = np.random.default_rng(0)
    height = np.zeros(np.shape(lon))
    for _ in range(8):
        east, north = rng.uniform(-0.06, 0.06, 2)
        spread, top = rng.uniform(0.008, 0.03), rng.uniform(50, 300)
        height += top * np.exp(-((lon - LON0 - east) ** 2 + (lat - LAT0 - north) ** 2)
                               / (2 * spread * spread))
    return height


def dem_in(crs):
    """(heights as float32, geotransform, CRS) of :func:`hills` on a 120 x 120 grid over the
    scene and its margins: 0.001 degree in EPSG:4326, 110 m in UTM."""
    n = 120
    if crs == "EPSG:4326":
        step = 0.001
        transform = affine.Affine(step, 0, LON0 - n * step / 2, 0, -step, LAT0 + n * step / 2)
        cols, rows = np.meshgrid(np.arange(n) + 0.5, np.arange(n) + 0.5)
        lon, lat = transform * (cols, rows)
    else:
        from rasterio.warp import transform as to_crs

        (x,), (y,) = to_crs("EPSG:4326", crs, [LON0], [LAT0])
        step = 110.0
        transform = affine.Affine(step, 0, x - n * step / 2, 0, -step, y + n * step / 2)
        cols, rows = np.meshgrid(np.arange(n) + 0.5, np.arange(n) + 0.5)
        xs, ys = transform * (cols, rows)
        lon, lat = (np.reshape(v, (n, n)) for v in to_crs(crs, "EPSG:4326", xs.ravel(),
                                                          ys.ravel()))
    return hills(lon, lat).astype(np.float32), transform, crs


def output_grid(grid, size):
    """(geotransform, CRS) of the ``size`` x ``size`` output grid over the scene."""
    if grid == "lonlat":
        step = 2 * HALF / size
        return affine.Affine(step, 0, LON0 - HALF, 0, -step, LAT0 + HALF), "EPSG:4326"
    from rasterio.warp import transform as to_crs

    (x,), (y,) = to_crs("EPSG:4326", UTM, [LON0], [LAT0])
    pixel = pixel_metres(size)
    half = size * pixel / 2
    return affine.Affine(pixel, 0, x - half, 0, -pixel, y + half), UTM


@dataclass
class Scene:
    """One grid of one size: what both libraries orthorectify, and the DEM's file for GDAL."""

    grid: str
    size: int
    rpc: object
    dem: np.ndarray
    dem_transform: affine.Affine
    dem_crs: str
    transform: affine.Affine
    crs: str
    dem_path: str


def make_scene(grid, size, folder):
    """The :class:`Scene` of ``grid`` (one of :data:`GRIDS`), its DEM written in ``folder``."""
    import rasterio

    dem, dem_transform, dem_crs = dem_in(UTM if grid == "utm_dem" else "EPSG:4326")
    path = str(Path(folder) / f"dem_{grid}_{size}.tif")
    with rasterio.open(path, "w", driver="GTiff", width=dem.shape[1], height=dem.shape[0],
                       count=1, dtype=dem.dtype, transform=dem_transform,
                       crs=dem_crs) as dataset:
        dataset.write(dem, 1)
    transform, crs = output_grid(grid, size)
    return Scene(grid, size, fitted_rpc(size), dem, dem_transform, dem_crs, transform, crs,
                 path)


# --- The peers --------------------------------------------------------------------------------


def rsgeo_runner(image, scene, method, threads, transform=None, shape=None):
    """A function that orthorectifies with rsgeo and returns the array."""
    def run():
        # heights above the ellipsoid: GDAL takes a DEM file without a vertical CRS so
        return orthorectify(image, scene.rpc, scene.dem, scene.dem_transform,
                            transform or scene.transform, shape or (scene.size, scene.size),
                            method, nodata=0, dst_crs=scene.crs, dem_crs=scene.dem_crs,
                            num_threads=threads, dem_vertical="ellipsoidal", scale=1)
    return run


def rpc_transformer_xml(scene):
    """GDAL's serialised RPCTransformer with the scene's RPC and DEM (bilinear)."""
    from xml.sax.saxutils import escape, quoteattr

    metadata = "".join(f"<MDI key={quoteattr(key)}>{escape(value)}</MDI>"
                       for key, value in scene.rpc.to_dict().items())
    return ("<RPCTransformer><Reversed>0</Reversed><HeightOffset>0</HeightOffset>"
            f"<DEMPath>{escape(scene.dem_path)}</DEMPath>"
            "<DEMInterpolation>bilinear</DEMInterpolation>"
            f"<PixErrThreshold>0.1</PixErrThreshold><Metadata>{metadata}</Metadata>"
            "</RPCTransformer>")


def vrt_xml(source_path, scene, method, dtype, threads, max_error=None):
    """A VRTWarpedDataset: GDAL's RPC transformer (and PROJ to a UTM grid), one block.

    As benchmarks/resample.py's VRT (benchmarks/gdal_vrt.py: destination
    nodata 0, XSCALE = YSCALE = 1, the warp option NUM_THREADS), with
    ``max_error`` None for the exact transformer or GDAL's approximate
    transformer's threshold.
    """
    reproject = ""
    if scene.crs != "EPSG:4326":
        # source georeferenced coordinates (the RPC's longitude, latitude) -> the grid's CRS
        reproject = ("<ReprojectTransformer><ReprojectionTransformer>"
                     f"<SourceSRS>EPSG:4326</SourceSRS><TargetSRS>{scene.crs}</TargetSRS>"
                     "</ReprojectionTransformer></ReprojectTransformer>")
    source = f"<SrcRPCTransformer>{rpc_transformer_xml(scene)}</SrcRPCTransformer>"
    return warped_vrt(source_path, scene.transform, (scene.size, scene.size),
                      gen_img_proj(source, scene.transform, reproject), method, dtype,
                      threads, max_error)


def gdal_runner(gdal, scene, method, threads, max_error=None):
    """GDAL's warp of ``scene`` through :class:`gdal_vrt.GdalWarps`."""
    return gdal.runner(vrt_xml(gdal.source, scene, method, gdal.dtype, threads, max_error))


# --- Timing -----------------------------------------------------------------------------------


def warm_up(image, scene, method, threads=(1,)):
    """Compile (or load) rsgeo's kernels on a 32 x 32 window at the grid's centre, with each
    thread count (PROJ's worker threads set up there too)."""
    offset = (scene.size - 32) / 2
    centre = scene.transform * affine.Affine.translation(offset, offset)
    for count in threads:
        rsgeo_runner(image, scene, method, count, centre, (32, 32))()


def _label(library, kind, threads):
    return f"{library}_{kind}_{threads}t"


def row_of(image, scene, method, threads, repeat, gdal, once_above=2.0):
    """One table row: the seconds of every peer, their ratios and their differing pixels."""
    warm_up(image, scene, method, threads)
    runners = {}
    for count in threads:
        runners[_label("rsgeo", "exact", count)] = rsgeo_runner(image, scene, method, count)
        runners[_label("gdal", "exact", count)] = gdal_runner(gdal, scene, method, count)
        runners[_label("gdal", "approx", count)] = gdal_runner(gdal, scene, method, count,
                                                               ERROR_THRESHOLD)
    first = threads[0]
    compared = [_label("rsgeo", "exact", first), _label("gdal", "exact", first),
                _label("gdal", "approx", first)]
    seconds, outputs, errors = time_in_turn(runners, repeat, compared, once_above)
    row = {f"{label}_s": value for label, value in seconds.items()}
    ours = outputs.get(_label("rsgeo", "exact", first))
    for kind in ("exact", "approx"):
        for count in threads:
            row[f"x_gdal_{kind}_{count}t"] = (seconds[_label("gdal", kind, count)]
                                              / seconds[_label("rsgeo", "exact", count)])
        theirs = outputs.get(_label("gdal", kind, first))
        row[f"differing_{kind}"] = (int(np.count_nonzero(ours != theirs))
                                    if ours is not None and theirs is not None else -1)
    for count in threads[1:]:
        row[f"speedup_{count}t"] = (seconds[_label("rsgeo", "exact", first)]
                                    / seconds[_label("rsgeo", "exact", count)])
    row["note"] = "; ".join(f"{label}: {text}" for label, text in errors.items())
    return row


def benchmark(sizes=(2048, 4096), dtypes=("uint8", "int16"), grids=("lonlat", "utm"),
              methods=METHODS, repeat=3, threads=(1, 2), once_above=2.0, memory=True,
              log=print):
    """The table: a dict per row (grid, method, size, dtype, then :func:`row_of`'s and, on
    bilinear rows with ``memory``, the peak bytes per output pixel)."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for size in sizes:
            scenes = [make_scene(grid, size, folder) for grid in grids]
            for dtype in dtypes:
                image = test_image(size, dtype)
                gdal = GdalWarps(folder, image)
                for scene in scenes:
                    for method in methods:
                        start = time.perf_counter()
                        row = row_of(image, scene, method, threads, repeat, gdal, once_above)
                        if memory and method == "bilinear":
                            for peer in ("rsgeo", "gdal"):
                                row[f"{peer}_peak_bytes_per_px"] = peak_bytes_per_pixel(
                                    peer, scene.grid, size, dtype)
                        rows.append({"grid": scene.grid, "method": method, "size": size,
                                     "dtype": dtype, **row})
                        log(f"{scene.grid} {method} {size} {dtype}: "
                            f"{time.perf_counter() - start:.1f} s")
                os.remove(gdal.source)
    return rows


# --- Memory: one orthorectification in a fresh process ---------------------------------------


def _kilobytes(field):
    """A VmRSS / VmHWM line of /proc/self/status, in kB."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1])
    raise OSError(f"no {field} in /proc/self/status")


def measure_child(peer, grid, size, dtype):
    """(In the child.) Build the scene, warm up, then the peak RSS of one bilinear run beyond
    what the process held before it, in bytes per output pixel (NaN where Linux's counters
    cannot be read or reset)."""
    with tempfile.TemporaryDirectory() as folder:
        scene = make_scene(grid, size, folder)
        image = test_image(size, dtype)
        if peer == "rsgeo":
            warm_up(image, scene, "bilinear")
            run = rsgeo_runner(image, scene, "bilinear", 1)
        else:
            # GDAL's drivers and PROJ set up on a 32 x 32 warp first
            run = gdal_runner(GdalWarps(folder, image), scene, "bilinear", 1)
            small = Scene(**{**scene.__dict__, "size": 32})
            gdal_runner(GdalWarps(folder, test_image(32, dtype)), small, "bilinear", 1)()
        try:
            Path("/proc/self/clear_refs").write_text("5")     # VmHWM := VmRSS
            before = _kilobytes("VmRSS")
        except OSError:
            return float("nan")
        out = run()
        peak = _kilobytes("VmHWM")
        return (peak - before) * 1024 / out.size


def peak_bytes_per_pixel(peer, grid, size, dtype):
    """:func:`measure_child` in a fresh Python process; NaN if it fails."""
    command = [sys.executable, __file__, "--memory-child", peer, grid, str(size), dtype]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    try:
        return float(done.stdout.split()[-1])
    except (IndexError, ValueError):
        return float("nan")


# --- Compile time, machine, output --------------------------------------------------------------

_COMPILE = """
import sys, tempfile, time
sys.path.insert(0, {benchmarks!r})
start = time.perf_counter()
import orthorectify as bench
image = bench.test_image(64, {dtype!r})
with tempfile.TemporaryDirectory() as folder:
    for grid in ("lonlat", "utm"):
        scene = bench.make_scene(grid, 64, folder)
        for method in bench.METHODS:
            bench.rsgeo_runner(image, scene, method, 1)()
print(time.perf_counter() - start)
"""


def jit_seconds(dtype="uint8"):
    """Seconds to import rsgeo, build two 64 x 64 scenes (lonlat and utm) and orthorectify
    each with the 3 methods, in a new process: (with an empty Numba cache, i.e. compiling;
    then loading what that run cached)."""
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        code = _COMPILE.format(benchmarks=str(ROOT / "benchmarks"), dtype=dtype)
        runs = [float(subprocess.run([sys.executable, "-c", code], env=env, check=True,
                                     capture_output=True, text=True).stdout.split()[-1])
                for _ in range(2)]
    return runs[0], runs[1]


def machine():
    """What the numbers depend on: date, processor, CPU count and library versions."""
    import numba
    import rasterio

    return describe(numba=f"{numba.__version__} (rsgeo's threads: Python threads over blocks "
                          "of rows)",
                    GDAL=rasterio.__gdal_version__, rasterio=rasterio.__version__)


def columns(threads):
    """The CSV's columns, in order, for the thread counts ``threads``."""
    names = ["grid", "method", "size", "dtype"]
    names += [f"{_label('rsgeo', 'exact', count)}_s" for count in threads]
    for kind in ("exact", "approx"):
        names += [f"{_label('gdal', kind, count)}_s" for count in threads]
    names += [f"x_gdal_{kind}_{count}t" for kind in ("exact", "approx") for count in threads]
    names += [f"speedup_{count}t" for count in threads[1:]]
    return names + ["differing_exact", "differing_approx", "rsgeo_peak_bytes_per_px",
                    "gdal_peak_bytes_per_px", "note"]


def save_csv(rows, file, threads, command="", extra=None):
    """Write the table with the machine's description (and ``extra``) as
    ``# key: value`` lines above it."""
    return save_table(file, {**machine(), **(extra or {}), "command": command},
                      columns(threads), rows)


def print_table(rows, threads):
    first, more = threads[0], threads[1:]
    print(f"{'grid':>7} {'method':>8} {'size':>5} {'dtype':>6} {'rsgeo s':>8} {'×exact':>7} "
          f"{'×approx':>7}" + "".join(f" {f'×exact {t}t':>10}" for t in more)
          + "".join(f" {f'speedup {t}t':>11}" for t in more) + f" {'differing':>10}"
          + f" {'B/px rsgeo':>10} {'B/px GDAL':>9}")
    for row in rows:
        print(f"{row['grid']:>7} {row['method']:>8} {row['size']:>5} {row['dtype']:>6} "
              f"{row[_label('rsgeo', 'exact', first) + '_s']:8.3f} "
              f"{row[f'x_gdal_exact_{first}t']:7.2f} {row[f'x_gdal_approx_{first}t']:7.2f}"
              + "".join(f" {row[f'x_gdal_exact_{t}t']:10.2f}" for t in more)
              + "".join(f" {row[f'speedup_{t}t']:11.2f}" for t in more)
              + f" {row['differing_exact']:>4}/{row['differing_approx']:<5}"
              + f" {row.get('rsgeo_peak_bytes_per_px', np.nan):10.1f}"
              + f" {row.get('gdal_peak_bytes_per_px', np.nan):9.1f}")


def misses(rows, threads, speedup_goal=0.85):
    """The rows that miss the speed goals (>= 1.0x GDAL exact with one thread, two threads
    >= 1.7x one), as text lines."""
    first = threads[0]
    lines = []
    for row in rows:
        where = f"{row['grid']} {row['method']} {row['size']} {row['dtype']}"
        ratio = row[f"x_gdal_exact_{first}t"]
        if not ratio >= 1.0:
            lines.append(f"{where}: {ratio:.2f}x GDAL exact, {first} thread(s)")
        for count in threads[1:]:
            speedup = row[f"speedup_{count}t"]
            if not speedup >= speedup_goal * count:
                lines.append(f"{where}: {count} threads {speedup:.2f}x one")
        if row["differing_exact"] != 0:
            lines.append(f"{where}: {row['differing_exact']} pixels differ from GDAL exact")
        if row["note"]:
            lines.append(f"{where}: {row['note']}")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2048, 4096])
    parser.add_argument("--dtypes", nargs="+", default=["uint8", "int16"],
                        choices=sorted(_DTYPES))
    parser.add_argument("--grids", nargs="+", default=["lonlat", "utm"], choices=GRIDS)
    parser.add_argument("--methods", nargs="+", default=list(METHODS), choices=list(METHODS))
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2],
                        help="thread counts to time, the first the reference (default: 1 2)")
    parser.add_argument("--repeat", type=int, default=3,
                        help="runs of each peer, the best timed (default: 3)")
    parser.add_argument("--once-above", type=float, default=2.0,
                        help="seconds: a peer's run longer than this is not repeated "
                             "(default: 2)")
    parser.add_argument("--no-memory", action="store_true",
                        help="leave out the peak memory columns (fresh processes)")
    parser.add_argument("--output",
                        default=ROOT / "benchmarks" / "results" / "orthorectify.csv",
                        help="CSV file to write (default: benchmarks/results/orthorectify.csv)")
    parser.add_argument("--memory-child", nargs=4, metavar=("PEER", "GRID", "SIZE", "DTYPE"),
                        help=argparse.SUPPRESS)
    arguments = parser.parse_args(argv)
    if arguments.memory_child:
        peer, grid, size, dtype = arguments.memory_child
        print(measure_child(peer, grid, int(size), dtype))
        return
    dtype = arguments.dtypes[0]
    compile_s, cached_s = jit_seconds(dtype)
    extra = {f"Numba JIT, first orthorectify of the 3 methods on {dtype}, lonlat and utm "
             "grids (s)": f"{compile_s:.1f} compiling (empty cache), {cached_s:.1f} from the "
                          "cache"}
    print("; ".join(f"{key}: {value}" for key, value in extra.items()))
    start = time.perf_counter()
    table = benchmark(arguments.sizes, arguments.dtypes, arguments.grids, arguments.methods,
                      arguments.repeat, arguments.threads, arguments.once_above,
                      not arguments.no_memory, log=lambda text: print(text, file=sys.stderr))
    extra["benchmark run time (s)"] = f"{time.perf_counter() - start:.0f}"
    print_table(table, arguments.threads)
    command = ("python benchmarks/orthorectify.py --sizes " + " ".join(map(str, arguments.sizes))
               + " --dtypes " + " ".join(arguments.dtypes)
               + " --grids " + " ".join(arguments.grids)
               + " --methods " + " ".join(arguments.methods)
               + " --threads " + " ".join(map(str, arguments.threads))
               + f" --repeat {arguments.repeat} --once-above {arguments.once_above:g}"
               + (" --no-memory" if arguments.no_memory else ""))
    print("saved", save_csv(table, arguments.output, arguments.threads, command, extra))
    missed = misses(table, arguments.threads)
    print(f"{len(missed)} miss(es) of the speed goals" + (":" if missed else ""))
    for line in missed:
        print("  " + line)


if __name__ == "__main__":
    main()
