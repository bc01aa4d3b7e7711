"""Figures and tables in the course's language, their code left in English.

The notebooks write their figures' texts in English, in their code (``ax.set_title("...")``,
f-strings, ``label=``, a table's columns). In a Portuguese notebook (``RSGEO_LANG=pt_BR``, see
``rsgeo._i18n``) :func:`translate_rendered_figures` translates every figure as it is rendered
and every pandas table as it is displayed, from the figures' catalogue
``rsgeo/locale/pt_BR/LC_MESSAGES/rsgeo_figures.po`` (made by ``python locales/update.py
--figures``, which collects those texts from the notebooks' code), then rsgeo's own catalogue.

A text made by an f-string is matched by its template, the f-string with a ``{}`` for each
field: ``"RMS {} px"`` matches ``"RMS 0.51 px"``, and the translation's ``{}`` are filled with
the values found, a number written with a decimal comma, a value that is itself a known text
translated too. A text the catalogues do not know keeps its words, its numbers get a decimal
comma. Tick labels get the same treatment when they are drawn (the axes' formatters are
wrapped), so a number axis reads ``0,5``. The language is looked up at every text, so all of
this does nothing while the language is English.

Examples
--------
>>> from rsgeo_course.figure_language import translate_text
>>> translate_text("row (pixels)", "pt_BR")
'linha (pixels)'
>>> translate_text("true gain 1.25", "pt_BR")
'ganho verdadeiro 1,25'
>>> translate_text("true gain 1.25", "en")
'true gain 1.25'
"""

import functools
import re
import string

from rsgeo.language import catalogue as gettext_catalogue
from rsgeo.language import translate as rsgeo_translate

from ._i18n import LOCALE_DIR, PORTUGUESE_SEPARATORS, get_language, resolve_language
from ._i18n import translate as course_translate

__all__ = ["DOMAIN", "translate_text", "translate_figure", "translate_table",
           "translate_rendered_figures"]

#: The figures' catalogue: ``LOCALE_DIR / language / "LC_MESSAGES" / (DOMAIN + ".mo")``.
DOMAIN = "rsgeo_figures"

# a number as Python writes it: 0.5, -1.25e-03, 25,000 (thousands), 1,234.5; not inside a
# name or a version (B3.tif, 3.11.2)
_NUMBER = re.compile(r"(?<![\w.,])(?:\d{1,3}(?:,\d{3})+(?:\.\d+)?|\d+\.\d+)(?:[eE][-+−]?\d+)?"
                     r"(?![\w]|[.,]\d)")
# a number with a decimal point only: in a whole text, where "0,384" may already be Portuguese
# (rsgeo's own figures write their numbers the language's way), a comma is left alone
_DECIMAL = re.compile(r"(?<![\w.,])\d+\.\d+(?:[eE][-+−]?\d+)?(?![\w]|[.,]\d)")


@functools.cache
def _catalogue(language):
    """``(exact, templates)`` of the figures' catalogue: ``{text: translation}`` and
    ``[(pattern, translation)]``, the most specific template first."""
    if language == "en":
        return {}, []
    # an install without the compiled catalogue speaks English (and rsgeo's own catalogue)
    catalogue = gettext_catalogue(language, DOMAIN, LOCALE_DIR)
    exact, templates = {}, []
    for message, translation in getattr(catalogue, "_catalog", {}).items():
        if not isinstance(message, str) or not message or not translation:
            continue
        try:
            parts = list(string.Formatter().parse(message))
        except ValueError:
            continue
        if all(field is None for _, field, _, _ in parts):
            exact[message.replace("{{", "{").replace("}}", "}")] = \
                translation.replace("{{", "{").replace("}}", "}")
            continue
        pattern = "".join(re.escape(literal) + ("" if field is None else "(.+?)")
                          for literal, field, _, _ in parts)
        literal_size = sum(len(literal.strip()) for literal, _, _, _ in parts)
        if not literal_size:                  # fields alone ("{} {}") would match anything
            continue
        templates.append((literal_size, re.compile(pattern, re.DOTALL), translation))
    templates.sort(key=lambda entry: -entry[0])
    return exact, [(pattern, translation) for _, pattern, translation in templates]


def _numbers(text, language, thousands=False):
    """``text`` with each number written the language's way (``0.5`` -> ``0,5`` in Portuguese;
    with ``thousands``, ``25,000`` -> ``25.000`` too, for a value Python wrote); inside
    ``$...$`` (mathtext) the decimal comma is ``{,}``, so that no space follows it."""
    if language == "en" or not any(character.isdigit() for character in text):
        return text
    number = _NUMBER if thousands else _DECIMAL
    pieces = text.split("$")
    for index, piece in enumerate(pieces):
        if index % 2:                          # mathtext
            pieces[index] = number.sub(
                lambda match: match.group().replace(",", "").replace(".", "{,}"), piece)
        else:
            pieces[index] = number.sub(
                lambda match: match.group().translate(PORTUGUESE_SEPARATORS), piece)
    return "$".join(pieces)


def _field(value, language):
    """A template's field, as an f-string filled it (Python's numbers): translated."""
    translated = _translated(value, language)
    return _numbers(translated, language, thousands=True) if translated == value else translated


def _untranslated_words(value, filled, exact):
    """Whether a template's field holds English words the catalogues do not know (a name such
    as ``X0``, ``G10`` or ``SIFT``, a number, a known text are fine)."""
    return filled == value and value not in exact and re.search(r"[a-z]{3,}", value)


def _known(text, language):
    """A table's label or word: translated when a catalogue knows it, else as it is (a table's
    texts are names and data, "1.2 Task" or "G10", whose numbers are not the prose's)."""
    if not isinstance(text, str) or not text:
        return text
    exact, templates = _catalogue(language)
    if text in exact or _message(text, language) != text or any(
            pattern.fullmatch(text) for pattern, _ in templates):
        return _translated(text, language)
    return text


def _message(text, language):
    """``text`` as a message of the course's catalogue or of rsgeo's, else unchanged."""
    known = course_translate(text, language)
    return known if known != text else rsgeo_translate(text, language)


@functools.lru_cache(maxsize=8192)
def _translated(text, language):
    exact, templates = _catalogue(language)
    if text in exact:
        return exact[text]
    known = _message(text, language)        # the course's and rsgeo's messages (verdicts, ...)
    if known != text:
        return known
    stripped = text.strip()
    if stripped and stripped != text:
        found = _translated(stripped, language)
        if found != stripped:
            return text.replace(stripped, found, 1)
    for pattern, translation in templates:
        match = pattern.fullmatch(text)
        if not match:
            continue
        values = [_field(value, language) for value in match.groups()]
        if any(_untranslated_words(value, filled, exact)
               for value, filled in zip(match.groups(), values)):
            continue          # "{} error (m)" is not "median error (m)": no mixed languages
        try:
            return translation.format(*values)
        except (IndexError, KeyError, ValueError):
            continue                               # a translation with other fields: not this
    for separator in ("\n", " → ", " | "):        # lines, a pair's ends, a checkerboard's sides
        if separator in text:
            return separator.join(_translated(part, language)
                                  for part in text.split(separator))
    return _numbers(text, language)


def translate_text(text, language=None):
    """One figure's or table's text in ``language``, from the figures' catalogue.

    Parameters
    ----------
    text : str
        The text as the notebook's code made it (``"RMS 0.51 px"``).
    language : str, optional
        ``"en"`` or ``"pt_BR"``; default the current language (``rsgeo.language.get_language()``).

    Returns
    -------
    str
        The catalogue's translation (a template's, its fields refilled: numbers with the
        language's decimal separator, known texts translated), else ``text`` with its numbers
        written the language's way; ``text`` itself in English or when it is not a string.

    Raises
    ------
    ValueError
        If ``language`` (or ``RSGEO_LANG``) is not a language rsgeo speaks.

    Examples
    --------
    >>> from rsgeo_course.figure_language import translate_text
    >>> translate_text("fitting RMS (px)", "pt_BR")
    'REQM de ajuste (px)'
    >>> translate_text("scan 3", "pt_BR")
    'varredura 3'
    >>> translate_text("scan 3", "en")
    'scan 3'
    """
    language = resolve_language(language)
    if language == "en" or not isinstance(text, str) or not text:
        return text
    return _translated(text, language)


def _translate_labels(labels, language):
    return [translate_text(label, language) if isinstance(label, str) else label
            for label in labels]


def _wrap_formatter(formatter):
    """Make a tick formatter give its labels in the language current when it draws them."""
    if formatter is None or getattr(formatter, "_rsgeo_language", False):
        return
    format_ticks, get_offset = formatter.format_ticks, formatter.get_offset

    def translated_ticks(values):
        return _translate_labels(format_ticks(values), None)

    def translated_offset():
        return translate_text(get_offset())

    # instance attributes: the axis calls formatter.format_ticks(...) and .get_offset()
    formatter.format_ticks = translated_ticks
    formatter.get_offset = translated_offset
    formatter._rsgeo_language = True


def translate_figure(figure, language=None):
    """Translate every text of a matplotlib figure, in place.

    Titles, the suptitle, axis labels, legend texts, colour-bar labels, text and annotation
    artists (any matplotlib ``Text`` of the figure) get :func:`translate_text`; the
    tick labels get it when they are drawn (each axis' formatters are wrapped once), so word
    ticks are translated and number ticks get the language's decimal separator. A text already
    translated is left alone, so calling this again (at every render) is safe.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure.
    language : str, optional
        ``"en"`` or ``"pt_BR"``; default the current language. English changes nothing.

    Returns
    -------
    matplotlib.figure.Figure
        ``figure``.

    Raises
    ------
    ValueError
        If ``language`` (or ``RSGEO_LANG``) is not a language rsgeo speaks.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from matplotlib.figure import Figure
    >>> from rsgeo_course.figure_language import translate_figure
    >>> figure = Figure()
    >>> ax = figure.subplots()
    >>> _ = ax.set(title="scan 2", xlabel="column (pixels)")
    >>> _ = translate_figure(figure, "pt_BR")
    >>> ax.get_title(), ax.get_xlabel()
    ('varredura 2', 'coluna (pixels)')
    """
    from matplotlib.quiver import QuiverKey
    from matplotlib.table import Cell
    from matplotlib.text import Text

    language = resolve_language(language)
    if language == "en":
        return figure
    # a quiver key's label and a table's cells are Text artists findobj does not reach
    texts = [*figure.findobj(Text), *(key.text for key in figure.findobj(QuiverKey)),
             *(cell.get_text() for cell in figure.findobj(Cell))]
    for artist in texts:
        text = artist.get_text()
        if not text or getattr(artist, "_rsgeo_translated", None) == text:
            continue
        translated = translate_text(text, language)
        if translated != text:
            artist.set_text(translated)
        artist._rsgeo_translated = translated
    for ax in figure.axes:
        for axis in (getattr(ax, name, None) for name in ("xaxis", "yaxis", "zaxis")):
            if axis is not None:
                _wrap_formatter(axis.get_major_formatter())
                _wrap_formatter(axis.get_minor_formatter())
    return figure


def _translated_index(index, language):
    renamed = index.map(lambda label: _known(label, language)) if index.nlevels == 1 else \
        index.set_levels([level.map(lambda label: _known(label, language))
                          for level in index.levels], verify_integrity=False)
    return renamed.set_names([_known(name, language) for name in index.names])


def translate_table(table, language=None):
    """A copy of a pandas table whose labels and words are translated, for display.

    Parameters
    ----------
    table : pandas.DataFrame or pandas.Series
        The table; it is not changed.
    language : str, optional
        ``"en"`` or ``"pt_BR"``; default the current language.

    Returns
    -------
    pandas.DataFrame or pandas.Series
        A shallow copy with every string label (each level of a MultiIndex too) and every
        string value the catalogues know translated (:func:`translate_text`; any other is
        left as it is: a name, an identifier, data), yes-or-no columns as words ("sim",
        "não"); ``table`` itself in English. Its floats get the language's decimal separator
        when IPython shows the table (:func:`translate_rendered_figures`).

    Raises
    ------
    ValueError
        If ``language`` (or ``RSGEO_LANG``) is not a language rsgeo speaks.

    Examples
    --------
    >>> import pandas as pd
    >>> from rsgeo_course.figure_language import translate_table
    >>> table = pd.DataFrame({"RMS (m)": [0.5]}, index=pd.Index(["raw"], name="stage"))
    >>> translated = translate_table(table, "pt_BR")
    >>> list(translated.columns), list(translated.index), translated.index.name
    (['REQM (m)'], ['bruto'], 'etapa')
    """
    from pandas.api.types import is_string_dtype

    language = resolve_language(language)
    if language == "en":
        return table
    copy = table.copy(deep=False)
    columns = [copy[name] for name in copy.columns] if hasattr(copy, "columns") else [copy]
    for position, column in enumerate(columns):
        values = None
        if column.dtype == bool:
            values = column.map(_YES_NO[language].get)
        elif column.dtype == object or is_string_dtype(column.dtype):   # pandas 3: "str"
            values = column.map(lambda value: _known(value, language))
        if values is not None:
            if hasattr(copy, "columns"):
                copy.isetitem(position, values)
            else:
                copy = values
    copy.index = _translated_index(table.index, language)
    if hasattr(table, "columns"):
        copy.columns = _translated_index(table.columns, language)
    elif isinstance(table.name, str):
        copy.name = translate_text(table.name, language)
    return copy


# how a table shows a yes-or-no column in each language other than English
_YES_NO = {"pt_BR": {True: "sim", False: "não"}}


def _frame_html(frame):
    """A DataFrame's notebook HTML as pandas writes it, translated, with a decimal comma."""
    language = get_language()
    if language == "en":
        return frame._repr_html_()
    translated = translate_table(frame, language)
    try:
        from pandas import get_option
        from pandas.io.formats import format as pandas_format

        if translated._info_repr() or not get_option("display.notebook_repr_html"):
            return translated._repr_html_()
        formatter = pandas_format.DataFrameFormatter(
            translated, float_format=get_option("display.float_format"), index_names=True,
            bold_rows=True, escape=True, max_rows=get_option("display.max_rows"),
            min_rows=get_option("display.min_rows"), max_cols=get_option("display.max_columns"),
            show_dimensions=get_option("display.show_dimensions"), decimal=",")
        return pandas_format.DataFrameRenderer(formatter).to_html(notebook=True)
    except (AttributeError, ImportError, TypeError):   # another pandas: its own HTML, translated
        return translated._repr_html_()


def _frame_text(frame, printer, cycle):
    language = get_language()
    if language == "en":
        printer.text(repr(frame))
        return
    translated = translate_table(frame, language)
    try:
        from pandas.io.formats.format import get_dataframe_repr_params

        printer.text(translated.to_string(decimal=",", **get_dataframe_repr_params()))
    except (AttributeError, ImportError, TypeError):
        printer.text(repr(translated))


def _series_text(series, printer, cycle):
    printer.text(repr(translate_table(series)))


def _styler_html(styler):
    """A Styler's HTML with its table's labels translated, its cells' numbers (formatted by
    the Styler's own format) written with the language's decimal separator."""
    import copy

    language = get_language()
    if language == "en":
        return styler._repr_html_()
    translated = copy.copy(styler)
    translated.data = translate_table(styler.data)
    translated.index, translated.columns = translated.data.index, translated.data.columns
    return re.sub(r"(<td[^>]*>)([^<]*)(</td>)",
                  lambda cell: cell.group(1) + _numbers(cell.group(2), language) + cell.group(3),
                  translated._repr_html_())


def _register_table_formatters():
    """Show pandas tables translated in this IPython kernel (nothing outside IPython)."""
    try:
        from IPython import get_ipython
    except ImportError:
        return
    shell = get_ipython()
    if shell is None:
        return
    formatters = shell.display_formatter.formatters
    # by name, so that pandas need not be imported yet; pandas 2 and 3 name the module apart
    for module in ("pandas", "pandas.core.frame", "pandas.core.series"):
        formatters["text/html"].for_type_by_name(module, "DataFrame", _frame_html)
        formatters["text/plain"].for_type_by_name(module, "DataFrame", _frame_text)
        formatters["text/plain"].for_type_by_name(module, "Series", _series_text)
    formatters["text/html"].for_type_by_name("pandas.io.formats.style", "Styler", _styler_html)


def translate_rendered_figures():
    """Translate every figure this process renders and every pandas table IPython shows.

    Patches matplotlib's ``FigureCanvasBase.print_figure`` (what shows, saves and animates a
    figure) to call :func:`translate_figure` first, and, in an IPython kernel, registers
    display formatters that show DataFrames (HTML and text), Stylers and Series through
    :func:`translate_table`, floats with a decimal comma. The language is looked up at each
    figure and table, so this changes nothing while it is English. The Portuguese notebooks'
    hidden first cell calls it.

    Returns
    -------
    None
        Only the first call patches matplotlib; later calls only re-register the tables'
        formatters (no harm).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from rsgeo_course.figure_language import translate_rendered_figures
    >>> translate_rendered_figures()
    >>> translate_rendered_figures()       # a second call changes nothing
    """
    import functools as _functools

    from matplotlib.backend_bases import FigureCanvasBase

    _register_table_formatters()
    if getattr(FigureCanvasBase.print_figure, "_rsgeo_language", False):
        return
    original = FigureCanvasBase.print_figure

    @_functools.wraps(original)       # keeps the figure audit's mark on the patched method
    def print_figure(self, *args, **kwargs):
        translate_figure(self.figure)
        return original(self, *args, **kwargs)

    print_figure._rsgeo_language = True
    FigureCanvasBase.print_figure = print_figure
