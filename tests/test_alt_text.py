"""Every figure says what it shows: rsgeo_course.alt_text.describe_figure, the PNG description the
book's kernels write (book/_ext/figure_audit.py) and the alt the book gives it
(book/_ext/figure_alt.py), and the animation player's alternative text and control names
(rsgeo.plot.animation_html)."""

import io
import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

from rsgeo import language as _i18n  # noqa: E402
from rsgeo.plot import animation_html  # noqa: E402
from rsgeo_course.alt_text import MAX_LENGTH, describe_figure  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")
    _i18n.set_language(None)


def one_panel():
    figure, ax = plt.subplots()
    ax.plot([0, 60], [1.0, 2.3], label="along track")
    ax.plot([0, 60], [1.0, 4.1], label="across track")
    ax.scatter([30, 30], [1.2, 1.4])
    ax.set(title="Pixels grow off nadir", xlabel="scan angle (degrees)",
           ylabel="pixel size (km)", xlim=(0, 60), ylim=(0.8, 4.2))
    ax.legend()
    return figure


def three_panels():
    figure, (left, middle, right) = plt.subplots(1, 3, figsize=(12, 4))
    image = left.imshow(np.zeros((300, 200)), cmap="gray", vmin=0, vmax=255)
    left.set(title="scene", xlabel="column (px)", ylabel="row (px)")
    figure.colorbar(image, ax=left, label="DN (0–255)")
    middle.bar(["G01", "G02", "G03"], [1.5, 0.5, 2.0])
    middle.set(title="residuals", xlabel="GCP (id)", ylabel="residual (px)")
    right.hist(np.linspace(0, 1, 100), bins=10)
    right.set(xlabel="ratio (–)", ylabel="count (pixels)")
    figure.suptitle("The scene and its GCPs")
    return figure


def test_one_panel_names_title_axes_lines_points_and_legend():
    text = describe_figure(one_panel())
    assert text == ("Figure “Pixels grow off nadir”: x: scan angle (degrees) from 0 to 60; "
                    "y: pixel size (km) from 0.8 to 4.2; 2 lines; 2 points; "
                    "legend: “along track”, “across track”.")


def test_three_panels_each_described_with_the_colour_bar_folded_into_its_panel():
    text = describe_figure(three_panels())
    assert text.startswith("Figure “The scene and its GCPs”, 3 panels. Panel 1, “scene”: ")
    assert ("x: column (px) from 0 to 200; y: row (px) from 300 to 0; an image of "
            "300×200 pixels; colour bar “DN (0–255)” from 0 to 255.") in text
    assert ("Panel 2, “residuals”: x: GCP (id), 3 categories: “G01”, “G02”, “G03”; "
            "y: residual (px) from 0 to 2.1; 3 bars.") in text
    assert "Panel 3: x: ratio (–) from " in text and "10 bars." in text
    assert "Panel 4" not in text and text.count("colour bar") == 1     # the bar is no panel


def test_a_figure_with_no_title_says_so_and_an_empty_figure_is_empty():
    figure, ax = plt.subplots()
    ax.imshow(np.zeros((4, 5, 3)))
    ax.axis("off")
    assert describe_figure(figure) == "Untitled figure: a colour image of 4×5 pixels."
    assert describe_figure(plt.figure()) == "Empty figure."


def test_panels_on_the_same_axes_say_so_instead_of_repeating_them():
    figure, axes = plt.subplots(1, 3, sharex=True, sharey=True)
    for ax, title in zip(axes, ("roll", "pitch", "yaw")):
        ax.plot([0, 300], [300, 0])
        ax.set(title=title, xlabel="column (px)", ylabel="row (px)", xlim=(0, 300),
               ylim=(300, 0))
        ax.yaxis.set_tick_params(labelleft=True)
    text = describe_figure(figure)
    assert text.count("x: column (px) from 0 to 300") == 1
    assert "Panel 2, “pitch”: same axes as panel 1; 1 line." in text
    assert "Panel 3, “yaw”: same axes as panel 1; 1 line." in text


def test_histograms_arrows_segments_and_contours_are_named():
    figure, ax = plt.subplots()
    ax.stairs([3, 5, 2], [0, 1, 2, 3], label="A")
    ax.quiver([0, 1], [0, 1], [1, 1], [1, 0])
    ax.vlines([0.5, 1.5, 2.5], 0, 1)
    ax.contour(np.arange(16.0).reshape(4, 4), levels=[2, 6, 10])
    ax.set(title="kinds", xlabel="DN", ylabel="count (pixels)")
    text = describe_figure(figure)
    assert "1 histogram;" in text and "2 arrows" in text and "3 line segments" in text
    assert "contour lines at 3 levels" in text


def test_numbers_are_rounded_to_the_range_and_math_markup_is_read_as_words():
    figure, ax = plt.subplots()
    ax.plot([7_350_123.4, 7_410_987.6], [0.000123, 0.000456])
    ax.set(title=r"$\sigma_x$ of the fit", xlabel="northing (m)", ylabel="rate (1/s)")
    ax.set_yscale("log")
    text = describe_figure(figure)
    assert "“σ x of the fit”" in text and "$" not in text
    low, high = ax.get_xlim()
    assert f"x: northing (m) from {low:,.0f} to {high:,.0f};" in text
    assert ", log scale; 1 line." in text


def test_twin_axes_are_one_panel_and_long_descriptions_are_cut():
    figure, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    ax.set(title="two scales", xlabel="time (s)", ylabel="height (m)")
    twin = ax.twinx()
    twin.plot([0, 1], [5, 3])
    twin.set_ylabel("speed (m/s)")
    text = describe_figure(figure)
    assert "Panel" not in text and "; y on the right: speed (m/s) from " in text
    assert text.count("x: time (s)") == 1

    figure, ax = plt.subplots()
    for number in range(40):
        ax.plot([0, 1], [number, number], label=f"a rather long legend entry number {number}")
    ax.legend()
    ax.set(title="many lines " * 20, xlabel="x (m)", ylabel="y (m)")
    text = describe_figure(figure)
    assert len(text) <= MAX_LENGTH and "and 32 more" in text
    assert len(describe_figure(figure, max_length=100)) <= 100
    with pytest.raises(ValueError, match="max_length"):
        describe_figure(figure, max_length=10)
    with pytest.raises(ValueError, match="matplotlib figure"):
        describe_figure("a figure")


def test_the_description_speaks_portuguese_with_a_decimal_comma():
    _i18n.set_language("pt_BR")
    text = describe_figure(one_panel())
    assert text == ("Figura “Pixels grow off nadir”: x: scan angle (degrees) de 0 a 60; "
                    "y: pixel size (km) de 0,8 a 4,2; 2 linhas; 2 pontos; "
                    "legenda: “along track”, “across track”.")
    text = describe_figure(three_panels())
    assert text.startswith("Figura “The scene and its GCPs”, com 3 painéis. Painel 1, “scene”:")
    assert "uma imagem de 300×200 pixels; barra de cores “DN (0–255)” de 0 a 255." in text
    assert "3 categorias" in text and "3 barras" in text


def test_the_audit_writes_the_description_into_every_png(monkeypatch):
    from matplotlib.backend_bases import FigureCanvasBase

    import figure_audit

    monkeypatch.setattr(FigureCanvasBase, "print_figure", FigureCanvasBase.print_figure)
    monkeypatch.setattr(figure_audit, "FIGURE_PROBLEMS", [])
    figure_audit.audit_rendered_figures()
    figure = one_panel()
    png = io.BytesIO()
    figure.savefig(png, format="png", dpi=20, pil_kwargs={"compress_level": 1})
    with Image.open(png) as image:
        assert image.text["Description"] == describe_figure(figure)
    svg = io.StringIO()
    figure.savefig(svg, format="svg")                   # only PNGs carry one
    assert "Pixels grow off nadir" in svg.getvalue()
    assert figure_audit.FIGURE_PROBLEMS == []


def test_the_book_gives_each_image_its_png_description(tmp_path, monkeypatch):
    import figure_alt
    from docutils import nodes
    from docutils.frontend import get_default_settings
    from docutils.utils import new_document
    from PIL.PngImagePlugin import PngInfo

    figure = one_panel()
    info = PngInfo()
    info.add_text("Description", describe_figure(figure))
    Image.new("L", (2, 2)).save(tmp_path / "described.png", pnginfo=info)
    Image.new("L", (2, 2)).save(tmp_path / "mute.png")

    class Environment:                   # the two things of Sphinx's environment it reads
        srcdir, docname = str(tmp_path), "page"

        def relfn2path(self, filename, docname):
            return filename, str(tmp_path / filename.lstrip("/"))

    document = new_document("page", get_default_settings())
    document.settings.env = Environment()
    images = [nodes.image(uri="described.png", candidates={"*": "described.png"}),
              nodes.image(uri="/mute.png"), nodes.image(uri="mute.png", alt="given by the author")]
    for image in images:
        document += image
    warnings = []
    monkeypatch.setattr(figure_alt.logger, "warning",
                        lambda message, **kwargs: warnings.append(message))
    figure_alt.FigureAltText(document).run()
    assert images[0]["alt"] == describe_figure(figure)
    assert "alt" not in images[1] and images[2]["alt"] == "given by the author"
    assert len(warnings) == 1 and "'page'" in warnings[0] and "mute.png" in warnings[0]


def tiny_animation():
    from matplotlib.animation import FuncAnimation

    figure, ax = plt.subplots(figsize=(2, 2), dpi=30)
    line, = ax.plot([], [])
    ax.set(xlabel="x (m)", ylabel="y (m)", xlim=(0, 4), ylim=(0, 4))

    def draw(frame):
        line.set_data([0, frame], [0, frame])
        ax.set_title(f"frame {frame}")

    return FuncAnimation(figure, draw, frames=4)


def test_the_animation_player_describes_its_first_frame_and_names_its_controls():
    player = animation_html(tiny_animation()).data
    (alt,) = re.findall(r'<img id="_anim_img\w+" alt="([^"]*)"', player)
    assert alt.startswith("Animation of 4 frames; the first: Figure “frame 0”: x: x (m) from 0 "
                          "to 4;")
    assert re.search(r'<input id="_anim_slider\w+" aria-label="frame" type="range"', player)
    buttons = re.findall(r'<button title="([^"]*)" aria-label="([^"]*)"', player)
    assert len(buttons) == 9 and all(title == label for title, label in buttons)
    assert ("Play", "Play") in buttons and 'title="Repetition mode"' in player
    assert "font-awesome" not in player


def test_the_animation_player_speaks_portuguese():
    _i18n.set_language("pt_BR")
    player = animation_html(tiny_animation()).data
    assert 'alt="Animação de 4 quadros; o primeiro: Figura “frame 0”' in player
    assert 'aria-label="quadro"' in player
    assert 'title="Reproduzir" aria-label="Reproduzir"' in player
    assert 'title="Play"' not in player and ">Uma vez</label>" in player
