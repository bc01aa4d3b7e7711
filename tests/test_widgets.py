"""Widgets that answer at once: every control's change updates the SAME figure in place (same
figure and axes, artists' data changed), with the right numbers in the titles, a new PNG frame in
the widget's output, and a clean figure audit at every frame. No timed assertions: the speed is
benchmarks/widgets.py's business."""

import base64
import html
import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from rsgeo import (  # noqa: E402
    accuracy,
    data,
    distortion,
    radiometry,
    registration,
    sensors,
    synthetic,
    transforms,
    widgets,
)
from rsgeo.plot import draw_grid, draw_mesh, draw_stretch_frame, fix_layout, grid_path  # noqa: E402
from rsgeo_course.alt_text import describe_figure  # noqa: E402

from figure_audit import figure_problems  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def controls(box):
    """Controls by description (the Play buttons are linked to their sliders in the browser)."""
    import ipywidgets

    found, stack = {}, [box]
    while stack:
        widget = stack.pop()
        if isinstance(widget, ipywidgets.Box):
            stack.extend(widget.children)
        elif hasattr(widget, "description") and not isinstance(widget, ipywidgets.Play):
            found[widget.description] = widget
    return found


def _frame_image(box):
    """(PNG as base64, alt text) of the frame the widget shows now (its HTML's only <img>)."""
    (shown,) = box.children[-1].outputs
    images = re.findall(r'<img src="data:image/png;base64,([^"]+)" alt="([^"]*)"',
                        shown["data"].get("text/html", ""))
    assert len(images) == 1, "the frame is not one <img> with an alt"
    return images[0]


def frame(box):
    """The PNG the widget's output shows now."""
    return base64.b64decode(_frame_image(box)[0])


def frame_alt(box):
    """The alternative text of the frame the widget shows now (its HTML's only <img>)."""
    return html.unescape(_frame_image(box)[1])


def changes_in_place(box, control, value):
    """Set a control; check the same figure and axes were updated and a new frame shown, with
    the alternative text of the new frame."""
    figure, axes, png = box.figure, list(box.figure.axes), frame(box)
    control.value = value
    assert box.figure is figure and box.figure.axes == axes, "a new figure or new axes were built"
    assert frame(box) != png, f"{control.description}: the frame did not change"
    assert frame(box).startswith(b"\x89PNG")
    assert figure_problems(figure) == []
    assert frame_alt(box) == describe_figure(figure) != ""


def test_distortion_explorer_moves_its_grid_and_markers():
    box = widgets.distortion_explorer()
    named = controls(box)
    left, right = box.figure.axes
    grid = left.lines[1]                      # the true grid (grey) is line 0
    for description, value in (("roll (px)", 10.0), ("yaw °", 4.0), ("latitude °", 50.0),
                               ("yaw °/line", 0.01), ("scan angle °", 45.0), ("pitch (px)", -5.0)):
        before = np.array(grid.get_xydata(), copy=True)
        changes_in_place(box, named[description], value)
        assert left.lines[1] is grid
        if description != "scan angle °":
            assert not np.allclose(np.nan_to_num(grid.get_xydata()), np.nan_to_num(before))
    model = sensors.SystematicDistortion(
        skew_per_line=distortion.earth_rotation_skew(50.0) / 185.0, roll_px=10.0, pitch_px=-5.0,
        yaw_deg=4.0, yaw_rate_deg_per_line=0.01)
    expected = np.column_stack(grid_path(sensors.distorted_grid(model, (300, 300), 50)))
    np.testing.assert_allclose(grid.get_xydata(), expected)
    assert f"last line {distortion.earth_rotation_skew(50.0):.1f} km west" in left.get_title()
    along, across = distortion.pixel_size(45.0, 705.0)
    assert f"{float(along):.2f} × {float(across):.2f} km at 45°" in right.get_title()
    np.testing.assert_allclose(right.collections[0].get_offsets(), [[45, along], [45, across]])
    with pytest.raises(ValueError, match="shape"):
        widgets.distortion_explorer(shape=(0, 300))


def test_gcp_explorer_updates_its_bars_and_rms():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    box = widgets.gcp_explorer(gcps, order=1, index=3)
    named = controls(box)
    (ax,) = box.figure.axes
    bars = list(ax.patches)
    for description, value in (("Δcol (px)", 6.0), ("Δrow (px)", -4.5), ("degree", 2), ("GCP", 5)):
        changes_in_place(box, named[description], value)
    assert list(ax.patches) == bars
    image_xy = gcps.image_xy.copy()
    image_xy[5] += (6.0, -4.5)
    model = transforms.fit_polynomial(gcps.map_xy, image_xy, 2)
    _, _, distance = accuracy.residuals(model, gcps.map_xy, image_xy)
    rms = model.rms(gcps.map_xy, image_xy)
    np.testing.assert_allclose([bar.get_height() for bar in bars], distance)
    assert ax.get_legend().get_texts()[0].get_text() == f"RMS = {rms:.2f} px"
    assert ax.get_title() == f"degree 2: residuals after moving {gcps.ids[5]} by (+6.0, -4.5) px"
    red = [i for i, bar in enumerate(bars)
           if np.allclose(bar.get_facecolor()[:3], (0.839, 0.153, 0.157), atol=0.01)]
    assert red == [5]
    with pytest.raises(ValueError, match="order"):
        widgets.gcp_explorer(gcps, order=4)


@pytest.mark.gdal
def test_model_explorer_draws_gdals_thin_plate_spline():
    # the spline gdalwarp -tps and QGIS use: fitted pixel -> map, inverted from map to pixel by
    # GDAL's TPS transformer (GDAL 3.10 through rasterio); with G10, where a spline fitted
    # map -> image is more than half a pixel away from it
    from gdal_tps_reference import gdal_spline_inverse

    gcps = data.load_gcps("cbers2b_ccd_hrc")
    box = widgets.model_explorer(gcps, model="tps", exaggeration=1)
    (ax,) = box.figure.axes
    drawn = np.asarray(ax.lines[0].get_xydata())
    drawn = drawn[~np.isnan(drawn).any(axis=1)]
    # the widget's grid: 9 lines each way, 41 points each, 5 % beyond the GCPs
    low, high = gcps.map_xy.min(axis=0), gcps.map_xy.max(axis=0)
    margin = 0.05 * (high - low)
    xs = np.linspace(low[0] - margin[0], high[0] + margin[0], 9)
    ys = np.linspace(low[1] - margin[1], high[1] + margin[1], 9)
    fine_x, fine_y = np.linspace(xs[0], xs[-1], 41), np.linspace(ys[0], ys[-1], 41)
    points = np.vstack([np.column_stack([np.full(41, x), fine_y]) for x in xs]
                       + [np.column_stack([fine_x, np.full(41, y)]) for y in ys])
    expected = gdal_spline_inverse(gcps.image_xy, gcps.map_xy, points)
    assert np.abs(drawn - expected).max() < 1e-9
    direct = transforms.fit_transform(gcps.map_xy, gcps.image_xy, "tps")(points)
    assert np.abs(drawn - direct).max() > 0.5                 # not the spline map -> image
    # the title's numbers are compare_models' (GDAL's spline, leave-one-out refitted by it)
    row = accuracy.compare_models(gcps.map_xy, gcps.image_xy).loc["tps"]
    assert (f"leave-one-out RMS {row['leave-one-out RMS (px)']:.2f} px" in ax.get_title())
    assert "tps (34 parameters)" in ax.get_title()


def test_model_explorer_refuses_too_few_gcps_for_leave_one_out():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    gcps.enabled = np.arange(len(gcps)) < 10            # degree 3's minimum: none left out
    with pytest.raises(ValueError, match="polynomial 3 need.* at least 11 enabled GCPs, got 10"):
        widgets.model_explorer(gcps)


def test_regression_stretch_updates_in_place_with_the_chosen_fit():
    pair = synthetic.contrast_pair()
    box = widgets.regression_stretch(pair.x_image, pair.y_image)
    named = controls(box)
    mosaic_axes, histogram_axes, scatter_axes = box.figure.axes
    image, line = mosaic_axes.images[0], scatter_axes.lines[0]
    for description, value in (("t × 10", 4), ("filter", 7), ("method", "rma"), ("t × 10", 10),
                               ("filter", 1)):
        changes_in_place(box, named[description], value)
        assert mosaic_axes.images[0] is image and scatter_axes.lines[0] is line
    fit = radiometry.fit_gain_offset(pair.x_image, pair.y_image, method="rma")
    assert scatter_axes.get_title() == (f"Y = {fit.gain:.3f} X + {fit.offset:.2f}\n"
                                        f"(rma, filter 1×1: r = {fit.r:.3f})")
    corrected = radiometry.apply_gain_offset(pair.x_image, fit.gain, fit.offset)
    mosaic, _ = radiometry.concatenate_halves(corrected, pair.y_image)
    np.testing.assert_array_equal(image.get_array(), mosaic)
    metrics = radiometry.seam_metrics(corrected, pair.y_image)
    assert mosaic_axes.get_title() == (f"t = 1.0: mean Δ {metrics['mean_difference']:+.1f} DN, "
                                       f"spread Δ {metrics['std_difference']:+.1f} DN")
    np.testing.assert_allclose(line.get_ydata(), fit.gain * np.array([0, 255]) + fit.offset)


def test_ga_evolution_moves_through_the_kept_run():
    reference, adjustment, truth = synthetic.synthetic_meshes(n=5, seed=1)
    box = widgets.ga_evolution(reference, adjustment, truth, generations=20)
    named = controls(box)
    left, right = box.figure.axes
    curves = list(right.lines)
    changes_in_place(box, named["generation"], 12)
    assert list(right.lines) == curves
    run = registration.genetic_match(reference, adjustment, seed=0, population_size=60,
                                     generations=20,
                                 elite_fraction=0.05, mutation_rate=0.04, selection="tournament",
                                 tournament_size=3)
    solution = run.history[12]["best_solution"]
    assert left.get_title() == f"generation 12: {np.asarray(solution).tolist()}"
    np.testing.assert_allclose(curves[0].get_ydata(), [h["best"] for h in run.history[:13]])
    assert len(left.collections[-1].get_segments()) == int(np.count_nonzero(solution))
    for description, value in (("population", 30), ("selection", "roulette"), ("mutation", 0.1),
                               ("elitism", 0.2)):
        changes_in_place(box, named[description], value)
    rerun = registration.genetic_match(reference, adjustment, seed=0, population_size=30,
                                   generations=20,
                                   elite_fraction=0.2, mutation_rate=0.1, selection="roulette",
                                   tournament_size=3)
    np.testing.assert_allclose(curves[1].get_ydata(), [h["mean"] for h in rerun.history[:13]])


def test_stretch_frame_and_evolution_frame_update_their_artists():
    pair = synthetic.contrast_pair()
    figure, axes = plt.subplots(1, 3)
    draw_stretch_frame(axes, pair.x_image, pair.y_image, 1.2, 5.0, 0.0)
    image = axes[0].images[0]
    draw_stretch_frame(axes, pair.x_image, pair.y_image, 1.2, 5.0, 1.0)
    assert list(axes[0].images) == [image] and len(axes[2].lines) == 1
    axes[0].clear()                                   # cleared axes: drawn afresh
    draw_stretch_frame(axes, pair.x_image, pair.y_image, 1.2, 5.0, 0.5)
    assert len(axes[0].images) == 1 and axes[0].images[0] is not image
    with pytest.raises(ValueError, match="three axes"):
        draw_stretch_frame(axes[:2], pair.x_image, pair.y_image, 1.2, 5.0, 0.5)

    reference, adjustment, truth = synthetic.synthetic_meshes(5, seed=1)
    run = registration.genetic_match(reference, adjustment, seed=0, generations=10)
    evolution = widgets.draw_evolution_frame(reference, adjustment, truth, run.history[:1],
                                             generations=10)
    left, right = evolution.axes
    widgets.draw_evolution_frame(reference, adjustment, truth, run.history, evolution,
                                 generations=10)
    assert evolution.axes == [left, right] and len(right.lines) == 3
    assert len(right.lines[0].get_xdata()) == 10 and left.get_title().startswith("generation 9:")
    assert figure_problems(evolution) == []


def test_grid_and_mesh_are_single_artists():
    lines = sensors.distorted_grid(sensors.SystematicDistortion(roll_px=3), (100, 100), 50)
    figure, ax = plt.subplots()
    line = draw_grid(ax, lines)
    assert list(ax.lines) == [line]
    cols, rows = grid_path(lines)
    assert np.isnan(cols).sum() == len(lines) and cols.size == sum(len(c) + 1 for c, _ in lines)
    with pytest.raises(ValueError, match="at least one"):
        grid_path([])
    with pytest.raises(ValueError, match="as many cols as rows"):
        grid_path([([0, 1, 2], [0, 1])])
    ax.clear()
    draw_mesh(ax, np.random.default_rng(0).random((5, 2)))
    assert list(ax.lines) == [] and len(ax.collections[0].get_segments()) == 10


def test_frames_are_drawn_once_and_widget_figures_stay_out_of_jupyter_cells(monkeypatch):
    figure, _ = plt.subplots(1, 2)
    fix_layout(figure)
    assert figure.get_layout_engine() is None          # an engine would make every save draw twice
    draws = []
    monkeypatch.setattr(type(figure), "draw", lambda self, renderer: draws.append(1))
    widgets.render_png(figure)
    assert len(draws) == 1
    with pytest.raises(ValueError, match="dpi"):
        widgets.render_png(figure, dpi=0)
    monkeypatch.undo()
    # under the inline backend the widget's figure is not pyplot's, so the cell does not show it
    # twice
    monkeypatch.setattr(matplotlib, "get_backend",
                        lambda: "module://matplotlib_inline.backend_inline")
    box = widgets.distortion_explorer()
    assert box.figure not in [plt.figure(number) for number in plt.get_fignums()]


def test_every_frame_says_what_it_shows_and_controls_are_plain_text():
    from ipywidgets.widgets.widget_description import DescriptionWidget

    box = widgets.distortion_explorer()
    alt = frame_alt(box)
    title = box.figure.axes[0].get_title()
    assert alt.startswith("Figure of 2 panels. Panel 1, “grid as recorded (last line ")
    assert title in alt and "legend: “along track”, “across track”" in alt
    assert box.children[-1].outputs[0]["data"]["text/plain"] == alt
    described = [widget for row in box.children[:-1] for widget in row.children]
    assert described and all(isinstance(widget, DescriptionWidget)
                             and widget.description_allow_html is False for widget in described)
    with pytest.raises(AssertionError, match="alt"):        # the check sees a frame without one
        box.children[-1].outputs = ({"output_type": "display_data",
                                     "data": {"image/png": "iVBORw0KGgo=",
                                              "text/html": '<img src="data:image/png;base64,'
                                                           'iVBORw0KGgo=">'},
                                     "metadata": {}},)
        frame_alt(box)


def test_widget_controls_and_frames_speak_portuguese(monkeypatch):
    from rsgeo import language as _i18n

    monkeypatch.setattr(_i18n, "_chosen", "pt_BR")
    box = widgets.distortion_explorer()
    assert {"rolamento (px)", "arfagem (px)", "guinada °"} <= set(controls(box))
    assert frame_alt(box).startswith("Figura com 2 painéis. Painel 1, ")
