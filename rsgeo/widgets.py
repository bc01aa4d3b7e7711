"""Interactive widgets for the chapters (ipywidgets), on top of rsgeo's maths.

Each function returns a widget to display as a notebook cell's last value.
In the HTML book the widgets keep the state saved at build time; in Jupyter or
Colab they redraw live.
"""

import numpy as np

from . import distortion, gcp, matching, radiometry
from .plot import draw_grid, draw_mesh, draw_stretch_frame


def _pyplot():
    import matplotlib.pyplot as plt

    return plt


def distortion_explorer(shape=(300, 300)):
    """Sliders for latitude, roll, pitch, yaw (constant and varying) and scan angle.

    The left panel redraws the true grid where a distorted image records it (a
    narrow-field scene: roll and pitch, in pixels of angle, are uniform shifts;
    the Earth-rotation skew of a descending pass puts each line's ground west of
    the line before); the right one the pixel size at the chosen scan angle for
    a MODIS-like sensor.
    """
    import ipywidgets as widgets

    plt = _pyplot()
    controls = {
        "latitude": widgets.FloatSlider(value=-23.0, min=-80, max=80, step=1, description="latitude °"),
        "roll": widgets.FloatSlider(value=0.0, min=-20, max=20, step=1, description="roll (px)"),
        "pitch": widgets.FloatSlider(value=0.0, min=-20, max=20, step=1, description="pitch (px)"),
        "yaw": widgets.FloatSlider(value=0.0, min=-10, max=10, step=0.5, description="yaw °"),
        "yaw_rate": widgets.FloatSlider(value=0.0, min=-0.03, max=0.03, step=0.005, readout_format=".3f",
                                        description="yaw °/line"),
        "scan": widgets.FloatSlider(value=30.0, min=0, max=60, step=1, description="scan angle °"),
    }

    def draw(latitude, roll, pitch, yaw, yaw_rate, scan):
        # skew of a 185 km Landsat frame, expressed per line of a 300-line image
        skew_km = distortion.earth_rotation_skew(latitude)
        model = distortion.SystematicDistortion(skew_per_line=skew_km / 185.0, roll_px=roll, pitch_px=pitch,
                                                yaw_deg=yaw, yaw_rate_deg_per_line=yaw_rate)
        figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
        draw_grid(left, distortion.distorted_grid(distortion.SystematicDistortion(), shape, 50),
                  color="lightgray")
        draw_grid(left, distortion.distorted_grid(model, shape, 50))
        left.set(xlim=(-60, shape[1] + 60), ylim=(shape[0] + 60, -60), xlabel="column (pixels)",
                 ylabel="row (pixels)", title=f"grid as recorded (last line {skew_km:.1f} km west per 185 km)")
        angles = np.linspace(0, 60, 121)
        along, across = distortion.pixel_size(angles, 705.0)
        right.plot(angles, along, label="along track")
        right.plot(angles, across, label="across track")
        a, c = distortion.pixel_size(scan, 705.0)
        right.scatter([scan, scan], [a, c], color="black", zorder=3)
        right.set(xlabel="scan angle (degrees)", ylabel="pixel size (km), 1 km at nadir",
                  title=f"MODIS-like, 705 km: {float(a):.2f} × {float(c):.2f} km at {scan:.0f}°")
        right.legend()
        plt.show()

    output = widgets.interactive_output(draw, controls)
    return widgets.VBox([widgets.HBox(list(controls.values())[:3]), widgets.HBox(list(controls.values())[3:]),
                         output])


def gcp_explorer(gcps, order=1, index=0):
    """Move one GCP's image position with sliders and watch residuals and RMS change."""
    import ipywidgets as widgets

    plt = _pyplot()
    dcol = widgets.FloatSlider(value=0, min=-15, max=15, step=0.5, description="Δcol (px)")
    drow = widgets.FloatSlider(value=0, min=-15, max=15, step=0.5, description="Δrow (px)")
    which = widgets.Dropdown(options=[(name, i) for i, name in enumerate(gcps.ids)], value=index, description="GCP")
    degree = widgets.Dropdown(options=[1, 2, 3], value=order, description="degree")

    def draw(which, dcol, drow, degree):
        image_xy = gcps.image_xy.copy()
        image_xy[which] += (dcol, drow)
        model = gcp.fit_polynomial(gcps.map_xy, image_xy, degree)
        _, _, distance = gcp.residuals(model, gcps.map_xy, image_xy)
        rms = gcp.rms_error(model(gcps.map_xy), image_xy)
        figure, ax = plt.subplots(figsize=(9, 3.5))
        colours = ["tab:red" if i == which else "tab:blue" for i in range(len(gcps))]
        ax.bar(gcps.ids, distance, color=colours)
        ax.axhline(rms, color="black", linestyle="--", label=f"RMS = {rms:.2f} px")
        ax.set(xlabel="GCP (id)", ylabel="residual R_i (pixels)", title=f"degree {degree}: residuals after moving "
               f"{gcps.ids[which]} by ({dcol:+.1f}, {drow:+.1f}) px")
        ax.legend()
        plt.show()

    output = widgets.interactive_output(draw, {"which": which, "dcol": dcol, "drow": drow, "degree": degree})
    return widgets.VBox([widgets.HBox([which, degree]), widgets.HBox([dcol, drow]), output])


def regression_stretch(x_image, y_image, sizes=(1, 3, 5, 7), size=3, methods=("ols", "rma")):
    """Animate the paper's correction: from no correction (t = 0) to a fitted gain and offset (t = 1).

    A Play button and a slider move t; the *filter* menu chooses the mean
    filter and the *method* menu the regression (``"ols"``, the paper's, or
    ``"rma"``, the reduced major axis) whose gain and offset are reached at
    t = 1. The mosaic's title gives the brightness step and the contrast
    mismatch over the whole overlap (:func:`rsgeo.radiometry.seam_metrics`);
    the scatter's title, the line at t and the chosen fit's r.

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

    Raises
    ------
    ValueError
        If ``size`` is not one of ``sizes`` or a method is unknown.
    """
    import ipywidgets as widgets

    from ._checks import check_choice

    if size not in sizes:
        raise ValueError(f"size {size!r} must be one of the offered sizes {tuple(sizes)}")
    for name in methods:
        check_choice(name, "method", radiometry.FIT_METHODS)
    plt = _pyplot()
    step = widgets.IntSlider(value=0, min=0, max=10, description="t × 10")
    play = widgets.Play(value=0, min=0, max=10, step=1, interval=400, description="play")
    widgets.jslink((play, "value"), (step, "value"))
    size = widgets.Dropdown(options=list(sizes), value=size, description="filter")
    method = widgets.Dropdown(options=list(methods), value=methods[0], description="method")
    fits = {}

    def draw(step, size, method):
        if (size, method) not in fits:
            fits[size, method] = radiometry.fit_gain_offset(
                x_image, y_image, smooth=size if size > 1 else None, method=method)
        fit = fits[size, method]
        figure, axes = plt.subplots(1, 3, figsize=(13, 4))
        draw_stretch_frame(axes, x_image, y_image, fit.gain, fit.offset, step / 10,
                           title_extra=f"\n({method}, filter {size}×{size}: r = {fit.r:.3f})")
        figure.tight_layout()
        plt.show()

    output = widgets.interactive_output(draw, {"step": step, "size": size, "method": method})
    return widgets.VBox([widgets.HBox([play, step]), widgets.HBox([size, method]), output])


def ga_evolution(reference, adjustment, truth, seed=0, generations=80):
    """The GA's evolution, generation by generation, with controls that rerun it.

    Left: the two meshes side by side with the best solution's match lines
    (green right, red wrong); right: best and mean fitness and the
    population's diversity up to the shown generation, on an axis that
    spans the whole run from the first frame on.

    Parameters
    ----------
    reference, adjustment : rsgeo.matching.Mesh
    truth : array_like of int
        The true matching (reference label of each adjustment segment).
    seed : int
        Seed of every run, so that only the controls change the outcome.
    generations : int
        Generations per run (at least 2).

    Returns
    -------
    ipywidgets.VBox

    Raises
    ------
    ValueError
        If ``generations`` is under 2 or ``truth`` has not one label per adjustment segment.
    """
    import ipywidgets as widgets

    if int(generations) < 2:
        raise ValueError(f"generations must be at least 2 to show an evolution, got {generations}")
    if len(truth) != len(adjustment):
        raise ValueError(f"truth needs one label per adjustment segment ({len(adjustment)}), "
                         f"got {len(truth)}")
    generations = int(generations)
    plt = _pyplot()
    population = widgets.IntSlider(value=60, min=10, max=200, step=10, description="population")
    elite = widgets.FloatSlider(value=0.05, min=0, max=0.3, step=0.01, description="elitism")
    mutation = widgets.FloatSlider(value=0.04, min=0.0, max=0.2, step=0.005, readout_format=".3f",
                                   description="mutation")
    selection = widgets.Dropdown(options=["tournament", "roulette"], value="tournament",
                                 description="selection")
    generation = widgets.IntSlider(value=0, min=0, max=generations - 1, description="generation")
    play = widgets.Play(value=0, min=0, max=generations - 1, step=1, interval=150,
                        description="play")
    widgets.jslink((play, "value"), (generation, "value"))
    runs = {}

    def run(population, elite, mutation, selection):
        key = (population, elite, mutation, selection)
        if key not in runs:
            runs[key] = matching.genetic_match(
                reference, adjustment, seed=seed, population_size=population,
                generations=generations, elite_fraction=elite, mutation_rate=mutation,
                selection=selection)
        return runs[key]

    def draw(population, elite, mutation, selection, generation):
        result = run(population, elite, mutation, selection)
        history = result.history[:generation + 1]
        figure = draw_evolution_frame(reference, adjustment, truth, history,
                                      generations=generations)
        figure.tight_layout()
        plt.show()

    output = widgets.interactive_output(draw, {"population": population, "elite": elite, "mutation": mutation,
                                               "selection": selection, "generation": generation})
    return widgets.VBox([widgets.HBox([population, elite]), widgets.HBox([mutation, selection]),
                         widgets.HBox([play, generation]), output])


def draw_evolution_frame(reference, adjustment, truth, history, figure=None, generations=None):
    """One frame of the GA's evolution (used by the widget and the jshtml animation).

    Parameters
    ----------
    reference, adjustment : rsgeo.matching.Mesh
    truth : array_like of int
        The true matching, to colour match lines green (right) or red (wrong).
    history : list of dict
        ``MatchResult.history`` up to the generation shown (at least one entry).
    figure : matplotlib Figure, optional
        Cleared and drawn on (a new one when None).
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
        raise ValueError("history must hold at least one generation to draw")
    plt = _pyplot()
    if figure is None:
        figure = plt.figure(figsize=(12, 4.5))
    figure.clear()
    left, right = figure.subplots(1, 2)
    offset = np.array([reference.centroids[:, 0].max() - adjustment.centroids[:, 0].min() + 80, 0.0])
    shifted = adjustment.centroids + offset
    draw_mesh(left, reference.centroids, color="tab:green")
    draw_mesh(left, shifted, color="tab:orange")
    solution = history[-1]["best_solution"]
    for k, label in enumerate(solution):
        if label:
            right_match = label == truth[k]
            left.plot(*np.array([shifted[k], reference.centroids[label - 1]]).T,
                      color="tab:green" if right_match else "tab:red", linewidth=1.5)
    left.set(title=f"generation {len(history) - 1}: {np.asarray(solution).tolist()}", xlabel="x (map units)",
             ylabel="y (map units)")
    left.invert_yaxis()
    shown = np.arange(len(history))
    last = max(len(history), int(generations or 0)) - 1
    style = {"marker": "o", "markersize": 3, "markevery": [len(history) - 1]}
    right.plot(shown, [h["best"] for h in history], label="best FA", **style)
    right.plot(shown, [h["mean"] for h in history], label="mean FA", **style)
    right.plot(shown, [h["diversity"] for h in history], label="diversity", linestyle=":", **style)
    right.set(xlabel="generation (count)", ylabel="FA or diversity (0–1)", ylim=(0, 1.02),
              xlim=(-0.5, max(last, 1) + 0.5), title="evolution")
    right.legend(loc="lower right")
    return figure
