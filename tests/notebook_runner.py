"""Running a notebook the way the tests and CI do, with every rendered figure audited.

Imported by the tests and by ``benchmarks/notebooks.py`` (never conftest.py, which pytest owns).
"""

import json
import tempfile
import time
from pathlib import Path

import nbformat
from jupyter_client.manager import KernelManager
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parent.parent

# Injected before a notebook's first cell and after its last: every figure the notebook renders
# (shown, animated or drawn by a widget) is checked by rsgeo.plot.figure_problems.
AUDIT_START = "import rsgeo.plot\nrsgeo.plot.audit_rendered_figures()"
AUDIT_END = "import json, rsgeo.plot\nprint('FIGURE_PROBLEMS=' + json.dumps(rsgeo.plot.FIGURE_PROBLEMS))"


def execute_notebook(path, timeout=600, audit_figures=False):
    """Execute a notebook top to bottom in its own folder; return it with outputs.

    The kernel talks to this process over Unix sockets in a private folder (IPC), not TCP ports,
    so kernels started at once by parallel test workers cannot take each other's ports.
    With ``audit_figures``, the returned notebook has ``metadata["figure_problems"]``
    (see :func:`rsgeo.plot.figure_problems`). ``metadata["seconds"]`` is its wall time.
    Raises nbclient's CellExecutionError at the first failing cell.
    """
    notebook = nbformat.read(path, as_version=4)
    if audit_figures:
        notebook.cells.insert(0, nbformat.v4.new_code_cell(AUDIT_START))
        notebook.cells.append(nbformat.v4.new_code_cell(AUDIT_END))
    with tempfile.TemporaryDirectory(prefix="rsgeo-kernel-") as sockets:
        manager = KernelManager(kernel_name="python3", transport="ipc", ip=str(Path(sockets) / "kernel"))
        client = NotebookClient(notebook, km=manager, timeout=timeout, kernel_name="python3",
                                resources={"metadata": {"path": str(Path(path).parent)}})
        start = time.perf_counter()
        client.execute()
        notebook.metadata["seconds"] = time.perf_counter() - start
    if audit_figures:
        text = "".join(output.get("text", "") for output in notebook.cells[-1].outputs)
        notebook.metadata["figure_problems"] = json.loads(text.split("FIGURE_PROBLEMS=", 1)[1])
        del notebook.cells[0], notebook.cells[-1]
    return notebook
