"""The student edition: the full course, in both languages, with only the solutions removed.

It is a folder to publish: no file in it holds a worked solution's code (rsgeo included), its
launch buttons and notebooks name the student repository, never the course's, and it carries
the Portuguese configuration and catalogues. Its chapters are executed when it is built (every
figure there), its exercise notebooks stop at their first task, and its own build command, from
the README, succeeds (the English book is built here; the Portuguese one is checked by its
configuration, cheaply).
"""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest
import yaml
from nbclient.exceptions import CellExecutionError

from notebook_runner import ROOT, execute_notebook

sys.path.insert(0, str(ROOT / "exercises"))
from make_student_edition import (  # noqa: E402
    BEGIN,
    INSTRUCTORS_ONLY,
    PLACEHOLDER,
    make_student_edition,
    solution_lines,
    strip_solutions,
    student_repository,
)

# the book's notebooks that students get (the teaching guide is for instructors only)
CHAPTERS = sorted(path.relative_to(ROOT) for path in (ROOT / "book").glob("*.ipynb")
                  if path.relative_to(ROOT).with_suffix("").as_posix() not in INSTRUCTORS_ONLY)


@pytest.fixture(scope="module")
def edition(tmp_path_factory):
    folder = tmp_path_factory.mktemp("student") / "student_edition"
    assert make_student_edition(folder) >= 16
    return folder


def test_solutions_are_gone_and_checks_stay(edition):
    for path in sorted((edition / "exercises").glob("*.ipynb")):
        sources = [cell.source for cell in nbformat.read(path, as_version=4).cells
                   if cell.cell_type == "code"]
        assert not any(BEGIN in source for source in sources)
        assert any("check_" in source for source in sources)


def test_the_teaching_guide_stays_with_the_instructors(edition):
    assert INSTRUCTORS_ONLY == ("book/teaching_guide",)
    assert (ROOT / "book" / "teaching_guide.ipynb").exists()
    assert not list(edition.rglob("teaching_guide*"))         # page, catalogues
    assert "teaching_guide" not in (edition / "_toc.yml").read_text()
    toc = yaml.safe_load((edition / "_toc.yml").read_text())
    course = yaml.safe_load((ROOT / "_toc.yml").read_text())
    pages = [entry["file"] for part in toc["parts"] for entry in part["chapters"]]
    assert pages == [entry["file"] for part in course["parts"] for entry in part["chapters"]
                     if entry["file"] not in INSTRUCTORS_ONLY]


def test_chapters_are_the_instructors_chapters(edition):
    for chapter in CHAPTERS:
        assert (edition / chapter).read_bytes() == (ROOT / chapter).read_bytes(), chapter
    config = (edition / "_config.yml").read_text()
    # chapters run, figures and all
    assert re.search(r"execute_notebooks:\s*(force|cache)", config)
    # exercises: students run them
    assert re.search(r"exclude_patterns:\n\s+- \"exercises/\*\"", config)


@pytest.mark.parametrize("name",
                         sorted(path.name for path in (ROOT / "exercises").glob("*.ipynb")))
def test_student_notebook_stops_at_its_first_task(edition, name):
    path = edition / "exercises" / name
    with pytest.raises(CellExecutionError) as failure:
        execute_notebook(path)
    assert failure.value.ename == "ExerciseNotSolved"
    assert "this task is yours" in str(failure.value)
    # it stopped at the first check, not earlier
    cells = nbformat.read(path, as_version=4).cells
    first_check = next(cell for cell in cells
                       if cell.cell_type == "code" and cell.source.startswith("check_"))
    assert first_check.source in str(failure.value)


def test_the_edition_builds_with_every_chapter_executed(edition):
    # The README's command (`jupyter-book build student_edition`), warnings as errors here.
    jupyter_book = Path(sys.executable).parent / "jupyter-book"
    build = subprocess.run([str(jupyter_book), "build", str(edition), "-W", "-n", "--keep-going"],
                           capture_output=True, text=True, timeout=1500)
    assert build.returncode == 0, (build.stdout + build.stderr)[-4000:]
    if os.environ.get("CI"):            # CI built the course just before: no chapter runs twice
        executed = re.findall(r"(\S+\.ipynb): Executing notebook", build.stdout + build.stderr)
        assert not executed, f"the edition executed again: {executed}"
    html = edition / "_build" / "html"
    for chapter in CHAPTERS:
        page = (html / chapter.with_suffix(".html")).read_text()
        assert "cell_output" in page, f"{chapter}: no outputs: the chapter was not executed"
        # the switch to the Portuguese student book, built beside it (README's second command)
        switch = f'href="../../pt_BR/_build/html/{chapter.with_suffix(".html").as_posix()}"'
        assert "rsgeo-language-switch" in page and switch in page, f"{chapter}: no switch"
        if chapter.name.startswith("0") and "_widget" not in chapter.name:
            assert re.search(r"<img[^>]+(_images/|data:image/png)", page), (
                f"{chapter} has no figure")
    for exercise in sorted((edition / "exercises").glob("*.ipynb")):
        page = (html / "exercises" / exercise.with_suffix(".html").name).read_text()
        assert BEGIN not in page and "check_" in page
    assert not (html / "book" / "teaching_guide.html").exists()


def test_unbalanced_markers_are_refused():
    with pytest.raises(ValueError, match="without"):
        strip_solutions("x = ...\n### BEGIN SOLUTION\nx = 1\n")


# -- A folder to publish: no solution in it, the student repository everywhere ------------------

def taught_solution_lines():
    """The lines of the worked solutions that the chapters do not teach themselves (a solution
    may reuse a chapter's line; that line is no secret): what the edition must not contain."""
    chapters = "".join(path.read_text() for path in (ROOT / "book").glob("*.ipynb"))
    lines = set()
    for path in (ROOT / "exercises").glob("*.ipynb"):
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type == "code":
                lines.update(line.strip() for line in solution_lines(cell.source))
    # short lines ("x = 1.0", "return dx") say nothing about a solution
    return {line for line in lines if len(line) >= 25 and json.dumps(line)[1:-1] not in chapters
            and line not in chapters}


def files_with_solutions(folder):
    """{file: a solution line it contains} over every text file under ``folder``."""
    lines = taught_solution_lines()
    found = {}
    for path in sorted(Path(folder).rglob("*")):
        if not path.is_file() or "_build" in path.parts:
            continue
        try:
            text = path.read_text()
        except UnicodeDecodeError:                    # images, compiled catalogues
            continue
        leaked = [line for line in lines if line in text or json.dumps(line)[1:-1] in text]
        if leaked:
            found[str(path.relative_to(folder))] = leaked[0]
    return found


def test_no_file_of_the_edition_holds_a_solution(edition):
    assert len(taught_solution_lines()) >= 50
    assert files_with_solutions(edition) == {}
    # rsgeo ships with it (what its first cell installs), and the instructors' tools do not
    assert (edition / "rsgeo_course" / "exercises" / "__init__.py").exists()
    assert (edition / "pyproject.toml").exists() and (edition / "requirements.txt").exists()
    assert sorted(path.name for path in (edition / "exercises").iterdir()) == sorted(
        path.name for path in (ROOT / "exercises").glob("*.ipynb"))


def test_the_solution_finder_finds_the_course_solutions():
    # the check above can fail: the course's own exercises hold every solution
    found = files_with_solutions(ROOT / "exercises")
    assert len(found) == len(list((ROOT / "exercises").glob("*.ipynb")))


def test_the_edition_has_a_readme_for_students(edition):
    readme = (edition / "README.md").read_text()
    assert "student edition" in readme and "Em português" in readme
    assert "_config_pt.yml" in readme and "ExerciseNotSolved" in readme
    for tool in ("grade.py", "print_course.py", "make_student_edition.py"):
        assert tool not in readme


def first_cell_urls(folder):
    urls = {}
    for path in sorted(folder.glob("book/*.ipynb")) + sorted(folder.glob("exercises/*.ipynb")):
        install = [cell.source for cell in nbformat.read(path, as_version=4).cells
                   if cell.source.startswith("# Outside the course's environment")]
        found = re.search(r'url = "([^"]*)"', install[0]) if len(install) == 1 else None
        urls[path.name] = found and found.group(1)
    return urls


def test_launch_buttons_and_notebooks_open_the_student_repository(tmp_path):
    url = "https://github.com/a-school/geometric-correction-students"
    folder = tmp_path / "edition"
    make_student_edition(folder, repository=url)
    assert set(first_cell_urls(folder).values()) == {url}
    for name in ("_config.yml", "_config_pt.yml"):
        config = yaml.safe_load((folder / name).read_text())
        assert config["repository"]["url"] == url, name
        assert "student_repository" not in config
    # the course's repository is named nowhere a student can follow it
    course = yaml.safe_load((ROOT / "_config.yml").read_text())["repository"]["url"]
    for path in folder.rglob("*"):
        if path.suffix in (".ipynb", ".yml", ".md"):
            assert course not in path.read_text(), path


def test_without_a_student_repository_the_edition_has_no_launch_button(edition):
    # the placeholder, which book/_ext/offline_book.py turns into no button at all
    sys.path.insert(0, str(ROOT / "book" / "_ext"))
    from offline_book import repository_configured

    assert not repository_configured(PLACEHOLDER)
    assert set(first_cell_urls(edition).values()) == {PLACEHOLDER}
    config = yaml.safe_load((edition / "_config.yml").read_text())
    assert config["repository"]["url"] == PLACEHOLDER


def test_the_student_repository_is_read_from_the_course_config(tmp_path):
    config = tmp_path / "_config.yml"
    config.write_text("title: x\nstudent_repository: https://github.com/a-school/students/\n")
    assert student_repository(config) == "https://github.com/a-school/students"
    for value in ("", "https://github.com/OWNER/REPOSITORY", "null"):
        config.write_text(f"title: x\nstudent_repository: {value}\n")
        assert student_repository(config) is None
    config.write_text("title: x\n")
    assert student_repository(config) is None


# -- Both languages ----------------------------------------------------------------------------

def test_the_portuguese_student_book_is_configured(edition):
    from jupyter_book.config import get_final_config

    english, portuguese = (
        get_final_config(user_yaml=edition / name, sourcedir=edition, raise_on_invalid=True,
                         cli_config={"latex_individualpages": False})[0]
        for name in ("_config.yml", "_config_pt.yml"))
    assert portuguese["language"] == "pt_BR" and portuguese["locale_dirs"] == ["locales"]
    # each book links to the other, as the course's books do (the language switch is kept)
    assert english["i18n_other_book"] == "../pt_BR/_build/html"
    assert portuguese["i18n_other_book"] == "../../../html"
    for config in (english, portuguese):
        assert config["nb_execution_excludepatterns"] == ["exercises/*"]
    assert "edição do estudante" in portuguese["html_title"]
    assert english["nb_execution_cache_path"] == portuguese["nb_execution_cache_path"]
    # a catalogue for every page of the table of contents (chapters, exercises, reference)
    pages = re.findall(r"(?:root|file): (\S+)", (edition / "_toc.yml").read_text())
    assert len(pages) > 20
    for page in pages:
        assert (edition / "locales" / "pt_BR" / "LC_MESSAGES" / f"{page}.po").exists(), page
