"""Print the whole course to one PDF: Jupyter Book's single-page HTML, printed by Chromium.

    python exercises/print_course.py [--out _build/pdf/rsgeo-course.pdf] [--build-dir DIR]

1. ``jupyter-book build . --builder singlehtml`` writes the whole book as one page
   (``DIR/_build/singlehtml/``; DIR is the repository by default). The notebooks'
   executions come from the HTML build's cache, ``_build/.jupyter_cache``: with another DIR the
   cache is linked there, so nothing runs twice when the HTML book is current.
2. Debian's Chromium (``apt-get install chromium``; no browser is downloaded), headless and
   driven by Playwright, opens that page from a local web server, waits until MathJax (served
   from the book, ``book/_vendor/mathjax``) has typeset every equation and every image has
   loaded, then prints it to A4 PDF with page numbers, each chapter from a new page. An
   equation left as TeX source stops the script with an error instead of printing it. A
   widget's controls are not printed (the single page keeps no widget state): a note says to
   run the notebook.

Instructors' tools live in ``exercises/`` beside ``make_student_edition.py`` and ``grade.py``;
``book/_ext`` holds only the extension Sphinx loads during a build.
"""

import argparse
import functools
import http.server
import re
import shutil
import subprocess
import sys
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CACHE = ROOT / "_build" / ".jupyter_cache"
DEFAULT_PDF = ROOT / "_build" / "pdf" / "rsgeo-course.pdf"
# Debian's Chromium (never one downloaded by Playwright), also what tests/test_browser.py opens
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
# TeX delimiters MathJax replaces: any left in the page's math elements means it did not run
UNRENDERED = r"""Array.from(document.querySelectorAll('.math'))
    .filter(element => !element.querySelector('mjx-container'))
    .map(element => element.textContent.trim().slice(0, 60))"""
# each chapter (a page of the book: the section after its "document-..." anchor) starts a new
# sheet; no heading, figure or code block is split across two
PRINT_CSS = """span[id^="document-"] + section { break-before: page; }
h1, h2, h3, h4 { break-inside: avoid; break-after: avoid; }
img, pre, figure, table { break-inside: avoid; }"""
# the single page holds no saved widget state, so a widget would print as an empty box: say so
WIDGETS_TO_NOTES = """document.querySelectorAll(
    "script[type='application/vnd.jupyter.widget-view+json']").forEach(view => {
    const note = document.createElement("p");
    note.textContent = "[An interactive widget: run the notebook to use it.]";
    view.replaceWith(note);
})"""
FOOTER = ("<div style='font-size:8px;width:100%;text-align:center;color:#555'>"
          "<span class='pageNumber'></span> / <span class='totalPages'></span></div>")


def build_singlehtml(build_dir=ROOT):
    """Build the book as one HTML page under ``build_dir``; return the page's path.

    Parameters
    ----------
    build_dir : path-like
        The folder whose ``_build/`` receives the build (``--path-output`` of jupyter-book).

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
    build_dir = Path(build_dir).resolve()
    cache = build_dir / "_build" / ".jupyter_cache"
    if build_dir != ROOT and CACHE.exists() and not cache.exists():
        cache.parent.mkdir(parents=True, exist_ok=True)
        cache.symlink_to(CACHE, target_is_directory=True)       # the HTML build's executions
    jupyter_book = Path(sys.executable).parent / "jupyter-book"
    build = subprocess.run([str(jupyter_book), "build", str(ROOT), "--builder", "singlehtml",
                            "--path-output", str(build_dir)], capture_output=True, text=True)
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


def print_pdf(page, out, chromium=None, timeout_s=120):
    """Print an HTML page to PDF with headless Chromium once its equations are typeset.

    Parameters
    ----------
    page : path-like
        The HTML file (served with its folder, so its scripts and fonts load).
    out : path-like
        The PDF to write.
    chromium : str, optional
        The browser's executable; default ``chromium`` on the PATH.
    timeout_s : float
        Seconds to wait for MathJax and the images.

    Returns
    -------
    pathlib.Path
        ``out``.

    Raises
    ------
    RuntimeError
        If Chromium is missing, or equations are still TeX source when printing.
    """
    from playwright.sync_api import sync_playwright

    chromium = chromium or CHROMIUM
    if chromium is None:
        raise RuntimeError("Chromium is not installed: apt-get install chromium")
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
            tab.evaluate(WIDGETS_TO_NOTES)
            tab.add_style_tag(content=PRINT_CSS)
            tab.emulate_media(media="print")
            tab.pdf(path=str(out), format="A4", print_background=True, display_header_footer=True,
                    header_template="<span></span>", footer_template=FOOTER,
                    margin={"top": "15mm", "bottom": "15mm", "left": "12mm", "right": "12mm"})
            browser.close()
    finally:
        server.shutdown()
    return out


def main(argv=None):
    """The command line: build the single page, print it, say where the PDF is."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(DEFAULT_PDF), help="the PDF to write")
    parser.add_argument("--build-dir", default=str(ROOT),
                        help="where _build/singlehtml goes (default: the repository)")
    options = parser.parse_args(argv)
    page = build_singlehtml(options.build_dir)
    out = print_pdf(page, options.out)
    print(f"{out} ({out.stat().st_size / 1e6:.1f} MB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
