"""Print the course to PDF, in the instructor's or the student edition, in English or in
Portuguese: Jupyter Book's single-page HTML, printed by Chromium.

    python exercises/print_course.py                      # the instructor's edition, English
    python exercises/print_course.py --edition student    # the student edition
    python exercises/print_course.py --language pt_BR     # the Portuguese book's
    python exercises/print_course.py --edition both --language both    # the four PDFs
    options: [--out PDF] [--with-api] [--only DOC ...] [--build-dir DIR]

The two editions, each labelled on its cover and in every page's running header:

- **Instructor's edition** (default; ``_build/pdf/rsgeo-course-instructor.pdf``): the course's
  book as built, with the exercises' worked solutions, the verdict of every check and the
  *Teaching guide*. Keep it with the instructors.
- **Student edition** (``_build/pdf/rsgeo-course-student.pdf``): printed from the student
  edition that ``exercises/make_student_edition.py`` makes (copied to
  ``DIR/_build/print-student/``): no solutions, no verdicts, since its exercises are not
  executed, and no teaching guide (``make_student_edition.INSTRUCTORS_ONLY``).

**Both languages.** ``--language pt_BR`` prints the Portuguese book (``_config_pt.yml``: its
catalogues, and the notebooks' executions with ``RSGEO_LANG=pt_BR``, from the Portuguese
build's cache) to ``rsgeo-course-EDITION-pt_BR.pdf``, with its cover, contents and running
header in Portuguese; ``both`` prints each language.

Options: ``--out`` the PDF to write (one edition and one language only); ``--with-api`` adds
the API reference, left out by default (it is half of the pages, and the HTML book has it);
``--only book/03_evaluating_models ...`` prints only those pages of ``_toc.yml`` (with the
introduction), for a quick look or a test.

How:

1. ``jupyter-book build --builder singlehtml`` writes the book as one page
   (``DIR/_build/singlehtml/``, the Portuguese one ``DIR/_build/pt_BR/_build/singlehtml/``; DIR
   is the repository by default), from a table of contents without the pages left out
   (``--toc``). The notebooks' executions come from the HTML build's cache,
   ``_build/.jupyter_cache``, so nothing runs again when the HTML books are current.
2. Debian's Chromium (``apt-get install chromium``; no browser is downloaded), headless and
   driven by Playwright, opens that page from a local web server, waits until MathJax (served
   from the book, ``book/_vendor/mathjax``) has typeset every equation and every image has
   loaded, prepares the page for paper and prints it to A4 with page numbers and a PDF outline
   (bookmarks from the headings). An equation left as TeX source stops the script with an
   error instead of printing it.
3. It prints twice: the first print tells on which page each entry of the contents starts
   (an invisible mark at each one, found with poppler's ``pdftotext``: ``apt-get install
   poppler-utils``), the second prints the contents with those page numbers. A page left
   blank, which the preparation below prevents, stops the script with an error naming it.

Preparing for paper (``PREPARE_FOR_PRINT`` and ``PRINT_CSS``): a cover (course title, edition,
date, the commit printed, or the package's version when the course is a copy without git
history such as a ``git archive``, language) and a numbered table of contents with page
numbers come first, each chapter starts a new sheet (the break is on the chapter's anchor, so
that no empty remainder of the chapter before makes a blank page); links between chapters
become links inside the PDF (those to pages left out become plain text, none points at the
temporary server), links to the web stay; code wraps at the right margin with a hanging indent
(a wrapped line continues indented under its own line's indentation, four characters more),
and a code block or output (shorter than a page) moves to the next page whole rather than
leaving its empty frame at the bottom of one; wide tables shrink to the page; cells that show
nothing (their code removed, no output) are dropped; the toggles ("Show code cell source"),
copy buttons and other screen controls are not printed: chapters print their figures without
the plotting code hidden behind them, exercise pages print their hidden code (in the
instructor's edition, the worked solutions) open. A widget's controls are not printed (the
single page keeps no widget state): a note says to run the notebook.

Instructors' tools live in ``exercises/`` beside ``make_student_edition.py``, ``grade.py`` and
``gradebook.py``; ``book/_ext`` holds only the extension Sphinx loads during a build.
"""

import argparse
import datetime
import functools
import http.server
import json
import re
import shutil
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

import tomllib
import yaml

ROOT = Path(__file__).resolve().parent.parent
CACHE = ROOT / "_build" / ".jupyter_cache"
PDF_FOLDER = ROOT / "_build" / "pdf"
EDITIONS = {"instructor": "Instructor's edition", "student": "Student edition"}
LANGUAGES = {"en": "_config.yml", "pt_BR": "_config_pt.yml"}
#: what the printer itself writes on the pages, in each book's language
TEXTS = {
    "en": {"editions": EDITIONS, "contents": "Contents",
           "printed": "Printed {date} from {origin}", "commit": "commit {commit}",
           "version": "{package} {version} (a copy without git history)",
           "language": "Language: {name}",
           "widget": "[An interactive widget: run the notebook to use it.]"},
    "pt_BR": {"editions": {"instructor": "Edição do instrutor",
                           "student": "Edição do estudante"},
              "contents": "Sumário", "printed": "Impresso em {date} a partir do {origin}",
              "commit": "commit {commit}",
              "version": "{package} {version} (uma cópia sem o histórico do git)",
              "language": "Língua: {name}",
              "widget": "[Um controle interativo: execute o notebook para usá-lo.]"},
}
LANGUAGE_NAMES = {"en": "English", "pt_BR": "Português (Brasil)"}
API_PAGE = "book/api"
# the first print's invisible marks (one per entry of the contents), found by pdftotext
MARK = "rsgeoprintmark{}x"
# Debian's Chromium (never one downloaded by Playwright), also what tests/test_browser.py opens
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
# TeX delimiters MathJax replaces: any left in the page's math elements means it did not run
UNRENDERED = r"""Array.from(document.querySelectorAll('.math'))
    .filter(element => !element.querySelector('mjx-container'))
    .map(element => element.textContent.trim().slice(0, 60))"""
# Paper has no right-hand scroll bar: code wraps (at a space when it can) with a hanging indent
# (each line a block, its wrapped part indented by --hang), tables shrink to the page's width,
# and what is only for a screen (toggles, copy buttons, permalinks, the theme's bars) is not
# printed; no animation (a toggle opened just before printing would print half faded in). Each
# chapter starts a new sheet: the break is on its anchor (the "document-..." span, made a block
# of no height), not on the section after it, which left the anchor alone on a blank page
# whenever the chapter before filled its last page. No heading, figure, code block or output,
# table (shorter than a page) or table row is split across two pages: the whole frame of a
# code cell moves (breaking inside it left its empty frame at the bottom of a page).
PRINT_CSS = """
span[id^="document-"] { display: block; height: 0; margin: 0; padding: 0;
                        break-before: page; }
span[id^="document-"] + section { break-before: auto !important; }
.print-cover { break-after: page; }
.print-toc { break-before: page; }
.print-toc + * { break-before: page; }
h1, h2, h3, h4 { break-inside: avoid; break-after: avoid; }
img, pre, figure, table, tr, div.cell_input, div.cell_output, div.highlight, div.output,
.print-line { break-inside: avoid; }
* { animation: none !important; transition: none !important; }
pre { white-space: pre-wrap !important; overflow-wrap: anywhere; word-break: normal;
      overflow: visible !important; max-height: none !important; }
.print-tall { break-inside: auto !important; }
pre .print-line { display: block; padding-left: var(--hang);
                  text-indent: calc(-1 * var(--hang)); }
pre .print-line:empty::before { content: " "; }
div.highlight, div.cell_output, div.output, div.output_area, .table-wrapper,
.pst-scrollable-table-container, .bd-article-container, .bd-content, .bd-article {
    overflow: visible !important; max-width: 100% !important; }
table { table-layout: auto; width: auto !important; max-width: 100% !important;
        font-size: 7pt !important; }
th, td { padding: 1px 3px !important; overflow-wrap: break-word; word-break: normal;
         white-space: normal !important; }
button, .copybtn, a.headerlink, summary, .toggle-button, .header-article,
.bd-header-article, .prev-next-area, .bd-footer, .bd-footer-article, .bd-sidebar-primary,
.bd-sidebar-secondary, .bd-header { display: none !important; }
.toggle-hidden { display: block !important; visibility: visible !important; }
.print-cover { text-align: center; padding-top: 30%; }
.print-cover .print-title { font-size: 26pt; font-weight: bold; margin-bottom: 1.5em; }
.print-cover .print-edition { font-size: 18pt; margin-bottom: 3em; }
.print-cover p { font-size: 11pt; margin: 0.3em; }
.print-toc .print-toc-title { font-size: 18pt; font-weight: bold; margin-bottom: 1em; }
.print-toc .print-toc-part { font-weight: bold; margin: 0.6em 0 0.1em; font-size: 10pt; }
.print-toc a { color: inherit; text-decoration: none; }
.print-toc p { margin: 0 0 0 1.5em; font-size: 10pt; line-height: 1.4; display: flex;
               gap: 0.5em; break-inside: avoid; }
.print-toc .print-toc-number { min-width: 2em; }
.print-toc .print-toc-entry { flex: 1; border-bottom: 1px dotted #999; }
.print-toc .print-toc-page { min-width: 2.5em; text-align: right; }
.print-mark { position: absolute; font-size: 4px; }
"""
# Run in the page before printing, with the cover's facts and the parts' captions as argument.
# Returns how many links it made internal and how many it turned into plain text.
PREPARE_FOR_PRINT = """facts => {
    // the single page keeps no widget state: a widget would print as an empty box
    document.querySelectorAll("script[type='application/vnd.jupyter.widget-view+json']")
        .forEach(view => {
            const note = document.createElement("p");
            note.className = "print-widget-note";
            note.textContent = facts.texts.widget;
            view.replaceWith(note);
        });
    // the theme's own print header repeats the title above our cover
    document.querySelectorAll("#jb-print-docs-body").forEach(element => element.remove());
    // hidden code: an exercise page prints it open, a chapter prints its figures without it
    document.querySelectorAll("details").forEach(details => {
        const anchor = details.closest("section[data-print-document]");
        const exercise = anchor && anchor.dataset.printDocument.startsWith("exercises/");
        if (details.classList.contains("above-input") && !exercise) details.remove();
        else details.open = true;
    });
    // what shows nothing (a cell whose code is removed and that has no output, an empty
    // input or output, an empty code block) is not printed as an empty frame
    const shows = element => element.textContent.trim() !== "" || element.querySelector(
        "img, svg, canvas, video, iframe, object, mjx-container, table, .print-widget-note");
    let dropped = 0;
    document.querySelectorAll("pre, div.highlight, div.cell_input, div.cell_output, div.cell")
        .forEach(element => {
            if (element.isConnected && !shows(element)) { element.remove(); dropped += 1; }
        });
    // code lines: each one a block whose wrapped part hangs under its own indentation
    document.querySelectorAll("pre").forEach(pre => {
        const lines = [[]];
        const walker = document.createTreeWalker(pre, NodeFilter.SHOW_TEXT);
        const texts = [];
        while (walker.nextNode()) texts.push(walker.currentNode);
        for (const text of texts) {
            const chain = [];
            for (let node = text.parentNode; node !== pre; node = node.parentNode) {
                chain.unshift(node);
            }
            text.data.split("\\n").forEach((part, index) => {
                if (index > 0) lines.push([]);
                if (!part) return;
                let node = document.createTextNode(part);
                for (let k = chain.length - 1; k >= 0; k--) {
                    const copy = chain[k].cloneNode(false);
                    copy.append(node);
                    node = copy;
                }
                lines[lines.length - 1].push(node);
            });
        }
        if (lines.length > 1 && lines[lines.length - 1].length === 0) lines.pop();
        pre.replaceChildren(...lines.map(parts => {
            const line = document.createElement("span");
            line.className = "print-line";
            const text = parts.map(part => part.textContent).join("");
            const indent = text.length - text.replace(/^[ \\t]+/, "").length;
            line.style.setProperty("--hang", (indent + 4) + "ch");
            line.append(...parts);
            return line;
        }));
    });
    // links: to a place in this page, an in-document link; to the print server otherwise
    // (a page left out, a download), plain text; to the web, unchanged
    let internal = 0, unlinked = 0;
    document.querySelectorAll("a[href]").forEach(link => {
        const url = new URL(link.getAttribute("href"), location.href);
        if (url.origin !== location.origin) return;
        const id = decodeURIComponent(url.hash.slice(1));
        if (id && document.getElementById(id)) {
            link.setAttribute("href", "#" + id);
            internal += 1;
        } else {
            link.removeAttribute("href");
            unlinked += 1;
        }
    });
    // the cover and the table of contents, before the first page
    const article = document.querySelector("article.bd-article") || document.body;
    const cover = document.createElement("div");
    cover.className = "print-cover";
    const line = (tag, className, text) => {
        const element = document.createElement(tag);
        element.className = className;
        element.textContent = text;
        return element;
    };
    cover.append(line("div", "print-title", facts.title),
                 line("div", "print-edition", facts.edition),
                 ...facts.lines.map(text => line("p", "", text)));
    const contents = document.createElement("nav");
    contents.className = "print-toc";
    contents.append(line("div", "print-toc-title", facts.texts.contents));
    let entries = 0;
    const entry = (heading, target) => {
        // a numbered entry, its title linked, a placeholder for its page; an invisible mark
        // at its target tells the first print on which page it starts
        entries += 1;
        if (!target.id) target.id = "print-entry-" + entries;
        const row = line("p", "", "");
        const link = line("a", "", heading.textContent.replace(/#$/, "").trim());
        link.href = "#" + target.id;
        const title = line("span", "print-toc-entry", "");
        title.append(link);
        const page = line("span", "print-toc-page", "000");
        page.dataset.mark = String(entries);
        row.append(line("span", "print-toc-number", entries + "."), title, page);
        contents.append(row);
        const mark = line("span", "print-mark", facts.mark.replace("{}", entries));
        target.prepend(mark);
    };
    const firstHeading = article.querySelector("h1");
    if (firstHeading) entry(firstHeading, firstHeading.closest("section") || firstHeading);
    for (const part of facts.parts) {
        contents.append(line("div", "print-toc-part", part.caption));
        for (const file of part.files) {
            const section = document.querySelector(`[data-print-document="${file}"]`);
            // a chapter's title is an h2 in the single page (the root page has the h1)
            const heading = section && section.querySelector(":scope > h1, :scope > h2");
            if (heading) entry(heading, section);
        }
    }
    article.prepend(cover, contents);
    return {internal, unlinked, dropped, entries};
}"""
# A4 less the margins, in CSS pixels: the width the page is laid out in, and a page's height
PRINT_WIDTH_PX, PRINT_HEIGHT_PX = 703, 1009
# blocks too tall for one page may break inside (an unbreakable block taller than what is
# left of a fresh page was pushed to the next one, and left its frame alone on a blank page)
MARK_TALL = """limit => {
    let tall = 0;
    document.querySelectorAll("pre, div.highlight, div.cell_input, div.cell_output, " +
                              "div.output, div.cell, table, figure, img").forEach(element => {
        if (element.getBoundingClientRect().height > limit) {
            element.classList.add("print-tall");
            tall += 1;
        }
    });
    return tall;
}"""
# after the first print: the contents' page numbers in, the marks out
NUMBER_CONTENTS = """pages => {
    document.querySelectorAll(".print-toc-page").forEach(page => {
        page.textContent = String(pages[page.dataset.mark] || "");
    });
    document.querySelectorAll(".print-mark").forEach(mark => mark.remove());
}"""
# mark each chapter's section with its document's name ("book/03_evaluating_models"), which
# the anchor Sphinx puts before it carries; sections without an id get one for the contents
MARK_DOCUMENTS = """() => {
    document.querySelectorAll('span[id^="document-"] + section').forEach((section, n) => {
        section.dataset.printDocument = section.previousElementSibling.id.slice(9);
        if (!section.id) section.id = "print-document-" + n;
    });
}"""
FOOTER = ("<div style='font-size:8px;width:100%;text-align:center;color:#555'>"
          "<span class='pageNumber'></span> / <span class='totalPages'></span></div>")
HEADER = ("<div style='font-size:8px;width:100%;text-align:center;color:#555'>"
          "{title} · {edition}</div>")


def print_toc(source=ROOT, with_api=False, only=None, edition="instructor"):
    """The table of contents to print: ``source``'s ``_toc.yml`` without the pages left out.

    Parameters
    ----------
    source : path-like
        The book's folder (the repository, or a student edition).
    with_api : bool
        Keep the API reference page (``book/api``).
    only : list of str, optional
        Keep only these pages (``_toc.yml``'s ``file`` entries); the root page always stays.
    edition : {"instructor", "student"}
        The student edition never has the pages for instructors only (the teaching guide),
        whatever ``source`` holds.

    Returns
    -------
    dict
        The table of contents, as ``_toc.yml`` holds it (parts left empty are dropped).

    Raises
    ------
    ValueError
        If ``only`` names a page that is not in the table of contents, or a page for
        instructors only in the student edition.
    """
    from make_student_edition import INSTRUCTORS_ONLY

    toc = yaml.safe_load((Path(source) / "_toc.yml").read_text())
    files = [entry["file"] for part in toc["parts"] for entry in part["chapters"]]
    left_out = set(INSTRUCTORS_ONLY) if edition == "student" else set()
    refused = sorted(set(only or []) & left_out)
    if refused:
        raise ValueError(f"for instructors only, not in the student edition: "
                         f"{', '.join(refused)}")
    unknown = sorted(set(only or []) - set(files))
    if unknown:
        raise ValueError(f"not in _toc.yml: {', '.join(unknown)}")
    parts = []
    for part in toc["parts"]:
        chapters = [entry for entry in part["chapters"]
                    if (with_api or entry["file"] != API_PAGE)
                    and entry["file"] not in left_out
                    and (only is None or entry["file"] in only)]
        if chapters:
            parts.append({**part, "chapters": chapters})
    return {**toc, "parts": parts}


def build_singlehtml(build_dir=ROOT, source=ROOT, toc=None, language="en"):
    """Build a book as one HTML page under ``build_dir``; return the page's path.

    Parameters
    ----------
    build_dir : path-like
        The folder whose ``_build/`` receives the build (``--path-output`` of jupyter-book;
        the Portuguese book's goes to ``build_dir/_build/pt_BR``, as the README builds it).
    source : path-like
        The book to build (the repository, or a student edition).
    toc : dict, optional
        The table of contents to build (see `print_toc`); default the book's ``_toc.yml``.
    language : {"en", "pt_BR"}
        The book: English (``_config.yml``) or Portuguese (``_config_pt.yml``).

    Returns
    -------
    pathlib.Path
        ``.../_build/singlehtml/rsgeo-course.html``: the whole book, beside the ``_static/``
        and ``_images/`` folders its links point to.

    Raises
    ------
    ValueError
        For a language the course has no configuration for.
    RuntimeError
        If the build fails (its last lines of output are in the message).
    """
    if language not in LANGUAGES:
        raise ValueError(f"language must be one of {sorted(LANGUAGES)}, not {language!r}")
    build_dir, source = Path(build_dir).resolve(), Path(source).resolve()
    cache = build_dir / "_build" / ".jupyter_cache"
    if build_dir != ROOT and CACHE.exists() and not cache.exists():
        cache.parent.mkdir(parents=True, exist_ok=True)
        cache.symlink_to(CACHE, target_is_directory=True)       # the HTML build's executions
    path_output = build_dir if language == "en" else build_dir / "_build" / language
    jupyter_book = Path(sys.executable).parent / "jupyter-book"
    command = [str(jupyter_book), "build", str(source), "--builder", "singlehtml",
               "--path-output", str(path_output)]
    if language != "en":
        # its cache is named relative to the repository (the English build's, which keeps the
        # Portuguese executions apart), hence the build runs there
        command += ["--config", str(source / LANGUAGES[language])]
    if toc is not None:
        toc_file = path_output / "_build" / "print_toc.yml"
        toc_file.parent.mkdir(parents=True, exist_ok=True)
        toc_file.write_text(yaml.safe_dump(toc, sort_keys=False, allow_unicode=True))
        command += ["--toc", str(toc_file)]
    build = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
    output = path_output / "_build" / "singlehtml"
    redirect = output / "index.html"            # points to the root document, book/intro.html
    found = re.search(r'url=([^"]+)"', redirect.read_text()) if redirect.exists() else None
    if build.returncode != 0 or found is None or not (output / found.group(1)).exists():
        raise RuntimeError("the single-page build failed:\n"
                           + (build.stdout + build.stderr)[-3000:])
    # the page's links (_static/, _images/) are relative to the output folder: print a copy there
    page = output / "rsgeo-course.html"
    shutil.copyfile(output / found.group(1), page)
    return page


def course_origin(root=ROOT):
    """What the course was printed from: ``("commit", "2ca3e0d")`` in a git work tree,
    ``("version", "0.1.0")`` in a copy without git history (a ``git archive``, a download),
    read from ``root``'s ``pyproject.toml`` (else the installed package's metadata).

    Raises
    ------
    RuntimeError
        If neither git nor the package metadata says anything.
    """
    root = Path(root).resolve()
    top = subprocess.run(["git", "-C", str(root), "rev-parse", "--show-toplevel"],
                         capture_output=True, text=True)
    # a copy inside another repository is not that repository's commit
    if top.returncode == 0 and Path(top.stdout.strip()).resolve() == root:
        commit = subprocess.run(["git", "-C", str(root), "describe", "--always", "--dirty"],
                                capture_output=True, text=True).stdout.strip()
        if commit:
            return "commit", commit
    project = root / "pyproject.toml"
    if project.exists():
        metadata = tomllib.loads(project.read_text()).get("project", {})
        if metadata.get("version"):
            return "version", f"{metadata.get('name', 'rsgeo')} {metadata['version']}"
    from importlib import metadata

    try:
        return "version", f"rsgeo {metadata.version('rsgeo')}"
    except metadata.PackageNotFoundError:
        raise RuntimeError(f"{root} has no git history, no pyproject.toml with a version and "
                           "no installed rsgeo: nothing says what is printed") from None


def cover_facts(source=ROOT, edition="instructor", toc=None, language="en", root=ROOT):
    """What the cover, the running header and the contents say, for `print_pdf`.

    Returns
    -------
    dict
        ``title`` (the book's, without the student edition's suffix), ``edition`` (its label),
        ``lines`` (date, commit or version, language), ``parts`` (each part's ``caption`` and
        ``files``, from ``toc``), ``texts`` (the printer's words, in the book's language),
        ``mark`` (the first print's marks).
    """
    config = yaml.safe_load((Path(source) / LANGUAGES[language]).read_text())
    title = re.sub(r"\s*\((student edition|edição do estudante)\)$", "",
                   config.get("title", "The course"))
    texts = TEXTS[language]
    kind, value = course_origin(root)
    if kind == "commit":
        origin = texts["commit"].format(commit=value)
    else:
        package, version = value.split(" ", 1)
        origin = texts["version"].format(package=package, version=version)
    toc = toc or yaml.safe_load((Path(source) / "_toc.yml").read_text())
    captions = part_captions(source, toc, language)
    return {"title": title, "edition": texts["editions"][edition],
            "lines": [texts["printed"].format(date=datetime.date.today().isoformat(),
                                              origin=origin),
                      texts["language"].format(name=LANGUAGE_NAMES[language])],
            "parts": [{"caption": captions.get(part.get("caption", ""),
                                               part.get("caption", "")),
                       "files": [entry["file"] for entry in part["chapters"]]}
                      for part in toc["parts"]],
            "texts": texts, "mark": MARK}


def part_captions(source, toc, language):
    """{caption: its translation} of the parts of ``toc`` in ``language``, from the root
    page's catalogue, as the Portuguese book translates them (book/_ext/i18n_book.py)."""
    if language == "en":
        return {}
    from babel.messages.pofile import read_po

    catalogue = Path(source) / "locales" / language / "LC_MESSAGES" / f"{toc['root']}.po"
    if not catalogue.exists():
        return {}
    with catalogue.open("rb") as handle:
        return {message.id: message.string for message in read_po(handle)
                if message.id and message.string and not message.fuzzy}


def pdf_pages(pdf, layout=True):
    """The text of each page of ``pdf`` (poppler's ``pdftotext``, with ``-layout`` or in the
    order the page draws it, which keeps overlapping texts apart)."""
    if shutil.which("pdftotext") is None:
        raise RuntimeError("pdftotext is needed to number the contents: "
                           "apt-get install poppler-utils")
    text = subprocess.run(["pdftotext", *(["-layout"] if layout else []), str(pdf), "-"],
                          capture_output=True, text=True, check=True).stdout
    return text.split("\f")[:-1]          # pdftotext ends every page with a form feed


def blank_pages(pdf):
    """The numbers of the pages of ``pdf`` with nothing on them but the running header and
    the page number: no text and no image (poppler's ``pdftotext`` and ``pdfimages``)."""
    listing = subprocess.run(["pdfimages", "-list", str(pdf)], capture_output=True,
                             text=True, check=True).stdout
    with_images = {int(line.split()[0]) for line in listing.splitlines()[2:] if line.strip()}
    blank = []
    for number, page in enumerate(pdf_pages(pdf), start=1):
        body = [line for line in page.splitlines()
                if line.strip() and not re.fullmatch(r"\s*\d+ / \d+\s*", line)]
        if len(body) <= 1 and number not in with_images:     # the header alone, or nothing
            blank.append(number)
    return blank


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


class _QuietServer(http.server.ThreadingHTTPServer):
    def handle_error(self, request, client_address):
        pass                       # the browser closing a connection early is not news


def serve(folder):
    """An HTTP server on a free loopback port, serving ``folder``; returns (server, base URL).

    The browser is given the page over HTTP, not ``file://``, so that its scripts and fonts load
    as on a web server. Stop it with ``server.shutdown()``.
    """
    handler = functools.partial(_QuietHandler, directory=str(folder))
    server = _QuietServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}"


def print_pdf(page, out, facts=None, chromium=None, timeout_s=120):
    """Print an HTML page to PDF with headless Chromium once its equations are typeset.

    Parameters
    ----------
    page : path-like
        The HTML file (served with its folder, so its scripts and fonts load).
    out : path-like
        The PDF to write.
    facts : dict, optional
        The cover's facts (see `cover_facts`); default the instructor's edition's.
    chromium : str, optional
        The browser's executable; default ``chromium`` on the PATH.
    timeout_s : float
        Seconds to wait for MathJax and the images.

    Returns
    -------
    dict
        ``internal``: links made internal; ``unlinked``: links to the print server that had no
        target in the page, printed as plain text; ``dropped``: empty cells and code blocks
        not printed; ``entries``: entries of the contents; ``pages``: each entry's page.

    Raises
    ------
    RuntimeError
        If Chromium or pdftotext is missing, equations are still TeX source when printing, an
        entry of the contents is found on no page, or a page is left blank.
    """
    from playwright.sync_api import sync_playwright

    chromium = chromium or CHROMIUM
    if chromium is None:
        raise RuntimeError("Chromium is not installed: apt-get install chromium")
    facts = facts or cover_facts()
    page, out = Path(page).resolve(), Path(out).resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    server, base = serve(page.parent)
    try:
        with sync_playwright() as playwright, tempfile.TemporaryDirectory() as scratch:
            browser = playwright.chromium.launch(executable_path=chromium, args=CHROMIUM_ARGS)
            tab = browser.new_page()
            tab.goto(f"{base}/{page.name}", wait_until="load", timeout=timeout_s * 1000)
            tab.wait_for_function("window.MathJax && MathJax.startup && MathJax.startup.promise",
                                  timeout=timeout_s * 1000)
            tab.evaluate("MathJax.startup.promise")
            tab.wait_for_function("Array.from(document.images).every(image => image.complete)",
                                  timeout=timeout_s * 1000)
            left = tab.evaluate(UNRENDERED)
            if left:
                raise RuntimeError(f"{len(left)} equations are still TeX source, e.g. {left[:3]}")
            tab.evaluate(MARK_DOCUMENTS)
            result = tab.evaluate(PREPARE_FOR_PRINT, facts)
            tab.add_style_tag(content=PRINT_CSS)
            tab.emulate_media(media="print")
            # laid out as on paper, to find the blocks taller than most of a page
            tab.set_viewport_size({"width": PRINT_WIDTH_PX, "height": PRINT_HEIGHT_PX})
            result["tall"] = tab.evaluate(MARK_TALL, 0.8 * PRINT_HEIGHT_PX)
            header = HEADER.format(title=_html_text(facts["title"]),
                                   edition=_html_text(facts["edition"]))
            options = dict(format="A4", print_background=True, display_header_footer=True,
                           header_template=header, footer_template=FOOTER, outline=True,
                           tagged=True, margin={"top": "15mm", "bottom": "15mm",
                                                "left": "12mm", "right": "12mm"})
            # first print: on which page each entry of the contents starts (its mark's page)
            first = Path(scratch) / "first.pdf"
            tab.pdf(path=str(first), **options)
            pages = {}
            for number, text in enumerate(pdf_pages(first, layout=False), start=1):
                for mark in re.findall(facts["mark"].replace("{}", r"(\d+)"), text):
                    pages.setdefault(mark, number)
            missing = [str(n) for n in range(1, result["entries"] + 1) if str(n) not in pages]
            if missing:
                raise RuntimeError(f"entries {', '.join(missing)} of the contents are on no "
                                   "page of the first print")
            tab.evaluate(NUMBER_CONTENTS, pages)
            tab.pdf(path=str(out), **options)
            browser.close()
    finally:
        server.shutdown()
    blank = blank_pages(out)
    if blank:
        raise RuntimeError(f"{out} has blank pages: {blank}")
    return {**result, "pages": {int(mark): page for mark, page in pages.items()}}


def _html_text(text):
    """``text`` escaped for an HTML template."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def default_out(edition, language):
    """``_build/pdf/rsgeo-course-EDITION[-LANGUAGE].pdf`` (no suffix for English)."""
    suffix = "" if language == "en" else f"-{language}"
    return PDF_FOLDER / f"rsgeo-course-{edition}{suffix}.pdf"


def print_edition(edition="instructor", out=None, build_dir=ROOT, with_api=False, only=None,
                  language="en"):
    """Build and print one edition in one language; return the PDF's path and what
    `print_pdf` returns.

    The student edition is made by ``make_student_edition.py`` in
    ``build_dir/_build/print-student/`` and built there.
    """
    if edition not in EDITIONS:
        raise ValueError(f"edition must be one of {sorted(EDITIONS)}, not {edition!r}")
    if language not in LANGUAGES:
        raise ValueError(f"language must be one of {sorted(LANGUAGES)}, not {language!r}")
    build_dir = Path(build_dir).resolve()
    out = Path(out) if out else default_out(edition, language)
    source = ROOT
    if edition == "student":
        from make_student_edition import make_student_edition

        source = build_dir / "_build" / "print-student"
        make_student_edition(source)
        build_dir = source
    toc = print_toc(source, with_api=with_api, only=only, edition=edition)
    page = build_singlehtml(build_dir, source, toc, language)
    result = print_pdf(page, out, cover_facts(source, edition, toc, language))
    return out, result


def main(argv=None):
    """The command line: build the single page, print it, say where the PDF is."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--edition", choices=[*sorted(EDITIONS), "both"], default="instructor",
                        help="instructor (solutions, verdicts, teaching guide; default), "
                             "student, or both")
    parser.add_argument("--language", choices=[*sorted(LANGUAGES), "both"], default="en",
                        help="the English book (default), the Portuguese one (pt_BR), or both")
    parser.add_argument("--out", help="the PDF to write (default: "
                        "_build/pdf/rsgeo-course-EDITION[-pt_BR].pdf)")
    parser.add_argument("--with-api", action="store_true",
                        help="add the API reference (left out by default)")
    parser.add_argument("--only", nargs="+", metavar="DOC",
                        help="print only these pages of _toc.yml, e.g. book/03_evaluating_models")
    parser.add_argument("--build-dir", default=str(ROOT),
                        help="where _build/singlehtml goes (default: the repository)")
    options = parser.parse_args(argv)
    editions = sorted(EDITIONS) if options.edition == "both" else [options.edition]
    languages = list(LANGUAGES) if options.language == "both" else [options.language]
    if options.out and len(editions) * len(languages) > 1:
        parser.error("--out names one PDF: print one edition in one language with it")
    for edition in editions:
        for language in languages:
            out, result = print_edition(edition, options.out, options.build_dir,
                                        options.with_api, options.only, language)
            links = {key: result[key] for key in ("internal", "unlinked")}
            print(f"{out} ({TEXTS[language]['editions'][edition]}, "
                  f"{out.stat().st_size / 1e6:.1f} MB, {len(pdf_pages(out))} pages; "
                  f"links: {json.dumps(links)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
