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

The book works on a phone, by keyboard and with a screen reader (book/_templates,
book/_static/rsgeo-book.css, and :func:`accessible_body` for what myst-nb and docutils write),
and weighs what it uses: Font Awesome holds only the icons the built pages use
(:func:`subset_fontawesome`), MathJax loads only on pages with mathematics, and the widgets' names
for screen readers (book/_static/rsgeo-widgets.js) only on pages with widgets. Search ranks the
chapters above the API reference's entries (book/_templates/search_scorer.js).

Every kernel the build starts talks over Unix sockets and audits the figures it renders
(:class:`AuditedKernelManager`, figure_audit.py): an unreadable figure fails the build.
"""

import os
import re
import shutil
import tempfile
from pathlib import Path

from docutils import nodes
from jupyter_client.manager import AsyncKernelManager
from nbclient import NotebookClient

from figure_audit import KERNEL_ARGUMENTS  # beside this file, on the path as the book's _ext

FONTS = Path("book") / "_vendor" / "widget-fonts"
FONT_FOLDERS = ("@jupyter-widgets", "@jupyter-widgets/html-manager/dist")
# repository URLs that name no real repository: the book gets no launch button while one is set
PLACEHOLDER_REPOSITORIES = ("https://github.com/OWNER/REPOSITORY",
                            "https://github.com/rsgeo-course/rsgeo-course")


# the book's templates, stylesheet and scripts, relative to the configuration folder (the root)
TEMPLATES = "book/_templates"
STATIC = "book/_static"
SEARCH_SCORER = "book/_templates/search_scorer.js"
STYLESHEET = "rsgeo-book.css"
WIDGET_SCRIPT = "rsgeo-widgets.js"
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
# names that rsgeo-widgets.js gives the widgets' icon-only buttons and unnamed slider handles
# (translated through the "sphinx" catalogue: locales/pt_BR/LC_MESSAGES/sphinx.po)
WIDGET_NAMES = {"play": "Play", "pause": "Pause", "stop": "Stop", "repeat": "Repeat",
                "slider": "Slider"}
# Font Awesome icons that scripts create after the page has loaded (the HTML of the built pages
# names all the others): the widgets' Play buttons, checkboxes and dropdowns (ipywidgets), the
# search dialog's close button (pydata-sphinx-theme), and the launch and repository buttons a
# configured repository brings (sphinx-book-theme)
RUNTIME_ICONS = {"play", "pause", "stop", "retweet", "repeat", "check", "times", "xmark",
                 "caret-down", "caret-right", "rocket", "github", "lightbulb", "pencil",
                 "pencil-alt", "spinner", "circle-notch"}
# one icon of Font Awesome's JavaScript packs: name: [width, height, [aliases], unicode, path]
FONTAWESOME_ICON = re.compile(r'(?:"([a-z0-9-]+)"|([a-z0-9_$]+)):\[\d+,\d+,\[([^\]]*)\],'
                              r'"[0-9a-f]+",(?:"[^"]*"|\[[^\]]*\])\]')
ICON_CLASS = re.compile(r"\bfa-([a-z0-9]+(?:-[a-z0-9]+)*)")
# docutils' bibliography: a role="list" whose items say role="doc-biblioentry" (deprecated, and
# not a list item: axe aria-required-children)
CITATION_ENTRY = 'role="doc-biblioentry"'
# myst-nb's toggle of a hidden cell: its aria-label hid the visible "Show code cell source"
HIDDEN_CELL_LABEL = ' aria-label="Toggle hidden content"'
# pandas' empty top-left header cell (axe empty-table-header): an empty data cell instead
EMPTY_HEADER = re.compile(r"<th(\s[^>]*)?>(\s|&nbsp;)*</th>")


def add_book_files(app, config):
    """``config-inited``: the book's templates (the theme's components overridden by name), its
    static files and its search scorer, so that the configurations need not list them."""
    confdir = Path(app.confdir)
    if (confdir / TEMPLATES).is_dir() and TEMPLATES not in config.templates_path:
        # first: the themes add their own components' folders to templates_path too
        config.templates_path = [TEMPLATES, *config.templates_path]
    if (confdir / STATIC).is_dir() and STATIC not in config.html_static_path:
        config.html_static_path = [*config.html_static_path, STATIC]
        app.add_css_file(STYLESHEET)
    if (confdir / SEARCH_SCORER).is_file() and not config.html_search_scorer:
        # absolute: Sphinx opens it from the working folder, not the configuration's
        config.html_search_scorer = str(confdir / SEARCH_SCORER)


def has_mathematics(doctree):
    """True when the page has an equation (inline or displayed) for MathJax to typeset."""
    return doctree is not None and doctree.next_node(
        lambda node: isinstance(node, (nodes.math, nodes.math_block))) is not None


def widget_names(app, pagename, templatename, context, doctree):
    """``html-page-context`` (before :func:`keep_scripts_once`): on a page with widgets only, the
    script that names their slider handles and Play buttons, with the names in the book's
    language as data attributes."""
    if app.builder.format != "html" or WIDGET_VIEW not in context.get("body", ""):
        return
    from sphinx.locale import _

    names = {f"data-{key}": _(label) for key, label in WIDGET_NAMES.items()}
    app.add_js_file(WIDGET_SCRIPT, defer="defer", **names)


def lighter_page(app, pagename, templatename, context, doctree):
    """``html-page-context``: no MathJax on a page without mathematics or widgets. Sphinx loads
    it on the root page too when any page of its table of contents has an equation."""
    if has_mathematics(doctree) or WIDGET_VIEW in context.get("body", ""):
        return
    mathjax = app.config.mathjax_path
    context["script_files"] = [
        script for script in context.get("script_files", [])
        if not (mathjax and (script.filename or "").endswith(mathjax))
        and not (script.attributes.get("body") or "").startswith("window.MathJax")]


def accessible_body(app, pagename, templatename, context, doctree):
    """``html-page-context``: what myst-nb, docutils and pandas write, made accessible.

    - the toggle of a hidden cell is named by its visible text ("Show code cell source"), not
      by an English aria-label that said something else (axe label-content-name-mismatch);
    - the bibliography's entries are the items of its list (role="listitem");
    - an empty table header cell (pandas' top-left corner) is an empty data cell.

    (A block of code or output that scrolls sideways in its own box on a phone is made
    reachable by the Tab key by pydata-sphinx-theme's own script, 300 ms after each resize.)
    """
    body = context.get("body")
    if not body:
        return
    body = body.replace(HIDDEN_CELL_LABEL, "")
    body = body.replace(CITATION_ENTRY, 'role="listitem"')
    body = EMPTY_HEADER.sub("<td></td>", body)
    context["body"] = body


def icons_used(html_folder):
    """The Font Awesome names (without "fa-") in the classes of every page under
    ``html_folder``, with the icons that scripts add after loading."""
    names = set(RUNTIME_ICONS)
    for page in Path(html_folder).rglob("*.html"):
        names.update(ICON_CLASS.findall(page.read_text(encoding="utf-8", errors="replace")))
    return names


def fontawesome_subset(script, names):
    """``script`` (the theme's fontawesome.js: Font Awesome Free's JavaScript, every icon) with
    only the icons called by one of ``names`` (an icon's name or one of its aliases).

    >>> packs = 'var p={a:[1,2,[],"f1","M0"],"b-c":[1,2,[9,"old-b"],"f2","M1"]};'
    >>> fontawesome_subset(packs, {"old-b"})
    'var p={"b-c":[1,2,[9,"old-b"],"f2","M1"]};'
    """
    pieces, position, pack = [], 0, []

    def close_pack():
        if pack:
            kept = [match.group(0) for match in pack if _icon_names(match) & names]
            pieces.append(",".join(kept))

    previous_end = None
    for match in FONTAWESOME_ICON.finditer(script):
        if previous_end is None or script[previous_end:match.start()] != ",":
            close_pack()
            pack = []
            pieces.append(script[position:match.start()])
        pack.append(match)
        previous_end = position = match.end()
    close_pack()
    pieces.append(script[position:])
    return "".join(pieces)


def _icon_names(match):
    aliases = re.findall(r'"([a-z0-9-]+)"', match.group(3))
    return {match.group(1) or match.group(2), *aliases}


def subset_fontawesome(app, exception):
    """``build-finished``: the theme's Font Awesome script (1.5 MB, some 2,000 icons, on every
    page) replaced by the same script with only the icons the book uses (see the README of
    book/_vendor for the licence)."""
    if exception is not None or app.builder.format != "html":
        return
    import pydata_sphinx_theme

    original = (Path(pydata_sphinx_theme.__file__).parent / "theme" / "pydata_sphinx_theme"
                / "static" / "scripts" / "fontawesome.js")
    target = Path(app.outdir) / "_static" / "scripts" / "fontawesome.js"
    if not original.is_file() or not target.parent.is_dir():
        return
    script = original.read_text(encoding="utf-8")
    target.write_text(fontawesome_subset(script, icons_used(app.outdir)), encoding="utf-8")


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
    app.connect("config-inited", add_book_files)
    app.connect("builder-inited", html_nodes_in_singlehtml)
    kernels_over_ipc()
    app.connect("html-page-context", widget_names, priority=850)
    app.connect("html-page-context", keep_scripts_once, priority=900)
    app.connect("html-page-context", lighter_page, priority=910)
    app.connect("html-page-context", accessible_body, priority=920)
    app.connect("build-finished", place_widget_fonts)
    app.connect("build-finished", subset_fontawesome)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
