"""The printable course: exercises/print_course.py prints the instructor's edition (the whole
book but its API reference) and the student edition; each PDF is labelled, has a cover, a table of
contents and an outline, every chapter with its figures and typeset equations (no TeX source
left by MathJax), links inside the document instead of to the print server, and nothing cut at
the right edge.

The instructor's edition is printed whole (about 40 s here, as before); the student edition only
chapter 3 (a wide table, a long code line) and exercises 1 (a few seconds), which is what sets
the editions apart. The single-page build reuses the HTML build's executions
(``_build/.jupyter_cache``), so the book must have been built first (the README's first
command). Needs Debian's Chromium and poppler's ``pdftotext`` and ``pdfinfo`` (``apt-get install
chromium poppler-utils``); without them these tests are skipped, unless RSGEO_REQUIRE_BROWSER=1
(CI sets it), when they fail.
"""

import re
import shutil
import subprocess
import sys

import nbformat
import pytest

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


STUDENT_PAGES = ["book/03_evaluating_models", "exercises/ex01_distortions"]
# chapter 3's code cell with an 88-character line, and its table's last column's header
LONG_LINE_END = "tolerance=2.5)"
GCP_TABLE_HEADER = re.compile(r"\bdx +dy +residual +residual_map\b")


def chapter_titles(with_api=False):
    """The first heading of every page that print_course.py prints, as the book shows it."""
    toc = print_course.print_toc(with_api=with_api)
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


def print_edition(folder, edition, *only):
    """Run print_course.py; return the PDF's path, its pages' text (``-layout``) and bytes."""
    out = folder / f"{edition}.pdf"
    command = [sys.executable, str(ROOT / "exercises" / "print_course.py"), "--edition", edition,
               "--build-dir", str(folder), "--out", str(out)]
    if only:
        command += ["--only", *only]
    run = subprocess.run(command, capture_output=True, text=True, timeout=1500)
    assert run.returncode == 0, (run.stdout + run.stderr)[-3000:]
    text = subprocess.run(["pdftotext", "-layout", str(out), "-"], capture_output=True,
                          text=True, check=True).stdout
    pages = text.split("\f")[:-1]          # pdftotext ends every page with a form feed
    print(f"{edition}: {len(pages)} pages, {out.stat().st_size / 1e6:.1f} MB")
    return out, pages, out.read_bytes()


@pytest.fixture(scope="module")
def pdf(tmp_path_factory):
    """The instructor's edition, whole (without the API reference, as by default)."""
    return print_edition(tmp_path_factory.mktemp("instructor"), "instructor")


@pytest.fixture(scope="module")
def student_pdf(tmp_path_factory):
    """The student edition of chapter 3 and exercises 1."""
    return print_edition(tmp_path_factory.mktemp("student"), "student", *STUDENT_PAGES)


@pytest.fixture(params=["instructor", "student"])
def edition(request):
    """Each edition's name and PDF (path, pages' text, bytes)."""
    return request.param, request.getfixturevalue("pdf" if request.param == "instructor"
                                                  else "student_pdf")


def flat(text):
    """``text`` on one line, single spaces, without page footers ("3 / 250")."""
    return " ".join(re.sub(r"^\s*\d+ / \d+\s*$", "", text, flags=re.M).split())


def test_the_pdf_has_pages_and_figures(pdf):
    out, pages, _ = pdf
    assert len(pages) >= 2 * len(chapter_titles())        # every chapter takes pages, not lines
    assert out.stat().st_size > 1e6                         # the figures are in it (PNG images)


def test_every_chapter_title_is_in_the_pdf_and_the_api_reference_is_not(pdf):
    text = flat("\n".join(pdf[1]))
    missing = [title for title in chapter_titles() if " ".join(title.split()) not in text]
    assert not missing, missing
    # left out unless --with-api (other pages name it: its heading and first words are absent)
    assert "this page is generated from its docstrings" not in text
    assert not re.search(rb"/Title \(API reference\)", pdf[2])


def test_the_api_reference_is_printed_only_when_asked():
    assert "book/api" not in str(print_course.print_toc())
    assert "book/api" in str(print_course.print_toc(with_api=True))
    only = print_course.print_toc(only=STUDENT_PAGES)
    assert [entry["file"] for part in only["parts"] for entry in part["chapters"]] == STUDENT_PAGES
    with pytest.raises(ValueError, match="not in _toc.yml: book/nowhere"):
        print_course.print_toc(only=["book/nowhere"])


def test_each_edition_says_which_it_is_on_its_cover_and_every_page(edition):
    name, (_, pages, _) = edition
    label = print_course.EDITIONS[name]
    other = print_course.EDITIONS["student" if name == "instructor" else "instructor"]
    cover = flat(pages[0])
    assert "Geometric correction of remote-sensing images" in cover.replace("- ", "-")
    assert label in cover and "Language: English" in cover
    assert re.search(r"Printed \d{4}-\d\d-\d\d from commit \w+", cover), cover
    unlabelled = [n for n, page in enumerate(pages, start=1) if label not in page]
    assert not unlabelled, f"pages without the running header {label!r}: {unlabelled[:10]}"
    assert other not in "\n".join(pages)


def test_only_the_instructors_edition_has_solutions_and_verdicts(pdf, student_pdf):
    instructor, student = flat("\n".join(pdf[1])), flat("\n".join(student_pdf[1]))
    assert "### BEGIN SOLUTION" in instructor and "Correct: `skew_km` =" in instructor
    assert "Exercises 1: systematic distortions" in student and "skew_km = ..." in student
    for solution_or_verdict in ("BEGIN SOLUTION", "Correct:", "Not yet"):
        assert solution_or_verdict not in student


def test_contents_and_outline_list_the_chapters(edition):
    name, (_, pages, data) = edition
    titles = (chapter_titles() if name == "instructor" else
              [title for title in chapter_titles() if title.startswith(("3.", "Exercises 1:"))])
    assert len(titles) == (len(chapter_titles()) if name == "instructor" else 2)
    contents = flat(pages[1])                      # one page, after the cover
    missing = [title for title in titles if " ".join(title.split()) not in contents]
    assert "Contents" in contents and not missing, missing
    # the outline (bookmarks) is made from the headings: one entry per chapter at least
    assert re.search(rb"/Type /Outlines\b", data)
    outline = re.findall(rb"/Title \(([^)]*)\)", data)
    assert b"Exercises 1: systematic distortions" in outline
    assert len(outline) >= len(titles)


def test_links_stay_in_the_document_or_go_to_the_web(edition):
    out = edition[1][0]
    urls = subprocess.run(["pdfinfo", "-url", str(out)], capture_output=True, text=True,
                          check=True).stdout.splitlines()[1:]
    assert urls, "the external links are gone"
    server = [url for url in urls if "127.0.0.1" in url or "localhost" in url]
    assert not server, server[:5]
    # links between chapters are go-to-a-place links (a destination, no URI)
    data = edition[1][2]
    assert data.count(b"/Subtype /Link") > len(urls)


def test_code_wraps_and_wide_tables_fit_the_page(edition):
    pages = edition[1][1]
    assert any(GCP_TABLE_HEADER.search(page) for page in pages), "residual_map column cut"
    assert any(LONG_LINE_END in page for page in pages), "the long code line is cut"


def test_screen_controls_are_not_printed(edition):
    text = "\n".join(edition[1][1])
    for control in ("Show code cell", "Hide code cell", "Copy to clipboard", "Toggle"):
        assert control not in text


def test_no_equation_is_left_as_tex_source(pdf):
    text = "\n".join(pdf[1])
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
