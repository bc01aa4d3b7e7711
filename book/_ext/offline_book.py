"""A Sphinx extension for the course's HTML book: each page's scripts, once each, and the widget
manager's icon fonts where it looks for them.

Jupyter Book 1 always loads sphinx-thebe, whose configuration script is registered at every
``env-before-read-docs``, so some pages declared ``const THEBE_JS_URL`` twice and the browser
threw "Identifier 'THEBE_JS_URL' has already been declared". Keeping the first copy of every
script fixes that without touching anything else.

The widget manager's two bundles (book/_vendor/widgets) look for their icon fonts next to the page
that loads them, under ``@jupyter-widgets/`` and ``@jupyter-widgets/html-manager/dist/``. After
the build, the fonts (book/_vendor/widget-fonts) are copied there for every folder that holds
pages, so the repository keeps one copy of each font and no symbolic link.

Launch buttons tell the truth: while ``repository.url`` in _config.yml is a placeholder (or
empty), the book has no Binder, Colab or repository button and names no repository at all.

Every kernel the build starts talks over Unix sockets and audits the figures it renders
(:class:`AuditedKernelManager`, figure_audit.py): an unreadable figure fails the build.
"""

import os
import shutil
import tempfile
from pathlib import Path

from jupyter_client.manager import AsyncKernelManager
from nbclient import NotebookClient

from figure_audit import KERNEL_ARGUMENTS  # beside this file, on the path as the book's _ext

FONTS = Path("book") / "_vendor" / "widget-fonts"
FONT_FOLDERS = ("@jupyter-widgets", "@jupyter-widgets/html-manager/dist")
# repository URLs that name no real repository: the book gets no launch button while one is set
PLACEHOLDER_REPOSITORIES = ("https://github.com/OWNER/REPOSITORY",
                            "https://github.com/rsgeo-course/rsgeo-course")


def keep_scripts_once(app, pagename, templatename, context, doctree):
    scripts, seen = [], set()
    for script in context.get("script_files", []):
        # An inline script is registered once with filename None and once with "": compare
        # inline scripts by their body, files by their name.
        key = script.filename or ("inline", script.attributes.get("body", ""))
        if key not in seen:
            seen.add(key)
            scripts.append(script)
    context["script_files"] = scripts


def place_widget_fonts(app, exception):
    if exception is not None or app.builder.format != "html":
        return
    fonts = sorted((Path(app.srcdir) / FONTS).glob("*.woff*"))
    if not fonts:
        raise FileNotFoundError(f"no widget fonts in {Path(app.srcdir) / FONTS}")
    page_folders = {Path(name).parent for name in app.env.found_docs}
    for folder in page_folders:
        for font_folder in FONT_FOLDERS:
            target = Path(app.outdir) / folder / font_folder
            target.mkdir(parents=True, exist_ok=True)
            for font in fonts:
                shutil.copyfile(font, target / font.name)


class IPCKernelManager(AsyncKernelManager):
    """A kernel that talks over Unix sockets in a private folder, not TCP ports.

    Kernels started at once by other processes on the machine (two test workers, another build)
    cannot take each other's ports, and the sockets' absolute path works whatever folder the
    kernel runs in. The folder is removed when the kernel is shut down.
    """

    def __init__(self, **kwargs):
        self._socket_folder = tempfile.mkdtemp(prefix="rsgeo-kernel-")
        kwargs.setdefault("transport", "ipc")
        kwargs.setdefault("ip", os.path.join(self._socket_folder, "kernel"))
        super().__init__(**kwargs)

    async def _async_cleanup_resources(self, restart=False):
        await super()._async_cleanup_resources(restart=restart)
        if not restart:
            shutil.rmtree(self._socket_folder, ignore_errors=True)

    cleanup_resources = _async_cleanup_resources


class AuditedKernelManager(IPCKernelManager):
    """An :class:`IPCKernelManager` whose kernel audits every figure it renders.

    The kernel runs the figure audit at its start-up (figure_audit.py, through IPython's
    ``exec_lines``): each problem is written to standard error, which fails the build
    (``stderr_output: remove-warn`` with ``-W``). The build's single execution of each notebook
    is so also its figure check, and the tests read the build's cache (tests/notebook_runner.py)
    instead of executing the notebooks again.
    """

    def format_kernel_cmd(self, extra_arguments=None):
        return super().format_kernel_cmd([*(extra_arguments or []), *KERNEL_ARGUMENTS])


def kernels_over_ipc():
    """Every notebook this process executes (myst-nb and jupyter-cache use nbclient) gets an
    :class:`AuditedKernelManager` unless told otherwise."""
    NotebookClient._kernel_manager_class_default = lambda client: AuditedKernelManager


def repository_configured(url):
    """True when ``url`` names a real repository: not empty, not a placeholder."""
    return bool(url) and url.strip().rstrip("/") not in PLACEHOLDER_REPOSITORIES


def honest_launch_buttons(app, config):
    """No launch or repository button, and no repository URL in any page, while the
    configured repository is a placeholder (see README, "Teach with it")."""
    options = dict(config.html_theme_options or {})
    if not repository_configured(options.get("repository_url", "")):
        options.update(repository_url="", launch_buttons={}, use_repository_button=False,
                       use_issues_button=False, use_edit_page_button=False)
        config.html_theme_options = options


def html_nodes_in_singlehtml(app):
    """The single-page builder (exercises/print_course.py) writes every node the HTML builder
    can: extensions such as myst-nb register their nodes' HTML writers for "html" only."""
    if app.builder.name == "singlehtml":
        handlers = app.registry.translation_handlers
        for node, visitors in handlers.get("html", {}).items():
            handlers.setdefault("singlehtml", {}).setdefault(node, visitors)


def setup(app):
    app.connect("config-inited", honest_launch_buttons)
    app.connect("builder-inited", html_nodes_in_singlehtml)
    kernels_over_ipc()
    app.connect("html-page-context", keep_scripts_once, priority=900)
    app.connect("build-finished", place_widget_fonts)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
