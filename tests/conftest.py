"""Shared test helpers: where the repository is, and running a notebook the way CI does."""

import json
import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parent.parent

# Injected before a notebook's first cell and after its last: every figure the notebook renders
# (shown, animated or drawn by a widget) is checked by rsgeo.plot.figure_problems.
AUDIT_START = "import rsgeo.plot\nrsgeo.plot.audit_rendered_figures()"
AUDIT_END = "import json, rsgeo.plot\nprint('FIGURE_PROBLEMS=' + json.dumps(rsgeo.plot.FIGURE_PROBLEMS))"


def execute_notebook(path, timeout=600, audit_figures=False):
    """Execute a notebook top to bottom in its own folder; return it with outputs.

    With ``audit_figures``, the returned notebook has ``metadata["figure_problems"]``
    (see :func:`rsgeo.plot.figure_problems`) and ``metadata["seconds"]``.
    Raises nbclient's CellExecutionError at the first failing cell.
    """
    notebook = nbformat.read(path, as_version=4)
    if audit_figures:
        notebook.cells.insert(0, nbformat.v4.new_code_cell(AUDIT_START))
        notebook.cells.append(nbformat.v4.new_code_cell(AUDIT_END))
    client = NotebookClient(notebook, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(Path(path).parent)}})
    start = time.perf_counter()
    client.execute()
    notebook.metadata["seconds"] = time.perf_counter() - start
    if audit_figures:
        text = "".join(output.get("text", "") for output in notebook.cells[-1].outputs)
        notebook.metadata["figure_problems"] = json.loads(text.split("FIGURE_PROBLEMS=", 1)[1])
        del notebook.cells[0], notebook.cells[-1]
    return notebook


@pytest.fixture(scope="session")
def root():
    return ROOT
