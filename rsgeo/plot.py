"""Figures of rsgeo's results, on top of the maths: titles, axes with units, colour bars.

Kept apart from the core modules so that rsgeo's maths never imports matplotlib.

A figure rsgeo renders as an image (a widget's frame, an animation's player) carries
alternative text for a reader who cannot see it: by default its titles; a package that
describes figures fully (the course's, for one) installs its describer with
:func:`set_figure_describer`.
"""

import re
import weakref

import numpy as np

from .errors import GCPError, RsgeoError
from .language import N_, _, prose_number
from .radiometry import apply_gain_offset, concatenate_halves, seam_metrics
from .resample import bilinear_weights, keys_weights

__all__ = [
    "show_image", "grid_path", "draw_grid", "draw_mesh", "draw_neighbour_weights",
    "draw_stretch_frame", "fix_layout", "animation_html", "label_points", "draw_residual_arrows",
    "draw_tiepoints", "set_figure_describer", "figure_description",
]

# describe(figure) -> str, installed by set_figure_describer; None: the figure's titles
_describer = None


def set_figure_describer(describe):
    """Use ``describe`` for the alternative text of every figure rsgeo renders as an image.

    Parameters
    ----------
    describe : callable or None
        ``describe(figure) -> str``; None restores the default (the figure's titles).

    Returns
    -------
    callable or None
        The describer used until now, so that a caller can restore it.

    Raises
    ------
    TypeError
        If ``describe`` is neither callable nor None.

    Examples
    --------
    >>> previous = set_figure_describer(lambda figure: "a test figure")
    >>> set_figure_describer(previous) is not None
    True
    """
    global _describer
    if describe is not None and not callable(describe):
        raise TypeError(f"set_figure_describer needs a function of a figure or None, got "
                        f"{type(describe).__name__}")
    previous, _describer = _describer, describe
    return previous


def figure_description(figure):
    """The alternative text of ``figure``: the installed describer's, else its titles.

    Parameters
    ----------
    figure : matplotlib.figure.Figure

    Returns
    -------
    str
        What the figure shows, for the ``alt`` of its image.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> figure = Figure()
    >>> _ = figure.subplots().set_title("slope")
    >>> previous = set_figure_describer(None)
    >>> figure_description(figure)
    'Figure “slope”.'
    >>> _ = set_figure_describer(previous)
    """
    if _describer is not None:
        return _describer(figure)
    titles = [text for text in [figure._suptitle.get_text() if figure._suptitle else ""]
              + [ax.get_title() for ax in figure.axes] if text]
    if not titles:
        return _("Untitled figure.")
    return _("Figure “{titles}”.").format(titles="”, “".join(titles))


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
    title : str
        The panel's title.
    cmap : str or matplotlib colormap
        Colour map of a 2-D image.
    label : str
        Colour-bar label, with its units (e.g. "DN", "height (m)").
    vmin, vmax : float, optional
        Values at the ends of the colour map (default: the image's range).
    colorbar : bool
        Add a colour bar (never for a 3-D image, drawn as RGB).
    units : {"km", "m"}
        Units of map axes when ``transform`` is given ("km" divides by 1000;
        anything else keeps the transform's units).

    Returns
    -------
    matplotlib.image.AxesImage
        The image artist (update it with ``set_data``).

    Raises
    ------
    ValueError
        If ``image`` is 1-D (no rows and columns); nothing else is checked
        here: matplotlib raises TypeError for an image it cannot draw
        (e.g. 4-D).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> ax = Figure().subplots()
    >>> artist = show_image(ax, np.zeros((4, 6)), title="zeros")
    >>> ax.get_xlabel(), artist.get_extent()
    ('column (pixels)', [0, 6, 4, 0])
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
        xlabel = _("easting ({units})").format(units=units)
        ylabel = _("northing ({units})").format(units=units)
    else:
        extent = (0, cols, rows, 0)
        xlabel, ylabel = _("column (pixels)"), _("row (pixels)")
    artist = ax.imshow(image, cmap=cmap, extent=extent, vmin=vmin, vmax=vmax,
                       interpolation="nearest")
    ax.set(title=title, xlabel=xlabel, ylabel=ylabel)
    if colorbar:
        ax.figure.colorbar(artist, ax=ax, label=label, shrink=0.8)
    return artist


def grid_path(lines):
    """Grid lines as one polyline: (cols, rows) arrays with NaN between lines.

    One Line2D for a whole grid draws several times faster than one per line,
    and a widget moves it with a single ``set_data``.

    Parameters
    ----------
    lines : sequence of (cols, rows) pairs
        As :func:`rsgeo.sensors.distorted_grid` returns them.

    Returns
    -------
    cols, rows : ndarray
        1-D, NaN-separated (the NaN breaks the line between grid lines).

    Raises
    ------
    ValueError
        If there are no lines or a line's cols and rows differ in length.

    Examples
    --------
    >>> cols, rows = grid_path([([0, 1], [0, 0]), ([0, 1], [1, 1])])
    >>> cols.tolist()[:3], len(rows)
    ([0.0, 1.0, nan], 6)
    """
    parts_c, parts_r = [], []
    for cols, rows in lines:
        cols, rows = np.asarray(cols, dtype=float).ravel(), np.asarray(rows, dtype=float).ravel()
        if cols.shape != rows.shape:
            raise RsgeoError(f"each grid line needs as many cols as rows, got {cols.size} and "
                             f"{rows.size}")
        parts_c += [cols, [np.nan]]
        parts_r += [rows, [np.nan]]
    if not parts_c:
        raise RsgeoError("grid_path needs at least one (cols, rows) line")
    return np.concatenate(parts_c), np.concatenate(parts_r)


def draw_grid(ax, lines, **style):
    """Draw grid lines given as (cols, rows) pairs (e.g. from rsgeo.sensors.distorted_grid).

    Parameters
    ----------
    ax : matplotlib Axes
    lines : sequence of (cols, rows) pairs
    **style
        Line2D properties (default: thin blue lines).

    Returns
    -------
    matplotlib.lines.Line2D
        The whole grid as one line (see :func:`grid_path`): move it with
        ``line.set_data(*grid_path(new_lines))``.

    Raises
    ------
    ValueError
        As :func:`grid_path`: no lines, or a line whose cols and rows differ
        in length.
    """
    style = {"color": "tab:blue", "linewidth": 0.8, **style}
    (line,) = ax.plot(*grid_path(lines), **style)
    ax.set_aspect("equal")
    return line


def draw_mesh(ax, centroids, labels=None, color="tab:green", edges=True):
    """A relational mesh: centroids joined by their distances (the GA paper, fig. 4).

    Parameters
    ----------
    ax : matplotlib Axes
    centroids : (n, 2) array_like
    labels : sequence, optional
        A label per centroid (default 1 to n).
    color : colour
    edges : bool
        Join every pair of centroids (one LineCollection).

    Returns
    -------
    matplotlib.collections.PathCollection
        The centroids' markers.

    Raises
    ------
    ValueError
        From matplotlib, if ``centroids`` is not an (n, 2) array (nothing is
        checked here); fewer ``labels`` than centroids raise IndexError.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), fig. 4.
    """
    from matplotlib.collections import LineCollection

    centroids = np.asarray(centroids, dtype=float)
    if edges and len(centroids) > 1:
        i, j = np.triu_indices(len(centroids), k=1)
        ax.add_collection(LineCollection(np.stack([centroids[i], centroids[j]], axis=1),
                                         colors=color,
                                         alpha=0.25, linewidths=0.7))
    points = ax.scatter(*centroids.T, s=40, color=color, edgecolor="black", zorder=3)
    for k, (x, y) in enumerate(centroids):
        ax.annotate(str(labels[k] if labels is not None else k + 1), (x, y), xytext=(4, 4),
                    textcoords="offset points", fontsize=9, weight="bold")
    return points


# the interpolators' names as a title shows them (marked for the catalogue)
_METHOD_NAMES = {"bilinear": N_("bilinear"), "cubic": N_("cubic")}


def draw_neighbour_weights(ax, position, method):
    """The pixels a bilinear or cubic interpolation uses around a position, sized by their weight.

    Circle area is proportional to ``|weight|``, red for negative weights (cubic
    convolution's lobes); the cross is the position, in GDAL's (col, row).

    Parameters
    ----------
    ax : matplotlib Axes
    position : (float, float)
        The position (col, row) in GDAL's continuous pixel coordinates.
    method : {"bilinear", "cubic"}
        The interpolator; any value but "bilinear" draws the cubic weights
        (:func:`rsgeo.resample.keys_weights`).

    Returns
    -------
    None
        The panel is drawn in place: its limits, labels and title set.

    Raises
    ------
    ValueError
        If ``position`` is not two numbers (nothing else is checked).

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``; Keys, R. G. (1981), "Cubic convolution
    interpolation for digital image processing", IEEE Transactions on
    Acoustics, Speech, and Signal Processing 29(6), 1153-1160.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> ax = Figure().subplots()
    >>> draw_neighbour_weights(ax, (2.3, 1.8), "bilinear")
    >>> ax.get_title()
    'bilinear: position (2.30, 1.80)'
    """

    col, row = position
    left, top = int(np.floor(col - 0.5)), int(np.floor(row - 0.5))
    dx, dy = col - 0.5 - left, row - 0.5 - top
    if method == "bilinear":
        weights, offsets = np.outer(bilinear_weights(dy), bilinear_weights(dx)), (0, 1)
    else:
        weights, offsets = np.outer(keys_weights(dy), keys_weights(dx)), (-1, 0, 1, 2)
    for j, oy in enumerate(offsets):
        for i, ox in enumerate(offsets):
            centre = (left + ox + 0.5, top + oy + 0.5)
            weight = weights[j, i]
            ax.scatter(*centre, s=2000 * abs(weight),
                       color="tab:red" if weight < 0 else "tab:blue", alpha=0.6)
            ax.annotate(format(prose_number(weight), ".2f"), centre, ha="center", va="center",
                        fontsize=8)
    ax.scatter(col, row, marker="x", color="black", s=80)
    ax.set(xlim=(left - 2.5, left + 4.5), ylim=(top + 4.5, top - 2.5), xlabel=_("column (px)"),
           ylabel=_("row (px)"),
           title=_("{method}: position ({col:.2f}, {row:.2f})").format(
               method=_(_METHOD_NAMES.get(method, method)), col=prose_number(col),
               row=prose_number(row)))
    ax.grid(True)
    ax.set_aspect("equal")


_STRETCH_ARTISTS = weakref.WeakKeyDictionary()   # first Axes of a stretch frame -> its artists


def draw_stretch_frame(axes, x_image, y_image, gain, offset, t, title_extra=""):
    """One frame of the regression stretch: mosaic, histograms, scatter with the line (chapter 5).

    ``t`` goes from 0 (no correction) to 1 (the fitted gain and offset):
    gain(t) = 1 + t·(gain − 1), offset(t) = t·offset. The mosaic's title gives
    :func:`rsgeo.radiometry.seam_metrics` of the stretched A against B over the
    whole overlap: the brightness step (difference of the means) and the
    contrast mismatch (difference of the standard deviations), in DN, the
    measures chapter 5's text uses.

    The first call on a set of axes draws every artist; later calls with the
    same images update them in place (image data, one histogram, the line,
    the titles), so that animation and widget frames draw fast. Axes cleared
    in between, or other images, are drawn afresh.

    Parameters
    ----------
    axes : sequence of three matplotlib Axes
    x_image, y_image : ndarray
        A (X, integer dtype, the image stretched) and B (Y), same shape.
    gain, offset : float
        The correction reached at t = 1.
    t : float
        Position along the correction, 0 to 1.
    title_extra : str
        Appended to the scatter's title.

    Returns
    -------
    dict
        The seam metrics shown in the title.

    Raises
    ------
    ValueError
        If ``axes`` are not three Axes (image problems raise as in
        :func:`rsgeo.radiometry.apply_gain_offset`).
    """

    axes = list(np.ravel(axes))
    if len(axes) != 3:
        raise RsgeoError(f"draw_stretch_frame needs three axes (mosaic, histograms, scatter), got "
                         f"{len(axes)}")
    gain_t, offset_t = 1 + t * (gain - 1), t * offset
    artists = _STRETCH_ARTISTS.get(axes[0])
    if (artists is not None and (artists["x_image"] is not x_image
                                 or artists["y_image"] is not y_image
                                 or any(artist.axes is not ax or artist not in ax.get_children()
                                        for artist, ax in zip(artists["owned"], axes)))):
        artists = None
    # a frame's inputs depend on (gain(t), offset(t)) only: kept, Play's next loop is free
    frames = artists["frames"] if artists is not None else {}
    key = (float(gain_t), float(offset_t))
    if key not in frames:
        if len(frames) >= 512:
            frames.clear()
        corrected = apply_gain_offset(x_image, gain_t, offset_t)
        mosaic, split = concatenate_halves(corrected, y_image)
        counts = np.histogram(corrected, np.arange(257))[0]
        frames[key] = (mosaic, split, counts, seam_metrics(corrected, y_image))
    mosaic, split, counts, metrics = frames[key]
    if artists is None:
        artists = _draw_stretch_axes(axes, x_image, y_image, mosaic, split, counts, np.arange(257))
        artists["frames"] = frames
        _STRETCH_ARTISTS[axes[0]] = artists
    artists["mosaic"].set_data(mosaic)
    artists["histogram"].set_data(counts)
    axes[1].set_ylim(0, 1.05 * max(counts.max(), artists["b_peak"]))
    artists["line"].set_ydata(gain_t * np.array([0, 255]) + offset_t)
    # y=1: a fixed title position, not re-derived from the tick labels at every frame
    axes[0].set_title(_("t = {t:.1f}: mean Δ {mean:+.1f} DN, spread Δ {spread:+.1f} DN").format(
        t=prose_number(t), mean=prose_number(metrics["mean_difference"]),
        spread=prose_number(metrics["std_difference"])), y=1.0)
    gain_text, offset_text = format(prose_number(gain_t), ".3f"), format(prose_number(offset_t),
                                                                         ".2f")
    axes[2].set_title(f"Y = {gain_text} X + {offset_text}{title_extra}", y=1.0)
    return dict(metrics)


def _draw_stretch_axes(axes, x_image, y_image, mosaic, split, counts, bins):
    """Draw a stretch frame's artists once (see :func:`draw_stretch_frame`)."""
    for ax in axes:
        ax.clear()
    mosaic_artist = axes[0].imshow(mosaic, cmap="gray", vmin=0, vmax=255)
    axes[0].axvline(split - 0.5, color="tab:red", linewidth=0.8)
    axes[0].set(xlabel=_("column (px)"), ylabel=_("row (px)"))
    # one filled step polygon per histogram, not 256 bars: a frame draws fast
    histogram = axes[1].stairs(counts, bins, fill=True, alpha=0.6, label=_("A stretched"),
                               color="tab:blue")
    b_counts = np.histogram(np.asarray(y_image), bins)[0]
    axes[1].stairs(b_counts, bins, fill=True, alpha=0.6, label="B", color="tab:orange")
    axes[1].set_title(_("histograms (1 DN bins)"), y=1.0)
    axes[1].set(xlabel="DN", ylabel=_("count (pixels)"), xlim=(0, 256))
    axes[1].legend()
    axes[2].scatter(np.ravel(x_image)[::5], np.ravel(y_image)[::5], s=2, alpha=0.3)
    (line,) = axes[2].plot([0, 255], [0, 255], color="tab:red")
    axes[2].set(xlabel="A = X (DN)", ylabel="B = Y (DN)", xlim=(0, 255), ylim=(0, 255))
    return {"x_image": x_image, "y_image": y_image, "mosaic": mosaic_artist,
            "histogram": histogram,
            "line": line, "b_peak": int(b_counts.max()), "owned": (mosaic_artist, histogram, line)}


def fix_layout(figure):
    """Lay a figure out tightly once, leaving no layout engine behind.

    ``figure.tight_layout()`` leaves a placeholder layout engine, and with any
    engine set every save draws the figure twice (once to lay it out). Frames
    of widgets and animations keep one layout: this sets it once, so that each
    frame is drawn once.

    Parameters
    ----------
    figure : matplotlib.figure.Figure

    Returns
    -------
    matplotlib.figure.Figure
        The same figure, its subplot parameters adjusted.

    Raises
    ------
    AttributeError
        If ``figure`` is not a matplotlib Figure (nothing is checked here).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> figure = Figure()
    >>> _ = figure.subplots(1, 2)
    >>> fix_layout(figure).get_layout_engine() is None
    True
    """
    from matplotlib.layout_engine import TightLayoutEngine

    TightLayoutEngine().execute(figure)
    return figure


def animation_html(animation):
    """An animation as a self-contained JavaScript player, so it plays in the static HTML book.

    Matplotlib's player links Font Awesome 4 from a CDN for its button icons; the link is
    dropped so that the page makes no request outside the book (the book's theme and
    Jupyter already provide Font Awesome, whose ``fa fa-play`` classes the buttons use).

    The player says what it shows: its frame image's ``alt`` is
    :func:`figure_description` of the first frame, with the number of frames; the
    frame slider is labelled ("frame"), and every button's ``title`` and ``aria-label`` and
    the repetition modes' labels are in rsgeo's language (``rsgeo.language``: "Play" is
    "Reproduzir" in Portuguese).

    The animation's figure is closed, so that the notebook does not show it a
    second time as a still image.

    Parameters
    ----------
    animation : matplotlib.animation.Animation
        The animation, e.g. a ``FuncAnimation``.

    Returns
    -------
    IPython.display.HTML
        The player: every frame as an embedded image, with its controls.

    Raises
    ------
    AttributeError
        If ``animation`` is not a matplotlib Animation (nothing is checked
        here); errors while drawing a frame propagate.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from matplotlib.animation import FuncAnimation
    >>> figure, ax = plt.subplots(figsize=(2, 2), dpi=30)
    >>> line, = ax.plot([], [])
    >>> _ = ax.set(title="a growing line", xlabel="x (m)", ylabel="y (m)", xlim=(0, 2),
    ...            ylim=(0, 2))
    >>> player = animation_html(FuncAnimation(figure, lambda i: line.set_data([0, i], [0, i]),
    ...                                       frames=3))
    >>> 'alt="Animation of 3 frames; the first: Figure “a growing line”' in player.data
    True
    >>> 'title="Play" aria-label="Play"' in player.data
    True
    """
    from html import escape

    from IPython.display import HTML

    figure = animation._fig
    first_frame = {}
    draw_next_frame = animation._draw_next_frame

    def draw_and_remember_the_first(*args, **kwargs):
        # the first frame is described once it has been saved (a translation of the figure's
        # texts, by a hook on saving, happens as a frame is saved), before the second is drawn
        if first_frame.get("drawn") and "description" not in first_frame:
            first_frame["description"] = figure_description(figure)
        first_frame["drawn"] = True
        return draw_next_frame(*args, **kwargs)

    own = vars(animation).get("_draw_next_frame")
    animation._draw_next_frame = draw_and_remember_the_first
    try:
        html = animation.to_jshtml()
    finally:
        if own is None:
            del animation._draw_next_frame      # the class's method again
        else:
            animation._draw_next_frame = own
    description = first_frame.get("description") or figure_description(figure)
    _pyplot().close(figure)
    frames = re.search(r"new Array\((\d+)\)", html)
    alt = _("Animation of {count} frames; the first: {description}").format(
        count=frames.group(1) if frames else "?", description=description)
    html = re.sub(r"<link[^>]*font-awesome[^>]*>", "", html)
    html = re.sub(r'<img id="(_anim_img\w*)"', lambda match: (
        f'<img id="{match.group(1)}" alt="{escape(alt)}"'), html)
    slider_name = escape(_("frame"))
    html = re.sub(r'<input id="(_anim_slider\w*)"', lambda match: (
        f'<input id="{match.group(1)}" aria-label="{slider_name}"'), html)
    titles = {"Decrease speed": _("Decrease speed"), "First frame": _("First frame"),
              "Previous frame": _("Previous frame"), "Play backwards": _("Play backwards"),
              "Pause": _("Pause"), "Play": _("Play"), "Next frame": _("Next frame"),
              "Last frame": _("Last frame"), "Increase speed": _("Increase speed"),
              "Repetition mode": _("Repetition mode")}

    def named(match):
        title = escape(titles.get(match.group(2), match.group(2)))
        return f'<{match.group(1)} title="{title}" aria-label="{title}"'

    html = re.sub(r'<(button|form) title="([^"]*)"(?: aria-label="[^"]*")?', named, html)
    modes = {"Once": _("Once"), "Loop": _("Loop"), "Reflect": _("Reflect")}
    html = re.sub(r'(<label for="_anim_radio\d_\w*">)(Once|Loop|Reflect)</label>',
                  lambda match: f"{match.group(1)}{escape(modes[match.group(2)])}</label>", html)
    return HTML(html)


# -- GCP figures (chapters 2 and 3) ------------------------------------------


def label_points(ax, xy, names, color="white", outline="black", fontsize=8):
    """Write a name beside each point, light text with a dark outline: readable on any image.

    Parameters
    ----------
    ax : matplotlib Axes
    xy : (n, 2) array_like
        Positions in the axes' data coordinates.
    names : sequence of str
        One name per point.
    color, outline : colour
        Text colour and the colour of its outline (a stroke drawn under it).
    fontsize : float

    Returns
    -------
    list of matplotlib.text.Annotation

    Raises
    ------
    ValueError
        If there is not one name per point.
    """
    from matplotlib import patheffects

    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    names = list(names)
    if len(names) != len(xy):
        raise RsgeoError(f"label_points needs one name per point, got {len(names)} names for "
                         f"{len(xy)} points")
    stroke = [patheffects.withStroke(linewidth=2.5, foreground=outline)]
    return [ax.annotate(str(name), (x, y), xytext=(4, 4), textcoords="offset points", color=color,
                        fontsize=fontsize, path_effects=stroke) for name, (x, y) in zip(names, xy)]


def draw_residual_arrows(ax, image_xy, dx, dy, exaggeration=20.0, key_px=2.0, color="yellow"):
    """GCP residuals as arrows on an image axis whose rows grow downwards.

    Each arrow starts at the GCP's measured (col, row) and points to where the
    model puts it, (col + dx, row + dy), drawn ``exaggeration`` times longer.
    A key arrow of ``key_px`` pixels (before exaggeration) gives the scale,
    in the panel's lower-left corner. Used for any (dcol, drow) field on an image: residuals,
    or a model's difference from a geotransform.

    Parameters
    ----------
    ax : matplotlib Axes
        Showing the image in (col, row) coordinates (e.g. from :func:`show_image`).
    image_xy : (n, 2) array_like
        Measured GCP positions (col, row).
    dx, dy : (n,) array_like
        Residuals model - GCP, in pixels (rows down), as ``rsgeo.accuracy.residuals`` returns.
    exaggeration : float
        How many times longer than the residual each arrow is drawn.
    key_px : float
        Length of the key arrow, in residual pixels.
    color : str
        Colour of the arrows and the key.

    Returns
    -------
    matplotlib.quiver.Quiver

    Raises
    ------
    ValueError
        If ``dx`` or ``dy`` does not hold one value per GCP, or
        ``exaggeration`` is not a positive number.
    """
    image_xy = np.asarray(image_xy, dtype=float).reshape(-1, 2)
    dx, dy = np.asarray(dx, dtype=float), np.asarray(dy, dtype=float)
    if dx.shape != (len(image_xy),) or dy.shape != (len(image_xy),):
        raise GCPError(f"dx and dy need one value per GCP ({len(image_xy)}), got shapes "
                       f"{dx.shape}, {dy.shape}")
    if not exaggeration > 0:
        raise RsgeoError(f"exaggeration must be a positive number, got {exaggeration!r}")
    # angles="xy" and scale_units="xy" draw in data coordinates: +dy goes down the image, as
    # rows do
    arrows = ax.quiver(image_xy[:, 0], image_xy[:, 1], dx, dy, color=color, angles="xy",
                       scale_units="xy", scale=1 / exaggeration, width=0.005, edgecolor="black",
                       linewidth=0.5)
    from matplotlib import patheffects

    key = ax.quiverkey(arrows, 0.1, 0.04, key_px,
                       _("key: {length:g} px, drawn ×{exaggeration:g}").format(
                           length=prose_number(key_px),
                           exaggeration=prose_number(exaggeration)),
                       labelpos="E", coordinates="axes", color=color, labelcolor="white")
    key.text.set_path_effects([patheffects.withStroke(linewidth=2.5, foreground="black")])
    return arrows


# -- Tie points (chapter 6c) --------------------------------------------------

# marker colour of each tie-point verdict of rsgeo.registration.correlation_tiepoints.
_TIEPOINT_COLOURS = {N_("reliable"): "tab:green", N_("outlier"): "tab:red",
                     N_("weak peak"): "tab:orange", N_("low contrast"): "tab:purple",
                     N_("constant"): "tab:pink", N_("invalid"): "tab:gray"}


def draw_tiepoints(ax, points, notes, size=30, colours=None):
    """Tie points on an image axis, one colour and legend entry ("reliable (53)") per verdict.

    Parameters
    ----------
    ax : matplotlib Axes
        Showing the image in the points' coordinates.
    points : (n, 2) array_like
        Positions (col, row), or map (x, y) on an axis drawn in map units.
    notes : sequence of str
        One verdict per point, as ``GCPSet.notes`` of
        :func:`rsgeo.registration.correlation_tiepoints` ("reliable", "outlier", ...).
    size : float
        Marker area, points².
    colours : dict, optional
        Verdict -> colour, for verdicts of your own (default: the tie-point
        verdicts' colours; blue for any other).

    Returns
    -------
    dict
        Verdict -> its scatter artist.

    Raises
    ------
    ValueError
        If there is not one verdict per point.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    notes = np.asarray(list(notes), dtype=object)
    if len(notes) != len(points):
        raise RsgeoError(f"draw_tiepoints needs one verdict per point, got {len(notes)} for "
                         f"{len(points)} points")
    colours = {**_TIEPOINT_COLOURS, **(colours or {})}
    artists = {}
    for verdict in dict.fromkeys(notes.tolist()):
        chosen = notes == verdict
        artists[verdict] = ax.scatter(*points[chosen].T, s=size, edgecolor="black", linewidth=0.5,
                                      color=colours.get(verdict, "tab:blue"),
                                      label=_("{verdict} ({count})").format(
                                          verdict=_(verdict),
                                          count=int(chosen.sum())),
                                      zorder=3)
    return artists
