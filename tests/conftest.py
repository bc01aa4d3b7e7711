"""Shared test helpers: where the repository is, and running a notebook the way CI does."""

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parent.parent


def execute_notebook(path, timeout=600):
    """Execute a notebook top to bottom in its own folder; return it with outputs.

    Raises nbclient's CellExecutionError at the first failing cell.
    """
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(notebook, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(Path(path).parent)}})
    client.execute()
    return notebook


@pytest.fixture(scope="session")
def root():
    return ROOT
