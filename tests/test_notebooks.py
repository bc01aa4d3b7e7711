"""Every notebook of the book and the exercises runs top to bottom; committed notebooks are clean."""

import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest
from nbclient.exceptions import CellExecutionError

from conftest import ROOT, execute_notebook

NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb")) + sorted((ROOT / "exercises").glob("*.ipynb"))


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 14


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda path: path.name)
def test_committed_without_outputs(path):
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        if cell.cell_type == "code":
            assert not cell.outputs and cell.execution_count is None, f"{path.name} holds outputs: clear them"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda path: path.name)
def test_notebook_runs(path):
    notebook = execute_notebook(path)
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            assert output.output_type != "error", f"{path.name}: {output.get('ename')}: {output.get('evalue')}"
    if path.parent.name == "exercises":
        verdicts = [output["data"]["text/plain"] for cell in notebook.cells for output in cell.get("outputs", [])
                    if "text/plain" in output.get("data", {}) and output["data"]["text/plain"].startswith(("Correct", "Not yet"))]
        assert verdicts, f"{path.name} checks nothing"
        assert all(verdict.startswith("Correct") for verdict in verdicts), verdicts


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda path: path.name)
def test_chapter_structure(path):
    text = "\n".join(cell.source for cell in nbformat.read(path, as_version=4).cells if cell.cell_type == "markdown")
    for heading in ("## Overview", "## Prerequisites", "## Summary", "## What's next"):
        assert heading in text, f"{path.name} lacks '{heading}'"


def failing_notebook(folder):
    notebook = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_markdown_cell("# Broken\n\nA chapter whose second cell fails."),
        nbformat.v4.new_code_cell("x = 1"),
        nbformat.v4.new_code_cell("raise RuntimeError('this cell is broken on purpose')"),
    ])
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    path = Path(folder) / "broken.ipynb"
    nbformat.write(notebook, path)
    return path


def test_a_failing_cell_fails_execution(tmp_path):
    with pytest.raises(CellExecutionError, match="broken on purpose"):
        execute_notebook(failing_notebook(tmp_path))


def test_a_failing_cell_fails_the_book_build(tmp_path):
    # the same configuration as the course's, on a one-page book whose page fails
    config = (ROOT / "_config.yml").read_text()
    (tmp_path / "_config.yml").write_text(config.replace("bibtex_bibfiles:\n  - references.bib\n", ""))
    (tmp_path / "_toc.yml").write_text("format: jb-book\nroot: broken\n")
    for folder in ("_ext", "_vendor"):                  # the local extension and the vendored JavaScript
        shutil.copytree(ROOT / "book" / folder, tmp_path / "book" / folder, symlinks=True)
    failing_notebook(tmp_path)
    jupyter_book = Path(sys.executable).parent / "jupyter-book"      # the command the README uses
    build = subprocess.run([str(jupyter_book), "build", str(tmp_path), "-W", "-n", "--keep-going"],
                           capture_output=True, text=True, timeout=600)
    assert build.returncode != 0, build.stdout[-2000:]
    assert "broken on purpose" in build.stdout + build.stderr
