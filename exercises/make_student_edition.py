"""Make the student edition of the course: a folder to publish, without the worked solutions.

    python exercises/make_student_edition.py [OUTPUT_FOLDER] [--repository URL]
                                                          # default folder: student_edition

The edition is what students install and open: a self-contained folder that the instructor
publishes as its own repository (never the course's, which holds the worked solutions). It holds

- the book in both languages: ``_config.yml``, ``_config_pt.yml``, ``_toc.yml``,
  ``references.bib``, ``book/``, ``locales/`` (the Portuguese catalogues), the saved benchmark
  tables that chapters show (``benchmarks/results/``) and chapter 6's experiment harness;
- ``exercises/`` with every solution removed: in each exercise notebook the lines of a code cell
  between ``### BEGIN SOLUTION`` and ``### END SOLUTION`` (both included) go, leaving the task's
  ``answer = ...`` placeholder and the check that follows it, shown rather than hidden;
- ``rsgeo/`` (the library and its data), ``rsgeo_course/`` (the course's checks, figure
  descriptions and translations), ``pyproject.toml``, ``requirements.txt`` and
  ``LICENSE``, so that ``pip install -r requirements.txt`` works from the edition alone;
- its own ``README.md``, for students, in English and Portuguese.

The instructors' tools (grader, gradebook, printer, this script), the tests and the benchmarks
stay out, and so does the book's *Teaching guide* (``INSTRUCTORS_ONLY``: its page, its
catalogue and its entry in ``_toc.yml``), which is written for instructors: marking, the
mistakes the checks recognise, how to run the course.

**Where the launch buttons point.** The edition's ``repository.url`` (Binder, Colab and the
repository button) and the URL every notebook's first cell clones outside the course's
environment (Colab) are the student edition's repository: ``--repository URL``, else
``student_repository`` in the course's ``_config.yml``. While neither names a real repository,
the edition keeps the placeholder ``OWNER/REPOSITORY`` (no launch button: book/_ext/
offline_book.py), so that it never sends a student to the course's own repository.

**Both languages.** The English and the Portuguese student books are built like the course's:

    jupyter-book build OUTPUT_FOLDER
    jupyter-book build OUTPUT_FOLDER --config OUTPUT_FOLDER/_config_pt.yml \\
        --path-output OUTPUT_FOLDER/_build/pt_BR

and link to each other page by page. Their chapters are executed, with every figure, exactly as
in the instructors' book (they reuse its executions when the course's book is built and its
notebooks name the student repository already); the exercise notebooks are not executed: they
stop at their first task, by design, for students to run.
"""

import argparse
import re
import shutil
import sys
from pathlib import Path

import nbformat
import yaml

ROOT = Path(__file__).resolve().parent.parent
BEGIN, END = "### BEGIN SOLUTION", "### END SOLUTION"
# what the edition needs to build its two books and to install rsgeo; chapter 6 imports its
# experiment harness, benchmarks/ga_experiments.py, beside the saved tables
SOURCES = ("_config.yml", "_config_pt.yml", "_toc.yml", "references.bib", "book", "exercises",
           "locales", "benchmarks/results", "benchmarks/ga_experiments.py", "rsgeo",
           "rsgeo_course",
           "pyproject.toml", "requirements.txt", "LICENSE")
CONFIGS = ("_config.yml", "_config_pt.yml")
# never copied: build products and caches; of exercises/, only the exercise notebooks are (the
# instructors' tools beside them, whatever they are, stay with the instructor)
IGNORED = ("_build", ".ipynb_checkpoints", "__pycache__", "*.pyc", "*.egg-info")
#: the repository the edition names while the student repository is not known: a placeholder
#: that book/_ext/offline_book.py recognises (no launch button)
PLACEHOLDER = "https://github.com/OWNER/REPOSITORY"
# the URL in every notebook's first cell, which clones the course outside its environment
FIRST_CELL_URL = re.compile(r'^(\s*url = )"[^"]*"', flags=re.M)
FIRST_CELL_MARK = "# Outside the course's environment"
TITLE_SUFFIX = {"_config.yml": " (student edition)", "_config_pt.yml": " (edição do estudante)"}
#: pages of the book for instructors only: the student edition (and its PDF) leaves them out
INSTRUCTORS_ONLY = ("book/teaching_guide",)


def ignored(folder, names):
    """The names in ``folder`` that the edition leaves out (shutil.copytree's ``ignore``)."""
    left_out = set(shutil.ignore_patterns(*IGNORED)(folder, names))
    if Path(folder) == ROOT / "exercises":
        left_out.update(name for name in names if not name.endswith(".ipynb"))
    # the instructors' pages, and their catalogues (locales/<language>/LC_MESSAGES/book/...)
    for page in INSTRUCTORS_ONLY:
        parent, stem = page.rsplit("/", 1)
        if Path(folder).as_posix().endswith("/" + parent):
            left_out.update(name for name in names if name.rsplit(".", 1)[0] == stem)
    return left_out


def student_toc(text):
    """``_toc.yml``'s ``text`` without the pages for instructors only (``INSTRUCTORS_ONLY``)."""
    for page in INSTRUCTORS_ONLY:
        text = re.sub(rf"^[ \t]*- file: {re.escape(page)}[ \t]*\n", "", text, flags=re.M)
    if any(re.search(rf"\b{re.escape(page)}\b", text) for page in INSTRUCTORS_ONLY):
        raise ValueError("_toc.yml names a page for instructors only in a way the student "
                         f"edition cannot remove: {', '.join(INSTRUCTORS_ONLY)}")
    return text


def strip_solutions(source):
    """A code cell's source without its solution blocks; raises ValueError on unbalanced
    markers."""
    kept, inside = [], False
    for number, line in enumerate(source.splitlines(), start=1):
        marker = line.strip()
        if marker == BEGIN:
            if inside:
                raise ValueError(f"line {number}: {BEGIN} inside another solution block")
            inside = True
        elif marker == END:
            if not inside:
                raise ValueError(f"line {number}: {END} without {BEGIN}")
            inside = False
        elif not inside:
            kept.append(line)
    if inside:
        raise ValueError(f"{BEGIN} without {END}")
    return "\n".join(kept).rstrip()


def solution_lines(source):
    """The lines of ``source`` inside its solution blocks (what the edition must not contain)."""
    lines, inside = [], False
    for line in source.splitlines():
        marker = line.strip()
        if marker in (BEGIN, END):
            inside = marker == BEGIN
        elif inside:
            lines.append(line)
    return lines


def student_notebook(path):
    """Rewrite one notebook in place for students; return the number of solution cells stripped."""
    notebook = nbformat.read(path, as_version=4)
    stripped = 0
    for cell in notebook.cells:
        if cell.cell_type == "code" and BEGIN in cell.source:
            cell.source = strip_solutions(cell.source)
            tags = cell.metadata.get("tags", [])
            cell.metadata["tags"] = [tag for tag in tags if tag != "hide-input"]
            stripped += 1
    nbformat.write(notebook, path)
    return stripped


def is_real_repository(url):
    """True when ``url`` names a repository rather than a placeholder (``OWNER/...``) or
    nothing."""
    return bool(url) and "/OWNER/" not in url and url.strip().rstrip("/") != ""


def student_repository(config_path=ROOT / "_config.yml"):
    """The student edition's repository URL from ``student_repository`` in ``_config.yml``, or
    None when the setting is missing, empty or a placeholder."""
    url = (yaml.safe_load(Path(config_path).read_text()) or {}).get("student_repository")
    return url.strip().rstrip("/") if isinstance(url, str) and is_real_repository(url) else None


def point_notebook_at(path, url):
    """Make the first cell of notebook ``path`` clone ``url``; return True if it changed."""
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        if cell.cell_type == "code" and cell.source.startswith(FIRST_CELL_MARK):
            source = FIRST_CELL_URL.sub(lambda match: f'{match.group(1)}"{url}"', cell.source,
                                        count=1)
            if source == cell.source:
                return False
            cell.source = source
            nbformat.write(notebook, path)
            return True
    return False


def student_config(text, name, repository):
    """One of the course's book configurations (``name``: _config.yml or _config_pt.yml, its
    ``text``) made the student edition's; raises ValueError when a setting it edits is missing."""

    def edit(pattern, replacement, what):
        nonlocal text
        text, count = re.subn(pattern, replacement, text, count=1, flags=re.M)
        if count != 1:
            raise ValueError(f"{name} has no {what}")

    # chapters run as in the instructors' book; exercises stop at their first task, so
    # students run them
    edit(r"^execute:\n", "execute:\n  exclude_patterns:\n    - \"exercises/*\"\n",
         "`execute:` section to exclude the exercises from")
    # its chapters are the instructors' chapters, code for code, and jupyter-cache matches a
    # notebook by its code: once the course's book is built, the edition reuses its executions
    # and runs no chapter again (a chapter changed since then runs, and joins that cache). The
    # Portuguese configuration names the English build's cache already: point it there too.
    cache = ROOT / "_build" / ".jupyter_cache"
    if cache.exists():
        text = re.sub(r"^  cache: .*\n", "", text, flags=re.M)
        edit(r"^(  execute_notebooks: cache.*\n)", rf"\1  cache: {cache}\n",
             "execution into a cache (execute_notebooks: cache)")
    edit(r"^title:\s*(.*?)(\s+#.*)?$", rf"title: \1{TITLE_SUFFIX[name]}\2", "`title:`")
    # the launch buttons open the student repository, never the course's
    edit(r"^(repository:\n  url:).*$", rf"\1 {repository}", "`repository: url:`")
    # the edition is published: the course's student_repository setting has no meaning there
    text = re.sub(r"^student_repository:.*\n", "", text, flags=re.M)
    return text


STUDENT_README = """\
# {title} — student edition

The course's book and exercises, for students: every chapter, executed, with its figures, and
an exercise notebook per chapter whose `check_...` calls say "Correct" or "Not yet" with a hint.
The worked solutions are not here: each task is yours.

## Open it

- **Online** (nothing to install): the book's launch buttons (Binder, Colab) open a notebook
  from this repository; its first cell installs `rsgeo` there.
- **On your computer** (Python 3.11 or newer), from this folder:

  ```bash
  python3 -m venv .venv && . .venv/bin/activate && pip install -r requirements.txt
  jupyter lab exercises/
  ```

Run an exercise notebook from top to bottom: it stops at the first task still to do with
`ExerciseNotSolved: ... this task is yours`. Replace the task's `...` with your code and run
the cell and the check below it again. Hand in the notebook as your instructor asks.

## Build the book (optional)

In English, then in Portuguese (each page links to the same page in the other language):

```bash
jupyter-book build . && jupyter-book build . --config _config_pt.yml --path-output _build/pt_BR
```

Open `_build/html/index.html` (Portuguese: `_build/pt_BR/_build/html/index.html`).

## Em português

Este é o curso para estudantes: todos os capítulos, executados, com as figuras, e um notebook de
exercícios por capítulo, cujas verificações `check_...` respondem "Correto" ou "Ainda não", com
uma dica. As soluções resolvidas não estão aqui: cada tarefa é sua. Instale como acima, abra
`exercises/` no Jupyter e execute cada notebook do início ao fim: ele para na primeira tarefa
por fazer. O livro em português é o segundo comando de "Build the book" acima; com a variável de
ambiente `RSGEO_LANG=pt_BR`, as verificações do `rsgeo` respondem em português.
"""


def make_student_edition(output, repository=None):
    """Write the student edition into the folder ``output`` (replaced if it exists); return the
    number of solution cells removed.

    ``repository`` is the edition's own repository URL (default: ``student_repository`` in
    ``_config.yml``; without one, a placeholder and no launch button).
    """
    output = Path(output)
    target = output.resolve()
    if target == ROOT or target in ROOT.parents or any(target == ROOT / name for name in SOURCES):
        raise ValueError(f"{output} would overwrite the course itself")
    repository = repository or student_repository() or PLACEHOLDER
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    for name in SOURCES:
        source = ROOT / name
        if not source.exists():
            raise FileNotFoundError(f"{source} is missing: the student edition needs it")
        (output / name).parent.mkdir(parents=True, exist_ok=True)
        if source.is_dir():
            shutil.copytree(source, output / name, ignore=ignored)
        else:
            shutil.copy2(source, output / name)
    for name in CONFIGS:
        path = output / name
        path.write_text(student_config(path.read_text(), name, repository))
    toc = output / "_toc.yml"
    toc.write_text(student_toc(toc.read_text()))
    title = yaml.safe_load((ROOT / "_config.yml").read_text())["title"]
    (output / "README.md").write_text(STUDENT_README.format(title=title))
    for notebook in sorted((output / "book").glob("*.ipynb")) + sorted(
            (output / "exercises").glob("*.ipynb")):
        point_notebook_at(notebook, repository)
    return sum(student_notebook(path) for path in sorted((output / "exercises").glob("*.ipynb")))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="student_edition",
                        help="the edition's folder (replaced if it exists)")
    parser.add_argument("--repository", help="the edition's own repository URL (default: "
                        "student_repository in _config.yml)")
    arguments = parser.parse_args(argv)
    repository = arguments.repository or student_repository()
    count = make_student_edition(arguments.output, repository)
    folder = arguments.output
    print(f"student edition in {folder}/: {count} solutions removed.")
    if repository is None:
        print("No student repository is set (--repository, or student_repository in "
              "_config.yml): the edition has no launch button until it names one.")
    else:
        print(f"Its launch buttons and notebooks open {repository}; publish the folder there.")
        renamed = [path.name for path in sorted((ROOT / "book").glob("*.ipynb"))
                   if point_notebook_copy_differs(path, repository)]
        if renamed:
            print(f"{len(renamed)} notebooks of the book name another repository: the "
                  "edition's build runs them again (make them name the student repository, "
                  "README's \"Launch buttons\", to reuse the course's executions).")
    print(f"Build it: jupyter-book build {folder} && jupyter-book build {folder} "
          f"--config {folder}/_config_pt.yml --path-output {folder}/_build/pt_BR")


def point_notebook_copy_differs(path, url):
    """True when the course's notebook ``path`` clones another URL than ``url``."""
    notebook = nbformat.read(path, as_version=4)
    return any(cell.cell_type == "code" and cell.source.startswith(FIRST_CELL_MARK)
               and f'url = "{url}"' not in cell.source for cell in notebook.cells)


if __name__ == "__main__":
    sys.exit(main())
