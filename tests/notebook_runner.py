"""Running a notebook the way the tests and CI do, with every rendered figure audited.

Imported by the tests and by ``benchmarks/notebooks.py`` (never conftest.py, which pytest owns).

CI executes each notebook once: the book's build (the README's first command) executes every
notebook into its cache, ``_build/.jupyter_cache``, with the figure audit on in its kernels
(book/_ext/offline_book.py, figure_audit.py). :func:`executed_notebook` reads that execution
when it matches the notebook's current code and is newer than every file of rsgeo and its data,
of the course's package (its checks, figure descriptions and translations),
the saved benchmark tables, chapter 6's experiment harness and the audit; otherwise it
executes the notebook itself, with the same audit.
"""

import datetime
import os
import sys
import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "book" / "_ext"))
# the book build's kernels, the same way: over IPC sockets, the audited ones auditing figures
from figure_audit import problems_written  # noqa: E402
from offline_book import AuditedKernelManager, IPCKernelManager  # noqa: E402

BOOK_CACHE = ROOT / "_build" / ".jupyter_cache"
# what a cached execution depends on besides the notebook's own code
DEPENDENCIES = ("rsgeo", "rsgeo_course", "benchmarks/results", "benchmarks/ga_experiments.py",
                "book/_ext/figure_audit.py")


def skip_module_unless_ready(missing, what):
    """Skip the calling test module when ``missing`` (a reason) is not None, or fail it when
    RSGEO_REQUIRE_BROWSER=1 (CI sets it: there, the browser-driven tests must run)."""
    if missing is None:
        return
    if os.environ.get("RSGEO_REQUIRE_BROWSER") == "1":
        pytest.fail(f"{what} required but {missing}", pytrace=False)
    pytest.skip(missing, allow_module_level=True)


def execute_notebook(path, timeout=1800, audit_figures=False):
    """Execute a notebook top to bottom in its own folder; return it with outputs.

    The kernel talks to this process over Unix sockets in a private folder (IPC), not TCP ports,
    so kernels started at once by parallel test workers cannot take each other's ports.
    With ``audit_figures``, the kernel audits every figure it renders, as the book build's
    kernels do (book/_ext/figure_audit.py), and the returned notebook has
    ``metadata["figure_problems"]``. ``metadata["seconds"]`` is its wall time.
    Raises nbclient's CellExecutionError at the first failing cell.
    """
    notebook = nbformat.read(path, as_version=4)
    manager = (AuditedKernelManager if audit_figures else IPCKernelManager)(kernel_name="python3")
    client = NotebookClient(notebook, km=manager, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(Path(path).parent)}})
    start = time.perf_counter()
    client.execute()
    notebook.metadata["seconds"] = time.perf_counter() - start
    if audit_figures:
        notebook.metadata["figure_problems"] = problems_written(notebook)
    return notebook


def _newest_dependency():
    files = [path for name in DEPENDENCIES for path in [ROOT / name, *(ROOT / name).rglob("*")]
             if path.is_file() and "__pycache__" not in path.parts]
    return max(path.stat().st_mtime for path in files)


def cached_execution(path):
    """The book build's execution of ``path`` if it is current, else None.

    Current: the cache holds an execution of the notebook's present code, made after the last
    change to rsgeo, the course's package or the saved tables. Its figure problems are the
    standard-error lines the audit wrote (``metadata["figure_problems"]``).
    """
    if not BOOK_CACHE.exists():
        return None
    from jupyter_cache import get_cache

    cache = get_cache(BOOK_CACHE)
    try:
        key, notebook = cache.merge_match_into_notebook(nbformat.read(path, as_version=4))
    except KeyError:
        return None
    record = cache.get_cache_record(key)
    created = record.created.replace(tzinfo=datetime.timezone.utc).timestamp()
    if created < _newest_dependency():
        return None
    notebook.metadata["figure_problems"] = problems_written(notebook)
    notebook.metadata["seconds"] = record.data.get("execution_seconds")
    notebook.metadata["executed_by"] = "the book build"
    return notebook


def executed_notebook(path):
    """The notebook with its outputs and figure problems: the build's execution, or a new one."""
    return cached_execution(path) or execute_notebook(path, audit_figures=True)
