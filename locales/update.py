"""Regenerate the message templates from the English sources and update the Portuguese catalogues.

Run from the repository's folder, after any change to the English text (pages, notebooks'
Markdown, rsgeo's messages):

    . .venv/bin/activate && python locales/update.py

1. The book: a gettext build of the current English sources (``_config.yml``, notebooks not
   executed, one template per page: ``gettext_compact = False``) into ``_build/gettext``, then
   ``sphinx-intl update -l pt_BR -d locales``: new paragraphs arrive untranslated, changed ones
   fuzzy (with the old translation as a suggestion), removed ones are dropped.
   Docstrings on the API page are not in the templates (book/_ext/i18n_book.py).
2. rsgeo: the messages wrapped in ``_()`` / ``N_()`` in rsgeo/ (:func:`rsgeo_messages`; the
   exercise checks' hints are ``N_()`` in their declarations) update
   ``rsgeo/locale/pt_BR/LC_MESSAGES/rsgeo.po``, which is compiled to \
``rsgeo.mo`` (shipped, so that rsgeo needs no Babel at run time;
   tests/test_i18n.py checks that it is current).
3. ``_config_pt.yml`` is remade from ``_config.yml`` (:func:`portuguese_config`).

Then translate what ``python locales/update.py --stat`` (or tests/test_i18n.py) reports missing.
"""

import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LOCALES = ROOT / "locales"
LANGUAGE = "pt_BR"
RSGEO_PO = ROOT / "rsgeo" / "locale" / LANGUAGE / "LC_MESSAGES" / "rsgeo.po"
#: gettext build settings: the English text only, nothing executed
GETTEXT_OVERRIDES = {"nb_execution_mode": "off", "gettext_compact": False,
                     "gettext_additional_targets": [], "latex_individualpages": False}


def build_templates(output, quiet=True):
    """Write one .pot per page of the English book into ``output`` (a folder); return ``output``.

    Raises
    ------
    RuntimeError
        If the gettext build fails.
    """
    from jupyter_book.sphinx import build_sphinx

    output = Path(output)
    if output.exists():
        shutil.rmtree(output)
    result = build_sphinx(ROOT, output, noconfig=True, path_config=str(ROOT / "_config.yml"),
                          confoverrides=dict(GETTEXT_OVERRIDES), builder="gettext",
                          freshenv=True, quiet=quiet, really_quiet=quiet,
                          doctreedir=output.parent / (output.name + ".doctrees"))
    if result != 0:
        raise RuntimeError(f"the gettext build into {output} failed: {result!r}")
    return output


def update_book(templates, only_new=False, pages=None):
    """``sphinx-intl update`` of every page's catalogue from ``templates``; with ``only_new``,
    only pages that have no catalogue yet get one (the others are left as they are); with
    ``pages`` (names such as ``book/04_resampling``), only those pages' catalogues."""
    if pages:
        chosen = templates.parent / (templates.name + ".pages")
        shutil.rmtree(chosen, ignore_errors=True)
        for page in pages:
            pot = templates / (page + ".pot")
            if not pot.exists():
                raise ValueError(f"no page {page!r} in the book (expected {pot})")
            (chosen / page).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(pot, chosen / (page + ".pot"))
        templates = chosen
    elif only_new:
        new = templates.parent / (templates.name + ".new")
        shutil.rmtree(new, ignore_errors=True)
        for pot in templates.rglob("*.pot"):
            name = pot.relative_to(templates)
            if name.parts[0] != "_static" and not (
                    LOCALES / LANGUAGE / "LC_MESSAGES" / name.with_suffix(".po")).exists():
                (new / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(pot, new / name)
        if not new.exists():
            return
        templates = new
    subprocess.run([sys.executable, "-m", "sphinx_intl", "update", "-p", str(templates),
                    "-l", LANGUAGE, "-d", str(LOCALES)], check=True, cwd=ROOT)


def rsgeo_messages():
    """``{message: (file, line)}``: every message rsgeo can show a student in its language.

    The messages wrapped in ``_()`` or ``N_()`` anywhere in rsgeo/ (a message is translated
    before it is filled in, so the marker holds the whole format string).
    """
    from babel.messages.extract import extract_from_dir

    messages = {}
    for filename, line, message, _, _ in extract_from_dir(
            str(ROOT / "rsgeo"), keywords={"_": None, "N_": None}):
        messages.setdefault(message, (f"rsgeo/{filename}", line))
    return messages


def update_rsgeo():
    """Bring rsgeo.po in line with :func:`rsgeo_messages` (new messages untranslated, gone ones
    dropped, none fuzzy-matched), then compile it."""
    from babel.messages.catalog import Catalog
    from babel.messages.pofile import read_po, write_po

    template = Catalog(project="rsgeo", fuzzy=False)
    for message in rsgeo_messages():
        template.add(message)
    if RSGEO_PO.exists():
        with open(RSGEO_PO, "rb") as handle:
            catalogue = read_po(handle, locale=LANGUAGE)
    else:
        catalogue = Catalog(locale=LANGUAGE, project="rsgeo", fuzzy=False,
                            language_team="pt_BR <LL@li.org>")
        RSGEO_PO.parent.mkdir(parents=True, exist_ok=True)
    catalogue.update(template, no_fuzzy_matching=True, update_header_comment=False)
    with open(RSGEO_PO, "wb") as handle:
        write_po(handle, catalogue, width=96, no_location=True, sort_output=True,
                 ignore_obsolete=True)
    compile_rsgeo()


def compile_rsgeo():
    """Compile rsgeo.po to rsgeo.mo beside it (translated, not fuzzy entries only)."""
    from babel.messages.mofile import write_mo
    from babel.messages.pofile import read_po

    with open(RSGEO_PO, "rb") as handle:
        catalogue = read_po(handle, locale=LANGUAGE)
    with open(RSGEO_PO.with_suffix(".mo"), "wb") as handle:
        write_mo(handle, catalogue, use_fuzzy=False)


PORTUGUESE_CONFIG_HEADER = """\
# The Portuguese edition (Brazilian Portuguese): the same book as _config.yml, built from the same
# English sources with the translations in locales/pt_BR/LC_MESSAGES (gettext, see \
locales/update.py).
# Build (after the English book, whose notebook executions it reuses):
#   jupyter-book build . --config _config_pt.yml --path-output _build/pt_BR -W -n --keep-going
# -> _build/pt_BR/_build/html. Made from _config.yml by `python locales/update.py --config`:
# everything is _config.yml's except the lines marked "pt_BR" (tests/test_i18n.py checks it).
"""
PORTUGUESE_TITLE = "Correção geométrica de imagens de sensoriamento remoto"
PORTUGUESE_SETTINGS = """\
    # pt_BR: the translations, one catalogue per page (locales/pt_BR/LC_MESSAGES/book/intro.po ...)
    locale_dirs:
      - locales
    gettext_compact: false
    # pt_BR: the switch back to the English book (_build/html), relative: it works offline
    i18n_other_book: ../../../html
    i18n_other_language: en
    i18n_other_label: English
    # pt_BR: every notebook runs again with RSGEO_LANG=pt_BR (figures, widgets, tables, verdicts
    # and hints in Portuguese), cached apart from the English executions
    i18n_execute_in_language:
      - "*"
    # pt_BR: the toggle of a hidden cell (the book hides inputs only: hide-input)
    nb_code_prompt_show: Mostrar o código da célula
    nb_code_prompt_hide: Ocultar o código da célula
    # pt_BR: said once, on the first page
    i18n_root_note:
      - Código em inglês, números à brasileira
      - >-
        O código dos notebooks (nomes, comentários) fica em inglês, assim como o que ele imprime:
        ali os números aparecem como o Python os imprime, com ponto decimal (0.5). No texto, nas
        figuras e nos quadros, os números seguem o uso brasileiro (0,5 m; 10.000 pares; 1:25.000),
        e as figuras, os controles interativos e as respostas das verificações dos exercícios
        (Correto, Ainda não, Dica) estão em português. O glossário dá cada termo nas duas
        línguas. Nos notebooks baixados desta edição, o rsgeo também fala português: vereditos,
        dicas, mensagens de erro e rótulos das figuras.
"""


def portuguese_config(english):
    """The text of ``_config_pt.yml`` made from the text of ``_config.yml``.

    Raises
    ------
    ValueError
        If ``_config.yml`` lacks a line this relies on (title, execute_notebooks, the
        i18n_book settings, language: en).
    """
    lines, out, skipping = english.splitlines(keepends=True), [], False
    for line in lines:
        if line.startswith("# Jupyter Book 1 configuration"):
            continue
        if line.startswith("title:"):
            out.append(f"title: {PORTUGUESE_TITLE}    # pt_BR\n")
            continue
        if line.startswith("author: The rsgeo course authors"):
            out.append("author: Os autores do curso rsgeo    # pt_BR\n")
            continue
        if skipping:                          # the English book's own i18n settings
            if line.startswith("    i18n_other_") or line.lstrip().startswith("# The Portuguese "
                                                                                "edition") \
                    or line.lstrip().startswith("# links to the same page"):
                continue
            skipping = False
        if line.startswith("  config:") and out and "i18n_book" in out[-1]:
            out += [line, PORTUGUESE_SETTINGS]
            skipping = True
            continue
        if line.strip() == "language: en":
            out.append("    language: pt_BR                 # pt_BR: <html lang=\"pt-BR\">, "
                       "Sphinx's and the theme's own labels\n")
            continue
        out.append(line)
        if line.startswith("  execute_notebooks:"):
            out.append("__CACHE__")
    text = "".join(out)
    # after the execute_notebooks comment's continuation lines
    cache = ("  cache: _build/.jupyter_cache  # pt_BR: the English build's cache, which keeps "
             "the Portuguese executions apart\n")
    text = re.sub(r"__CACHE__((?:\s{20,}#.*\n)*)", lambda m: m.group(1) + cache, text)
    for needed in ("# pt_BR\n", "locale_dirs", "language: pt_BR", "cache: _build/.jupyter_cache"):
        if needed not in text:
            raise ValueError(f"_config.yml has changed shape: could not place {needed.strip()!r} "
                             "in _config_pt.yml; edit locales/update.py's portuguese_config")
    return PORTUGUESE_CONFIG_HEADER + text


def write_portuguese_config():
    (ROOT / "_config_pt.yml").write_text(portuguese_config((ROOT / "_config.yml").read_text()))


def statistics():
    """Print, per catalogue, how many entries are translated, fuzzy and untranslated."""
    from babel.messages.pofile import read_po

    missing = 0
    for po in sorted([*LOCALES.glob(f"{LANGUAGE}/LC_MESSAGES/**/*.po"), RSGEO_PO]):
        with open(po, "rb") as handle:
            entries = [message for message in read_po(handle) if message.id]
        fuzzy = sum(message.fuzzy for message in entries)
        empty = sum(not message.string for message in entries)
        missing += fuzzy + empty
        print(f"{po.relative_to(ROOT)}: {len(entries) - fuzzy - empty} translated, "
              f"{fuzzy} fuzzy, {empty} untranslated")
    return missing


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stat", action="store_true", help="only print the statistics")
    parser.add_argument("--config", action="store_true",
                        help="only remake _config_pt.yml from _config.yml")
    parser.add_argument("--new-pages", action="store_true",
                        help="only make the catalogues of pages that have none (the others, "
                             "being translated, are left alone)")
    parser.add_argument("--page", action="append", metavar="PAGE",
                        help="only update this page's catalogue (e.g. book/04_resampling; "
                             "repeatable): the templates are built in a folder of their own, "
                             "so that two people can update different pages at once")
    parser.add_argument("--rsgeo", action="store_true",
                        help="only update and compile rsgeo's own catalogue (rsgeo.po)")
    parser.add_argument("--templates", metavar="FOLDER",
                        help="only write the English book's templates (.pot) into FOLDER")
    arguments = parser.parse_args(argv)
    if arguments.templates:
        build_templates(Path(arguments.templates))
        return 0
    if arguments.config:
        write_portuguese_config()
        return 0
    if arguments.rsgeo:
        update_rsgeo()
        return 0
    if arguments.page:
        import tempfile

        # inside _build, like the full update, so that the catalogues' location comments stay
        # relative to the repository
        (ROOT / "_build").mkdir(exist_ok=True)
        with tempfile.TemporaryDirectory(prefix="gettext-", dir=ROOT / "_build") as folder:
            try:
                update_book(build_templates(Path(folder)), pages=arguments.page)
            finally:
                shutil.rmtree(folder + ".doctrees", ignore_errors=True)
                shutil.rmtree(folder + ".pages", ignore_errors=True)
                Path(folder).mkdir(exist_ok=True)       # TemporaryDirectory removes it
        return 0
    if not arguments.stat:
        write_portuguese_config()
        update_book(build_templates(ROOT / "_build" / "gettext"), only_new=arguments.new_pages)
        if not arguments.new_pages:
            update_rsgeo()
    return 1 if statistics() else 0


if __name__ == "__main__":
    sys.exit(main())
