"""The language rsgeo speaks: English or Brazilian Portuguese.

Messages a user reads (the ``ValueError`` messages of :mod:`rsgeo.validation` and the public verbs,
the labels of the figures :mod:`rsgeo.plot` draws, the widgets' controls) are written in English
in the code and wrapped in ``_()`` (a message chosen later is marked with :func:`N_` and
translated when it is shown); their Portuguese lives in the gettext catalogue
``rsgeo/locale/pt_BR/LC_MESSAGES/rsgeo.po``, shipped compiled (``rsgeo.mo``). A package built on
rsgeo keeps its own catalogue and reads it with :func:`catalogue`, in the language chosen here.

The language is, in this order: the one given to :func:`set_language`, the environment variable
``RSGEO_LANG`` (``pt_BR`` in the Portuguese notebooks), else English. It is looked up at every
message, so setting ``RSGEO_LANG`` in a running kernel takes effect at once. Code stays English:
names, arguments and the values a message quotes are never translated.

Format strings are translated before they are filled, so that a translation can move the fields::

    _("order {order} needs at least {n} GCPs, got {got}").format(order=2, n=6, got=4)

A number a message shows in prose (not in a code span) is passed as :func:`prose_number`, which
writes it the way the language does: ``22.5`` and ``50,000`` in English, ``22,5`` and ``50.000``
in Portuguese. Values quoted as code (``{value!r}``, inside backticks) keep Python's point.
"""

import functools
import gettext as _gettext
import os
from pathlib import Path

from .errors import RsgeoError

__all__ = ["LANGUAGES", "ENVIRONMENT_VARIABLE", "LOCALE_DIR", "PORTUGUESE_SEPARATORS",
           "get_language", "set_language", "resolve_language", "catalogue", "translate", "_",
           "N_", "prose_number"]

#: The languages rsgeo speaks; the first is the language of the code and the default.
LANGUAGES = ("en", "pt_BR")
#: The environment variable that chooses the language when :func:`set_language` was not called.
ENVIRONMENT_VARIABLE = "RSGEO_LANG"
#: Where the compiled catalogues are: ``LOCALE_DIR / language / "LC_MESSAGES" / "rsgeo.mo"``.
LOCALE_DIR = Path(__file__).parent / "locale"
DOMAIN = "rsgeo"

_chosen = None
# the unknown language names already warned about (each once per process)
_warned = set()


def _normalise(language, source):
    """``language`` as one of :data:`LANGUAGES` ("pt-BR", "pt", "pt_BR.UTF-8" -> "pt_BR").

    Raises RsgeoError for a language rsgeo does not speak; :func:`_speakable` falls back.
    """
    if not isinstance(language, str):
        raise TypeError(f"{source} must be a language name such as 'pt_BR', "
                        f"got {type(language).__name__} {language!r}")
    name = language.split(".")[0].split("@")[0].replace("-", "_").strip()
    lowered = name.lower()
    if lowered in ("", "c", "posix") or lowered.startswith("en"):
        return "en"
    if lowered in ("pt", "pt_br"):
        return "pt_BR"
    raise RsgeoError(f"{source} is {language!r}, a language rsgeo does not speak: "
                     f"use one of {', '.join(LANGUAGES)}")


def _speakable(language, source):
    """``language`` as one of :data:`LANGUAGES`, never an error for a name rsgeo lacks.

    Another Portuguese (``pt_PT``) is spoken as Brazilian Portuguese, the one rsgeo has (its
    decimal comma is the same); any other language as English. Either way a UserWarning
    names the value and the languages rsgeo speaks, once per value: a message must reach
    its reader whatever ``RSGEO_LANG`` holds.
    """
    if not isinstance(language, str):
        language = str(language)
    try:
        return _normalise(language, source)
    except RsgeoError:
        pass
    lowered = language.split(".")[0].split("@")[0].replace("-", "_").strip().lower()
    spoken = "pt_BR" if lowered.startswith("pt_") else "en"
    if (source, language) not in _warned:
        _warned.add((source, language))
        import warnings

        warnings.warn(f"{source} is {language!r}, a language rsgeo does not speak; rsgeo "
                      f"speaks {', '.join(LANGUAGES)} and uses {spoken!r}", UserWarning,
                      stacklevel=4)
    return spoken


def set_language(language=None):
    """Choose the language of rsgeo's messages for this process.

    Parameters
    ----------
    language : str or None
        ``"en"`` or ``"pt_BR"`` (``"pt-BR"``, ``"pt"`` and a locale name such as
        ``"pt_BR.UTF-8"`` mean the same); None goes back to the environment variable
        ``RSGEO_LANG``, else English.

    Returns
    -------
    str
        The language now in use.

    Raises
    ------
    ValueError
        If ``language`` is not a language rsgeo speaks.

    Examples
    --------
    >>> from rsgeo.language import _, set_language
    >>> set_language("pt_BR")
    'pt_BR'
    >>> _("Play")
    'Reproduzir'
    >>> set_language("en")
    'en'
    """
    global _chosen
    _chosen = None if language is None else _normalise(language, "language")
    return get_language()


def get_language():
    """The language rsgeo speaks now.

    Returns
    -------
    str
        One of :data:`LANGUAGES`: the one given to :func:`set_language`, else the
        environment variable ``RSGEO_LANG``, else ``"en"``.

    Warns
    -----
    UserWarning
        Once, if ``RSGEO_LANG`` names a language rsgeo does not speak: another Portuguese
        (``pt_PT``) is spoken as ``pt_BR``, any other language as English.

    Examples
    --------
    >>> from rsgeo.language import get_language
    >>> get_language() in ("en", "pt_BR")
    True
    """
    if _chosen is not None:
        return _chosen
    return _speakable(os.environ.get(ENVIRONMENT_VARIABLE, "en"), ENVIRONMENT_VARIABLE)


def resolve_language(language):
    """``language`` normalised, or the current language when it is None.

    Parameters
    ----------
    language : str or None
        A language name (``"pt_BR"``, ``"pt-BR"``, ``"en_US.UTF-8"``...), or None.

    Returns
    -------
    str
        One of :data:`LANGUAGES`.

    Raises
    ------
    ValueError
        If ``language`` is not a language rsgeo speaks.

    Examples
    --------
    >>> resolve_language("pt-BR")
    'pt_BR'
    """
    return get_language() if language is None else _normalise(language, "language")


@functools.cache
def catalogue(language, domain=DOMAIN, locale_dir=LOCALE_DIR):
    """The compiled gettext catalogue of ``domain`` in ``language``.

    A package built on rsgeo (the course's own messages, say) keeps its catalogue in its own
    ``locale_dir`` and speaks the language rsgeo speaks.

    Parameters
    ----------
    language : str
        One of :data:`LANGUAGES`.
    domain : str, optional
        The catalogue's name (its ``.mo`` file's stem); default rsgeo's own messages.
    locale_dir : str or pathlib.Path, optional
        The folder holding ``<language>/LC_MESSAGES/<domain>.mo``; default rsgeo's.

    Returns
    -------
    gettext.NullTranslations
        The catalogue; English (no translation) when ``language`` is ``"en"`` or the compiled
        catalogue is missing.
    """
    if language == "en":
        return _gettext.NullTranslations()
    # an install without the compiled catalogue (see pyproject's package data) speaks English
    return _gettext.translation(domain, Path(locale_dir), languages=[language], fallback=True)


def translate(message, language=None, domain=DOMAIN, locale_dir=LOCALE_DIR):
    """``message`` in ``language`` (default: :func:`get_language`); English when not translated.

    Parameters
    ----------
    message : str
        The English text, as written in the code (a format string is translated unfilled).
    language : str, optional
        ``"en"`` or ``"pt_BR"``; default the current language.
    domain : str, optional
        The catalogue (default rsgeo's messages; a package built on rsgeo names its own).
    locale_dir : str or pathlib.Path, optional
        The folder of ``domain``'s catalogues (default rsgeo's).

    Returns
    -------
    str
        The translation, or ``message`` itself when the catalogue has none.

    Warns
    -----
    UserWarning
        Once per value, if ``language`` (or ``RSGEO_LANG``) is not a language rsgeo speaks:
        the message is then given in English (in ``pt_BR`` for another Portuguese).

    Examples
    --------
    >>> from rsgeo.language import translate
    >>> translate("Pause", "pt_BR")
    'Pausar'
    >>> translate("Pause", "en")
    'Pause'
    >>> translate("", "pt_BR")
    ''
    """
    # a message must reach its reader: an unknown language warns and falls back (_speakable)
    language = get_language() if language is None else _speakable(language, "language")
    if not message:                     # gettext("") is the catalogue's header, not a message
        return message
    return catalogue(language, domain, locale_dir).gettext(message)


_ = translate


class _Number:
    """A number that formats with the decimal and thousands separators of the language."""

    __slots__ = ("value",)

    def __init__(self, value):
        self.value = value

    def __format__(self, spec):
        text = format(self.value, spec)
        if get_language() == "pt_BR":
            text = text.translate(PORTUGUESE_SEPARATORS)
        return text

    def __str__(self):
        return format(self, "")

    def __repr__(self):
        return repr(self.value)


#: Python's separators swapped for Brazilian ones: "1,234.5" -> "1.234,5" (rsgeo's messages,
#: figure descriptions and figure texts all write numbers through this one table).
PORTUGUESE_SEPARATORS = str.maketrans({".": ",", ",": "."})


def prose_number(value):
    """``value`` for a message's ``{field}``: formatted with the language's separators.

    Parameters
    ----------
    value : int or float
        A number a message shows in prose, with any format spec (``{value:.2f}``,
        ``{scale:,.0f}``).

    Returns
    -------
    object
        A wrapper whose ``format`` gives a decimal comma and a thousands point when the
        language is ``pt_BR``, Python's point and comma otherwise.

    Examples
    --------
    >>> from rsgeo.language import prose_number, set_language
    >>> set_language("pt_BR")
    'pt_BR'
    >>> "{:.2f} m, 1:{:,.0f}".format(prose_number(22.514), prose_number(50000))
    '22,51 m, 1:50.000'
    >>> set_language("en")
    'en'
    >>> "{:.2f} m, 1:{:,.0f}".format(prose_number(22.514), prose_number(50000))
    '22.51 m, 1:50,000'
    """
    return _Number(value)


def N_(message):
    """Mark ``message`` for the catalogue without translating it yet; translate it when shown.

    Parameters
    ----------
    message : str
        English text.

    Returns
    -------
    str
        ``message`` unchanged.

    Examples
    --------
    >>> from rsgeo.language import N_, translate
    >>> translate(N_("Next frame"), "pt_BR")
    'Próximo quadro'
    """
    return message
