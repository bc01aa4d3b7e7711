"""Alternative text for figures: what a figure shows, in words a screen reader can read aloud.

A blind student cannot see a figure; its alternative text (an image's ``alt``) has to say what
it shows. :func:`describe_figure` reads a matplotlib figure itself (not its picture): its title,
then, for every panel, its title, what each axis plots (label with units and range), what is
drawn (an image of N×M pixels, N points, N lines, ...), the legend's entries and the colour
bar's label and range. The course's titles state each figure's point, so the description
carries it too.

The fixed words are rsgeo messages (``rsgeo._i18n``): with ``RSGEO_LANG=pt_BR`` the
description is Portuguese, its numbers written with a decimal comma. The figure's own texts are
quoted as they are.

The book gives every figure its description: the build's kernels write it into each PNG they
render (a ``Description`` text chunk, book/_ext/figure_audit.py) and the book's extension
(book/_ext/figure_alt.py) makes it the image's ``alt``; the animations
(:func:`rsgeo.plot.animation_html`) and the widgets (:mod:`rsgeo.widgets`) put it on their
frames themselves.
"""

import math
import re

import numpy as np

from ._i18n import PORTUGUESE_SEPARATORS, _, get_language

__all__ = ["MAX_LENGTH", "describe_figure"]

#: The longest description :func:`describe_figure` returns (characters): about a minute read
#: aloud; a longer one is cut after its last whole item and ends with "…".
MAX_LENGTH = 1000
#: The legend entries (and categories) named before "and N more".
MAX_ENTRIES = 8
#: Texts written on a panel are quoted when there are at most this many, else counted.
MAX_QUOTED_TEXTS = 3

_SUPERSCRIPT = str.maketrans("-+0123456789", "⁻⁺⁰¹²³⁴⁵⁶⁷⁸⁹")
_GREEK = {name: chr(code) for name, code in (
    ("alpha", 945), ("beta", 946), ("gamma", 947), ("delta", 948), ("epsilon", 949),
    ("theta", 952), ("lambda", 955), ("mu", 956), ("pi", 960), ("rho", 961), ("sigma", 963),
    ("tau", 964), ("phi", 966), ("chi", 967), ("omega", 969), ("Delta", 916), ("Sigma", 931),
    ("Omega", 937), ("circ", 176), ("times", 215), ("cdot", 183), ("pm", 177), ("approx", 8776),
    ("leq", 8804), ("geq", 8805), ("le", 8804), ("ge", 8805))}


def _plain(text):
    """A figure's text as it reads: one line, mathtext without its markup ($\\sigma_x$ -> σ x)."""

    def unmath(match):
        body = match.group(1)
        body = re.sub(r"\\([A-Za-z]+)", lambda m: _GREEK.get(m.group(1), m.group(1)), body)
        body = body.replace("_", " ").replace("{", "").replace("}", "").replace("\\", "")
        return body

    text = re.sub(r"(?<!\\)\$(.+?)(?<!\\)\$", unmath, str(text or ""))
    return " ".join(text.replace("\\$", "$").split())


def _quoted(text, limit=160):
    text = _plain(text)
    if len(text) > limit:
        text = text[:limit - 1].rsplit(" ", 1)[0] + "…"
    return f"“{text}”"


def _format_number(value, span=None):
    """``value`` rounded to about three significant digits of ``span`` (the range it is read
    in), with thousands separators, in the current language's way (decimal comma in
    Portuguese); very small or large numbers as powers of ten (8.5 × 10⁻⁸)."""
    value = float(value)
    if not math.isfinite(value):
        return _("infinity") if math.isinf(value) else _("not a number")
    scale = abs(float(span)) if span is not None and math.isfinite(span) and span else abs(value)
    if scale == 0:
        text = "0"
    elif 1e-3 <= scale and abs(value) < 1e15:
        decimals = min(max(0, 2 - math.floor(math.log10(scale))), 12)
        text = f"{value:,.{decimals}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        text = "0" if text == "-0" else text
    else:
        mantissa, exponent = f"{value:.3g}".partition("e")[::2]
        power = str(int(exponent)).translate(_SUPERSCRIPT) if exponent else ""
        if not power:
            text = mantissa
        elif mantissa in ("1", "-1"):
            text = f"{mantissa[:-1]}10{power}"
        else:
            text = f"{mantissa} × 10{power}"
    if get_language() == "pt_BR":
        text = text.translate(PORTUGUESE_SEPARATORS)
    return text.replace("-", "−")


def _counted(count, singular, plural):
    """``singular`` or ``plural`` (translated messages with a ``{count}`` field) for ``count``."""
    return (singular if count == 1 else plural).format(count=_format_number(count, 1))


def _listed(texts):
    """Quoted texts joined by commas, the first :data:`MAX_ENTRIES` of them and a count of the
    rest."""
    texts = [_quoted(text, 60) for text in texts]
    shown = ", ".join(texts[:MAX_ENTRIES])
    if len(texts) > MAX_ENTRIES:
        shown = _("{entries} and {count} more").format(entries=shown,
                                                       count=len(texts) - MAX_ENTRIES)
    return shown


def _range(low, high):
    span = abs(high - low)
    return _format_number(low, span), _format_number(high, span)


def _shows_tick_labels(axis):
    return axis.get_visible() and any(tick.get_visible() and tick.get_text()
                                      for tick in axis.get_ticklabels())


def _categories(axis):
    """The category names of a categorical axis (bars named by strings), else None."""
    from matplotlib.category import UnitData

    units = axis.get_units()
    if isinstance(units, UnitData):
        return list(getattr(units, "_mapping", {}))
    return None


def _axis_item(name, axis, label, limits):
    """``x: label from a to b`` for an axis, or None when it shows neither label nor numbers."""
    label = _plain(label)
    head = f"{name}: {label}" if label else name
    if not _shows_tick_labels(axis):
        return head if label else None
    categories = _categories(axis)
    if categories:
        if len(categories) <= MAX_ENTRIES:
            return _("{axis}, {count} categories: {names}").format(
                axis=head, count=len(categories), names=_listed(categories))
        return _("{axis}, {count} categories from {first} to {last}").format(
            axis=head, count=len(categories), first=_quoted(categories[0], 40),
            last=_quoted(categories[-1], 40))
    low, high = _range(*limits)
    item = _("{axis} from {low} to {high}").format(axis=head, low=low, high=high)
    if axis.get_scale() == "log":
        item += ", " + _("log scale")
    return item


def _image_items(ax):
    images = [image for image in ax.images
              if image.get_visible() and image.get_array() is not None]
    if not images:
        return []
    shape = np.shape(images[0].get_array())
    rows, cols = (_format_number(n, 1) for n in shape[:2])
    if len(images) > 1:
        return [_("{count} images, the first of {rows}×{cols} pixels").format(
            count=len(images), rows=rows, cols=cols)]
    if len(shape) == 3:
        return [_("a colour image of {rows}×{cols} pixels").format(rows=rows, cols=cols)]
    return [_("an image of {rows}×{cols} pixels").format(rows=rows, cols=cols)]


def _collection_items(ax):
    """What the panel's collections draw: contours, colour grids, arrows, points, segments,
    shaded areas, shapes."""
    from matplotlib.collections import LineCollection, PathCollection, PolyCollection, QuadMesh
    from matplotlib.contour import ContourSet
    from matplotlib.quiver import Quiver

    counts = {"arrows": 0, "points": 0, "segments": 0, "areas": 0, "shapes": 0}
    items = []
    for collection in ax.collections:
        if not collection.get_visible():
            continue
        if isinstance(collection, ContourSet):
            levels = len(collection.levels)
            message = (_("filled contours at {count} levels") if collection.filled
                       else _("contour lines at {count} levels"))
            items.append(message.format(count=levels))
        elif isinstance(collection, QuadMesh):
            rows, cols = (n - 1 for n in collection.get_coordinates().shape[:2])
            items.append(_("a colour grid of {rows}×{cols} cells").format(
                rows=_format_number(rows, 1), cols=_format_number(cols, 1)))
        elif isinstance(collection, Quiver):
            counts["arrows"] += len(collection.get_offsets())
        elif isinstance(collection, PathCollection):
            counts["points"] += len(collection.get_offsets())
        elif isinstance(collection, LineCollection):
            counts["segments"] += sum(1 for segment in collection.get_segments()
                                      if len(segment))
        elif isinstance(collection, PolyCollection):
            counts["areas"] += len(collection.get_paths())
        else:
            counts["shapes"] += len(collection.get_paths())
    return items, counts


def _drawn_items(ax):
    """What a panel draws, in words: images, lines, points, bars, ... (counts of each)."""
    from matplotlib.container import BarContainer
    from matplotlib.patches import StepPatch

    items = _image_items(ax)
    collection_items, counts = _collection_items(ax)
    items += collection_items
    lines = sum(1 for line in ax.lines if line.get_visible() and np.size(line.get_xdata()))
    bars = {id(patch) for container in ax.containers if isinstance(container, BarContainer)
            for patch in container.patches if patch.get_visible()}
    others = [patch for patch in ax.patches if patch.get_visible() and id(patch) not in bars]
    steps = sum(1 for patch in others if isinstance(patch, StepPatch))     # ax.stairs
    counts["shapes"] += len(others) - steps
    for count, singular, plural in (
            (lines, _("{count} line"), _("{count} lines")),
            (counts["points"], _("{count} point"), _("{count} points")),
            (len(bars), _("{count} bar"), _("{count} bars")),
            (steps, _("{count} histogram"), _("{count} histograms")),
            (counts["segments"], _("{count} line segment"), _("{count} line segments")),
            (counts["arrows"], _("{count} arrow"), _("{count} arrows")),
            (counts["areas"], _("{count} shaded area"), _("{count} shaded areas")),
            (counts["shapes"], _("{count} shape"), _("{count} shapes"))):
        if count:
            items.append(_counted(count, singular, plural))
    texts = [text.get_text() for text in ax.texts
             if text.get_visible() and _plain(text.get_text())]
    if texts:
        item = _counted(len(texts), _("{count} text label"), _("{count} text labels"))
        if len(texts) <= MAX_QUOTED_TEXTS:
            item += ": " + ", ".join(_quoted(text, 60) for text in texts)
        items.append(item)
    return items


def _colorbar_item(colorbar):
    axis = colorbar.ax.yaxis if colorbar.orientation == "vertical" else colorbar.ax.xaxis
    label = _plain(axis.get_label_text())
    norm = colorbar.norm
    low, high = norm.vmin, norm.vmax
    if low is None or high is None:
        low, high = colorbar.vmin, colorbar.vmax
    low, high = _range(low, high)
    if label:
        item = _("colour bar {label} from {low} to {high}").format(label=_quoted(label),
                                                                   low=low, high=high)
    else:
        item = _("colour bar from {low} to {high}").format(low=low, high=high)
    if axis.get_scale() == "log":
        item += ", " + _("log scale")
    return item


def _title(ax):
    parts = [ax.get_title(loc) for loc in ("left", "center", "right")]
    return " ".join(_plain(part) for part in parts if _plain(part))


def _axis_items(ax, host=None):
    """The items that describe a panel's axes; with ``host``, ``ax`` is a twin of ``host``
    (same place, one shared axis), and only its own axis is described, named as the second
    one."""
    items = []
    shared_x = host is not None and host.get_shared_x_axes().joined(host, ax)
    shared_y = host is not None and host.get_shared_y_axes().joined(host, ax)
    if ax.axison:
        if not shared_x:
            name = _("x at the top") if host is not None else "x"
            items.append(_axis_item(name, ax.xaxis, ax.get_xlabel(), ax.get_xlim()))
        if not shared_y:
            name = _("y on the right") if host is not None else "y"
            items.append(_axis_item(name, ax.yaxis, ax.get_ylabel(), ax.get_ylim()))
    return [item for item in items if item]


def _content_items(ax):
    """The items that describe what a panel draws and its legend."""
    items = _drawn_items(ax)
    legend = ax.get_legend()
    if legend is not None and legend.get_visible():
        entries = [text.get_text() for text in legend.get_texts() if _plain(text.get_text())]
        if entries:
            items.append(_("legend: {entries}").format(entries=_listed(entries)))
    return items


def _cut(text, limit):
    if len(text) <= limit:
        return text
    head = text[:limit - 1]
    cut = max(head.rfind("; "), head.rfind(". "))
    return (head[:cut + 1] if cut > limit // 2 else head.rsplit(" ", 1)[0]) + " …"


def describe_figure(figure, max_length=MAX_LENGTH):
    """What a figure shows, in one plain-language text for its alternative text.

    It names the figure's title, then, for each visible panel, its title, each axis (its label,
    with units, and the range it shows, left to right and bottom to top, rounded to about three
    significant digits of the range), what is drawn (images with their size in pixels, lines,
    points, bars, arrows, contours, texts), the legend's entries and the colour bar (folded into
    the panel it belongs to) with its label and range. Fixed words are in the current language
    (``rsgeo.language.get_language()``; numbers with a decimal comma in Portuguese); the
    figure's own texts are quoted as they are, without mathtext markup.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure to describe; it is read, not drawn or changed (reading an axis' tick labels
        updates its ticks, as drawing would).
    max_length : int
        The longest text returned (default :data:`MAX_LENGTH`); a longer description is cut
        after its last whole item and ends with "…".

    Returns
    -------
    str
        The description, one paragraph.

    Raises
    ------
    ValueError
        If ``figure`` is not a matplotlib figure or ``max_length`` is under 40.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> figure = Figure()
    >>> ax = figure.subplots()
    >>> _ = ax.plot([0, 60], [1, 2.3], label="along track")
    >>> _ = ax.set(title="Pixels grow off nadir", xlabel="scan angle (degrees)",
    ...            ylabel="pixel size (km)", xlim=(0, 60), ylim=(0.8, 2.4))
    >>> _ = ax.legend()
    >>> describe_figure(figure)
    'Figure “Pixels grow off nadir”: x: scan angle (degrees) from 0 to 60; y: pixel size (km) \
from 0.8 to 2.4; 1 line; legend: “along track”.'
    """
    from matplotlib.figure import FigureBase

    from rsgeo.errors import RsgeoError

    if not isinstance(figure, FigureBase):
        raise RsgeoError(_("describe_figure needs a matplotlib figure, got {type}").format(
            type=type(figure).__name__))
    if not (isinstance(max_length, int) and max_length >= 40):
        raise RsgeoError(_("max_length must be an integer of at least 40, got {value!r}").format(
            value=max_length))
    suptitle = _plain(figure._suptitle.get_text()) if getattr(figure, "_suptitle", None) else ""
    visible = [ax for ax in figure.axes if ax.get_visible()]
    colorbars = {ax: ax._colorbar for ax in visible if getattr(ax, "_colorbar", None) is not None}
    panels, twins = [], {}
    for ax in visible:
        if ax in colorbars:
            continue
        place = tuple(np.round(ax.get_position().bounds, 4))
        host = next((panel for panel in panels
                     if tuple(np.round(panel.get_position().bounds, 4)) == place
                     and (panel.get_shared_x_axes().joined(panel, ax)
                          or panel.get_shared_y_axes().joined(panel, ax))), None)
        if host is None:
            panels.append(ax)
        else:
            twins.setdefault(host, []).append(ax)
    items, axes_of = {}, {}
    for number, ax in enumerate(panels, start=1):
        axes_items = _axis_items(ax)
        earlier = axes_of.setdefault(tuple(axes_items), number)
        if earlier != number and axes_items:      # a row of panels on the same axes
            axes_items = [_("same axes as panel {number}").format(number=earlier)]
        items[ax] = axes_items + _content_items(ax)
    for host, twinned in twins.items():
        for twin in twinned:
            items[host] += _axis_items(twin, host) + _content_items(twin)
    loose = []                              # colour bars of no panel here
    for colorbar in colorbars.values():
        owner = getattr(colorbar.mappable, "axes", None)
        owner = next((host for host, twinned in twins.items() if owner in twinned), owner)
        (items[owner] if owner in items else loose).append(_colorbar_item(colorbar))

    sentences = []
    if len(panels) > 1:
        sentences.append(
            _("Figure {title}, {count} panels.").format(title=_quoted(suptitle),
                                                        count=len(panels)) if suptitle
            else _("Figure of {count} panels.").format(count=len(panels)))
    elif suptitle:
        sentences.append(_("Figure {title}.").format(title=_quoted(suptitle)))
    figure_legends = [text.get_text() for legend in figure.legends if legend.get_visible()
                      for text in legend.get_texts() if _plain(text.get_text())]
    if figure_legends:
        sentences.append(_("legend: {entries}").format(entries=_listed(figure_legends)) + ".")
    labels = [_plain(label.get_text()) for label in (getattr(figure, "_supxlabel", None),
                                                     getattr(figure, "_supylabel", None))
              if label is not None and _plain(label.get_text())]
    notes = [text.get_text() for text in figure.texts
             if text.get_visible() and _plain(text.get_text()) and text is not figure._suptitle
             and text not in (getattr(figure, "_supxlabel", None),
                              getattr(figure, "_supylabel", None))]
    if labels:
        sentences.append(_("Axis labels for all panels: {labels}.").format(
            labels=", ".join(_quoted(label) for label in labels)))
    if notes:
        sentences.append(_counted(len(notes), _("{count} text label"), _("{count} text labels"))
                         + ": " + ", ".join(_quoted(note, 120) for note in notes[:3]) + ".")
    for number, ax in enumerate(panels, start=1):
        title = _title(ax)
        details = "; ".join(items[ax]) or _("nothing drawn")
        if len(panels) > 1:
            sentence = (_("Panel {number}, {title}: {details}.") if title
                        else _("Panel {number}: {details}."))
        elif suptitle:
            sentence = _("Panel {title}: {details}.") if title else "{details}."
        else:
            sentence = (_("Figure {title}: {details}.") if title
                        else _("Untitled figure: {details}."))
        sentences.append(sentence.format(number=number, title=_quoted(title), details=details))
    if loose:
        sentences.append("; ".join(loose) + ".")
    if not sentences:
        sentences.append(_("Empty figure."))
    return _cut(" ".join(sentences), max_length)
