"""Interactive widgets for the chapters (ipywidgets), on top of rsgeo's maths.

Each function returns a widget to display as a notebook cell's last value.
In the HTML book the widgets keep the state saved at build time; in Jupyter or
Colab they redraw live.

Every widget answers at once: it builds its figure once, and a control's
change updates that figure's artists in place (``set_data``, ``set_offsets``,
bar heights, titles) and puts a new PNG of the same figure in the widget's
``ipywidgets.Output``, as an ``<img>`` whose alternative text says what the
frame shows (:func:`rsgeo.plot.figure_description`). Control names and the
figures' texts are in rsgeo's language (``rsgeo.language``). Expensive
inputs (fitted models, GA runs) are computed once and kept. The box a widget
function returns carries that figure as its ``figure`` attribute
(``benchmarks/widgets.py`` times every control).
"""

import base64
import io
import weakref
from html import escape

import numpy as np

from . import accuracy, distortion, radiometry, registration, sensors, transforms
from .errors import GCPError, GridError, RsgeoError
from .language import _, prose_number
from .plot import (
    draw_grid,
    draw_mesh,
    draw_stretch_frame,
    figure_description,
    fix_layout,
    grid_path,
)
from .validation import as_number, check_choice

__all__ = [
    "DPI", "render_png", "distortion_explorer", "gcp_explorer",
    "regression_stretch", "ga_evolution", "draw_evolution_frame", "model_explorer",
]

#: Resolution of a widget's PNG frames (dots per inch): the figures are 9 to 13 inches wide,
#: 720 to 1040 pixels, about the width of the book's page.
DPI = 80


def _pyplot():
    import matplotlib.pyplot as plt

    return plt


def _widget_figure(figsize):
    """A figure a widget keeps and redraws.

    Under Jupyter's inline (or ipympl) backend it is released from pyplot at
    once, so that the cell does not show it a second time below the widget;
    elsewhere (scripts, tests on Agg) it stays pyplot's current figure.
    """
    import matplotlib

    plt = _pyplot()
    figure = plt.figure(figsize=figsize)
    backend = matplotlib.get_backend().lower()
    if any(name in backend for name in ("inline", "ipympl", "widget")):
        plt.close(figure)
    return figure


def render_png(figure, dpi=DPI):
    """A figure as PNG bytes, as a widget shows it.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
    dpi : float
        Dots per inch (default :data:`DPI`).

    Returns
    -------
    bytes
        The PNG file's content.

    Raises
    ------
    ValueError
        If ``dpi`` is not a positive number.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> render_png(Figure(figsize=(1, 1)), dpi=10)[:4]
    b'\\x89PNG'
    """
    if not (isinstance(dpi, (int, float)) and dpi > 0):
        raise RsgeoError(f"dpi must be a positive number, got {dpi!r}")
    buffer = io.BytesIO()
    # zlib level 1: faster to encode than the default (6), and these frames come out no larger
    figure.savefig(buffer, format="png", dpi=dpi, pil_kwargs={"compress_level": 1})
    return buffer.getvalue()


def _frame_output(figure):
    """A widget's frame: a PNG of the figure with its alternative text, as a display output.

    Jupyter, Colab and the book's widget manager show the ``text/html``: an ``<img>`` whose
    ``alt`` is :func:`rsgeo.plot.figure_description` of the figure (made after the PNG, so
    that it reads the figure's texts as rendered, translated when the book is Portuguese); a
    text-only front end shows the description. The PNG is not given a second time as
    ``image/png``: it would double every frame a saved widget page carries.

    Parameters
    ----------
    figure : matplotlib.figure.Figure

    Returns
    -------
    dict
        A ``display_data`` output (nbformat), as an ``ipywidgets.Output`` holds it.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> figure = Figure(figsize=(1, 1))
    >>> _ = figure.subplots().set(title="nothing yet", xticks=[], yticks=[])
    >>> frame = _frame_output(figure)
    >>> sorted(frame["data"])
    ['text/html', 'text/plain']
    >>> frame["data"]["text/plain"] == figure_description(figure)
    True
    >>> f'alt="{figure_description(figure)}"' in frame["data"]["text/html"]
    True
    """
    png = base64.b64encode(render_png(figure)).decode("ascii")
    description = figure_description(figure)
    html = (f'<img src="data:image/png;base64,{png}" alt="{escape(description)}" '
            'style="max-width: 100%; height: auto">')
    return {"output_type": "display_data",
            "data": {"text/html": html, "text/plain": description},
            "metadata": {}}


def _show(output, figure):
    """Replace the output's content with the figure's frame (one trait change, no flicker)."""
    output.outputs = (_frame_output(figure),)


def _plain_descriptions(box):
    """Every control's description in ``box`` is shown as plain text, never parsed as HTML."""
    import ipywidgets
    from ipywidgets.widgets.widget_description import DescriptionWidget

    stack = [box]
    while stack:
        widget = stack.pop()
        if isinstance(widget, ipywidgets.Box):
            stack.extend(widget.children)
        elif isinstance(widget, DescriptionWidget):
            widget.description_allow_html = False


def _live(box, output, figure, update, controls):
    """Draw once (with the layout), then redraw on every control's change; return ``box``."""
    _plain_descriptions(box)

    def redraw(change=None):
        try:
            update()
        except Exception as error:
            output.outputs = ({"output_type": "stream", "name": "stderr",
                               "text": f"{type(error).__name__}: {error}\n"},)
            raise
        _show(output, figure)

    update()
    fix_layout(figure)           # once: every frame keeps the same layout
    _show(output, figure)
    for control in controls:
        control.observe(redraw, names="value")
    box.figure = figure
    return box


def distortion_explorer(shape=(300, 300)):
    """Sliders for latitude, roll, pitch, yaw (constant and varying) and scan angle.

    The left panel shows the true grid where a distorted image records it (a
    narrow-field scene: roll and pitch, in pixels of angle, are uniform shifts;
    the Earth-rotation skew of a descending pass puts each line's ground west of
    the line before); the right one the pixel size at the chosen scan angle for
    a MODIS-like sensor. A change moves the grid line and the two markers.

    Parameters
    ----------
    shape : (int, int)
        Rows and columns of the image whose grid is drawn.

    Returns
    -------
    ipywidgets.VBox
        With ``figure``, the matplotlib Figure it updates.

    Raises
    ------
    ValueError
        If ``shape`` is not two positive integers.
    """
    import ipywidgets as widgets

    if len(shape) != 2 or min(int(n) for n in shape) < 1:
        raise GridError(f"shape must be two positive integers (rows, cols), got {shape!r}")
    shape = (int(shape[0]), int(shape[1]))
    controls = {
        "latitude": widgets.FloatSlider(value=-23.0, min=-80, max=80, step=1,
                                        description=_("latitude °")),
        "roll": widgets.FloatSlider(value=0.0, min=-20, max=20, step=1,
                                    description=_("roll (px)")),
        "pitch": widgets.FloatSlider(value=0.0, min=-20, max=20, step=1,
                                     description=_("pitch (px)")),
        "yaw": widgets.FloatSlider(value=0.0, min=-10, max=10, step=0.5, description=_("yaw °")),
        "yaw_rate": widgets.FloatSlider(value=0.0, min=-0.03, max=0.03, step=0.005,
                                        readout_format=".3f",
                                        description=_("yaw °/line")),
        "scan": widgets.FloatSlider(value=30.0, min=0, max=60, step=1,
                                    description=_("scan angle °")),
    }
    figure = _widget_figure((11, 4.5))
    left, right = figure.subplots(1, 2)
    nominal = sensors.distorted_grid(sensors.SystematicDistortion(), shape, 50)
    draw_grid(left, nominal, color="lightgray")
    grid = draw_grid(left, nominal)
    left.set(xlim=(-60, shape[1] + 60), ylim=(shape[0] + 60, -60), xlabel=_("column (pixels)"),
             ylabel=_("row (pixels)"))
    angles = np.linspace(0, 60, 121)
    along, across = distortion.pixel_size(angles, 705.0)
    right.plot(angles, along, label=_("along track"))
    right.plot(angles, across, label=_("across track"))
    marks = right.scatter([0, 0], [1, 1], color="black", zorder=3)
    right.set(xlabel=_("scan angle (degrees)"), ylabel=_("pixel size (km), 1 km at nadir"))
    right.legend()

    def update():
        value = {name: float(control.value) for name, control in controls.items()}
        # skew of a 185 km Landsat frame, expressed per line of a 300-line image
        skew_km = distortion.earth_rotation_skew(value["latitude"])
        model = sensors.SystematicDistortion(
            skew_per_line=skew_km / 185.0, roll_px=value["roll"], pitch_px=value["pitch"],
            yaw_deg=value["yaw"], yaw_rate_deg_per_line=value["yaw_rate"])
        grid.set_data(*grid_path(sensors.distorted_grid(model, shape, 50)))
        left.set_title(_("grid as recorded (last line {skew:.1f} km west per 185 km)").format(
            skew=prose_number(skew_km)), y=1.0)
        a, c = distortion.pixel_size(value["scan"], 705.0)
        marks.set_offsets([[value["scan"], float(a)], [value["scan"], float(c)]])
        right.set_title(_("MODIS-like, 705 km: {along:.2f} × {across:.2f} km at {angle:.0f}°")
                        .format(along=prose_number(float(a)), across=prose_number(float(c)),
                                angle=prose_number(value["scan"])), y=1.0)

    output = widgets.Output()
    box = widgets.VBox([widgets.HBox(list(controls.values())[:3]),
                        widgets.HBox(list(controls.values())[3:]),
                        output])
    return _live(box, output, figure, update, controls.values())


def gcp_explorer(gcps, order=1, index=0):
    """Move one GCP's image position with sliders and watch residuals and RMS change.

    Parameters
    ----------
    gcps : rsgeo.gcp.GCPSet
    order : int
        Polynomial degree shown first (1 to 3).
    index : int
        The GCP moved first (0-based).

    Returns
    -------
    ipywidgets.VBox
        With ``figure``, the matplotlib Figure it updates: one bar per GCP
        (the moved one red), the RMS as a dashed line.

    Raises
    ------
    ValueError
        If ``order`` is not 1, 2 or 3 or ``index`` names no GCP.
    """
    import ipywidgets as widgets

    if order not in (1, 2, 3):
        raise GCPError(f"order must be 1, 2 or 3, got {order!r}")
    if not 0 <= int(index) < len(gcps):
        raise GCPError(f"index must name one of the {len(gcps)} GCPs (0 to {len(gcps) - 1}), got "
                       f"{index}")
    dcol = widgets.FloatSlider(value=0, min=-15, max=15, step=0.5, description=_("Δcol (px)"))
    drow = widgets.FloatSlider(value=0, min=-15, max=15, step=0.5, description=_("Δrow (px)"))
    which = widgets.Dropdown(options=[(name, i) for i, name in enumerate(gcps.ids)],
                             value=int(index),
                             description=_("GCP"))
    degree = widgets.Dropdown(options=[1, 2, 3], value=order, description=_("degree"))
    figure = _widget_figure((9, 3.5))
    ax = figure.subplots()
    names = [str(name) for name in gcps.ids]
    bars = ax.bar(names, np.zeros(len(names)), color="tab:blue")
    rms_line = ax.axhline(0.0, color="black", linestyle="--", label="RMS")
    legend = ax.legend(loc="upper right")
    ax.set(xlabel=_("GCP (id)"), ylabel=_("residual R_i (pixels)"))

    def update():
        image_xy = gcps.image_xy.copy()
        image_xy[which.value] += (dcol.value, drow.value)
        model = transforms.fit_polynomial(gcps.map_xy, image_xy, degree.value)
        distance = accuracy.residuals(model, gcps.map_xy, image_xy)[2]
        rms = model.rms(gcps.map_xy, image_xy)
        for i, (bar, height) in enumerate(zip(bars, distance)):
            bar.set_height(height)
            bar.set_facecolor("tab:red" if i == which.value else "tab:blue")
        rms_line.set_ydata([rms, rms])
        legend.get_texts()[0].set_text(_("RMS = {rms:.2f} px").format(rms=prose_number(rms)))
        ax.set_ylim(0, 1.15 * max(float(np.max(distance)), rms, 1e-3))
        ax.set_title(_("degree {degree}: residuals after moving {name} by ({dcol:+.1f}, "
                       "{drow:+.1f}) px").format(degree=degree.value, name=names[which.value],
                                                 dcol=prose_number(dcol.value),
                                                 drow=prose_number(drow.value)), y=1.0)

    output = widgets.Output()
    box = widgets.VBox([widgets.HBox([which, degree]), widgets.HBox([dcol, drow]), output])
    return _live(box, output, figure, update, (which, dcol, drow, degree))


def regression_stretch(x_image, y_image, sizes=(1, 3, 5, 7), size=3, methods=("ols", "rma")):
    """Animate the paper's correction: from none (t = 0) to a fitted gain and offset (t = 1).

    A Play button and a slider move t; the *filter* menu chooses the mean
    filter and the *method* menu the regression (``"ols"``, the paper's, or
    ``"rma"``, the reduced major axis) whose gain and offset are reached at
    t = 1. The mosaic's title gives the brightness step and the contrast
    mismatch over the whole overlap (:func:`rsgeo.radiometry.seam_metrics`);
    the scatter's title, the line at t and the chosen fit's r. Every
    (filter, method) fit is computed once, when the widget is built.

    Parameters
    ----------
    x_image, y_image : ndarray
        A (X, integer dtype, the image corrected) and B (Y), same shape.
    sizes : sequence of int
        Filter sizes offered (1: no filter).
    size : int
        The filter shown first (3, the paper's).
    methods : sequence of str
        Regression methods offered (see :func:`rsgeo.radiometry.fit_gain_offset`).

    Returns
    -------
    ipywidgets.VBox
        With ``figure``, the matplotlib Figure it updates.

    Raises
    ------
    ValueError
        If ``size`` is not one of ``sizes`` or a method is unknown.

    References
    ----------
    The regression paper: *Linear regression to match the contrast of
    overlapping aerial photographs* (seed document 000 of this course).
    """
    import ipywidgets as widgets


    if size not in sizes:
        raise RsgeoError(f"size {size!r} must be one of the offered sizes {tuple(sizes)}")
    for name in methods:
        check_choice(name, "method", radiometry.FIT_METHODS)
    fits = {(s, m): radiometry.fit_gain_offset(x_image, y_image, smooth=s if s > 1 else None,
                                               method=m)
            for s in sizes for m in methods}
    step = widgets.IntSlider(value=0, min=0, max=10, description=_("t × 10"))
    play = widgets.Play(value=0, min=0, max=10, step=1, interval=400, description=_("play"))
    widgets.jslink((play, "value"), (step, "value"))
    size = widgets.Dropdown(options=list(sizes), value=size, description=_("filter"))
    method = widgets.Dropdown(options=list(methods), value=methods[0], description=_("method"))
    figure = _widget_figure((13, 4))
    axes = figure.subplots(1, 3)

    def update():
        fit = fits[size.value, method.value]
        draw_stretch_frame(axes, x_image, y_image, fit.gain, fit.offset, step.value / 10,
                           title_extra="\n" + _("({method}, filter {size}×{size}: r = {r:.3f})")
                           .format(method=method.value, size=size.value,
                                   r=prose_number(fit.r)))

    output = widgets.Output()
    box = widgets.VBox([widgets.HBox([play, step]), widgets.HBox([size, method]), output])
    return _live(box, output, figure, update, (step, size, method))


def ga_evolution(reference, adjustment, truth, seed=0, generations=80):
    """The GA's evolution, generation by generation, with controls that rerun it.

    Left: the two meshes side by side with the best solution's match lines
    (green right, red wrong); right: best and mean fitness and the
    population's diversity up to the shown generation, on an axis that
    spans the whole run from the first frame on. Each run is computed once
    per setting of the GA's controls and kept; the generation slider (and
    Play) only moves through the kept history.

    Parameters
    ----------
    reference, adjustment : rsgeo.registration.Mesh
    truth : array_like of int
        The true matching (reference label of each adjustment segment).
    seed : int
        Seed of every run, so that only the controls change the outcome.
    generations : int
        Generations per run (at least 2).

    Returns
    -------
    ipywidgets.VBox
        With ``figure``, the matplotlib Figure it updates.

    Raises
    ------
    ValueError
        If ``generations`` is under 2 or ``truth`` has not one label per adjustment segment.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 3.

    Goldberg, D. E. (1989), *Genetic Algorithms in Search, Optimization, and
    Machine Learning*, Addison-Wesley.
    """
    import ipywidgets as widgets

    if int(generations) < 2:
        raise RsgeoError(f"generations must be at least 2 to show an evolution, got {generations}")
    if len(truth) != len(adjustment):
        raise RsgeoError(f"truth needs one label per adjustment segment ({len(adjustment)}), "
                         f"got {len(truth)}")
    generations = int(generations)
    # a GA run per change: the sliders report on release, not at every step of a drag
    population = widgets.IntSlider(value=60, min=10, max=200, step=10, description=_("population"),
                                   continuous_update=False)
    elite = widgets.FloatSlider(value=0.05, min=0, max=0.3, step=0.01, description=_("elitism"),
                                continuous_update=False)
    mutation = widgets.FloatSlider(value=0.04, min=0.0, max=0.2, step=0.005, readout_format=".3f",
                                   description=_("mutation"), continuous_update=False)
    selection = widgets.Dropdown(options=["tournament", "roulette"], value="tournament",
                                 description=_("selection"))
    generation = widgets.IntSlider(value=0, min=0, max=generations - 1,
                                   description=_("generation"))
    play = widgets.Play(value=0, min=0, max=generations - 1, step=1, interval=150,
                        description=_("play"))
    widgets.jslink((play, "value"), (generation, "value"))
    runs = {}
    figure = _widget_figure((12, 4.5))

    def update():
        key = (population.value, elite.value, mutation.value, selection.value)
        if key not in runs:
            runs[key] = registration.genetic_match(
                reference, adjustment, seed=seed, population_size=population.value,
                generations=generations, elite_fraction=elite.value, mutation_rate=mutation.value,
                selection=selection.value, tournament_size=3)   # as chapter 6b's runs
        draw_evolution_frame(reference, adjustment, truth,
                             runs[key].history[:generation.value + 1],
                             figure, generations=generations)

    output = widgets.Output()
    box = widgets.VBox([widgets.HBox([population, elite]), widgets.HBox([mutation, selection]),
                        widgets.HBox([play, generation]), output])
    return _live(box, output, figure, update, (population, elite, mutation, selection, generation))


_EVOLUTION_ARTISTS = weakref.WeakKeyDictionary()   # figure -> the artists of its evolution frame


def draw_evolution_frame(reference, adjustment, truth, history, figure=None, generations=None):
    """One frame of the GA's evolution (used by the widget and the jshtml animation).

    The first call on a figure clears it and draws both panels (and sets the
    layout); later calls for the same meshes, truth and run length update the
    match lines, curves and title in place, so that frames draw fast.

    Parameters
    ----------
    reference, adjustment : rsgeo.registration.Mesh
    truth : array_like of int
        The true matching, to colour match lines green (right) or red (wrong).
    history : list of dict
        ``MatchResult.history`` up to the generation shown (at least one entry).
    figure : matplotlib Figure, optional
        Drawn on (a new one when None).
    generations : int, optional
        Generations of the whole run: the evolution panel's x axis spans them
        from the first frame on, so that no frame is empty (default: the
        generations in ``history``).

    Returns
    -------
    matplotlib Figure

    Raises
    ------
    ValueError
        If ``history`` is empty.
    """
    if not history:
        raise RsgeoError("history must hold at least one generation to draw")
    if figure is None:
        figure = _pyplot().figure(figsize=(12, 4.5))
    last = max(len(history), int(generations or 0)) - 1
    state = _EVOLUTION_ARTISTS.get(figure)
    fresh = (state is None or state["reference"] is not reference
             or state["adjustment"] is not adjustment
             or state["truth"] is not truth or state["last"] != last
             or any(ax not in figure.axes for ax in state["axes"]))
    if fresh:
        state = _draw_evolution_axes(figure, reference, adjustment, truth, last)
        _EVOLUTION_ARTISTS[figure] = state
    left = state["axes"][0]
    solution = history[-1]["best_solution"]
    segments, colours = [], []
    for k, label in enumerate(solution):
        if label:
            segments.append([state["shifted"][k], reference.centroids[label - 1]])
            colours.append("tab:green" if label == truth[k] else "tab:red")
    state["matches"].set_segments(segments)
    state["matches"].set_color(colours or "none")
    left.set_title(_("generation {number}: {solution}").format(
        number=len(history) - 1, solution=np.asarray(solution).tolist()), y=1.0)
    shown = np.arange(len(history))
    for line, name in zip(state["curves"], ("best", "mean", "diversity")):
        line.set_data(shown, [h[name] for h in history])
        line.set_markevery([len(history) - 1])
    if fresh:
        fix_layout(figure)       # once: every frame keeps the same layout
    return figure


def _draw_evolution_axes(figure, reference, adjustment, truth, last):
    """Draw an evolution frame's fixed parts and empty moving artists.

    See :func:`draw_evolution_frame`.
    """
    from matplotlib.collections import LineCollection

    figure.clear()
    left, right = figure.subplots(1, 2)
    offset = np.array([reference.centroids[:, 0].max() - adjustment.centroids[:, 0].min() + 80,
                       0.0])
    shifted = adjustment.centroids + offset
    draw_mesh(left, reference.centroids, color="tab:green")
    draw_mesh(left, shifted, color="tab:orange")
    matches = LineCollection([], linewidths=1.5)
    left.add_collection(matches, autolim=False)
    left.set(xlabel=_("x (map units)"), ylabel=_("y (map units)"))
    left.invert_yaxis()
    style = {"marker": "o", "markersize": 3}
    curves = (right.plot([], [], label=_("best FA"), **style)[0],
              right.plot([], [], label=_("mean FA"), **style)[0],
              right.plot([], [], label=_("diversity"), linestyle=":", **style)[0])
    right.set(xlabel=_("generation (count)"), ylabel=_("FA or diversity (0–1)"), ylim=(0, 1.02),
              xlim=(-0.5, max(last, 1) + 0.5))
    right.set_title(_("evolution"), y=1.0)
    right.legend(loc="lower right")
    return {"reference": reference, "adjustment": adjustment, "truth": truth, "last": last,
            "axes": (left, right), "shifted": shifted, "matches": matches, "curves": curves}


def model_explorer(gcps, model="polynomial 1", exaggeration=20.0):
    """Switch among QGIS's Georeferencer models and watch the deformation grid and residuals.

    The blue grid is a regular map grid over the GCPs, drawn where the model
    puts it in the image, its departure from the degree-1 polynomial (an
    affine map) drawn ``exaggeration`` times larger: straight for linear,
    Helmert and degree 1, bent for the others. The arrows are the GCPs'
    residuals (model - measured), as long times the same factor; the title
    gives the fitting and leave-one-out RMS, those of
    :func:`rsgeo.accuracy.compare_models`. Every model and its leave-one-out
    errors are computed once, when the widget is built.

    Every model maps map -> image. The thin-plate spline is GDAL's, as
    ``gdalwarp -tps`` and QGIS's Georeferencer make it (and
    :func:`rsgeo.resample.georeference` warps with it): fitted image -> map
    and inverted point by point (:meth:`rsgeo.transforms.TPSModel.inverse`),
    not a spline fitted map -> image, which passes through the same GCPs but
    bends differently between them.

    Parameters
    ----------
    gcps : rsgeo.gcp.GCPSet
        Its enabled GCPs are used (map -> image).
    model : str
        Label shown first, one of ``rsgeo.transforms.GEOREFERENCER_MODELS``' labels.
    exaggeration : float
        Initial factor for the grid's departure and the arrows (1 to 50).

    Returns
    -------
    ipywidgets.VBox
        With ``figure``, the matplotlib Figure it updates.

    Raises
    ------
    ValueError
        If ``model`` is not one of the labels, ``exaggeration`` is not in
        [1, 50], or there are too few GCPs for one of the models' leave-one-out
        errors (one more than its minimum).
    """
    import ipywidgets as widgets

    labels = [label for label, _, _ in transforms.GEOREFERENCER_MODELS]
    check_choice(model, "model", labels)
    exaggeration = as_number(exaggeration, "exaggeration", low=1, high=50)
    enabled = np.asarray(getattr(gcps, "enabled", np.ones(len(gcps), bool)), bool)
    map_xy, image_xy = gcps.map_xy[enabled], gcps.image_xy[enabled]
    low, high = map_xy.min(axis=0), map_xy.max(axis=0)
    margin = 0.05 * (high - low)
    xs = np.linspace(low[0] - margin[0], high[0] + margin[0], 9)
    ys = np.linspace(low[1] - margin[1], high[1] + margin[1], 9)
    fine_x = np.linspace(xs[0], xs[-1], 41)
    fine_y = np.linspace(ys[0], ys[-1], 41)
    lines = ([np.column_stack([np.full(41, x), fine_y]) for x in xs]
             + [np.column_stack([fine_x, np.full(41, y)]) for y in ys])
    points = np.vstack(lines)
    affine = transforms.fit_transform(map_xy, image_xy, "polynomial", 1)
    base = affine(points)
    table = accuracy.compare_models(map_xy, image_xy)
    short = table.index[table["leave-one-out RMS (px)"].isna()]
    if len(short):
        raise GCPError(_("the model explorer shows every model's leave-one-out RMS, which needs "
                         "one GCP more than the model's minimum: {models} need(s) at least "
                         "{needed} enabled GCPs, got {count}").format(
                             models=", ".join(short),
                             needed=int(table.loc[short, "min GCPs"].max()) + 1,
                             count=len(map_xy)))
    fitted = {}
    for label, kind, order in transforms.GEOREFERENCER_MODELS:
        if kind == "tps":
            # GDAL's spline (gdalwarp -tps, QGIS): fitted image -> map, inverted as GDAL does
            fitted_model = transforms.fit_transform(image_xy, map_xy, "tps").inverse()
        else:
            fitted_model = transforms.fit_transform(map_xy, image_xy, kind, order)
        row = table.loc[label]
        fitted[label] = (int(row["parameters"]), fitted_model(points) - base,
                         fitted_model(map_xy) - image_xy, float(row["fitting RMS (px)"]),
                         float(row["leave-one-out RMS (px)"]))

    choice = widgets.Dropdown(options=labels, value=model, description=_("model"))
    factor = widgets.FloatSlider(value=exaggeration, min=1, max=50, step=1,
                                 description=_("× drawn"))
    figure = _widget_figure((7.5, 7))
    ax = figure.subplots()
    grid_line, = ax.plot([], [], color="tab:blue", linewidth=0.8)
    arrows = ax.quiver(image_xy[:, 0], image_xy[:, 1], np.zeros(len(image_xy)),
                       np.zeros(len(image_xy)), color="tab:red", angles="xy",
                       scale_units="xy", scale=1.0, width=0.005)
    ax.scatter(image_xy[:, 0], image_xy[:, 1], s=12, color="black", zorder=3)
    span = image_xy.max(axis=0) - image_xy.min(axis=0)
    ax.set(xlim=(image_xy[:, 0].min() - 0.25 * span[0], image_xy[:, 0].max() + 0.25 * span[0]),
           ylim=(image_xy[:, 1].max() + 0.25 * span[1], image_xy[:, 1].min() - 0.25 * span[1]),
           xlabel=_("column (px)"), ylabel=_("row (px)"), aspect="equal")
    sizes = [len(line) for line in lines]

    def update():
        n_parameters, departure, residual, rms, loo = fitted[choice.value]
        k = float(factor.value)
        drawn = base + k * departure
        parts = np.split(drawn, np.cumsum(sizes)[:-1])
        grid_line.set_data(*grid_path([(part[:, 0], part[:, 1]) for part in parts]))
        arrows.set_UVC(residual[:, 0], residual[:, 1])
        arrows.scale = 1.0 / k
        ax.set_title(_("{model} ({count} parameters), drawn ×{factor:g}: fitting RMS {rms:.2f} "
                       "px, leave-one-out RMS {loo:.2f} px").format(
                           model=choice.value, count=n_parameters, factor=prose_number(k),
                           rms=prose_number(rms), loo=prose_number(loo)),
                     y=1.0, fontsize=9)

    output = widgets.Output()
    box = widgets.VBox([widgets.HBox([choice, factor]), output])
    return _live(box, output, figure, update, (choice, factor))
