"""The Portuguese edition: catalogues complete and current, the built book Portuguese, rsgeo in
Portuguese when asked.

The book's translations live in ``locales/pt_BR/LC_MESSAGES/{book,exercises}/*.po`` (one per
page, made by ``python locales/update.py`` from the English sources); rsgeo's in
``rsgeo/locale/pt_BR/LC_MESSAGES/rsgeo.po`` (+ the compiled ``rsgeo.mo`` it ships). The tests on
the built books read ``_build/html`` and ``_build/pt_BR/_build/html`` (the README's first
command builds both); without them they are skipped, unless ``RSGEO_REQUIRE_BROWSER=1`` (CI),
when they fail.
"""

import gettext
import importlib.util
import json
import os
import re
import subprocess
import sys

import pytest
import yaml
from babel.messages.pofile import read_po

from notebook_runner import ROOT

sys.path.insert(0, str(ROOT / "book" / "_ext"))
import i18n_book  # noqa: E402  (the book's extension: download translation, language switch)

LANGUAGE = "pt_BR"
CATALOGUES = ROOT / "locales" / LANGUAGE / "LC_MESSAGES"
RSGEO_PO = ROOT / "rsgeo" / "locale" / LANGUAGE / "LC_MESSAGES" / "rsgeo.po"
COURSE_PO = ROOT / "rsgeo_course" / "locale" / LANGUAGE / "LC_MESSAGES" / "rsgeo_course.po"
MESSAGE_PO = {"rsgeo": RSGEO_PO, "rsgeo_course": COURSE_PO}
ENGLISH_BUILD = ROOT / "_build" / "html"
PORTUGUESE_BUILD = ROOT / "_build" / "pt_BR" / "_build" / "html"
BOOK_PO = sorted(CATALOGUES.glob("*/*.po"))
THEME_PO = CATALOGUES / "sphinx.po"          # Sphinx's and the themes' labels, kept by hand
ALL_PO = [*BOOK_PO, THEME_PO, RSGEO_PO, COURSE_PO]

# English words that are no Portuguese words: a text holding one (outside code, maths and
# links) has English left to translate. A catalogue entry may keep its English only without them
# (a name, a term of the glossary's English column, a formula).
ENGLISH_WORDS = frozenset(
    "the of and is are was were be been with which that this these those to for from by on it "
    "its an at into than then when where what how why we you your our each every has have not "
    "there their they can will would should must may after before between without only also "
    "does".split())


def _spec(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


update = _spec(ROOT / "locales" / "update.py", "locales_update")


def entries(po):
    with open(po, "rb") as handle:
        return [message for message in read_po(handle) if message.id]


def prose(text):
    """``text`` without code, maths, roles, link targets and URLs: the words a reader reads."""
    text = re.sub(r"\{[\w:-]+\}`[^`]*`", " ", text)            # MyST roles: {cite}`key`
    text = re.sub(r"`[^`]*`", " ", text)                        # inline code
    text = re.sub(r"\$\$.*?\$\$|\$[^$]*\$", " ", text, flags=re.S)  # maths
    text = re.sub(r"\]\([^)]*\)", "]", text)                    # link targets
    text = re.sub(r"\b\w+(?:\.\w+)+", " ", text)                  # dotted names: rsgeo.resample
    return re.sub(r"https?://\S+", " ", text)


def english_words(text):
    return sorted({word for word in re.findall(r"[a-z]+", prose(text).lower())
                   if word in ENGLISH_WORDS})


def glossary_english_terms():
    """The glossary's English column (book/glossary.md's first table column): English on purpose
    in both books, so that a student finds the term the English literature uses."""
    rows = re.findall(r"^\|([^|\n]+)\|", (ROOT / "book" / "glossary.md").read_text(), flags=re.M)
    return {" ".join(cell.split()) for cell in rows} - {"English", "---"}


def relative(path):
    return str(path.relative_to(ROOT))


# -- The catalogues ------------------------------------------------------------------------------

def test_every_page_has_a_catalogue():
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    pages = [toc["root"]] + [chapter["file"] for part in toc["parts"]
                             for chapter in part["chapters"]]
    missing = [page for page in pages if not (CATALOGUES / (page + ".po")).exists()]
    assert not missing, f"pages without a catalogue (run python locales/update.py): {missing}"


@pytest.mark.parametrize("po", ALL_PO, ids=relative)
def test_catalogue_is_completely_translated(po):
    # Fails while anything is untranslated or fuzzy: what `python locales/update.py --stat` lists.
    messages = entries(po)
    fuzzy = [message.id for message in messages if message.fuzzy]
    empty = [message.id for message in messages if not message.string]
    assert not fuzzy and not empty, (
        f"{relative(po)}: {len(empty)} of {len(messages)} entries untranslated, "
        f"{len(fuzzy)} fuzzy (translate them; fuzzy ones after checking the suggestion). "
        f"First: {[str(text)[:70] for text in (empty + fuzzy)[:3]]}")


@pytest.mark.parametrize("po", ALL_PO, ids=relative)
def test_an_entry_kept_in_english_has_no_words_to_translate(po):
    terms = glossary_english_terms() if po.name == "glossary.po" else set()
    kept = [(message.id, english_words(message.id)) for message in entries(po)
            if message.string == message.id and english_words(message.id)
            and message.id not in terms]
    assert not kept, f"{relative(po)}: entries whose translation is the English text: {kept[:3]}"


@pytest.mark.parametrize("po", ALL_PO, ids=relative)
def test_translations_keep_the_code_maths_and_references(po):
    # inline code, roles ({cite}`...`, {py:class}`...`), maths and format fields are not translated
    def kept(text):
        # a role's link text may be translated, its target not: {ref}`text <target>` -> target
        found = re.findall(r"\{[\w:-]+\}`[^`]*`|(?<!\})`[^`]*`|"
                           r"\$[^$]+\$|\{\w*(?:![rsa])?(?::[^}]*)?\}", text)
        # a glue role names its notebook in a translation ({glue:text}`04_resampling.ipynb::rms`):
        # myst-nb resolves a translated paragraph's glue only in that form
        found = [re.sub(r"^(\{glue(?::\w+)?\}`)[\w.-]+\.ipynb::", r"\1", item) for item in found]
        return sorted(re.sub(r"`[^`<]*<([^>]*)>`$", r"<\1>", item) for item in found)

    changed = [message.id[:60] for message in entries(po)
               if message.string and kept(message.id) != kept(portuguese_maths(message.string))]
    assert not changed, f"{relative(po)}: code, maths or a reference changed in {changed[:3]}"


def portuguese_maths(text):
    """A translation's maths written the Brazilian way (``0{,}885``, ``\\operatorname{sen}``,
    TERMS.md) compares equal to the English maths (``0.885``, ``\\sin``)."""
    return (text.replace("{,}", ".").replace(r"\operatorname{sen}", r"\sin")
            .replace(r"\operatorname{tg}", r"\tan"))


# The glossary's terms (book/glossary.md) are the translation's terms: an English term in a
# paragraph comes back as its Portuguese term (a stem: plural and gender vary).
GLOSSARY_TERMS = [
    (r"georeferenc", r"georreferenc"), (r"resampl", r"reamostr"),
    (r"check[- ]points?", r"pontos? de verificação"), (r"control points?", r"pontos? de controle"),
    (r"nearest[- ]neighbou?r", r"vizinhos? mais próximos?"),
    (r"cubic convolution", r"convolução cúbica"),
    (r"relational mesh", r"malhas? relaciona"), (r"\bfitness\b", r"aptidão"),
    (r"\bresiduals?\b", r"resíduo"), (r"genetic algorithm", r"algoritmos? genétic"),
    (r"output grid", r"grades? de saída"),
    (r"tie points?", r"pontos? de ligação|pontos? homólogos?"),
    (r"orthorectif", r"ortorretific"), (r"relief displacement", r"deslocamento devido ao relevo"),
    (r"\bsegments?\b", r"segmento"), (r"\bmosaic", r"mosaic"), (r"\bregistration\b", r"registro"),
    (r"\bgain\b(?!·)", r"ganho"),
]


@pytest.mark.parametrize("po", [*BOOK_PO, RSGEO_PO, COURSE_PO], ids=relative)
def test_glossary_terms_are_the_translations_terms(po):
    def text(message, translation):
        # a title quoted in both (a paper's, in italics) is not translated
        for title in re.findall(r"\*[^*]+\*", message):
            if title in translation:
                message = message.replace(title, " ")
        return prose(message)

    off = [(english, message.id[:60], message.string[:60]) for message in entries(po)
           if message.string and message.string != message.id
           for english, portuguese in GLOSSARY_TERMS
           if re.search(english, text(message.id, message.string), flags=re.I)
           and not re.search(portuguese, prose(message.string), flags=re.I)]
    assert not off, f"{relative(po)}: a glossary term translated otherwise: {off[:3]}"


@pytest.fixture(scope="module")
def templates(tmp_path_factory):
    """The message templates of the English book as it is now (a gettext build, ~30 s, in its own
    process: the book's extensions change the process they load in)."""
    folder = tmp_path_factory.mktemp("gettext") / "pot"
    run = subprocess.run([sys.executable, str(ROOT / "locales" / "update.py"), "--templates",
                          str(folder)], cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, (
        f"the gettext build failed:\n{run.stdout[-2000:]}{run.stderr[-2000:]}")
    return folder


def test_catalogues_match_the_current_english_text(templates):
    # An English edit without its translation fails here: regenerate with locales/update.py
    stale = {}
    for pot in sorted(templates.rglob("*.pot")):
        name = pot.relative_to(templates).with_suffix(".po")
        if name.parts[0] == "_static":
            continue
        po = CATALOGUES / name
        wanted = {message.id for message in entries(pot)}
        held = {message.id for message in entries(po)} if po.exists() else set()
        if po == THEME_PO:
            # kept by hand: the themes' labels besides the book's own templates' (the template)
            wanted |= held
        if wanted != held:
            stale[str(name)] = {
                "new English text": [text[:70] for text in sorted(wanted - held)][:3],
                "no longer in the book": [text[:70] for text in sorted(held - wanted)][:3]}
    assert not stale, ("catalogues out of date (python locales/update.py, then translate):\n"
                       + json.dumps(stale, indent=1, ensure_ascii=False))


def test_docstrings_stay_out_of_the_api_catalogue(templates):
    from rsgeo import transforms

    first_line = transforms.fit_polynomial.__doc__.strip().splitlines()[0]
    ids = {message.id for message in entries(templates / "book" / "api.pot")}
    assert "API reference" in ids                      # the page's own prose is there
    assert not any(first_line in text for text in ids), "a docstring reached the catalogue"
    assert not any(text.startswith(":py:obj:") for text in ids), "autosummary rows reached it"


def test_the_portuguese_config_is_the_english_one_with_the_language_set():
    english, portuguese = (yaml.safe_load((ROOT / name).read_text())
                           for name in ("_config.yml", "_config_pt.yml"))
    assert portuguese["sphinx"]["config"]["language"] == LANGUAGE
    assert portuguese["sphinx"]["config"]["locale_dirs"] == ["locales"]
    assert portuguese["sphinx"]["config"]["gettext_compact"] is False
    # one execution for both books: the Portuguese build reads the English build's cache
    assert portuguese["execute"]["cache"] == "_build/.jupyter_cache"
    assert english["execute"]["execute_notebooks"] == portuguese["execute"]["execute_notebooks"]
    assert (ROOT / "_config_pt.yml").read_text() == update.portuguese_config(
        (ROOT / "_config.yml").read_text()), \
        "_config.yml changed: remake _config_pt.yml with `python locales/update.py --config`"


# -- rsgeo in Portuguese -------------------------------------------------------------------------

@pytest.mark.parametrize("package", sorted(MESSAGE_PO))
def test_each_catalogue_holds_every_message_of_its_package(package):
    # _() / N_() anywhere in the package: the exercise checks' hints are N_() in their
    # declarations (the course's)
    found = set(update.messages_of(package))
    held = {message.id for message in entries(MESSAGE_PO[package])}
    assert found == held, (f"{MESSAGE_PO[package].name} out of date (python locales/update.py, "
                           f"then translate): new {sorted(found - held)[:3]}, gone "
                           f"{sorted(held - found)[:3]}")


def test_every_declared_hint_is_a_message_of_the_catalogue():
    from rsgeo_course import exercises

    found = set(update.course_messages())
    hints = {hint for name in exercises.declarations()
             for _kind, hint in exercises.recognised_mistakes(name)}
    assert len(hints) > 100 and hints <= found, sorted(hints - found)[:3]


@pytest.mark.parametrize("po", [RSGEO_PO, COURSE_PO], ids=relative)
def test_each_mo_is_the_compiled_po(po):
    with open(po.with_suffix(".mo"), "rb") as handle:
        compiled = {key: value for key, value in gettext.GNUTranslations(handle)._catalog.items()
                    if key}
    source = {message.id: message.string for message in entries(po)
              if message.string and not message.fuzzy}
    assert compiled == source, f"{po.with_suffix('.mo').name} is stale: python locales/update.py"


@pytest.fixture
def portuguese(monkeypatch):
    from rsgeo import language as _i18n

    monkeypatch.setenv("RSGEO_LANG", "pt_BR")
    monkeypatch.setattr(_i18n, "_chosen", None)
    return _i18n


def test_verdicts_speak_the_chosen_language(portuguese, monkeypatch):
    from rsgeo_course.exercises import Verdict

    wrong = Verdict(False, "`x` is too large.", "Square, average, root.")
    assert repr(wrong) == "Ainda não: `x` is too large.\nDica: Square, average, root."
    assert repr(Verdict(True, "`x` = 1.")).startswith("Correto: ")
    assert "<strong>Ainda não:</strong>" in wrong._repr_html_()
    monkeypatch.setenv("RSGEO_LANG", "en")
    assert repr(wrong).startswith("Not yet: ")
    assert portuguese.set_language("pt-BR") == "pt_BR"          # an explicit choice wins
    assert repr(wrong).startswith("Ainda não: ")
    portuguese.set_language(None)
    from rsgeo_course import _i18n as course

    assert [course.translate(label, "pt_BR") for label in course.VERDICT_LABELS] == [
        "Correto", "Ainda não", "não tentado", "erro", "tempo esgotado"]


def test_check_hints_and_messages_speak_the_chosen_language(portuguese, monkeypatch):
    from rsgeo_course.exercises import ExerciseNotSolved, check_skew

    metres = check_skew(12.6 * 1000, 0.0, 185.0, 705.0, 98.2)          # a known mistake's hint
    assert repr(metres) == ("Ainda não: `skew_km` está mais de 100 vezes maior do que deveria.\n"
                            "Dica: Isso parece estar em metros; a verificação quer quilômetros.")
    assert "grande demais, com erro de 10 a 50 %" in repr(
        check_skew(16.4, 0.0, 185.0, 705.0, 98.2))
    with pytest.raises(ExerciseNotSolved, match="esta tarefa é sua"):
        check_skew(..., 0.0, 185.0, 705.0, 98.2)
    monkeypatch.setenv("RSGEO_LANG", "en")                   # a check run in English answers in it
    assert repr(check_skew(12.6 * 1000, 0.0, 185.0, 705.0, 98.2)) == (
        "Not yet: `skew_km` is more than 100 times too large.\n"
        "Hint: That looks like metres; the check wants kilometres.")


def test_common_value_errors_speak_the_chosen_language(portuguese, monkeypatch):
    import numpy as np

    from rsgeo.validation import as_image, as_points, as_shape

    with pytest.raises(ValueError, match=r"gcps deve ser um array \(n, 2\) de pares"):
        as_points(np.zeros((3, 3)), "gcps")
    with pytest.raises(ValueError, match="deve ser 2-D"):
        as_image(np.zeros(4))
    with pytest.raises(ValueError, match="dois inteiros positivos"):
        as_shape(351)
    monkeypatch.setenv("RSGEO_LANG", "en")
    with pytest.raises(ValueError, match=r"must be an \(n, 2\) array"):
        as_points(np.zeros((3, 3)), "gcps")


def test_figure_labels_speak_the_chosen_language_and_pass_the_audit(portuguese):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from affine import Affine

    from rsgeo.plot import draw_neighbour_weights, show_image

    from figure_audit import figure_problems

    figure, axes = plt.subplots(1, 3)
    show_image(axes[0], np.zeros((4, 6)), title="pixels")
    show_image(axes[1], np.zeros((4, 6)), transform=Affine(20, 0, 5e5, 0, -20, 7e6), title="map")
    draw_neighbour_weights(axes[2], (3.3, 2.6), "bilinear")
    assert (axes[0].get_xlabel(), axes[0].get_ylabel()) == ("coluna (pixels)", "linha (pixels)")
    assert axes[1].get_xlabel() == "coordenada leste (km)"
    assert axes[2].get_title().startswith("bilinear: posição (")
    assert figure_problems(figure) == []
    plt.close(figure)


@pytest.mark.parametrize("setting", ["fr", "klingon", ""])
def test_an_unknown_language_is_refused_or_falls_back_to_english(setting, monkeypatch):
    # set_language refuses a language rsgeo does not speak; the environment's RSGEO_LANG,
    # which a user may share with other programs, falls back to English with a warning
    from rsgeo import language as _i18n

    monkeypatch.setattr(_i18n, "_chosen", None)
    monkeypatch.setattr(_i18n, "_warned", set())        # it warns once per value and process
    if setting:
        with pytest.raises(ValueError, match="does not speak"):
            _i18n.set_language(setting)
        monkeypatch.setenv("RSGEO_LANG", setting)
        with pytest.warns(UserWarning, match="RSGEO_LANG"):
            assert _i18n.translate("Not a raster") == "Not a raster"
    else:                                                   # empty: the default, English
        monkeypatch.setenv("RSGEO_LANG", setting)
        assert _i18n.translate("Not a raster") == "Not a raster"
    with pytest.raises(TypeError, match="language name"):        # a wrong type
        _i18n.set_language(3)


# -- Notebooks to download in Portuguese ---------------------------------------------------------

@pytest.mark.parametrize(
    "po", [po for po in BOOK_PO
           if (ROOT / po.relative_to(CATALOGUES)).with_suffix(".ipynb").exists()],
    ids=relative)
def test_every_message_is_found_in_its_notebook(po):
    # the download's translation replaces each msgid in the Markdown cells: each must be found
    notebook = json.loads((ROOT / po.relative_to(CATALOGUES)).with_suffix(".ipynb").read_text())
    markdown = "\n\n".join("".join(cell["source"]) for cell in notebook["cells"]
                           if cell["cell_type"] == "markdown")
    lost = [message.id[:70] for message in entries(po)
            if not i18n_book._pattern(message.id).search(markdown)]
    assert not lost, f"messages of {relative(po)} not found in the notebook: {lost[:3]}"


def test_a_translated_notebook_reads_portuguese_and_sets_the_language():
    catalogue = {"Overview": "Visão geral",
                 "Time to learn: 50 minutes.": "Tempo de estudo: 50 minutos.",
                 "Concept": "Conceito"}
    notebook = i18n_book.translated_notebook(ROOT / "book" / "01_systematic_distortions.ipynb",
                                             catalogue, "pt_BR")
    markdown = "".join("".join(cell["source"]) for cell in notebook["cells"]
                       if cell["cell_type"] == "markdown")
    assert "## Visão geral" in markdown and "Tempo de estudo: 50 minutos." in markdown
    assert "Overview" not in markdown and "| Conceito" in markdown
    assert 'os.environ["RSGEO_LANG"] = "pt_BR"' in "".join(notebook["cells"][0]["source"])
    # a short message never rewrites the inside of a longer one already translated
    assert i18n_book.translate_markdown("Concept map. Concept",
                                        {"Concept map.": "Mapa.", "Concept": "Conceito"}) \
        == "Mapa. Conceito"


def test_a_translated_title_that_starts_like_a_list_stays_a_title():
    assert (i18n_book.escape_list_start("1. Distorções sistemáticas")
            == "1\\. Distorções sistemáticas")
    assert i18n_book.escape_list_start("- item") == "\\- item"
    for kept in ("2b. Sistemas", "1.5 m de erro", "*ênfase*", "Texto. 1. Outro"):
        assert i18n_book.escape_list_start(kept) == kept


def test_language_switch_links_are_relative():
    assert i18n_book.other_page_url("book/intro", "../pt_BR/_build/html") == \
        "../../pt_BR/_build/html/book/intro.html"
    assert i18n_book.other_page_url("index", "../../../html") == "../../../html/index.html"


# -- The built books -----------------------------------------------------------------------------

def _built():
    for folder in (ENGLISH_BUILD, PORTUGUESE_BUILD):
        if not (folder / "book" / "intro.html").exists():
            return (f"{relative(folder)} is not built "
                    "(the README's first command builds both books)")
    return None


built = pytest.mark.skipif(_built() is not None and os.environ.get("RSGEO_REQUIRE_BROWSER") != "1",
                           reason=str(_built()))
PAGES = sorted(str(path.relative_to(ENGLISH_BUILD)) for folder in ("book", "exercises")
               for path in (ENGLISH_BUILD / folder).glob("*.html"))


def paragraphs(path):
    """The reader's paragraphs, list items and headings of a built page: not code, outputs,
    docstrings (API page) or bibliography entries."""
    from bs4 import BeautifulSoup

    soup = BeautifulSoup(path.read_text(encoding="utf-8"), "html.parser")
    article = soup.find("article") or soup
    for unread in article.select("div.cell_output, div.output, pre, div.highlight, dl.py, "
                                 "table.autosummary, .citation, div.docutils.container, "
                                 ".rsgeo-docstring, .rsgeo-language-switch, script, style"):
        unread.decompose()
    texts = (" ".join(element.get_text(" ").split())
             for element in article.find_all(["p", "li", "h1", "h2", "h3", "td", "dt", "dd"]))
    return {text for text in texts if text}


@built
def test_every_page_is_built_in_portuguese_with_its_language_and_switch():
    assert _built() is None, _built()
    assert len(PAGES) >= 17
    for page in PAGES:
        english, portuguese = ENGLISH_BUILD / page, PORTUGUESE_BUILD / page
        assert portuguese.exists(), f"{page} missing from the Portuguese book"
        html = portuguese.read_text(encoding="utf-8")
        assert '<html lang="pt-BR"' in html, page
        depth = page.count("/")
        assert f'href="{"../" * depth}../../../html/{page}"' in html, (
            f"{page}: no switch to English")
        target = (portuguese.parent / ("../" * depth + "../../../html/" + page)).resolve()
        assert target == english.resolve() and target.exists()
        back = (english.parent / ("../" * depth + "../pt_BR/_build/html/" + page)).resolve()
        assert back == portuguese.resolve(), f"{page}: the English switch misses"
        assert f'href="{"../" * depth}../pt_BR/_build/html/{page}"' in english.read_text(
            encoding="utf-8"), f"{page}: no switch to Portuguese"


@built
def test_sphinx_exercise_labels_and_the_first_page_note_are_portuguese():
    exercise = (PORTUGUESE_BUILD / "exercises" / "ex01_distortions.html").read_text(
        encoding="utf-8")
    assert "Exercício" in exercise
    # the exercises ran again in Portuguese (i18n_execute_in_language): the checks answer in it
    assert "<strong>Correto:</strong>" in exercise and "<strong>Correct:" not in exercise
    english = (ENGLISH_BUILD / "exercises" / "ex01_distortions.html").read_text(encoding="utf-8")
    assert "<strong>Correct:</strong>" in english and "Correto" not in english
    assert "Mostrar o código da célula" in exercise and "Show code cell" not in exercise
    intro = (PORTUGUESE_BUILD / "book" / "intro.html").read_text(encoding="utf-8")
    assert "Voltar ao topo" in intro and "Back to top" not in intro        # the theme's labels
    assert intro.count("rsgeo-language-note") == 1 and "ponto decimal" in intro
    assert not any("rsgeo-language-note" in (PORTUGUESE_BUILD / page).read_text(encoding="utf-8")
                   for page in PAGES if page != "book/intro.html")


@built
def test_the_table_of_contents_parts_are_portuguese():
    captions = [part["caption"]
                for part in yaml.safe_load((ROOT / "_toc.yml").read_text())["parts"]]
    translations = {message.id: message.string
                    for message in entries(CATALOGUES / "book" / "intro.po")}
    html = (PORTUGUESE_BUILD / "book" / "04_resampling.html").read_text(encoding="utf-8")
    shown = re.findall(r'caption-text">([^<]*)<', html)
    assert shown == [translations.get(caption) or caption for caption in captions]
    assert not set(shown) & {caption for caption in captions
                             if translations.get(caption) != caption}


@built
@pytest.mark.parametrize("page", PAGES)
def test_no_english_paragraph_is_left_in_the_portuguese_page(page):
    shared = paragraphs(ENGLISH_BUILD / page) & paragraphs(PORTUGUESE_BUILD / page)
    allowed = glossary_english_terms() if page == "book/glossary.html" else set()
    english = sorted(text[:80] for text in shared - allowed if english_words(text))
    assert not english, f"{page}: {len(english)} English paragraphs left, e.g. {english[:3]}"


@built
def test_the_portuguese_download_is_a_portuguese_notebook():
    path = PORTUGUESE_BUILD / "_sources" / "book" / "04_resampling.ipynb"
    notebook = json.loads(path.read_text(encoding="utf-8"))
    markdown = " ".join(" ".join("".join(cell["source"]).split()) for cell in notebook["cells"]
                        if cell["cell_type"] == "markdown")
    translated = [message for message in entries(CATALOGUES / "book" / "04_resampling.po")
                  if message.string and len(message.id.split()) > 12]
    assert translated, "04_resampling.po has no translated paragraph yet"
    for message in translated[:5]:
        assert " ".join(message.string.split()) in markdown
        assert " ".join(message.id.split()) not in markdown
    assert "RSGEO_LANG" in "".join(notebook["cells"][0]["source"])
    english = json.loads((ENGLISH_BUILD / "_sources" / "book" / "04_resampling.ipynb").read_text())
    assert "RSGEO_LANG" not in json.dumps(english["cells"][0])
