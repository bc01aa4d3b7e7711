"""What the course says to a student, in the language rsgeo speaks (:mod:`rsgeo.language`).

The exercises' verdicts, messages and hints are written in English in the code and wrapped in
:func:`_` (a check's hints are marked with :func:`N_` in its declaration and translated when the
check gives them, before their fields are filled); their Portuguese lives in the course's own
gettext catalogue ``rsgeo_course/locale/pt_BR/LC_MESSAGES/rsgeo_course.po``, shipped compiled
(``rsgeo_course.mo``, made by ``locales/update.py``, which collects the messages; a test checks
that both are current). The language is rsgeo's: :func:`rsgeo.language.set_language`, else the
environment variable ``RSGEO_LANG``, else English.
"""

from pathlib import Path

from rsgeo.language import (
    N_,
    PORTUGUESE_SEPARATORS,
    get_language,
    prose_number,
    resolve_language,
    set_language,
)
from rsgeo.language import translate as rsgeo_translate

__all__ = ["DOMAIN", "LOCALE_DIR", "VERDICT_LABELS", "translate", "_", "N_", "prose_number",
           "get_language", "set_language", "resolve_language", "PORTUGUESE_SEPARATORS"]

#: The course's catalogues: its messages (``rsgeo_course``) and its figures' texts.
LOCALE_DIR = Path(__file__).parent / "locale"
DOMAIN = "rsgeo_course"


def translate(message, language=None):
    """``message`` in ``language`` (default: rsgeo's language); English when not translated.

    Parameters
    ----------
    message : str
        The English text, as written in the code (a format string is translated unfilled).
    language : str, optional
        ``"en"`` or ``"pt_BR"``; default the current language.

    Returns
    -------
    str
        The translation, or ``message`` itself when the catalogue has none.

    Examples
    --------
    >>> translate("Not yet", "pt_BR")
    'Ainda não'
    >>> translate("Not yet", "en")
    'Not yet'
    """
    return rsgeo_translate(message, language, DOMAIN, LOCALE_DIR)


_ = translate

#: The verdicts an exercise can get, in a check (:class:`rsgeo_course.exercises.Verdict`) or in
#: a class's grading run (``exercises/grade.py``); ``translate(label)`` shows one to a student.
VERDICT_LABELS = (N_("Correct"), N_("Not yet"), N_("not attempted"), N_("error"), N_("timed out"))
