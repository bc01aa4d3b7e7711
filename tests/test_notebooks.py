"""Every notebook of the book and the exercises runs top to bottom, with readable figures;
chapters assert the numbers their prose states. (Notebooks stored without outputs and with short
code lines: nbstripout and nbQA-ruff check that, run by pre-commit.)"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest
from nbclient.exceptions import CellExecutionError

from notebook_runner import BOOK_CACHE, ROOT, execute_notebook, executed_notebook

NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb")) + sorted((ROOT / "exercises").glob("*.ipynb"))


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 14


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda path: path.name)
def test_notebook_runs(path):
    notebook = executed_notebook(path)          # the book build's execution when it is current
    # every figure it renders (shown, animated, drawn by a widget) is readable on its own
    problems = notebook.metadata["figure_problems"]
    assert problems == [], "\n".join(problems)
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            assert output.output_type != "error", (
                f"{path.name}: {output.get('ename')}: {output.get('evalue')}")
    # CI executes each notebook once: in the build
    if os.environ.get("CI") and BOOK_CACHE.exists():
        assert notebook.metadata.get("executed_by") == "the book build", f"{path.name} ran twice"
    if path.parent.name == "exercises":
        texts = [output["data"]["text/plain"] for cell in notebook.cells
                 for output in cell.get("outputs", []) if "text/plain" in output.get("data", {})]
        verdicts = [text for text in texts if text.startswith(("Correct", "Not yet"))]
        assert verdicts, f"{path.name} checks nothing"
        assert all(verdict.startswith("Correct") for verdict in verdicts), verdicts


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda path: path.name)
def test_chapter_structure(path):
    cells = nbformat.read(path, as_version=4).cells
    text = "\n".join(cell.source for cell in cells if cell.cell_type == "markdown")
    for heading in ("## Overview", "## Prerequisites", "## Summary", "## What's next"):
        assert heading in text, f"{path.name} lacks '{heading}'"


CHAPTERS = [path for path in NOTEBOOKS if path.parent.name == "book" and path.name[0].isdigit()]


@pytest.mark.parametrize("path", CHAPTERS, ids=lambda path: path.name)
def test_chapter_asserts_the_numbers_its_prose_states(path):
    # a hidden cell (tag remove-cell) after each stated result: a change that moves the result
    # fails the build instead of falsifying the text
    cells = nbformat.read(path, as_version=4).cells
    checks = [cell for cell in cells if cell.cell_type == "code"
              and "remove-cell" in cell.metadata.get("tags", []) and "assert" in cell.source]
    assert checks, f"{path.name} has no remove-cell assertion"
    for cell in checks:
        assert len(cell.source.splitlines()) <= 15, f"{path.name}: keep assertion cells short"


def test_figure_rules_catch_what_they_say():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from figure_audit import figure_problems

    figure, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], color="white", label="true relation")
    ax.legend()
    ax.set(title="a line", xlabel="column", ylabel="row (px)")
    problems = figure_problems(figure)
    assert any("x label 'column' has no units" in problem for problem in problems)
    assert any("'true relation' is drawn in the background colour" in problem
               for problem in problems)
    assert not any("y label" in problem for problem in problems)
    image = ax.imshow([[0, 1], [2, 3]])
    figure.colorbar(image, ax=ax, label="value")
    assert any("colour bar label 'value'" in problem for problem in figure_problems(figure))
    plt.close(figure)


KERNELSPEC = {"name": "python3", "display_name": "Python 3", "language": "python"}


def failing_notebook(folder):
    notebook = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_markdown_cell("# Broken\n\nA chapter whose second cell fails."),
        nbformat.v4.new_code_cell("x = 1"),
        nbformat.v4.new_code_cell("raise RuntimeError('this cell is broken on purpose')"),
    ])
    notebook.metadata["kernelspec"] = KERNELSPEC
    path = Path(folder) / "broken.ipynb"
    nbformat.write(notebook, path)
    return path


def test_a_failing_cell_fails_execution(tmp_path):
    with pytest.raises(CellExecutionError, match="broken on purpose"):
        execute_notebook(failing_notebook(tmp_path))


def test_a_failing_cell_or_an_unreadable_figure_fails_the_book_build(tmp_path):
    # the same configuration as the course's, on a two-page book: one page raises, the other draws
    # a figure without title or axis labels (the build's kernels audit figures, see offline_book.py
    # and figure_audit.py)
    config = (ROOT / "_config.yml").read_text()
    config = config.replace("bibtex_bibfiles:\n  - references.bib\n", "")
    (tmp_path / "_config.yml").write_text(config)
    (tmp_path / "_toc.yml").write_text("format: jb-book\nroot: broken\n"
                                       "chapters:\n  - file: unlabelled\n")
    # the local extensions (with the figure audit) and the vendored JavaScript
    for folder in ("_ext", "_vendor"):
        shutil.copytree(ROOT / "book" / folder, tmp_path / "book" / folder, symlinks=True)
    failing_notebook(tmp_path)
    unlabelled = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_markdown_cell("# Unlabelled\n\nA page whose figure has no labels."),
        nbformat.v4.new_code_cell("import rsgeo\nimport matplotlib.pyplot as plt\n"
                                  "plt.plot([0, 1], [1, 0])\nplt.show()"),
    ])
    unlabelled.metadata["kernelspec"] = KERNELSPEC
    nbformat.write(unlabelled, tmp_path / "unlabelled.ipynb")
    jupyter_book = Path(sys.executable).parent / "jupyter-book"      # the command the README uses
    build = subprocess.run([str(jupyter_book), "build", str(tmp_path), "-W", "-n", "--keep-going"],
                           capture_output=True, text=True, timeout=600)
    output = build.stdout + build.stderr
    assert build.returncode != 0, output[-2000:]
    assert "broken on purpose" in output
    assert "unlabelled" in output and "stderr" in output.lower(), output[-3000:]
    assert "running over TCP" not in output          # the build's kernels talk over IPC sockets


# -- The first code cell: installs the course outside its environment (Colab), nothing inside --

INSTALL_MARKER = "# Outside the course's environment"


def _toc_notebooks():
    import yaml

    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    files = [entry["file"] for part in toc["parts"] for entry in part["chapters"]]
    return [ROOT / (name + ".ipynb") for name in files if (ROOT / (name + ".ipynb")).exists()]


@pytest.mark.parametrize("path", _toc_notebooks(), ids=lambda path: path.name)
def test_first_code_cell_installs_the_course_outside_its_environment(path):
    import yaml

    url = yaml.safe_load((ROOT / "_config.yml").read_text())["repository"]["url"]
    code = [cell for cell in nbformat.read(path, as_version=4).cells if cell.cell_type == "code"]
    first = code[0]
    assert first.source.startswith(INSTALL_MARKER), f"{path.name}: the install cell is not first"
    assert "remove-input" in first.metadata.get("tags", []), f"{path.name}: the book must hide it"
    assert f'url = "{url}"' in first.source, f"{path.name}: not the repository of _config.yml"
    assert f'os.chdir("course/{path.parent.name}")' in first.source
    assert sum(cell.source.startswith(INSTALL_MARKER) for cell in code) == 1


def test_the_install_cell_does_nothing_inside_and_installs_outside(monkeypatch):
    import importlib.util
    import os
    import subprocess

    source = next(cell.source for cell in nbformat.read(_toc_notebooks()[0], as_version=4).cells
                  if cell.cell_type == "code")
    calls = []
    monkeypatch.setattr(subprocess, "run", lambda command, **kwargs: calls.append(command))
    monkeypatch.setattr(os, "chdir", lambda folder: calls.append(["chdir", folder]))
    exec(source, {})                                   # rsgeo is installed here: nothing runs
    assert calls == []
    monkeypatch.setattr(importlib.util, "find_spec", lambda name: None)     # as on Colab
    exec(source, {})
    assert calls[0][:2] == ["git", "clone"] and calls[0][-2].startswith("https://github.com/")
    assert calls[1][1:4] == ["-m", "pip", "install"] and calls[1][-1] == "./course[widgets]"
    assert calls[2][0] == "chdir"
