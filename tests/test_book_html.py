"""The built HTML books, read without a browser: the API reference's signatures, what the
accessibility fixes write into every page (book/_templates, book/_ext/offline_book.py), the
pages' scripts (Font Awesome's icons, MathJax, the widgets' names) and the search ranking.

Both books are read where the README's first command builds them, ``_build/html`` and
``_build/pt_BR/_build/html`` (``RSGEO_BOOK_BUILD`` names another folder laid out the same way);
a book that is not built is skipped, unless ``RSGEO_REQUIRE_BROWSER=1`` (CI), when it fails. The
browser tests (tests/test_browser.py) check the same pages in Chromium with axe-core.
"""

import importlib
import inspect
import json
import os
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser

import pytest

from notebook_runner import ROOT

sys.path.insert(0, str(ROOT / "book" / "_ext"))
import offline_book  # noqa: E402  (the book's extension: the Font Awesome subset)

BUILD = ROOT / "_build"
if os.environ.get("RSGEO_BOOK_BUILD"):
    BUILD = type(ROOT)(os.environ["RSGEO_BOOK_BUILD"])
BOOKS = {"en": BUILD / "html", "pt_BR": BUILD / "pt_BR" / "_build" / "html"}
WIDGET_NAMES_PT = {"data-play": "Reproduzir", "data-pause": "Pausar", "data-stop": "Parar",
                   "data-repeat": "Repetir"}


def book(language):
    """The built book's folder, or a skip (a failure in CI) when it is not built."""
    folder = BOOKS[language]
    if not (folder / "book" / "api.html").exists():
        message = f"{folder} is not built (the README's first command builds both books)"
        if os.environ.get("RSGEO_REQUIRE_BROWSER") == "1":
            pytest.fail(message)
        pytest.skip(message)
    return folder


def pages(folder):
    return sorted(path for part in ("book", "exercises")
                  for path in (folder / part).glob("*.html"))


class Elements(HTMLParser):
    """Every start tag of a page: (tag, attributes, the language it inherits, its text when it
    is a signature's parameter)."""

    VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source",
            "track", "wbr"}

    def __init__(self, html):
        super().__init__(convert_charrefs=True)
        self.elements, self.stack, self.parameters = [], [], []
        self._parameter = None
        self.feed(html)

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        inherited = next((lang for _, lang in reversed(self.stack) if lang), None)
        language = attributes.get("lang") or inherited
        self.elements.append((tag, attributes, language))
        if tag not in self.VOID:
            self.stack.append((tag, attributes.get("lang")))
        if tag == "em" and "sig-param" in attributes.get("class", ""):
            self._parameter = []

    def handle_endtag(self, tag):
        while self.stack:
            open_tag, _ = self.stack.pop()
            if open_tag == tag:
                break
        if tag == "em" and self._parameter is not None:
            self.parameters.append("".join(self._parameter))
            self._parameter = None

    def handle_data(self, data):
        if self._parameter is not None:
            self._parameter.append(data)


def signatures(html):
    """``{object's full name: [its parameters as shown]}`` of an API page."""
    found = {}
    for match in re.finditer(r'<dt class="sig[^"]*"[^>]*id="([^"]+)">(.*?)</dt>', html, re.S):
        parser = Elements(match.group(2))
        found[match.group(1)] = [" ".join(text.split()) for text in parser.parameters]
    return found


def documented(name):
    """The Python object called ``name`` (``rsgeo.resample.warp``), or None."""
    parts = name.split(".")
    for split in range(len(parts), 0, -1):
        try:
            target = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        for attribute in parts[split:]:
            target = getattr(target, attribute, None)
        return target
    return None


# -- The API reference --------------------------------------------------------------------------

@pytest.mark.parametrize("language", BOOKS)
def test_api_signatures_show_each_parameter_with_its_name_then_its_default(language):
    html = (book(language) / "book" / "api.html").read_text(encoding="utf-8")
    shown = signatures(html)
    assert len(shown) > 100, "the API page lists too few signatures"
    # "Raster(:ndarrayarray, ...)", "(=transformNone)": a name moved behind its annotation
    garbled = {name: parameters for name, parameters in shown.items()
               if any(parameter[:1] in ":=" for parameter in parameters)}
    assert not garbled, f"{len(garbled)} garbled signatures, e.g. {next(iter(garbled.items()))}"
    warp = shown["rsgeo.resample.warp"]
    assert warp[:6] == ["image", "mapping", "dst_shape", "dst_transform=None", "*",
                        "method='nearest'"], warp
    compared = 0
    for name, parameters in shown.items():
        target = documented(name)
        if not callable(target):
            continue
        try:
            expected = [parameter for parameter in inspect.signature(target).parameters.values()]
        except (TypeError, ValueError):
            continue
        expected_names = [parameter.name for parameter in expected]
        if inspect.isclass(target) or name.count(".") > 2:  # methods show no self
            expected_names = [n for n in expected_names if n not in ("self", "cls")]
        names = [re.split(r"[:=\s]", parameter.lstrip("*"), maxsplit=1)[0]
                 for parameter in parameters if parameter not in ("*", "/")]
        assert names == expected_names, f"{name}: shows {names}, has {expected_names}"
        compared += 1
    assert compared > 100


def test_the_portuguese_books_docstrings_say_they_are_english():
    html = (book("pt_BR") / "book" / "api.html").read_text(encoding="utf-8")
    elements = Elements(html).elements
    descriptions = [(tag, attributes, language) for tag, attributes, language in elements
                    if tag == "dl" and attributes.get("class", "").startswith("py ")]
    assert len(descriptions) > 100
    assert all(language == "en" for _, _, language in descriptions), "a docstring without lang"
    docstrings = [(tag, language) for tag, attributes, language in elements
                  if "rsgeo-docstring" in attributes.get("class", "").split()]
    assert docstrings and all(language == "en" for _, language in docstrings)
    # the page's own prose stays Portuguese
    assert '<html lang="pt-BR"' in html
    article = html[html.index('<article'):]
    assert re.search(r'<p>[^<]*\b(?:de|da|do|uma?)\b', article), "no Portuguese prose left"


# -- Every page ----------------------------------------------------------------------------------

@pytest.mark.parametrize("language", BOOKS)
def test_every_page_has_the_accessibility_fixes(language):
    folder = book(language)
    for page in pages(folder):
        html = page.read_text(encoding="utf-8")
        where = f"{language}/{page.relative_to(folder)}"
        # the language switch: once, right after the skip link, before the sidebar
        switch = html.find('class="rsgeo-language-switch')
        sidebar = html.find("bd-sidebar-primary")
        assert html.count('class="rsgeo-language-switch') == 1, where
        assert html.find('id="pst-skip-link"') < switch < sidebar, where
        # names that say what the control shows (axe label-content-name-mismatch)
        assert 'aria-label="Toggle hidden content"' not in html, where
        search = re.search(r'<button class="btn search-button-field[^>]*>', html).group(0)
        assert "aria-label" not in search, where
        switcher = html[html.index("theme-switch-button"):]
        switcher = switcher[:switcher.index("</button>")]
        assert " title=" not in switcher and switcher.count('aria-hidden="true"') == 3, where
        # the bibliography's entries are its list's items; no empty header cell
        assert 'role="doc-biblioentry"' not in html, where
        assert not re.search(r"<th(\s[^>]*)?>(\s|&nbsp;)*</th>", html), where
        assert "rsgeo-book.css" in html, where


@pytest.mark.parametrize("language", BOOKS)
def test_the_bibliography_is_a_list_of_items(language):
    html = (book(language) / "book" / "bibliography.html").read_text(encoding="utf-8")
    assert 'role="list" class="citation-list"' in html
    assert html.count('role="listitem"') >= 5


def test_the_portuguese_book_speaks_portuguese_in_the_themes_labels():
    folder = book("pt_BR")
    html = (folder / "book" / "glossary.html").read_text(encoding="utf-8")
    assert 'placeholder="Buscar neste livro..."' in html
    assert "Autoria: Os autores do curso rsgeo" in html and "De Os autores" not in html
    assert 'aria-label="Mostrar ou ocultar o sumário"' in html
    assert "Search this book" not in html and "Toggle primary sidebar" not in html


# -- Scripts: only what a page uses --------------------------------------------------------------

def _loads(html, name):
    return re.search(r'<script[^>]*src="[^"]*' + re.escape(name), html) is not None


@pytest.mark.parametrize("language", BOOKS)
def test_font_awesome_holds_the_icons_the_book_uses_and_no_other(language):
    folder = book(language)
    script = (folder / "_static" / "scripts" / "fontawesome.js").read_text(encoding="utf-8")
    assert len(script) < 200_000, "the theme's whole Font Awesome (1.5 MB) is still served"
    defined = set()
    for match in offline_book.FONTAWESOME_ICON.finditer(script):
        defined |= offline_book._icon_names(match)
    # the theme's, the download menu's, the animation player's and the Play widget's icons
    needed = {"magnifying-glass", "bars", "sun", "moon", "circle-half-stroke", "download",
              "expand", "file", "file-pdf", "angle-left", "angle-right", "list", "arrow-up",
              "play", "pause", "stop", "retweet", "fast-backward", "step-backward",
              "fast-forward", "step-forward", "plus", "minus"}
    assert needed <= defined, needed - defined
    used = set()
    for page in pages(folder):
        used |= set(offline_book.ICON_CLASS.findall(page.read_text(encoding="utf-8")))
    modifiers = {"solid", "regular", "brands", "lg", "fw", "spin", "flip-horizontal",
                 "flip-vertical", "flip-both", "pull-left", "pull-right"}
    assert used - modifiers <= defined, (used - modifiers) - defined
    assert len(defined) < 150


def test_the_subset_keeps_the_icons_asked_for_by_name_or_alias():
    packs = ('x();var p={a:[1,2,[],"f1","M0"],"b-c":[1,2,[9,"old-b"],"f2","M1"]};y();'
             'var q={d:[3,4,[],"f3","M2"]};')
    assert offline_book.fontawesome_subset(packs, {"old-b"}) == (
        'x();var p={"b-c":[1,2,[9,"old-b"],"f2","M1"]};y();var q={};')
    assert offline_book.fontawesome_subset(packs, {"a", "d"}) == (
        'x();var p={a:[1,2,[],"f1","M0"]};y();var q={d:[3,4,[],"f3","M2"]};')


@pytest.mark.parametrize("language", BOOKS)
def test_mathjax_and_the_widget_scripts_load_only_where_needed(language):
    folder = book(language) / "book"
    for name in ("intro", "glossary", "api", "bibliography"):
        html = (folder / f"{name}.html").read_text(encoding="utf-8")
        assert not _loads(html, "tex-chtml.js"), f"{name} loads MathJax"
        assert not _loads(html, "embed-amd.js") and not _loads(html, "rsgeo-widgets.js"), name
    assert _loads((folder / "03_evaluating_models.html").read_text(encoding="utf-8"),
                  "tex-chtml.js")
    widgets = (folder / "06b_ga_widget.html").read_text(encoding="utf-8")
    tag = re.search(r'<script[^>]*rsgeo-widgets\.js[^>]*>', widgets).group(0)
    assert _loads(widgets, "embed-amd.js")
    if language == "pt_BR":
        for attribute, name in WIDGET_NAMES_PT.items():
            assert f'{attribute}="{name}"' in tag, tag
    else:
        assert 'data-play="Play"' in tag and 'data-repeat="Repeat"' in tag, tag


# -- Search --------------------------------------------------------------------------------------

@pytest.mark.parametrize("language", BOOKS)
def test_search_ranks_a_chapter_above_the_api_entries(language):
    folder = book(language)
    language_data = (folder / "_static" / "language_data.js").read_text(encoding="utf-8")
    assert "var Scorer" in language_data
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is not installed: the scorer is there, its ranking is not run")
    results = [["book/api", "API reference", "#rsgeo.evaluate.rms", "function", 11 + 5, "a"],
               ["book/03_evaluating_models", "3. Evaluating", "", None, 5, "b"],
               ["book/api", "API reference", "", None, 5, "c"]]
    program = (language_data + "\nconst results = " + json.dumps(results) + ";\n"
               "console.log(JSON.stringify(results.map((r) => Scorer.score(r))));")
    scores = json.loads(subprocess.run([node, "-e", program], capture_output=True, text=True,
                                       check=True, timeout=900).stdout)
    assert scores[1] > scores[0], scores
    assert scores[2] == 5, "the API page itself (its prose) keeps its score"
