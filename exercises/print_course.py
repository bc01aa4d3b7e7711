"""Print the course to PDF, in the instructor's or the student edition: Jupyter Book's
single-page HTML, printed by Chromium.

    python exercises/print_course.py                      # the instructor's edition
    python exercises/print_course.py --edition student    # the student edition
    options: [--out PDF] [--with-api] [--only DOC ...] [--build-dir DIR]

The two editions, each labelled on its cover and in every page's running header:

- **Instructor's edition** (default; ``_build/pdf/rsgeo-course-instructor.pdf``): the course's
  book as built, with the exercises' worked solutions and the verdict of every check. Keep it
  with the instructors.
- **Student edition** (``_build/pdf/rsgeo-course-student.pdf``): printed from the student
  edition that ``exercises/make_student_edition.py`` makes (copied to
  ``DIR/_build/print-student/``): no solutions, and no verdicts, since its exercises are not
  executed.

Options: ``--out`` the PDF to write; ``--with-api`` adds the API reference, left out by default
(it is half of the pages, and the HTML book has it); ``--only book/03_evaluating_models ...``
prints only those pages of ``_toc.yml`` (with the introduction), for a quick look or a test.

How:

1. ``jupyter-book build --builder singlehtml`` writes the book as one page
   (``DIR/_build/singlehtml/``; DIR is the repository by default), from a table of contents
   without the pages left out (``--toc``). The notebooks' executions come from the HTML build's
   cache, ``_build/.jupyter_cache``, so nothing runs again when the HTML book is current.
2. Debian's Chromium (``apt-get install chromium``; no browser is downloaded), headless and
   driven by Playwright, opens that page from a local web server, waits until MathJax (served
   from the book, ``book/_vendor/mathjax``) has typeset every equation and every image has
   loaded, prepares the page for paper and prints it to A4 with page numbers and a PDF outline
   (bookmarks from the headings). An equation left as TeX source stops the script with an
   error instead of printing it.

Preparing for paper (``PREPARE_FOR_PRINT`` and ``PRINT_CSS``): a cover (course title, edition,
date, commit, language) and a table of contents come first, each chapter starts a new sheet;
links between chapters become links inside the PDF (those to pages left out become plain text,
none points at the temporary server), links to the web stay; code wraps at the right margin and
wide tables shrink to the page; the toggles ("Show code cell source"), copy buttons and other
screen controls are not printed: chapters print their figures without the plotting code hidden
behind them, exercise pages print their hidden code (in the instructor's edition, the worked
solutions) open. A widget's controls are not printed (the single page keeps no widget state): a
note says to run the notebook.

Instructors' tools live in ``exercises/`` beside ``make_student_edition.py`` and ``grade.py``;
``book/_ext`` holds only the extension Sphinx loads during a build.
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
import threading
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
CACHE = ROOT / "_build" / ".jupyter_cache"
PDF_FOLDER = ROOT / "_build" / "pdf"
EDITIONS = {"instructor": "Instructor's edition", "student": "Student edition"}
API_PAGE = "book/api"
# Debian's Chromium (never one downloaded by Playwright), also what tests/test_browser.py opens
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
# TeX delimiters MathJax replaces: any left in the page's math elements means it did not run
UNRENDERED = r"""Array.from(document.querySelectorAll('.math'))
    .filter(element => !element.querySelector('mjx-container'))
    .map(element => element.textContent.trim().slice(0, 60))"""
# Paper has no right-hand scroll bar: code wraps (at a space when it can), tables shrink to the
# page's width, and what is only for a screen (toggles, copy buttons, permalinks, the theme's
# bars) is not printed; no animation (a toggle opened just before printing would print half
# faded in). Each chapter (the section after its "document-..." anchor) starts a new sheet; no
# heading, figure, code block, table (shorter than a page) or table row is split across two.
PRINT_CSS = """
span[id^="document-"] + section { break-before: page; }
.print-cover, .print-toc { break-after: page; }
h1, h2, h3, h4 { break-inside: avoid; break-after: avoid; }
img, pre, figure, table, tr { break-inside: avoid; }
* { animation: none !important; transition: none !important; }
pre { white-space: pre-wrap !important; overflow-wrap: anywhere; word-break: normal;
      overflow: visible !important; max-height: none !important; }
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
.print-toc p { margin: 0 0 0 1.5em; font-size: 10pt; line-height: 1.4; }
"""
# Run in the page before printing, with the cover's facts and the parts' captions as argument.
# Returns how many links it made internal and how many it turned into plain text.
PREPARE_FOR_PRINT = """facts => {
    // the single page keeps no widget state: a widget would print as an empty box
    document.querySelectorAll("script[type='application/vnd.jupyter.widget-view+json']")
        .forEach(view => {
            const note = document.createElement("p");
            note.textContent = "[An interactive widget: run the notebook to use it.]";
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
    contents.append(line("div", "print-toc-title", "Contents"));
    const firstHeading = article.querySelector("h1");
    if (firstHeading) {
        const entry = line("p", "", "");
        const link = line("a", "", firstHeading.textContent.replace(/#$/, "").trim());
        link.href = "#" + firstHeading.closest("section").id;
        entry.append(link);
        contents.append(entry);
    }
    for (const part of facts.parts) {
        contents.append(line("div", "print-toc-part", part.caption));
        for (const file of part.files) {
            const section = document.querySelector(`[data-print-document="${file}"]`);
            // a chapter's title is an h2 in the single page (the root page has the h1)
            const heading = section && section.querySelector(":scope > h1, :scope > h2");
            if (!heading) continue;
            const entry = line("p", "", "");
            const link = line("a", "", heading.textContent.replace(/#$/, "").trim());
            link.href = "#" + section.id;
            entry.append(link);
            contents.append(entry);
        }
    }
    article.prepend(cover, contents);
    return {internal, unlinked};
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


def print_toc(source=ROOT, with_api=False, only=None):
    """The table of contents to print: ``source``'s ``_toc.yml`` without the pages left out.

    Parameters
    ----------
    source : path-like
        The book's folder (the repository, or a student edition).
    with_api : bool
        Keep the API reference page (``book/api``).
    only : list of str, optional
        Keep only these pages (``_toc.yml``'s ``file`` entries); the root page always stays.

    Returns
    -------
    dict
        The table of contents, as ``_toc.yml`` holds it (parts left empty are dropped).

    Raises
    ------
    ValueError
        If ``only`` names a page that is not in the table of contents.
    """
    toc = yaml.safe_load((Path(source) / "_toc.yml").read_text())
    files = [entry["file"] for part in toc["parts"] for entry in part["chapters"]]
    unknown = sorted(set(only or []) - set(files))
    if unknown:
        raise ValueError(f"not in _toc.yml: {', '.join(unknown)}")
    parts = []
    for part in toc["parts"]:
        chapters = [entry for entry in part["chapters"]
                    if (with_api or entry["file"] != API_PAGE)
                    and (only is None or entry["file"] in only)]
        if chapters:
            parts.append({**part, "chapters": chapters})
    return {**toc, "parts": parts}


def build_singlehtml(build_dir=ROOT, source=ROOT, toc=None):
    """Build a book as one HTML page under ``build_dir``; return the page's path.

    Parameters
    ----------
    build_dir : path-like
        The folder whose ``_build/`` receives the build (``--path-output`` of jupyter-book).
    source : path-like
        The book to build (the repository, or a student edition).
    toc : dict, optional
        The table of contents to build (see `print_toc`); default the book's ``_toc.yml``.

    Returns
    -------
    pathlib.Path
        ``build_dir/_build/singlehtml/rsgeo-course.html``: the whole book, beside the
        ``_static/`` and ``_images/`` folders its links point to.

    Raises
    ------
    RuntimeError
        If the build fails (its last lines of output are in the message).
    """
    build_dir, source = Path(build_dir).resolve(), Path(source).resolve()
    cache = build_dir / "_build" / ".jupyter_cache"
    if build_dir != ROOT and CACHE.exists() and not cache.exists():
        cache.parent.mkdir(parents=True, exist_ok=True)
        cache.symlink_to(CACHE, target_is_directory=True)       # the HTML build's executions
    jupyter_book = Path(sys.executable).parent / "jupyter-book"
    command = [str(jupyter_book), "build", str(source), "--builder", "singlehtml",
               "--path-output", str(build_dir)]
    if toc is not None:
        toc_file = build_dir / "_build" / "print_toc.yml"
        toc_file.parent.mkdir(parents=True, exist_ok=True)
        toc_file.write_text(yaml.safe_dump(toc, sort_keys=False))
        command += ["--toc", str(toc_file)]
    build = subprocess.run(command, capture_output=True, text=True)
    output = build_dir / "_build" / "singlehtml"
    redirect = output / "index.html"            # points to the root document, book/intro.html
    found = re.search(r'url=([^"]+)"', redirect.read_text()) if redirect.exists() else None
    if build.returncode != 0 or found is None or not (output / found.group(1)).exists():
        raise RuntimeError("the single-page build failed:\n"
                           + (build.stdout + build.stderr)[-3000:])
    # the page's links (_static/, _images/) are relative to the output folder: print a copy there
    page = output / "rsgeo-course.html"
    shutil.copyfile(output / found.group(1), page)
    return page


def cover_facts(source=ROOT, edition="instructor", toc=None):
    """What the cover, the running header and the contents say, for `print_pdf`.

    Returns
    -------
    dict
        ``title`` (``_config.yml``'s, without the student edition's suffix), ``edition`` (its
        label), ``lines`` (date, commit, language), ``parts`` (each part's ``caption`` and
        ``files``, from ``toc``).
    """
    config = yaml.safe_load((Path(source) / "_config.yml").read_text())
    title = re.sub(r"\s*\(student edition\)$", "", config.get("title", "The course"))
    commit = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    language = config.get("sphinx", {}).get("config", {}).get("language", "en")
    names = {"en": "English", "pt_BR": "Português (Brasil)"}
    toc = toc or yaml.safe_load((Path(source) / "_toc.yml").read_text())
    return {"title": title, "edition": EDITIONS[edition],
            "lines": [f"Printed {datetime.date.today().isoformat()} from commit {commit}",
                      f"Language: {names.get(language, language)}"],
            "parts": [{"caption": part.get("caption", ""),
                       "files": [entry["file"] for entry in part["chapters"]]}
                      for part in toc["parts"]]}


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
        target in the page, printed as plain text.

    Raises
    ------
    RuntimeError
        If Chromium is missing, or equations are still TeX source when printing.
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
        with sync_playwright() as playwright:
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
            links = tab.evaluate(PREPARE_FOR_PRINT, facts)
            tab.add_style_tag(content=PRINT_CSS)
            tab.emulate_media(media="print")
            header = HEADER.format(title=_html_text(facts["title"]),
                                   edition=_html_text(facts["edition"]))
            tab.pdf(path=str(out), format="A4", print_background=True, display_header_footer=True,
                    header_template=header, footer_template=FOOTER, outline=True, tagged=True,
                    margin={"top": "15mm", "bottom": "15mm", "left": "12mm", "right": "12mm"})
            browser.close()
    finally:
        server.shutdown()
    return links


def _html_text(text):
    """``text`` escaped for an HTML template."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def print_edition(edition="instructor", out=None, build_dir=ROOT, with_api=False, only=None):
    """Build and print one edition; return the PDF's path and the link counts of `print_pdf`.

    The student edition is made by ``make_student_edition.py`` in
    ``build_dir/_build/print-student/`` and built there.
    """
    if edition not in EDITIONS:
        raise ValueError(f"edition must be one of {sorted(EDITIONS)}, not {edition!r}")
    build_dir = Path(build_dir).resolve()
    out = Path(out) if out else PDF_FOLDER / f"rsgeo-course-{edition}.pdf"
    source = ROOT
    if edition == "student":
        from make_student_edition import make_student_edition

        source = build_dir / "_build" / "print-student"
        make_student_edition(source)
        build_dir = source
    toc = print_toc(source, with_api=with_api, only=only)
    page = build_singlehtml(build_dir, source, toc)
    links = print_pdf(page, out, cover_facts(source, edition, toc))
    return out, links


def main(argv=None):
    """The command line: build the single page, print it, say where the PDF is."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--edition", choices=sorted(EDITIONS), default="instructor",
                        help="instructor (solutions and verdicts; default) or student")
    parser.add_argument("--out", help="the PDF to write (default: "
                        "_build/pdf/rsgeo-course-EDITION.pdf)")
    parser.add_argument("--with-api", action="store_true",
                        help="add the API reference (left out by default)")
    parser.add_argument("--only", nargs="+", metavar="DOC",
                        help="print only these pages of _toc.yml, e.g. book/03_evaluating_models")
    parser.add_argument("--build-dir", default=str(ROOT),
                        help="where _build/singlehtml goes (default: the repository)")
    options = parser.parse_args(argv)
    out, links = print_edition(options.edition, options.out, options.build_dir,
                               options.with_api, options.only)
    print(f"{out} ({EDITIONS[options.edition]}, {out.stat().st_size / 1e6:.1f} MB; "
          f"links: {json.dumps(links)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
