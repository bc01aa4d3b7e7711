"""The course's figure audit: every figure a notebook renders is readable on its own.

Course tooling, not part of rsgeo: the book's build runs it in every kernel it starts
(:class:`offline_book.AuditedKernelManager` passes :data:`KERNEL_ARGUMENTS`, IPython's
``exec_lines``), so each problem is written to standard error, which fails the build
(``stderr_output: remove-warn`` with ``-W``). The tests (tests/notebook_runner.py) and
``benchmarks/notebooks.py`` read the same lines back with :func:`problems_written`.

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> fig, ax = plt.subplots()
>>> _ = ax.plot([0, 1], [0, 1])
>>> figure_problems(fig)[0]
'panel 1 of a figure with no title: no title (set one on the panel or the figure)'
>>> _ = ax.set(title="a line", xlabel="x (m)", ylabel="y (m)")
>>> figure_problems(fig)
[]
>>> plt.close(fig)
"""

import re
import sys
from pathlib import Path

import numpy as np

__all__ = ["FIGURE_PROBLEMS", "FIGURE_PROBLEM_PREFIX", "KERNEL_ARGUMENTS", "figure_problems",
           "audit_rendered_figures", "problems_written"]

#: Every problem found in this process so far, in the order found.
FIGURE_PROBLEMS = []
#: What starts each problem's line on standard error.
FIGURE_PROBLEM_PREFIX = "rsgeo figure problem: "
#: An IPython kernel's command-line arguments that turn the audit on at its start-up, writing
#: to standard error; the kernel finds this module by this folder, and nothing is left in the
#: notebook's namespace.
KERNEL_ARGUMENTS = [
    "--IPKernelApp.exec_lines="
    f"__import__('sys').path.append({str(Path(__file__).resolve().parent)!r}); "
    "__import__('figure_audit').audit_rendered_figures(to_stderr=True)"]

_UNIT = re.compile(r"\(.*\S.*\)|\[.*\S.*\]|\bDN\b")   # DN is its own unit


def _has_unit(label):
    return bool(_UNIT.search(label or ""))


def _shows_tick_labels(axis):
    return any(tick.get_visible() and tick.get_text() for tick in axis.get_ticklabels())


def _legend_colour(handle):
    """The RGBA colour a legend handle is drawn in, or None when it has none to speak of."""
    from matplotlib.colors import to_rgba, to_rgba_array

    for getter in ("get_color", "get_facecolor"):
        if hasattr(handle, getter):
            try:
                colours = to_rgba_array(getattr(handle, getter)())
            except (TypeError, ValueError):
                return None
            return np.asarray(to_rgba(colours[0])) if len(colours) else None
    return None


def _panel_name(number, title, suptitle):
    if title:
        return f"panel {number} ({title!r})"
    if suptitle:
        return f"panel {number} of {suptitle!r}"
    return f"panel {number} of a figure with no title"


def figure_problems(figure):
    """What makes a figure hard to read on its own, as a list of sentences (empty: none).

    The course's rules for a figure: every panel has a title (its own or the
    figure's), every axis that shows tick labels has a label with its units in
    parentheses or brackets ("row (px)", "ratio (–)"; "DN" counts as its own unit), every colour
    bar a label with units, and no legend entry is drawn in the panel's
    background colour (it would be invisible).

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure to read.

    Returns
    -------
    list of str
        One sentence per problem, naming the panel.
    """
    from matplotlib.colors import to_rgba

    suptitle = figure._suptitle.get_text() if getattr(figure, "_suptitle", None) else ""
    panels = [ax for ax in figure.axes if ax.get_visible() and ax.axison]
    titled_positions = {tuple(np.round(ax.get_position().bounds, 4)) for ax in panels
                        if ax.get_title() or ax.get_title("left") or ax.get_title("right")}
    problems = []
    for number, ax in enumerate(panels, start=1):
        title = ax.get_title() or ax.get_title("left") or ax.get_title("right")
        name = _panel_name(number, title, suptitle)
        colorbar = getattr(ax, "_colorbar", None)
        if colorbar is not None:
            label = ax.get_ylabel() if colorbar.orientation == "vertical" else ax.get_xlabel()
            if not _has_unit(label):
                problems.append(f"{name}: colour bar label {label!r} has no units in parentheses")
            continue
        position = tuple(np.round(ax.get_position().bounds, 4))
        if not (title or suptitle or position in titled_positions):
            problems.append(f"{name}: no title (set one on the panel or the figure)")
        for axis_name, axis, label in (("x", ax.xaxis, ax.get_xlabel()),
                                       ("y", ax.yaxis, ax.get_ylabel())):
            if _shows_tick_labels(axis) and not _has_unit(label):
                problems.append(f"{name}: {axis_name} label {label!r} has no units in parentheses")
        legend = ax.get_legend()
        if legend is not None:
            background = np.asarray(to_rgba(ax.get_facecolor()))[:3]
            for handle, text in zip(legend.legend_handles, legend.get_texts()):
                colour = _legend_colour(handle)
                if (colour is not None and colour[3] > 0
                        and np.abs(colour[:3] - background).max() < 0.1):
                    problems.append(f"{name}: legend entry {text.get_text()!r} is drawn in the "
                                    "background colour")
    return problems


def audit_rendered_figures(to_stderr=False):
    """Record :func:`figure_problems` of every figure as it is rendered (shown, saved, animated).

    Each new problem is appended to ``FIGURE_PROBLEMS`` and, with ``to_stderr``, written to
    standard error as a line starting with ``FIGURE_PROBLEM_PREFIX``. The book's build turns
    this on in its kernels (:data:`KERNEL_ARGUMENTS`), where any standard-error output fails
    the build. Every PNG gets a ``Description`` text chunk,
    :func:`rsgeo_course.alt_text.describe_figure` of its figure, which the book's extension
    figure_alt.py makes the image's alternative text. It patches matplotlib's
    ``FigureCanvasBase.print_figure`` for the running process only. The first description
    imports the course's package, which installs the same description for the figures rsgeo
    renders itself (:func:`rsgeo.plot.set_figure_describer`): a widget's frame or an animation's
    player is saved as a PNG before it is described.

    Parameters
    ----------
    to_stderr : bool
        Also write each new problem to standard error.

    Returns
    -------
    None
        Only the first call patches matplotlib; later calls do nothing (the
        first call's ``to_stderr`` stays in force).
    """
    from matplotlib.backend_bases import FigureCanvasBase

    if getattr(FigureCanvasBase.print_figure, "_figure_audit", False):
        return
    original = FigureCanvasBase.print_figure

    def print_figure(self, *args, **kwargs):
        problems = figure_problems(self.figure)
        if _saved_format(args, kwargs) == "png":
            # the PNG says what it shows (a tEXt/iTXt chunk): figure_alt.py makes it the alt
            description, problem = _description(self.figure)
            kwargs["metadata"] = {"Description": description, **(kwargs.get("metadata") or {})}
            problems += [problem] if problem else []
        for problem in problems:
            if problem not in FIGURE_PROBLEMS:
                FIGURE_PROBLEMS.append(problem)
                if to_stderr:
                    print(f"{FIGURE_PROBLEM_PREFIX}{problem}", file=sys.stderr)
        return original(self, *args, **kwargs)

    print_figure._figure_audit = True
    FigureCanvasBase.print_figure = print_figure


def _saved_format(args, kwargs):
    """The format ``print_figure(filename, ..., format=None)`` saves in, as matplotlib decides:
    the ``format`` argument, else the file name's extension, else ``savefig.format``."""
    import matplotlib

    chosen = kwargs.get("format") or (args[5] if len(args) > 5 else None)
    if chosen is None and args:
        name = args[0] if isinstance(args[0], (str, Path)) else getattr(args[0], "name", None)
        if isinstance(name, (str, Path)) and Path(name).suffix:
            chosen = Path(name).suffix[1:]
    return str(chosen or matplotlib.rcParams["savefig.format"]).lower()


def _description(figure):
    """(:func:`rsgeo_course.alt_text.describe_figure` of ``figure``, None), or (None, the problem)
    when rsgeo cannot describe it: the figure is still saved, without a description."""
    try:
        from rsgeo_course.alt_text import describe_figure

        return describe_figure(figure), None
    except Exception as error:  # noqa: BLE001 - an audit must not stop the figure it audits
        titles = [ax.get_title() for ax in figure.axes if ax.get_title()]
        return None, (f"the figure {titles[0] if titles else ''!r} has no description: "
                      f"{type(error).__name__}: {error}")


def problems_written(notebook):
    """The figure problems an audited kernel wrote to standard error while running ``notebook``.

    Parameters
    ----------
    notebook : nbformat.NotebookNode
        An executed notebook, its outputs in it.

    Returns
    -------
    list of str
        Each problem's sentence, without :data:`FIGURE_PROBLEM_PREFIX`.
    """
    texts = [output.get("text", "") for cell in notebook.cells
             for output in cell.get("outputs", []) if output.get("name") == "stderr"]
    return [line[len(FIGURE_PROBLEM_PREFIX):] for text in texts for line in text.splitlines()
            if line.startswith(FIGURE_PROBLEM_PREFIX)]
