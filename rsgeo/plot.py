"""Figures for the course, on top of the maths: titles, axes with units, colour bars.

Kept apart from the core modules so that rsgeo's maths never imports matplotlib.
"""

import numpy as np


def _pyplot():
    import matplotlib.pyplot as plt

    return plt


def show_image(ax, image, transform=None, title="", cmap="gray", label="DN", vmin=None, vmax=None,
               colorbar=True, units="km"):
    """Draw an image with map (or pixel) axes, a title and a colour bar.

    Parameters
    ----------
    ax : matplotlib Axes
    image : ndarray
        2-D, or 3-D bands first (shown as RGB, stretched 2-98 %).
    transform : affine.Affine, optional
        Geotransform: axes in map coordinates (``units`` "km" or "m"); else pixels.
    label : str
        Colour-bar label.
    """
    image = np.asarray(image)
    if image.ndim == 3:
        low, high = np.percentile(image, (2, 98), axis=(1, 2))
        rgb = np.clip((np.moveaxis(image, 0, -1) - low) / np.maximum(high - low, 1e-9), 0, 1)
        image, colorbar = rgb, False
    rows, cols = image.shape[:2]
    if transform is not None:
        scale = 1000.0 if units == "km" else 1.0
        left, top = transform @ (0, 0)
        right, bottom = transform @ (cols, rows)
        extent = (left / scale, right / scale, bottom / scale, top / scale)
        xlabel, ylabel = f"easting ({units})", f"northing ({units})"
    else:
        extent = (0, cols, rows, 0)
        xlabel, ylabel = "column (pixels)", "row (pixels)"
    artist = ax.imshow(image, cmap=cmap, extent=extent, vmin=vmin, vmax=vmax, interpolation="nearest")
    ax.set(title=title, xlabel=xlabel, ylabel=ylabel)
    if colorbar:
        ax.figure.colorbar(artist, ax=ax, label=label, shrink=0.8)
    return artist


def draw_grid(ax, lines, **style):
    """Draw grid lines given as (cols, rows) pairs (e.g. from rsgeo.distortion.distorted_grid)."""
    style = {"color": "tab:blue", "linewidth": 0.8, **style}
    for cols, rows in lines:
        ax.plot(cols, rows, **style)
    ax.set_aspect("equal")


def draw_mesh(ax, centroids, labels=None, color="tab:green", edges=True):
    """A relational mesh: centroids joined by their distances (paper 001, fig. 4)."""
    centroids = np.asarray(centroids)
    if edges:
        for i in range(len(centroids)):
            for j in range(i + 1, len(centroids)):
                ax.plot(*centroids[[i, j]].T, color=color, alpha=0.25, linewidth=0.7)
    ax.scatter(*centroids.T, s=40, color=color, edgecolor="black", zorder=3)
    for k, (x, y) in enumerate(centroids):
        ax.annotate(str(labels[k] if labels is not None else k + 1), (x, y), xytext=(4, 4),
                    textcoords="offset points", fontsize=9, weight="bold")


def animation_html(animation):
    """An animation as a self-contained JavaScript player, so it plays in the static HTML book.

    Matplotlib's player links Font Awesome 4 from a CDN for its button icons; the link is
    dropped so that the page makes no request outside the book (the book's theme and
    Jupyter already provide Font Awesome, whose ``fa fa-play`` classes the buttons use).
    """
    import re

    from IPython.display import HTML

    html = animation.to_jshtml()
    _pyplot().close(animation._fig)
    return HTML(re.sub(r"<link[^>]*font-awesome[^>]*>", "", html))
