"""Resampling speed: rsgeo beside GDAL, scikit-image and OpenCV, measured in the same run.

    python benchmarks/resample.py [--sizes 2048 4096] [--repeat 3] [--output FILE]

Each peer warps the same random uint8 image with the same affine mapping (a
rotation of 3° and a scale of 1.02, so that GDAL uses its plain 2 × 2 and
4 × 4 kernels). GDAL runs single-threaded through rasterio's ``reproject``;
OpenCV is skipped when it is not installed. The table gives megapixels of
output per second (best of ``--repeat`` runs) and the ratio to GDAL. It is
printed and saved as CSV (default ``benchmarks/results/resample.csv``, which
chapter 4 shows), with the date, the machine's CPU count and the library
versions as ``# key: value`` lines above the header (read it with
``pandas.read_csv(file, comment="#")``).
"""

import argparse
import csv
import datetime
import os
import platform
import time
from pathlib import Path

import affine
import numpy as np

from rsgeo.resample import warp

METHODS = ("nearest", "bilinear", "cubic")


def mapping(size):
    """Output-to-source affine: a rotation about the centre and a slight zoom."""
    centre = size / 2
    return (affine.Affine.translation(centre, centre) * affine.Affine.rotation(3.0)
            * affine.Affine.scale(1 / 1.02) * affine.Affine.translation(-centre, -centre))


def run_rsgeo(image, to_source, method):
    return warp(image, to_source, image.shape, method=method)


def run_gdal(image, to_source, method):
    from rasterio.enums import Resampling
    from rasterio.warp import reproject

    out = np.zeros_like(image)
    # source pixel -> "map" is the identity; output pixel -> map is to_source.
    reproject(image, out, src_transform=affine.Affine.identity(), dst_transform=to_source,
              src_crs="EPSG:3857", dst_crs="EPSG:3857", resampling=Resampling[method], num_threads=1)
    return out


def run_skimage(image, to_source, method):
    from skimage.transform import AffineTransform, warp

    order = {"nearest": 0, "bilinear": 1, "cubic": 3}[method]
    # skimage works on pixel centres at integers: shift by half a pixel each way.
    half = affine.Affine.translation(0.5, 0.5)
    matrix = ~half * to_source * half
    transform = AffineTransform(matrix=np.array(matrix).reshape(3, 3))
    return warp(image, transform, order=order, preserve_range=True).astype(image.dtype)


def run_opencv(image, to_source, method):
    import cv2

    half = affine.Affine.translation(0.5, 0.5)
    matrix = np.array(~half * to_source * half).reshape(3, 3)[:2]
    flag = {"nearest": cv2.INTER_NEAREST, "bilinear": cv2.INTER_LINEAR, "cubic": cv2.INTER_CUBIC}[method]
    return cv2.warpAffine(image, matrix, image.shape[::-1], flags=flag | cv2.WARP_INVERSE_MAP)


PEERS = {"rsgeo": run_rsgeo, "GDAL": run_gdal, "scikit-image": run_skimage, "OpenCV": run_opencv}


def best_time(function, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def benchmark(sizes=(2048, 4096), repeat=3, peers=None):
    """Rows of (size, method, peer, megapixels per second, ratio to GDAL)."""
    peers = peers or list(PEERS)
    rows = []
    for size in sizes:
        image = np.random.default_rng(0).integers(0, 256, (size, size), dtype=np.uint8)
        to_source = mapping(size)
        for method in METHODS:
            speeds = {}
            for peer in peers:
                try:
                    seconds = best_time(lambda: PEERS[peer](image, to_source, method), repeat)
                except ImportError:
                    continue
                speeds[peer] = size * size / seconds / 1e6
            for peer, speed in speeds.items():
                rows.append((size, method, peer, speed, speed / speeds["GDAL"] if "GDAL" in speeds else np.nan))
    return rows


def machine():
    """What the numbers depend on: date, processor, CPU count and library versions."""
    import numpy
    import rasterio
    import skimage

    import rsgeo

    info = {"date": datetime.date.today().isoformat(),
            "cpus": str(os.cpu_count()),
            "cpus usable": str(len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                               else os.cpu_count()),
            "processor": _processor_name(),
            "python": platform.python_version(), "numpy": numpy.__version__,
            "rsgeo": getattr(rsgeo, "__version__", "?"), "GDAL": rasterio.__gdal_version__,
            "rasterio": rasterio.__version__, "scikit-image": skimage.__version__}
    try:
        import cv2

        info["OpenCV"] = cv2.__version__
    except ImportError:
        info["OpenCV"] = "not installed"
    return info


def _processor_name():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def save_csv(rows, file, command=""):
    """Write the table with the machine's description as ``# key: value`` lines above it."""
    file = Path(file)
    file.parent.mkdir(parents=True, exist_ok=True)
    with open(file, "w", newline="") as handle:
        for key, value in {**machine(), "command": command}.items():
            handle.write(f"# {key}: {value}\n")
        writer = csv.writer(handle)
        writer.writerow(["size", "method", "peer", "Mpx_per_s", "ratio_to_GDAL"])
        for size, method, peer, speed, ratio in rows:
            writer.writerow([size, method, peer, f"{speed:.2f}", f"{ratio:.3f}"])
    return file


def print_table(rows):
    print(f"{'size':>6} {'method':>9} {'peer':>13} {'Mpx/s':>8} {'× GDAL':>7}")
    for size, method, peer, speed, ratio in rows:
        print(f"{size:>6} {method:>9} {peer:>13} {speed:8.1f} {ratio:7.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2048, 4096])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--output", default=Path(__file__).parent / "results" / "resample.csv",
                        help="CSV file to write (default: benchmarks/results/resample.csv)")
    arguments = parser.parse_args()
    table = benchmark(arguments.sizes, arguments.repeat)
    print_table(table)
    command = ("python benchmarks/resample.py --sizes "
               + " ".join(map(str, arguments.sizes)) + f" --repeat {arguments.repeat}")
    print("saved", save_csv(table, arguments.output, command))
