"""Nothing English on a Portuguese page but code: the built Portuguese book, read as a Brazilian
student reads it.

Every page of ``_build/pt_BR/_build/html``: its text (paragraphs, titles, table cells, the
theme's labels), the alternative text of its figures, the names of its buttons and the labels of
its widgets hold no English sentence. Left out on purpose: code, printed output, maths, the
API's docstrings (English like the code, marked ``lang="en"``), the values inside a notebook's
printed tables (data, such as a GCP's recorded description; their headers are checked), and the
titles of works published in English (in italics, in the bibliography and in the prose). The
glued numbers are written the Brazilian way (``book/_ext/glue_numbers.py``). The books must have
been built (the README's first command); without them these tests are skipped, unless
``RSGEO_REQUIRE_BROWSER=1`` (CI), when they fail.
"""

import collections
import json
import os
import re

import pytest
from glue_numbers import brazilian_number
from test_i18n import ENGLISH_WORDS, glossary_english_terms

from notebook_runner import ROOT

ENGLISH_BUILD = ROOT / "_build" / "html"
PORTUGUESE_BUILD = ROOT / "_build" / "pt_BR" / "_build" / "html"
PAGES = sorted(str(path.relative_to(ENGLISH_BUILD)) for folder in ("book", "exercises")
               for path in (ENGLISH_BUILD / folder).glob("*.html"))

# What a reader does not read as the page's language: code, maths, printed output, docstrings,
# and titles of works published in English (in italics, as a title is written, or as the text of
# a link to the work)
UNREAD = ("script, style, code, pre, kbd, .math, mjx-container, [lang='en'], .rsgeo-docstring, "
          "em, cite, a.reference.external, "
          "dl.py, table.autosummary, .citation, div.highlight, .output.stream, "
          ".output.text_plain, .cell_output td, .pasted-text")
BLOCKS = ("p, li, td, th, h1, h2, h3, h4, h5, figcaption, caption, dt, dd, summary, button, "
          "label, .admonition-title, title, .caption-text")
ATTRIBUTES = ("alt", "aria-label", "title", "placeholder")
# English names a Portuguese text quotes as they are: institutions, standards, journals
ENGLISH_NAMES = ("American Society for Photogrammetry and Remote Sensing",
                 "National Standard for Spatial Data Accuracy",
                 "IEEE Transactions on Geoscience and Remote Sensing",
                 "IEEE Geoscience and Remote Sensing Letters")
# a title quoted in a Portuguese sentence (“Multispectral misregistration of …”)
QUOTED = re.compile(r"“[^”]*”")


def _missing():
    for folder in (ENGLISH_BUILD, PORTUGUESE_BUILD):
        if not (folder / "book" / "intro.html").exists():
            return f"{folder.relative_to(ROOT)} is not built (the README's first command)"
    return None


built = pytest.mark.skipif(_missing() is not None
                           and os.environ.get("RSGEO_REQUIRE_BROWSER") != "1",
                           reason=str(_missing()))


def english_words(text):
    """The English function words (test_i18n's ENGLISH_WORDS, whole words, any accent kept in
    the word) in ``text``: two different ones make it an English sentence or phrase ("FA of the
    truth", "compared with the grid"); one alone may be a name or a quoted term. Quoted titles
    and English names are left out."""
    for name in ENGLISH_NAMES:
        text = text.replace(name, " ")
    text = QUOTED.sub(" ", text)
    return {word for word in re.findall(r"[^\W\d_]+", text.lower()) if word in ENGLISH_WORDS}


def _soup(path):
    from bs4 import BeautifulSoup

    return BeautifulSoup(path.read_text(encoding="utf-8"), "html.parser")


def reader_texts(path):
    """What a reader of the page reads or hears, as a list of texts: its text blocks (not code,
    maths, output or docstrings) and its images', buttons' and fields' names."""
    soup = _soup(path)
    # a citation's tooltip is its bibliography entry (checked by test_sources_...)
    named = [element for element in soup.select(",".join(f"[{a}]" for a in ATTRIBUTES))
             if not element.find_parent(attrs={"lang": "en"})
             and not element.find_parent(class_="bibtex-citation")]
    texts = [element[attribute] for element in named for attribute in ATTRIBUTES
             if element.get(attribute)]
    for unread in soup.select(UNREAD):
        unread.decompose()
    for block in soup.select(BLOCKS):
        if not block.find(["p", "li", "table", "ul", "ol"]):
            texts.append(" ".join(block.get_text(" ").split()))
    return [text for text in texts if text]


def english_texts(page):
    allowed = glossary_english_terms() if page == "book/glossary.html" else set()
    return sorted({text[:100] for text in reader_texts(PORTUGUESE_BUILD / page)
                   if len(english_words(text)) >= 2 and text not in allowed})


def test_english_words_find_english_and_not_portuguese():
    assert english_words("FA of the truth") == {"of", "the"}
    assert english_words("compared with the grid") == {"with", "the"}
    assert len(english_words("até a borda da faixa, o erro é de 3 px em relação ao mapa")) < 2
    assert len(english_words("O vizinho mais próximo apenas copia valores existentes")) < 2
    assert not english_words("o artigo “Analysis of the misregistration” da American Society "
                             "for Photogrammetry and Remote Sensing")


@built
@pytest.mark.parametrize("page", PAGES)
def test_no_english_sentence_on_a_portuguese_page(page):
    english = english_texts(page)
    assert not english, f"{page}: {len(english)} English texts, e.g. {english[:4]}"


def _widget_labels(path):
    labels = []
    for state in _soup(path).select("script[type='application/vnd.jupyter.widget-state+json']"):
        for model in json.loads(state.string)["state"].values():
            description = model.get("state", {}).get("description")
            if description and re.search(r"[^\W\d_]", description):
                labels.append(description)
    return labels


def _kept_on_purpose():
    """rsgeo's messages its catalogue translates as themselves ("latitude °" is Portuguese too)."""
    from babel.messages.pofile import read_po

    po = ROOT / "rsgeo" / "locale" / "pt_BR" / "LC_MESSAGES" / "rsgeo.po"
    with po.open("rb") as handle:
        return {message.id for message in read_po(handle) if message.id == message.string}


@built
def test_widget_labels_are_portuguese():
    pages = [page for page in PAGES if _widget_labels(ENGLISH_BUILD / page)]
    assert len(pages) >= 3, pages
    kept = _kept_on_purpose()
    for page in pages:
        english = set(_widget_labels(ENGLISH_BUILD / page)) - kept
        left = [label for label in _widget_labels(PORTUGUESE_BUILD / page)
                if label in english and len(re.findall(r"[^\W\d_]{3,}", label))]
        assert not left, f"{page}: widget labels left in English: {left}"


def _glued(path):
    return [span.get_text() for span in _soup(path).select("span.pasted-text")]


@built
def test_glued_numbers_are_written_the_brazilian_way():
    # the same executions' numbers in both books, with a decimal comma in Portuguese
    differing = collections.Counter()
    for page in PAGES:
        english = sorted(brazilian_number(text) for text in _glued(ENGLISH_BUILD / page))
        portuguese = sorted(_glued(PORTUGUESE_BUILD / page))
        assert len(english) == len(portuguese), page
        differing[page] = sum((collections.Counter(english) - collections.Counter(portuguese))
                              .values())
    assert sum(differing.values()) == 0, {page: n for page, n in differing.items() if n}


@built
def test_sources_are_cited_the_brazilian_way():
    intro = (PORTUGUESE_BUILD / "book" / "intro.html").read_text(encoding="utf-8")
    bibliography = (PORTUGUESE_BUILD / "book" / "bibliography.html").read_text(encoding="utf-8")
    assert "Meneses e Almeida" in intro and "Meneses and Almeida" not in intro
    for english in ("n.d.", "Lecture slides", "Paper in Portuguese", "seed document"):
        assert english not in intro + bibliography, english
    assert "Pré-processamento: correções geométricas" in bibliography
