"""Regenerate the message templates from the English sources and update the Portuguese catalogues.

Run from the repository's folder, after any change to the English text (pages, notebooks'
Markdown, rsgeo's messages):

    . .venv/bin/activate && python locales/update.py

1. The book: a gettext build of the current English sources (``_config.yml``, notebooks not
   executed, one template per page: ``gettext_compact = False``) into ``_build/gettext``, then
   ``sphinx-intl update -l pt_BR -d locales``: new paragraphs arrive untranslated, changed ones
   fuzzy (with the old translation as a suggestion), removed ones are dropped.
   Docstrings on the API page are not in the templates (book/_ext/i18n_book.py).
2. rsgeo and the course: the messages wrapped in ``_()`` / ``N_()`` in rsgeo/ and in
   rsgeo_course/ (:func:`messages_of`; the exercise checks' hints are ``N_()`` in their
   declarations) update ``rsgeo/locale/pt_BR/LC_MESSAGES/rsgeo.po`` and
   ``rsgeo_course/locale/pt_BR/LC_MESSAGES/rsgeo_course.po``, compiled to ``.mo`` files
   (shipped, so that neither needs Babel at run time; tests/test_i18n.py checks that they are
   current).
3. ``_config_pt.yml`` is remade from ``_config.yml`` (:func:`portuguese_config`).
4. The figures (``--figures``, also part of the full update): the texts the notebooks' code gives
   matplotlib (titles, axis labels, legends, colour-bar labels, text and annotations) and the
   column and index names of the tables they build, found statically (:func:`figure_messages`;
   an f-string is a template, each field a ``{}``), update
   ``rsgeo_course/locale/pt_BR/LC_MESSAGES/rsgeo_figures.po``, compiled to
   ``rsgeo_figures.mo``, which :mod:`rsgeo_course.figure_language` applies to every figure the
   Portuguese book renders.

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
COURSE_PO = ROOT / "rsgeo_course" / "locale" / LANGUAGE / "LC_MESSAGES" / "rsgeo_course.po"
FIGURES_PO = COURSE_PO.with_name("rsgeo_figures.po")
#: Each package's catalogue of messages (the figures' texts are the course's, apart)
MESSAGE_PO = {"rsgeo": RSGEO_PO, "rsgeo_course": COURSE_PO}
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


def messages_of(package="rsgeo"):
    """``{message: (file, line)}``: every message ``package`` can show in its language.

    The messages wrapped in ``_()`` or ``N_()`` anywhere in the package's folder (a message is
    translated before it is filled in, so the marker holds the whole format string): rsgeo's
    (errors, figure labels, widget controls) or the course's (``rsgeo_course``: the exercise
    checks' verdicts and hints, the figure descriptions).
    """
    from babel.messages.extract import extract_from_dir

    messages = {}
    for filename, line, message, _, _ in extract_from_dir(
            str(ROOT / package), keywords={"_": None, "N_": None}):
        messages.setdefault(message, (f"{package}/{filename}", line))
    return messages


def rsgeo_messages():
    """``{message: (file, line)}``: every message rsgeo can show in its language."""
    return messages_of("rsgeo")


def course_messages():
    """``{message: (file, line)}``: every message the course's package can show."""
    return messages_of("rsgeo_course")


def update_messages(package="rsgeo"):
    """Bring ``package``'s catalogue in line with :func:`messages_of` (new messages
    untranslated, gone ones dropped, none fuzzy-matched), then compile it. A message new to
    one catalogue takes the translation the other one holds, if any (a message that moves
    between rsgeo and the course keeps its Portuguese)."""
    from babel.messages.catalog import Catalog
    from babel.messages.pofile import read_po, write_po

    po = MESSAGE_PO[package]
    template = Catalog(project=package, fuzzy=False)
    for message in messages_of(package):
        template.add(message)
    if po.exists():
        with open(po, "rb") as handle:
            catalogue = read_po(handle, locale=LANGUAGE)
    else:
        catalogue = Catalog(locale=LANGUAGE, project=package, fuzzy=False,
                            language_team="pt_BR <LL@li.org>")
        po.parent.mkdir(parents=True, exist_ok=True)
    catalogue.update(template, no_fuzzy_matching=True, update_header_comment=False)
    known = {}
    for other in MESSAGE_PO.values():
        if other != po and other.exists():
            with open(other, "rb") as handle:
                known.update({entry.id: entry.string for entry in read_po(handle)
                              if entry.id and entry.string and not entry.fuzzy})
    for entry in catalogue:
        if entry.id and not entry.string and entry.id in known:
            entry.string = known[entry.id]
    with open(po, "wb") as handle:
        write_po(handle, catalogue, width=96, no_location=True, sort_output=True,
                 ignore_obsolete=True)
    compile_catalogue(po)


def update_rsgeo():
    """Bring rsgeo.po and rsgeo_course.po in line with their packages' messages."""
    for package in MESSAGE_PO:
        update_messages(package)


# -- The figures' texts ---------------------------------------------------------------------

#: The notebooks whose code draws the figures and tables of the book.
FIGURE_NOTEBOOKS = ("book/*.ipynb", "exercises/*.ipynb")
#: Calls whose positional string arguments are a figure's text.
TEXT_CALLS = {"set_title", "set_xlabel", "set_ylabel", "suptitle", "supxlabel", "supylabel",
              "title", "xlabel", "ylabel", "text", "figtext", "annotate", "set_text", "set_label",
              "legend", "quiverkey", "set_xticklabels", "set_yticklabels", "table",
              # tables: a Series' or an axis' name
              "rename", "rename_axis"}
#: Keyword arguments whose string value is a figure's or a table's text.
TEXT_KEYWORDS = {"title", "label", "labels", "xlabel", "ylabel", "xticklabels", "yticklabels",
                 "text", "s", "name", "names",
                 "columns", "index", "colLabels", "rowLabels", "cellText"}
#: rsgeo.plot's functions whose positional string arguments are a figure's text
#: (``show_image(ax, image, transform, "title")``).
PLOT_CALLS = {"show_image"}
#: String methods a label may be made with from a name's values (``column.removesuffix(...)``).
STRING_METHODS = {"removesuffix", "removeprefix", "strip", "capitalize", "title", "lower",
                  "upper"}
#: Labels the notebooks show that their code does not spell: the columns and rows of tables
#: rsgeo returns (``fit.table(...)``, ``georef.datum_grids()``, ``transforms.kinds_table()``)
#: and of the benchmarks' result files the chapters read. Their code names stay English (a
#: student indexes ``table["estimate"]``); the Portuguese book shows them translated.
LIBRARY_TEXTS = (
    "estimate", "true", "error / std", "parameters", "codes", "accuracy", "grids", "available",
    "omega", "phi", "kappa", "polynomial 2",
    # benchmarks/ga_experiments (chapter 6)
    "optimum is the truth (%)", "GA finds the truth (%)", "GA finds the optimum (%)", "fitness",
    "one-to-one", "optimum", "FA of the optimum", "optimum reached (%)", "exact matches (%)",
    "segments right (%)", "mean s/run", "worst s/run", "matcher",
    # benchmarks/registration (chapter 6c)
    "success (%)", "median error (px)", "worst error (px)", "median error (m)",
    "tie points (median)", "correlation", "tie points", "windows", "pair", "se dx (px)",
    "se dy (px)", "sd dx (px)", "sd dy (px)", "one segment at 31%",
    "QAP (SciPy FAQ, 20 restarts)",
    "max FA over all {}^{} solutions by branch and bound: certified in {} of {} seeds; it is the "
    "truth in {}",
    "max FA over all {}^{} solutions by branch and bound: certified in {} of {} seeds, else the "
    "best FA found by any search; it is the truth in {}",
    # the kinds of an exercise check's hints (the teaching guide's table)
    "mistake", "general",
    # computed from another label (f"{name.split(',')[0]}: histograms", chapter 5)
    "3 × 3 OLS (the paper)",
)
#: Keyword arguments holding matplotlib settings, never text (their dicts' keys are options).
SETTING_KEYWORDS = {"bbox", "arrowprops", "gridspec_kw", "subplot_kw", "fontdict", "props",
                    "textprops", "wedgeprops", "boxprops", "kwargs", "style", "formatter"}


def _template(node):
    """The message of a string node: a constant as it is, an f-string / ``"...".format`` /
    ``"..." % ...`` with ``{}`` for each field (literal braces doubled); None for anything else."""
    import ast
    import string

    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value.replace("{", "{{").replace("}", "}}")
    if isinstance(node, ast.JoinedStr):
        parts = []
        for value in node.values:
            if isinstance(value, ast.Constant):
                parts.append(str(value.value).replace("{", "{{").replace("}", "}}"))
            else:
                parts.append("{}")
        return "".join(parts)
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
            and node.func.attr == "format" and isinstance(node.func.value, ast.Constant)
            and isinstance(node.func.value.value, str)):
        try:
            fields = list(string.Formatter().parse(node.func.value.value))
        except ValueError:
            return None
        return "".join(literal.replace("{", "{{").replace("}", "}}")
                       + ("{}" if name is not None else "") for literal, name, _, _ in fields)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mod):
        text = _template(node.left)
        return None if text is None else re.sub(r"%[-+ 0#]*\d*(?:\.\d+)?[sdifgeErx]", "{}", text)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _template(node.left), _template(node.right)
        if left is not None and right is not None:
            return left + right
    return None


def _is_text(message):
    """Whether a collected string is words a reader reads (not a colour, a marker, a field)."""
    from matplotlib.colors import is_color_like

    words = message.replace("{}", " ")
    # a template needs a letter (``"h = {} m"``), a constant a word
    if not re.search(r"[^\W\d_]{2,}" if words == message else r"[^\W\d_]", words) \
            or is_color_like(message):
        return False
    # an identifier (as96_max, HEIGHT_SCALE), a file's name
    return not re.fullmatch(r"[A-Za-z][A-Za-z0-9]*(_[A-Za-z0-9]+)+|\S+\.(ipynb|py|csv|tif)",
                            message)


def _strings(node, names, seen=None):
    """The messages a node may evaluate to: string nodes, both arms of a conditional, the
    strings of a literal container, and the values a name is given in the notebook."""
    import ast

    seen = set() if seen is None else seen
    message = _template(node)
    if message is not None:
        # an f-string's fields may be texts too (f"{pass_direction} pass"): the values they
        # are given, so that a template's fields are translated
        fields = [found for value in getattr(node, "values", ())
                  if isinstance(value, ast.FormattedValue)
                  for found in _strings(value.value, names, seen)]
        return [message, *fields]
    if isinstance(node, ast.IfExp):
        return _strings(node.body, names, seen) + _strings(node.orelse, names, seen)
    if isinstance(node, (ast.List, ast.Tuple, ast.Set)):
        return [found for element in node.elts for found in _strings(element, names, seen)]
    if isinstance(node, ast.Dict):
        return [found for part in (*node.keys, *node.values) if part is not None
                for found in _strings(part, names, seen)]
    if isinstance(node, ast.Name) and node.id not in seen:
        seen.add(node.id)
        return [found for value in names.get(node.id, ()) for found in _strings(value, names,
                                                                                 seen)]
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
            node.func.attr in ("items", "keys", "values"):
        return _strings(node.func.value, names, seen)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and \
            node.func.id in ("zip", "enumerate", "reversed", "sorted", "list", "tuple"):
        return [found for argument in node.args for found in _strings(argument, names, seen)]
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):    # list + [(...)]
        return _strings(node.left, names, seen) + _strings(node.right, names, seen)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
            node.func.attr in STRING_METHODS and all(
                isinstance(argument, ast.Constant) for argument in node.args):
        # label=column.removesuffix(" (px)"): the method applied to the name's values
        arguments = [argument.value for argument in node.args]
        return [getattr(found, node.func.attr)(*arguments)
                for found in _strings(node.func.value, names, seen)]
    return []


def _bound_names(tree):
    """``{name: [value nodes]}``: what each name is assigned or iterates over in ``tree``."""
    import ast

    names = {}

    def bind(target, value):
        if isinstance(target, ast.Name):
            names.setdefault(target.id, []).append(value)
        elif isinstance(target, (ast.Tuple, ast.List)):
            for element in target.elts:    # a loop's unpacked tuples: any of their strings
                bind(element, value)

    for node in ast.walk(tree):
        if isinstance(node, ast.Assign):
            for target in node.targets:
                bind(target, node.value)
        elif isinstance(node, (ast.AnnAssign, ast.AugAssign)) and node.value is not None:
            bind(node.target, node.value)
        elif isinstance(node, (ast.For, ast.comprehension)):
            bind(node.target, node.iter)
    return names


def _code_cells(path):
    """``[(cell number, source)]`` of a notebook's code cells, IPython magics commented out."""
    import json

    notebook = json.loads(Path(path).read_text(encoding="utf-8"))
    cells = []
    for number, cell in enumerate(notebook["cells"], 1):
        if cell["cell_type"] == "code":
            source = cell["source"]
            source = "".join(source) if isinstance(source, list) else source
            cells.append((number, re.sub(r"(?m)^(\s*)([%!])", r"\1#\2", source)))
    return cells


def figure_messages(paths=None):
    """``{message: (notebook, cell number)}``: every text the notebooks' code gives a figure or
    a table, for the figures' catalogue (:mod:`rsgeo_course.figure_language` translates them).

    Collected statically from each code cell's syntax tree: the string arguments of matplotlib's
    text calls (:data:`TEXT_CALLS`) and the string values of the text keywords
    (:data:`TEXT_KEYWORDS`: ``title=``, ``label=``, ``xlabel=``, ``columns=``, ``index=``,
    ``name=`` ...) of any call, following a name to the values it is assigned or loops over in
    the notebook; in notebooks that use pandas, the string keys of dict literals (a table's
    columns), the texts in dict values and string subscripts (a column or row named) too. An
    f-string, ``"...".format(...)`` or ``"..." % ...`` is a template with ``{}`` for each
    field. Strings with no word (numbers, ``{}`` alone), colours and identifiers are left out;
    :data:`LIBRARY_TEXTS` are added (the labels of tables rsgeo and the benchmarks make).
    """
    import ast
    import glob

    if paths is None:
        paths = sorted(Path(found) for pattern in FIGURE_NOTEBOOKS
                       for found in glob.glob(str(ROOT / pattern)))
    messages = {}
    for path in paths:
        cells = []
        for number, source in _code_cells(path):
            try:
                cells.append((number, ast.parse(source)))
            except SyntaxError:
                continue
        names = _bound_names(ast.Module(body=[node for _, tree in cells for node in tree.body],
                                        type_ignores=[]))
        where = Path(path).resolve().relative_to(ROOT).as_posix()
        # a notebook that uses pandas: any cell may name a table's columns and rows
        uses_pandas = any("pandas" in ast.unparse(tree) for _, tree in cells)
        for number, tree in cells:
            found = []
            tables = uses_pandas
            settings = {id(value) for node in ast.walk(tree) if isinstance(node, ast.keyword)
                        and (node.arg in SETTING_KEYWORDS or str(node.arg).endswith("_kw"))
                        for value in [node.value]}
            for node in ast.walk(tree):
                if isinstance(node, ast.Call):
                    if isinstance(node.func, ast.Attribute) and node.func.attr in TEXT_CALLS \
                            or isinstance(node.func, ast.Name) and node.func.id in PLOT_CALLS:
                        for argument in node.args:
                            found += _strings(argument, names)
                    for keyword in node.keywords:
                        if keyword.arg in TEXT_KEYWORDS:
                            found += _strings(keyword.value, names)
                        elif keyword.arg == "columns" or (
                                isinstance(node.func, ast.Attribute)
                                and node.func.attr in ("rename", "agg")):
                            found += _strings(keyword.value, names)
                    if isinstance(node.func, ast.Attribute) and node.func.attr == "agg":
                        for argument in node.args:
                            found += _strings(argument, names)
                elif tables and isinstance(node, ast.Dict) and id(node) not in settings:
                    found += [message for key in node.keys if key is not None
                              for message in [_template(key)] if message is not None]
                    # a row's label given by a loop's name ({"GCPs": label}) may become an
                    # index label
                    found += [message for value in node.values if isinstance(value, ast.Name)
                              for message in _strings(value, names)]
                    # a table's words ({"independent of": "nothing"})
                    found += [message for value in node.values
                              for element in getattr(value, "elts", [value])
                              if isinstance(element, (ast.Constant, ast.JoinedStr))
                              for message in [_template(element)] if message is not None]
                elif tables and isinstance(node, ast.Subscript):
                    # a column or row named by subscript: row[f"PEC at 1:{scale:,} (m)"] = ...,
                    # passes["median shift (px)"], table.loc["RPC as delivered (no GCP)"]
                    found += _strings(node.slice, names)
            for message in found:
                if _is_text(message):
                    messages.setdefault(message, (where, number))
    for message in LIBRARY_TEXTS:
        messages.setdefault(message, ("locales/update.py", 0))
    return messages


def update_figures():
    """Bring rsgeo_figures.po in line with :func:`figure_messages` (new texts untranslated, gone
    ones dropped, none fuzzy-matched), then compile it."""
    from babel.messages.catalog import Catalog
    from babel.messages.pofile import read_po, write_po

    template = Catalog(project="rsgeo figures", fuzzy=False)
    messages = figure_messages()
    for message, (notebook, cell) in messages.items():
        template.add(message, locations=[(notebook, cell)])
    if FIGURES_PO.exists():
        with open(FIGURES_PO, "rb") as handle:
            catalogue = read_po(handle, locale=LANGUAGE)
        if {message.id for message in catalogue if message.id} == set(messages):
            template.creation_date = catalogue.creation_date   # unchanged: no new header date
    else:
        catalogue = Catalog(locale=LANGUAGE, project="rsgeo figures", fuzzy=False,
                            language_team="pt_BR <LL@li.org>")
    catalogue.update(template, no_fuzzy_matching=True, update_header_comment=False)
    with open(FIGURES_PO, "wb") as handle:
        write_po(handle, catalogue, width=96, sort_output=True, ignore_obsolete=True)
    compile_catalogue(FIGURES_PO)


def compile_catalogue(po):
    """Compile a catalogue (.po) to the .mo beside it (translated, not fuzzy entries only)."""
    from babel.messages.mofile import write_mo
    from babel.messages.pofile import read_po

    with open(po, "rb") as handle:
        catalogue = read_po(handle, locale=LANGUAGE)
    with open(Path(po).with_suffix(".mo"), "wb") as handle:
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
        if line.strip() == "bibtex_reference_style: author_year":
            out.append('    bibtex_reference_style: author_year_pt    # pt_BR: "Meneses e '
                       'Almeida, 2012", "s.d." (book/_ext/bibliography_pt.py)\n')
            continue
        if line.strip() == "bibtex_default_style: plain":
            out.append("    bibtex_default_style: plain_pt    # pt_BR: the bibliography in "
                       "Portuguese, with references.bib's *_pt fields\n")
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
    for po in sorted([*LOCALES.glob(f"{LANGUAGE}/LC_MESSAGES/**/*.po"), RSGEO_PO, COURSE_PO,
                      FIGURES_PO]):
        if not po.exists():
            continue
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
                        help="only update and compile the messages' catalogues (rsgeo.po, "
                             "rsgeo_course.po)")
    parser.add_argument("--figures", action="store_true",
                        help="only update and compile the figures' catalogue (rsgeo_figures.po) "
                             "from the notebooks' code")
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
    if arguments.figures:
        update_figures()
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
            update_figures()
    return 1 if statistics() else 0


if __name__ == "__main__":
    sys.exit(main())
