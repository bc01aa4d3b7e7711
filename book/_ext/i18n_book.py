"""The course in two languages: one English source, a Portuguese book from gettext catalogues.

Loaded by both builds (``_config.yml`` and ``_config_pt.yml``):

- **Docstrings stay English, like code.** Every text node that autodoc or autosummary makes from
  rsgeo's docstrings (descriptions, parameter lists, examples, summary tables) is marked
  ``translatable=False`` before Sphinx's ``Locale`` transform, so it never enters the catalogue
  (``api.po`` holds the API page's own prose only) and is never replaced. Inline nodes (a
  signature's names, parameters and defaults) are left alone: Sphinx never translates an inline
  node without that attribute, and ``RemoveTranslatableInline`` moves any inline node that has
  it to the end of its parent, which garbled the signatures ("Raster(:ndarrayarray, ...)"). In a
  translated book every docstring block says ``lang="en"`` to screen readers and search.
- **Translations that start like a Markdown list** ("1. Distorções sistemáticas", a chapter's
  title) are escaped before Sphinx parses them, which would otherwise keep the English silently.
- **Exercise titles** (sphinx-exercise's subtitles, made without a source) become messages of
  their page's catalogue.
- **The parts' captions of the table of contents** (inserted by sphinx-external-toc after
  Sphinx has translated the page) are translated from the root page's catalogue too.
- **A language switch on every page**, to the same page in the other book, by a relative link
  (``i18n_other_book``: the other book's HTML folder relative to this one's), so that it works
  from the built folders offline; plus ``<link rel="alternate" hreflang=...>``.
- **A note on the root page** of a translated book (``i18n_root_note``: title and text), said
  once: code stays English, numbers are written as the code prints them.
- **Notebooks executed in the book's language** (``i18n_execute_in_language``: docname
  patterns; the Portuguese book gives ``*``, every notebook): a hidden first cell sets
  ``RSGEO_LANG`` and translates every figure as it is rendered and every table as it is shown
  (:mod:`rsgeo_course.figure_language`), so the figures, widgets, tables, verdicts and hints of the
  translated book speak its language; a notebook no pattern matches shows the English build's
  execution.
- **Notebooks to download in the book's language.** After a translated build, the copies of the
  notebooks under ``_sources/`` (what the download button gives) get their Markdown cells
  translated from the same catalogues, and a first cell that sets ``RSGEO_LANG`` so that rsgeo's
  verdicts, hints, errors and figure labels speak that language too.

Sphinx's ``lang`` attribute on ``<html>`` comes from ``language`` (``pt_BR`` gives ``pt-BR``).
"""

import fnmatch
import json
import re
from pathlib import Path

from docutils import nodes
from sphinx import addnodes
from sphinx.transforms import SphinxTransform

ENGLISH = "en"
#: The name of the language switch's landmark, in the book's language.
SWITCH_NAMES = {"en": "Other language", "pt_BR": "Outra língua"}
ENGLISH_CLASS = "language-" + ENGLISH
# the theme options that are texts the reader sees (see translate_theme_texts)
THEME_TEXTS = ("theme_search_bar_text",)


# -- Docstrings stay English ------------------------------------------------------------------

def _from_docstring(node):
    # autodoc parses a docstring with the source "<module file>:docstring of <name>"
    return ":docstring of " in (node.source or "")


def _in_signature(node):
    while node is not None:
        if isinstance(node, addnodes.desc_signature):
            return True
        node = node.parent
    return False


class KeepDocstringsEnglish(SphinxTransform):
    """Mark autodoc's and autosummary's text untranslatable (Sphinx's ``is_translatable`` skips a
    TextElement whose ``translatable`` is False); runs before ``Locale`` (priority 20)."""

    default_priority = 5

    def apply(self, **kwargs):
        generated, english_blocks = set(), []
        for container in self.document.findall(addnodes.desc):
            english_blocks.append(container)
            generated.update(container.findall(nodes.TextElement))
        for table in self.document.findall(nodes.table):
            # autosummary's table has the class "autosummary longtable" (one string)
            if any("autosummary" in name for name in table.get("classes", [])):
                english_blocks.append(table)
                generated.update(table.findall(nodes.TextElement))
        docstrings = [node for node in self.document.findall(nodes.TextElement)
                      if _from_docstring(node)]
        generated.update(docstrings)
        for node in generated:
            # a signature's nodes are never translated, and Sphinx's RemoveTranslatableInline
            # moves an inline node that has the attribute to the end of its parent: marked, a
            # signature read "Raster(:ndarrayarray, ...)"
            if not _in_signature(node):
                node["translatable"] = False
        # a module's docstring (its paragraphs, its own sections) sits outside any desc node:
        # the class says "English on purpose" to the reader's stylesheet and to the tests
        for node in docstrings:
            target = node.parent if isinstance(node, nodes.title) else node
            if "rsgeo-docstring" not in target["classes"]:
                target["classes"].append("rsgeo-docstring")
            if not isinstance(target, nodes.Inline):
                english_blocks.append(target)
        if (self.config.language or ENGLISH) != ENGLISH:
            for block in english_blocks:
                # docutils' HTML writer turns the class "language-en" into lang="en"
                if ENGLISH_CLASS not in block["classes"]:
                    block["classes"].append(ENGLISH_CLASS)


# -- Exercise titles ---------------------------------------------------------------------------

class TranslatableExerciseTitles(SphinxTransform):
    """Make sphinx-exercise's subtitles ("1.1 Earth-rotation skew of a CBERS frame") messages.

    sphinx-exercise builds them from the directive's argument without a source, and Sphinx skips a
    text node without one, so the Portuguese book showed "Exercício (1.1 Earth-rotation ...)".
    Given the page's source, line and text, they enter the page's catalogue and get translated
    like any paragraph (before ``Locale``, priority 20).
    """

    default_priority = 12

    def apply(self, **kwargs):
        for node in self.document.findall(nodes.subtitle):
            if type(node).__name__ != "exercise_subtitle" or node.source:
                continue
            title, exercise = node.parent, node.parent.parent
            node.source = self.document["source"]
            node.line = title.line or exercise.line
            node.rawsource = node.astext()
            # sphinx-exercise's post-transform folds the subtitle into a new title before the
            # gettext builder reads the page: keep the message where catalogue_exercise_titles
            # finds it
            exercise["rsgeo_subtitle"] = (node.rawsource, node.source, node.line)


def catalogue_exercise_titles(app, doctree, docname):
    """``doctree-resolved`` of the gettext build: put the exercise titles in the page's catalogue
    (see :class:`TranslatableExerciseTitles`)."""
    if app.builder.name != "gettext":
        return
    from sphinx.builders.gettext import MsgOrigin
    from sphinx.util.i18n import docname_to_domain

    catalogue = app.builder.catalogs[docname_to_domain(docname, app.config.gettext_compact)]
    for node in doctree.findall(nodes.Element):
        if node.get("rsgeo_subtitle"):
            text, source, line = node["rsgeo_subtitle"]
            catalogue.add(text, MsgOrigin(source, line))


# -- The table of contents' captions -----------------------------------------------------------

class TranslateInsertedToctrees(SphinxTransform):
    """Translate the toctrees that sphinx-external-toc inserts (the parts' captions of _toc.yml).

    They are inserted at priority 100, after Sphinx's ``Locale`` (20) has translated the page, so
    their captions, which the gettext build does put in the root page's catalogue, would stay
    English in the sidebar; this runs after the insertion and before the toctrees are collected.
    """

    default_priority = 150

    def apply(self, **kwargs):
        if (self.config.language or ENGLISH) == ENGLISH or not self.config.locale_dirs:
            return
        from sphinx.locale import init as init_locale
        from sphinx.util.i18n import docname_to_domain

        domain = docname_to_domain(self.env.docname, self.config.gettext_compact)
        folders = [str(Path(self.env.srcdir) / folder) for folder in self.config.locale_dirs]
        catalogue, found = init_locale(folders, self.config.language, domain)
        if not found:
            return
        for toctree in self.document.findall(addnodes.toctree):
            toctree.preserve_original_messages()
            messages = [title for title, _ in toctree["entries"] if title]
            messages += [toctree["caption"]] if toctree.get("caption") else []
            for message in messages:
                translation = catalogue.gettext(message)
                if translation and translation != message:
                    toctree.apply_translated_message(message, translation)


# -- Translated Markdown that starts like a list -------------------------------------------------

LIST_START = re.compile(r"^(\d{1,9})([.)])(\s)|^([-+*])(\s)")


def escape_list_start(text):
    r"""``text`` with a leading list marker escaped, so that Markdown reads it as text.

    Sphinx parses each translation on its own; for a MyST page, "1. Distorções sistemáticas"
    (a chapter's title) would parse as an ordered list, and Sphinx would silently keep the
    English title (``Locale`` skips a translation that is not a paragraph or a title).

    >>> escape_list_start("1. Distorções sistemáticas")
    '1\\. Distorções sistemáticas'
    >>> escape_list_start("2b. Datums")
    '2b. Datums'
    """
    return LIST_START.sub(lambda m: (f"{m[1]}\\{m[2]}{m[3]}" if m[1] else f"\\{m[4]}{m[5]}"),
                          text, count=1)


def markdown_safe_translations():
    """Wrap Sphinx's ``publish_msgstr`` so that translations of MyST pages and notebooks keep a
    leading "1." or "-" as text (see :func:`escape_list_start`)."""
    from sphinx.transforms import i18n

    if getattr(i18n.publish_msgstr, "_rsgeo", False):
        return
    original = i18n.publish_msgstr

    def publish_msgstr(app, source, source_path, source_line, config, settings):
        if str(source_path).endswith((".md", ".ipynb")):
            source = escape_list_start(source)
        return original(app, source, source_path, source_line, config, settings)

    publish_msgstr._rsgeo = True
    i18n.publish_msgstr = publish_msgstr


# -- The language switch ------------------------------------------------------------------------

def other_page_url(pagename, other_book):
    """The relative URL of ``pagename`` in the other book, seen from ``pagename`` in this one.

    >>> other_page_url("book/intro", "../pt_BR/_build/html")
    '../../pt_BR/_build/html/book/intro.html'
    """
    depth = pagename.count("/")
    return "../" * depth + other_book.strip("/") + "/" + pagename + ".html"


def add_language_switch(app, pagename, templatename, context, doctree):
    """``html-page-context``: the switch to the same page in the other book.

    The page template (book/_templates/layout.html) puts ``rsgeo_language_switch`` right after
    the theme's skip link, before the sidebar's table of contents: it is the second Tab stop and
    the first line of the page on a phone, where the sidebar is folded away.
    """
    other_book = app.config.i18n_other_book
    # the page-per-document HTML books only (not singlehtml, which the printed course uses)
    if (not other_book or app.builder.name != "html" or doctree is None
            or pagename not in app.env.found_docs):
        return
    url = other_page_url(pagename, other_book)
    language, label = app.config.i18n_other_language, app.config.i18n_other_label
    hreflang = language.replace("_", "-")
    # a landmark of its own, named in this book's language (axe "region": all content in one)
    name = SWITCH_NAMES.get(app.config.language or ENGLISH, SWITCH_NAMES[ENGLISH])
    context["rsgeo_language_switch"] = (
        f'<nav class="rsgeo-language-switch d-print-none" aria-label="{name}">'
        f'<a href="{url}" hreflang="{hreflang}" lang="{hreflang}">{label}</a></nav>')
    context["metatags"] = (context.get("metatags", "")
                           + f'\n<link rel="alternate" hreflang="{hreflang}" href="{url}" />')


def translate_theme_texts(app, pagename, templatename, context, doctree):
    """``html-page-context``: theme options that are texts (Jupyter Book's search placeholder
    "Search this book...") in the book's language, from the "sphinx" catalogue
    (locales/pt_BR/LC_MESSAGES/sphinx.po), like the themes' own labels."""
    if (app.config.language or ENGLISH) == ENGLISH:
        return
    from sphinx.locale import _

    for option in THEME_TEXTS:
        if context.get(option):
            context[option] = _(context[option])


# -- The note on the root page of a translated book ---------------------------------------------

def add_root_note(app, doctree):
    title, text = app.config.i18n_root_note or ("", "")
    if not text or app.env.docname != app.config.root_doc:
        return
    note = nodes.admonition("", nodes.title("", title), nodes.paragraph("", text),
                            classes=["note", "rsgeo-language-note"])
    section = next(iter(doctree.findall(nodes.section)), None)
    parent = section if section is not None else doctree
    # after the page's title, before its first paragraph
    index = 1 if section is not None and isinstance(section[0], nodes.title) else 0
    parent.insert(index, note)


# -- Notebooks to download, translated ----------------------------------------------------------

def read_catalogue(path):
    """``{msgid: msgstr}`` of the translated, not fuzzy, entries of a .po file."""
    from babel.messages.pofile import read_po

    with open(path, "rb") as handle:
        catalogue = read_po(handle)
    return {message.id: message.string for message in catalogue
            if message.id and isinstance(message.id, str) and message.string
            and not message.fuzzy}


def _pattern(msgid):
    # the catalogue joins a paragraph's lines with spaces: any run of white space in the source
    # (a line break, a list item's indentation) matches one space of the msgid
    body = r"\s+".join(re.escape(word) for word in msgid.split())
    start = r"(?<!\w)" if msgid[:1].isalnum() else ""
    end = r"(?!\w)" if msgid[-1:].isalnum() else ""
    return re.compile(start + body + end)


def translate_markdown(source, catalogue):
    """``source`` (a Markdown cell), each message of ``catalogue`` replaced by its translation.

    Longest messages first; a translated stretch is never searched again, so a short message
    ("Concept") cannot change the inside of a longer one already translated.

    >>> translate_markdown("# Overview\\n\\nSome\\ntext.", {"Overview": "Visão geral",
    ...                                                     "Some text.": "Algum texto."})
    '# Visão geral\\n\\nAlgum texto.'
    """
    pieces = [(source, False)]
    for msgid in sorted(catalogue, key=len, reverse=True):
        if msgid == catalogue[msgid]:
            continue
        pattern, result = _pattern(msgid), []
        for text, done in pieces:
            if done:
                result.append((text, done))
                continue
            position = 0
            for match in pattern.finditer(text):
                result += [(text[position:match.start()], False), (catalogue[msgid], True)]
                position = match.end()
            result.append((text[position:], False))
        pieces = result
    return "".join(text for text, _ in pieces)


def language_cell(language):
    """A code cell that makes rsgeo speak ``language`` in the kernel (hidden in the book): its
    verdicts, hints and errors, and
    (:func:`rsgeo_course.figure_language.translate_rendered_figures`)
    every figure the notebook renders and every table it shows."""
    return {"cell_type": "code", "execution_count": None, "id": "rsgeo-language",
            "metadata": {"tags": ["remove-cell"]}, "outputs": [],
            "source": ["import os\n", "\n",
                       f'os.environ["RSGEO_LANG"] = "{language}"  # rsgeo speaks {language}: '
                       "verdicts, hints, errors,\n",
                       "# and the figures' and tables' texts (the notebook's code stays "
                       "English)\n",
                       "from rsgeo_course.figure_language import translate_rendered_figures\n",
                       "\n",
                       "translate_rendered_figures()"]}


def translated_notebook(path, catalogue, language):
    """The notebook at ``path``, its Markdown in Portuguese, its first cell setting RSGEO_LANG."""
    notebook = json.loads(Path(path).read_text(encoding="utf-8"))
    for cell in notebook["cells"]:
        if cell["cell_type"] == "markdown":
            source = cell["source"]
            source = "".join(source) if isinstance(source, list) else source
            cell["source"] = translate_markdown(source, catalogue)
    notebook["cells"].insert(0, language_cell(language))
    return notebook


# -- Notebooks executed in the book's language ----------------------------------------------------

def execute_in_language(app, docname, source):
    """``source-read``: in a translated build, the notebooks matching ``i18n_execute_in_language``
    get the hidden language cell first. Their code changes, so jupyter-cache keeps their
    Portuguese execution apart from the English one in the same cache; a notebook no pattern
    matches is read from the English build's execution (or executed without RSGEO_LANG)."""
    language = app.config.language or ENGLISH
    patterns = app.config.i18n_execute_in_language
    if language == ENGLISH or not any(fnmatch.fnmatch(docname, pattern) for pattern in patterns):
        return
    if not str(app.env.doc2path(docname)).endswith(".ipynb"):
        return
    notebook = json.loads(source[0])
    notebook["cells"].insert(0, language_cell(language))
    source[0] = json.dumps(notebook, ensure_ascii=False)


def translate_downloads(app, exception):
    language = app.config.language or ENGLISH
    if exception is not None or language == ENGLISH or app.builder.format != "html":
        return
    for docname in sorted(app.env.found_docs):
        source = Path(app.env.doc2path(docname))
        target = Path(app.outdir) / "_sources" / (docname + source.suffix)
        if source.suffix != ".ipynb" or not target.exists():
            continue
        catalogue = {}
        for folder in app.config.locale_dirs:
            po = Path(app.srcdir) / folder / language / "LC_MESSAGES" / (docname + ".po")
            if po.exists():
                catalogue.update(read_catalogue(po))
        notebook = translated_notebook(source, catalogue, language)
        target.write_text(json.dumps(notebook, ensure_ascii=False, indent=1) + "\n",
                          encoding="utf-8")


def setup(app):
    app.add_config_value("i18n_other_book", "", "html")
    app.add_config_value("i18n_other_language", "pt_BR", "html")
    app.add_config_value("i18n_other_label", "Português", "html")
    app.add_config_value("i18n_root_note", None, "env")
    app.add_config_value("i18n_execute_in_language", [], "env")
    app.add_transform(KeepDocstringsEnglish)
    app.add_transform(TranslateInsertedToctrees)
    app.add_transform(TranslatableExerciseTitles)
    markdown_safe_translations()
    app.connect("source-read", execute_in_language)
    app.connect("doctree-read", add_root_note)
    app.connect("doctree-resolved", catalogue_exercise_titles)
    app.connect("html-page-context", add_language_switch)
    app.connect("html-page-context", translate_theme_texts)
    app.connect("build-finished", translate_downloads)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
