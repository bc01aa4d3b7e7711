"""rsgeo_course.figure_language: the Portuguese book's figures and tables, their code left English.

A figure with literal and f-string texts, a legend, a colour bar, text and annotation artists is
Portuguese after :func:`translate_figure` under pt_BR (tick labels with a decimal comma, drawn)
and unchanged in English; a DataFrame's labels likewise; the figures' catalogue holds a
translation of every text ``locales/update.py --figures`` extracts from the notebooks, and is
compiled.
"""

import gettext
import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

from matplotlib.figure import Figure  # noqa: E402

from rsgeo import language as _i18n
from rsgeo_course import figure_language  # noqa: E402
from rsgeo_course.figure_language import translate_figure, translate_table, translate_text  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "locales"))
import update  # noqa: E402  (locales/update.py: the extraction)

FIGURES_PO = ROOT / "rsgeo_course" / "locale" / "pt_BR" / "LC_MESSAGES" / "rsgeo_figures.po"


@pytest.fixture
def language(monkeypatch):
    """Set the language for one test (RSGEO_LANG, as the Portuguese notebooks do)."""
    monkeypatch.setattr(_i18n, "_chosen", None)

    def choose(name):
        monkeypatch.setenv("RSGEO_LANG", name)

    return choose


def _figure(rms=0.514, degree=2):
    """A figure as a chapter draws it: literal and f-string texts everywhere."""
    figure = Figure(figsize=(9, 4))
    ax, bars = figure.subplots(1, 2)
    image = ax.imshow([[0.0, 1.5], [2.5, 3.0]])
    figure.colorbar(image, ax=ax, label="vegetation (DN)")
    ax.plot([0, 1], [0, 0.5], label="fitting RMS")
    ax.plot([0, 1], [0.5, 0], label=f"degree {degree}")
    ax.legend()
    ax.set(title=f"{7} GCPs: worst corner {1.25:.2f} px, scene RMS {rms:.2f} px",
           xlabel="column (pixels)", ylabel="row (pixels)")
    figure.suptitle("Overlap of successive scans")
    ax.text(0.1, 0.1, "check points")
    ax.annotate(f"scan {3}", (0.5, 0.5))
    arrows = ax.quiver([0], [0], [1], [1])
    ax.quiverkey(arrows, 0.1, 0.9, 1, "truth")
    bars.bar(["nearest", "cubic"], [1, 2])                 # word tick labels
    bars.set(title="interpolation kernels", ylabel="weight (–)")
    return figure, ax


def _texts(figure):
    """Every text of the figure: its Text artists, tick labels and quiver keys' labels."""
    from matplotlib.quiver import QuiverKey
    from matplotlib.text import Text

    texts = [*figure.findobj(Text), *(key.text for key in figure.findobj(QuiverKey))]
    for ax in figure.axes:
        texts += ax.get_xticklabels() + ax.get_yticklabels()
    return [text.get_text() for text in texts if text.get_text()]


def test_a_figure_is_portuguese_under_pt_br(language):
    language("pt_BR")
    figure, ax = _figure()
    translate_figure(figure)
    figure.canvas.draw()                      # the tick labels: formatted when drawn
    assert figure.get_suptitle() == "Sobreposição de varreduras sucessivas"
    assert ax.get_title() == ("7 pontos de controle: pior canto 1,25 px, REQM da cena 0,51 px")
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("coluna (pixels)", "linha (pixels)")
    assert [text.get_text() for text in ax.get_legend().get_texts()] == ["REQM de ajuste",
                                                                         "grau 2"]
    colour_bar = figure.axes[2]
    assert colour_bar.get_ylabel() == "vegetação (DN)"
    texts = _texts(figure)
    assert {"pontos de verificação", "varredura 3", "verdade", "vizinho mais próximo",
            "cúbica", "núcleos de interpolação"} <= set(texts)
    ticks = [tick.get_text() for tick in ax.get_yticklabels() + colour_bar.get_yticklabels()]
    assert "0,5" in ticks and "1,5" in ticks and not any("." in tick for tick in ticks)
    # English words left: none of the figure's texts is one of the English ones
    english = set(_texts(_figure()[0]))
    assert not (set(texts) & english - {"DN"}), set(texts) & english


def test_translating_again_changes_nothing(language):
    language("pt_BR")
    figure, ax = _figure()
    translate_figure(figure)
    before = _texts(figure)
    translate_figure(figure)
    assert _texts(figure) == before
    ax.set_title(f"{7} GCPs: worst corner {2.5:.2f} px, scene RMS {0.75:.2f} px")  # a widget
    translate_figure(figure)
    assert ax.get_title() == "7 pontos de controle: pior canto 2,50 px, REQM da cena 0,75 px"


def test_a_figure_is_unchanged_in_english(language):
    language("en")
    figure, ax = _figure()
    before = _texts(figure)
    translate_figure(figure)
    figure.canvas.draw()
    assert _texts(figure)[:len(before)] == before
    assert ax.get_title() == "7 GCPs: worst corner 1.25 px, scene RMS 0.51 px"
    assert "0.50" in [tick.get_text() for tick in ax.get_yticklabels()]


def test_rendered_figures_follow_the_language_of_the_moment(language, tmp_path):
    figure_language.translate_rendered_figures()
    figure_language.translate_rendered_figures()         # idempotent: one patch
    language("en")
    figure, ax = _figure()
    figure.savefig(tmp_path / "en.png")
    assert ax.get_xlabel() == "column (pixels)"
    language("pt_BR")
    figure.savefig(tmp_path / "pt.png")
    assert ax.get_xlabel() == "coluna (pixels)"


def test_template_fields_numbers_and_unknown_texts():
    assert translate_text("descending pass", "pt_BR") == "passagem descendente"   # field known
    assert translate_text("roll, curved Earth", "pt_BR") == "rolamento, Terra curva"
    assert translate_text("Relief displacement on a 1:25,000 photo (H = 3000 m)", "pt_BR") == \
        "Deslocamento devido ao relevo numa foto 1:25.000 (H = 3000 m)"
    assert translate_text("a text no catalogue has, 0.25 m", "pt_BR") == \
        "a text no catalogue has, 0,25 m"
    assert translate_text("B3.tif, 1.5e-03, $0.5$", "pt_BR") == "B3.tif, 1,5e-03, $0{,}5$"
    assert translate_text("descending pass", "en") == "descending pass"
    # rsgeo's own figures are written in the language already: their commas are decimal
    assert translate_text("Y = 0,384 X + 86,12", "pt_BR") == "Y = 0,384 X + 86,12"
    assert translate_text("fitted: Y = 1.234 X + 5,000.5", "pt_BR") == \
        "ajustada: Y = 1,234 X + 5.000,5"              # an f-string's fields are Python's


def test_a_table_is_portuguese_under_pt_br(language):
    import pandas as pd

    table = pd.DataFrame({"fitting RMS (px)": [0.514], "leave-one-out RMS (px)": [0.75],
                          "compared with the grid": ["nothing"], "meets at 1:25,000": [False]},
                         index=pd.Index(["raw"], name="stage"))
    language("pt_BR")
    translated = translate_table(table)
    assert list(translated.columns) == ["REQM de ajuste (px)", "REQM deixando um de fora (px)",
                                        "comparado com a grade", "atende em 1:25.000"]
    assert list(translated.index) == ["bruto"] and translated.index.name == "etapa"
    assert translated.iloc[0, 2:].tolist() == ["nada", "não"]        # words in the cells
    tasks = translate_table(pd.DataFrame({"task": ["1.2 Is ±10.3° still irrelevant?"]}))
    assert tasks.iloc[0, 0] == "1.2 Is ±10.3° still irrelevant?"    # data the catalogue lacks
    html = figure_language._frame_html(table)
    assert "REQM de ajuste (px)" in html and "0,514" in html and "fitting" not in html
    assert list(table.columns)[0] == "fitting RMS (px)"          # the notebook's table is kept
    by_level = pd.DataFrame([[1.0, 2.0]], columns=pd.MultiIndex.from_tuples(
        [("gain", "mean"), ("gain", "std")]))
    assert list(translate_table(by_level).columns) == [("ganho", "média"),
                                                       ("ganho", "desvio-padrão")]
    styled = figure_language._styler_html(table.style.format("{:.3f}", subset=[
        "fitting RMS (px)"]))
    assert "REQM de ajuste (px)" in styled and ">0,514<" in styled and "fitting" not in styled
    language("en")
    assert translate_table(table) is table
    assert figure_language._frame_html(table) == table._repr_html_()


def test_the_catalogue_translates_every_extracted_text():
    from babel.messages.pofile import read_po

    with open(FIGURES_PO, "rb") as handle:
        catalogue = read_po(handle)
    translated = {message.id: message.string for message in catalogue
                  if message.id and message.string and not message.fuzzy}
    missing = sorted(set(update.figure_messages()) - set(translated))
    assert not missing, (f"{len(missing)} figure texts without a translation: run "
                         f"python locales/update.py --figures and translate {missing[:10]}")
    for message, translation in translated.items():      # a template keeps its fields
        assert message.count("{}") == translation.count("{}"), (message, translation)
    with open(FIGURES_PO.with_suffix(".mo"), "rb") as handle:
        compiled = gettext.GNUTranslations(handle)._catalog
    assert {key: value for key, value in compiled.items() if key} == translated, \
        "rsgeo_figures.mo is stale: python locales/update.py --figures compiles it"


def test_the_extraction_finds_chapter_1s_labels(tmp_path):
    found = update.figure_messages([ROOT / "book" / "01_systematic_distortions.ipynb"])
    assert "Earth-rotation skew of a 185 km Landsat frame" in found       # set(title=...)
    assert "scan {}" in found                                             # label=f"scan {...}"
    assert {"ascending", "descending"} <= set(found)     # an f-string's field, from its loop
    assert found["latitude (degrees)"][0] == "book/01_systematic_distortions.ipynb"
    assert not {"tab:blue", "gray", "{}"} & set(found)                   # colours, no words
