"""The printable course: exercises/print_course.py makes one PDF of the whole book, and the PDF has
every chapter, its figures and typeset equations (no TeX source left by MathJax).

The single-page build reuses the HTML build's executions (``_build/.jupyter_cache``), so the book
must have been built first (the README's first command). Needs Debian's Chromium and poppler's
``pdftotext`` and ``pdfinfo`` (``apt-get install chromium poppler-utils``); without them these
tests are skipped, unless RSGEO_REQUIRE_BROWSER=1 (CI sets it), when they fail.
"""

import re
import shutil
import subprocess
import sys

import nbformat
import pytest
import yaml

from notebook_runner import BOOK_CACHE, ROOT, skip_module_unless_ready

sys.path.insert(0, str(ROOT / "exercises"))
import print_course  # noqa: E402


def _missing():
    if print_course.CHROMIUM is None:
        return "Chromium is not installed (apt-get install chromium)"
    if not (shutil.which("pdftotext") and shutil.which("pdfinfo")):
        return "pdftotext is not installed (apt-get install poppler-utils)"
    if not BOOK_CACHE.exists():
        return "the book is not built (jupyter-book build . -W -n --keep-going)"
    return None


skip_module_unless_ready(_missing(), "PDF tests")


def chapter_titles():
    """The first heading of every page in _toc.yml, as the book shows it."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    titles = []
    for entry in [{"file": toc["root"]}] + [entry for part in toc["parts"]
                                            for entry in part["chapters"]]:
        path = next(ROOT.glob(entry["file"] + ".*"))
        if path.suffix == ".ipynb":
            text = "\n".join(cell.source for cell in nbformat.read(path, as_version=4).cells
                             if cell.cell_type == "markdown")
        else:
            text = path.read_text()
        title = re.search(r"^# (.+)$", text, flags=re.M).group(1)
        titles.append(re.sub(r"[*`]", "", title).strip())
    return titles


@pytest.fixture(scope="module")
def pdf(tmp_path_factory):
    folder = tmp_path_factory.mktemp("print")
    out = folder / "rsgeo-course.pdf"
    run = subprocess.run([sys.executable, str(ROOT / "exercises" / "print_course.py"),
                          "--build-dir", str(folder), "--out", str(out)],
                         capture_output=True, text=True, timeout=1500)
    assert run.returncode == 0, (run.stdout + run.stderr)[-3000:]
    text = subprocess.run(["pdftotext", "-layout", str(out), "-"], capture_output=True,
                          text=True, check=True).stdout
    info = subprocess.run(["pdfinfo", str(out)], capture_output=True, text=True, check=True).stdout
    pages = int(re.search(r"^Pages:\s+(\d+)", info, flags=re.M).group(1))
    print(f"PDF: {pages} pages, {out.stat().st_size / 1e6:.1f} MB")
    return out, text, pages


def test_the_pdf_has_pages_and_figures(pdf):
    out, text, pages = pdf
    assert pages >= 2 * len(chapter_titles())              # every chapter takes pages, not lines
    assert out.stat().st_size > 1e6                         # the figures are in it (PNG images)


def test_every_chapter_title_is_in_the_pdf(pdf):
    body = re.sub(r"^\s*\d+ / \d+\s*$", "", pdf[1], flags=re.M)       # page footers
    flat = " ".join(body.split())
    missing = [title for title in chapter_titles() if " ".join(title.split()) not in flat]
    assert not missing, missing


def test_no_equation_is_left_as_tex_source(pdf):
    text = pdf[1]
    for source in ("\\(", "\\)", "\\[", "$$", "\\frac", "\\sqrt", "\\begin{"):
        assert source not in text, f"{source!r} in the PDF: MathJax did not typeset every equation"


def test_untypeset_math_stops_the_print(tmp_path):
    # a page whose equation MathJax never sees (no MathJax at all): the script refuses to print
    (tmp_path / "page.html").write_text(
        "<html><head><script>window.MathJax = {startup: {promise: Promise.resolve()}};</script>"
        "</head><body><h1>A page</h1><span class='math'>\\(\\frac{a}{b}\\)</span></body></html>")
    with pytest.raises(RuntimeError, match="still TeX source"):
        print_course.print_pdf(tmp_path / "page.html", tmp_path / "page.pdf", timeout_s=20)
    assert not (tmp_path / "page.pdf").exists()
