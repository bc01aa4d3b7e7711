"""The printable course: exercises/print_course.py prints the instructor's edition (the whole
book but its API reference) and the student edition (without the teaching guide), in English and
in Portuguese; each PDF is labelled, has a cover (naming the commit, or the package's version in
a copy without git history), a numbered table of contents with each entry's page and an outline,
every chapter with its figures and typeset equations (no TeX source left by MathJax), links
inside the document instead of to the print server, nothing cut at the right edge, no blank page,
no empty code frame, and wrapped code lines that keep their indentation.

The four small PDFs (each edition in each language, of chapter 1 and exercises 1: their
executions are the HTML build's, so they take seconds each) check the languages, the contents'
page numbers and the blank pages; a page made here checks the hanging indent, the empty cells
and a code block taller than what is left of a page.

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
    assert re.search(r"Printed \d{4}-\d\d-\d\d from (commit \w+|rsgeo \d)", cover), cover
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


# -- Both editions in both languages, on a small book ------------------------------------------

SMALL_PAGES = ["book/01_systematic_distortions", "exercises/ex01_distortions"]
COVERS = {"en": ("Geometric correction of remote-sensing images", "Language: English",
                 "Contents", "1. Systematic distortions"),
          "pt_BR": ("Correção geométrica de imagens de sensoriamento remoto",
                    "Língua: Português (Brasil)", "Sumário", "1. Distorções sistemáticas")}
# a line of the contents: "  2.   1. Systematic distortions ........ 5"
CONTENTS_LINE = re.compile(r"^\s*(\d+)\.\s+(.+?)\s{2,}(\d+)\s*$")


@pytest.fixture(scope="module", params=[(edition, language) for edition in print_course.EDITIONS
                                        for language in print_course.LANGUAGES],
                ids=lambda param: "-".join(param))
def small(request, tmp_path_factory):
    """(edition, language, path, pages' text) of chapter 1 and exercises 1 printed."""
    edition, language = request.param
    folder = tmp_path_factory.mktemp(f"{edition}-{language}")
    out = folder / "small.pdf"
    run = subprocess.run([sys.executable, str(ROOT / "exercises" / "print_course.py"),
                          "--edition", edition, "--language", language, "--build-dir",
                          str(folder), "--out", str(out), "--only", *SMALL_PAGES],
                         capture_output=True, text=True, timeout=1500)
    assert run.returncode == 0, (run.stdout + run.stderr)[-3000:]
    return edition, language, out, print_course.pdf_pages(out)


def test_each_edition_prints_in_both_languages(small):
    edition, language, _, pages = small
    title, language_line, contents, chapter = COVERS[language]
    label = print_course.TEXTS[language]["editions"][edition]
    cover = flat(pages[0]).replace("- ", "-")
    assert title in cover and label in cover and language_line in cover, cover
    assert re.search(r"\d{4}-\d\d-\d\d (from|a partir do) commit \w+", cover), cover
    assert all(label in page for page in pages), "a page without the running header"
    text = flat("\n".join(pages))
    assert contents in flat(pages[1]) and chapter in text
    others = {print_course.TEXTS[lang]["editions"][ed] for lang in print_course.LANGUAGES
              for ed in print_course.EDITIONS} - {label}
    assert not [other for other in others if other in text]
    if language == "pt_BR":          # the Portuguese book: its text, its verdicts
        assert "Exercícios 1: distorções sistemáticas" in text
        assert "Systematic distortions" not in text and "Correct:" not in text
    if edition == "student":
        assert "BEGIN SOLUTION" not in text and "skew_km = ..." in text
        assert not re.search(r"\b(Correct|Correto):", text)
    else:
        assert "BEGIN SOLUTION" in text and re.search(r"\b(Correct|Correto): `skew_km`", text)


def test_the_contents_give_each_entry_its_page(small):
    _, language, _, pages = small
    entries = [CONTENTS_LINE.match(line) for line in pages[1].splitlines()]
    entries = [(int(found[1]), found[2], int(found[3])) for found in entries if found]
    assert [number for number, *_ in entries] == [1, 2, 3], pages[1]
    assert entries[0][2] == 3                      # the introduction, after cover and contents
    for number, title, page in entries[1:]:
        first_lines = " ".join(pages[page - 1].split()[:40])
        assert title.strip() in first_lines, (number, title, page)
        assert title.strip() not in " ".join(pages[page - 2].split()), "on the page before"
    assert entries[1][2] < entries[2][2] <= len(pages)


def test_no_page_is_blank(small):
    assert print_course.blank_pages(small[2]) == []


def test_the_teaching_guide_is_for_the_instructors_edition_only():
    guide = "book/teaching_guide"
    files = lambda toc: [entry["file"] for part in toc["parts"]  # noqa: E731
                         for entry in part["chapters"]]
    assert guide in files(print_course.print_toc())
    assert guide not in files(print_course.print_toc(edition="student"))
    with pytest.raises(ValueError, match="for instructors only"):
        print_course.print_toc(only=[guide], edition="student")
    assert "Teaching guide" in chapter_titles()


def test_a_copy_without_git_history_names_its_version(tmp_path):
    assert print_course.course_origin()[0] == "commit"
    shutil.copyfile(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    assert print_course.course_origin(tmp_path) == ("version", "rsgeo 0.1.0")
    facts = print_course.cover_facts(root=tmp_path)
    assert facts["lines"][0].endswith("from rsgeo 0.1.0 (a copy without git history)")
    facts = print_course.cover_facts(root=tmp_path, language="pt_BR")
    assert "a partir do rsgeo 0.1.0" in facts["lines"][0]


LONG_LINE = ("    value = compute(first_argument, second_argument, third_argument, "
             "fourth_argument, fifth_argument, sixth_argument)")


def test_wrapped_code_hangs_under_its_indentation_and_empty_frames_go(tmp_path):
    # a long indented line; an empty cell (its code removed, no output); then, after text
    # that fills part of the page, a code block taller than what is left of it
    tall = "\n".join(f"line_{n} = {n}" for n in range(70))
    (tmp_path / "page.html").write_text(
        "<html><head><meta charset='utf-8'><script>window.MathJax = {startup: "
        "{promise: Promise.resolve()}};</script></head><body><h1>A page</h1>"
        f"<div class='cell'><div class='cell_input'><pre>def f():\n{LONG_LINE}\n"
        "    return value\n</pre></div></div>"
        "<div class='cell tag_remove-input'><div class='cell_input'><pre>\n</pre></div></div>"
        + "<p>Some text.</p>" * 25
        + f"<div class='cell'><div class='cell_input' style='border-left: 3px solid green'>"
        f"<pre>{tall}</pre></div></div></body></html>")
    result = print_course.print_pdf(tmp_path / "page.html", tmp_path / "page.pdf",
                                    timeout_s=30)
    assert result["dropped"] >= 1 and result["tall"] >= 1        # the empty cell, the tall one
    lines = [line for line in print_course.pdf_pages(tmp_path / "page.pdf")[2].splitlines()
             if line.strip()]
    start = next(n for n, line in enumerate(lines) if "value = compute(" in line)
    indent = len(lines[start]) - len(lines[start].lstrip())
    continued = lines[start + 1]
    assert "return value" not in continued, "the line did not wrap"
    # the wrapped part starts further right than the line's own indentation
    assert len(continued) - len(continued.lstrip()) > indent, lines[start:start + 2]
    assert print_course.blank_pages(tmp_path / "page.pdf") == []
