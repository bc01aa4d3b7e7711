"""Checks of exercises 3b (chapter 3b, choosing a transformation model)."""

import numpy as np

from rsgeo import accuracy, transforms
from rsgeo.validation import as_points

from .._i18n import N_, _, prose_number
from .engine import Declaration, Mistake, Verdict, WrongForm, declare, how_far, listed, require

__all__ = ["check_helmert", "check_projective_matrix", "check_model_choice"]

_HELMERT_NAMES = ("a", "b", "c", "d")


def _four_numbers(answer, name):
    answer = require(answer, name)
    if isinstance(answer, (str, bytes)):
        raise WrongForm(_("`{name}` is text; the check needs four numbers (a, b, c, d).")
                         .format(name=name))
    try:
        array = np.asarray(answer, dtype=float).ravel()
    except (TypeError, ValueError):
        raise WrongForm(_("`{name}` is not four numbers (a, b, c, d).").format(
            name=name)) from None
    if array.size != 4:
        raise WrongForm((_("`{name}` holds one value; the Helmert model has four unknowns, "
                            "(a, b, c, d).") if array.size == 1 else
                          _("`{name}` holds {size} values; the Helmert model has four "
                            "unknowns, (a, b, c, d).")).format(name=name, size=array.size))
    if not np.isfinite(array).all():
        raise WrongForm(_("`{name}` holds NaN or infinite values.").format(name=name))
    return array


def _helmert_parameters(src, dst):
    """(a, b, c, d) of the least-squares Helmert model from ``src`` to ``dst``."""
    matrix = transforms.fit_transform(src, dst, "helmert").matrix
    return np.array([matrix[0, 0], matrix[1, 0], matrix[0, 2], matrix[1, 2]])


HELMERT = Declaration(
    check="check_helmert", answer="parameters", inputs=("src", "dst"),
    derive=lambda task: {"src": as_points(task.src, "src"), "dst": as_points(task.dst, "dst")},
    right=lambda task: _helmert_parameters(task.src, task.dst),
    general=N_("Two rows per point: [x, -y, 1, 0] for u and [y, x, 0, 1] for v; solve the "
               "2n × 4 system with np.linalg.lstsq."),
    mistakes=(
        Mistake(N_("b has the wrong sign: the model is u = a x − b y + c, v = b x + a y + d."),
                lambda task: task.right * [1, -1, 1, 1]),
        Mistake(N_("That is the exact model through the first two points; use every point, by "
                   "least squares."), lambda task: _helmert_parameters(task.src[:2],
                                                                       task.dst[:2])),
        Mistake(N_("The order is (a, b, c, d): the scale-rotation pair first, then the shifts."),
                lambda task: task.right[[2, 3, 0, 1]]),
    ))


@declare(HELMERT)
def check_helmert(parameters, src, dst):
    """A Helmert (similarity) model fitted by hand: u = a x - b y + c, v = b x + a y + d.

    Parameters
    ----------
    parameters : sequence of 4 floats
        The student's (a, b, c, d), by least squares on all the points.
    src, dst : (n, 2) array_like
        The points the task gives (both systems with y up).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``parameters`` is still ``...``.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> check_helmert([2, 0, 1, 1], src, src * 2 + 1)
    Correct: (a, b, c, d) fit all the points by least squares.
    """
    try:
        value = _four_numbers(parameters, "parameters")
    except WrongForm as form:
        return form.verdict(_(HELMERT.general))
    task = HELMERT.task(src=src, dst=dst)
    expected = task.right
    tolerance = 1e-9 * np.abs(expected).max()
    if np.allclose(value, expected, rtol=1e-6, atol=tolerance):
        return Verdict(True, _("(a, b, c, d) fit all the points by least squares."))
    wrong = [name for name, got, want in zip(_HELMERT_NAMES, value, expected)
             if not np.isclose(got, want, rtol=1e-6, atol=tolerance)]
    if len(wrong) == 1:
        i = _HELMERT_NAMES.index(wrong[0])
        message = _("{name} is not right: `{name}` is {how}.").format(
            name=wrong[0], how=how_far(value[i], expected[i]))
    else:
        message = _("{names} are not right.").format(names=", ".join(wrong))
    hints = HELMERT.hints(value, task, lambda answer, wrong: np.allclose(
        answer, wrong, rtol=1e-6, atol=tolerance), exclude_right=False, first=True)
    return Verdict(False, message, hints[0] if hints else _(HELMERT.general))


def _miss(h, a, b):
    """The largest distance between ``h`` applied to ``a`` and ``b``."""
    with np.errstate(all="ignore"):
        mapped = np.column_stack([a, np.ones(len(a))]) @ h.T
        return float(np.max(np.hypot(*(mapped[:, :2] / mapped[:, 2:] - b).T)))


def _projective_derived(task):
    src, dst = as_points(task.src, "src"), as_points(task.dst, "dst")
    return {"src": src, "dst": dst, "extent": float(np.abs(dst - dst.mean(axis=0)).max())}


def _maps_exactly(h, task, a=None, b=None):
    return _miss(h, task.src if a is None else a, task.dst if b is None else b) \
        <= 1e-6 * task.extent


PROJECTIVE_MATRIX = Declaration(
    check="check_projective_matrix", answer="matrix", inputs=("src", "dst"),
    derive=_projective_derived,
    right=lambda task: transforms.fit_transform(task.src, task.dst, "projective").matrix,
    general=N_("Multiply out the denominator: u (c1 x + c2 y + 1) = a0 + a1 x + a2 y gives one "
               "linear equation in the 8 unknowns per coordinate; solve the 8 × 8 system and put "
               "h33 = 1."),
    mistakes=(
        Mistake(N_("The matrix is transposed: H @ [x, y, 1] must give [u·w, v·w, w], so row 0 "
                   "holds the u coefficients."),
                recognise=lambda answer, task: _maps_exactly(answer.T, task)),
        Mistake(N_("It maps dst to src: the task asks for src -> dst."),
                recognise=lambda answer, task: _maps_exactly(answer, task, task.dst, task.src)),
        Mistake(N_("The last row is (0, 0, 1): that is an affine model, which cannot pass "
                   "through four general points."),
                recognise=lambda answer, task: np.allclose(answer[2, :2], 0)),
    ))
_AFFINE = PROJECTIVE_MATRIX.mistakes[-1]


@declare(PROJECTIVE_MATRIX)
def check_projective_matrix(matrix, src, dst):
    """A projective (homography) matrix computed from exactly four points.

    Parameters
    ----------
    matrix : (3, 3) array_like
        The student's homography, mapping ``src`` to ``dst`` (any scale).
    src, dst : (4, 2) array_like
        The four points the task gives.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``matrix`` is still ``...``.

    Examples
    --------
    >>> src = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    >>> check_projective_matrix(np.diag([2.0, 2.0, 1.0]), src, src * 2)
    Correct: the matrix maps the four points exactly.
    """
    general = _(PROJECTIVE_MATRIX.general)
    try:
        matrix = require(matrix, "matrix")
        try:
            array = np.asarray(matrix, dtype=float)
        except (TypeError, ValueError):
            raise WrongForm(_("`matrix` is not a 3 × 3 table of numbers.")) from None
        if array.shape != (3, 3):
            raise WrongForm(_("`matrix` has shape {shape}; a homography is 3 × 3 (reshape the "
                               "8 unknowns and h33 = 1).").format(shape=array.shape))
        if not np.isfinite(array).all():
            raise WrongForm(_("`matrix` holds NaN or infinite values."))
        if abs(array[2, 2]) < 1e-12:
            raise WrongForm(_("`matrix[2, 2]` is zero; with the usual convention it is 1."))
    except WrongForm as form:
        return form.verdict(general)
    task = PROJECTIVE_MATRIX.task(src=src, dst=dst)
    if _maps_exactly(array, task):
        return Verdict(True, _("the matrix maps the four points exactly."))
    message = _("the matrix misses the points by up to {error:.3g} (in dst units).").format(
        error=prose_number(_miss(array, task.src, task.dst)))
    hints = PROJECTIVE_MATRIX.hints(array, task, None, first=True)
    if not hints:
        return Verdict(False, message, general)
    return Verdict(False, message, hints[0] + (" " + general if hints[0] == _AFFINE.text()
                                               else ""))


def _models_derived(task):
    is_check = np.asarray(task.is_check, dtype=bool)
    fitted = int((~is_check).sum())
    models = [m for m in transforms.GEOREFERENCER_MODELS
              if fitted > transforms.min_gcps(m[1], m[2])]
    return {"is_check": is_check, "models": models,
            "table": accuracy.compare_models(task.src, task.dst, is_check, models)}


MODEL_CHOICE = Declaration(
    check="check_model_choice", answer="model", inputs=("src", "dst", "is_check"),
    derive=_models_derived,
    right=lambda task: task.table["check RMS (px)"].idxmin(),
    general=N_("Fit each model on the GCPs that are not check points and compare their RMS on "
               "the check points; the fitting RMS always prefers more parameters."),
    mistakes=(
        Mistake(N_("That model has the lowest RMS on the GCPs used in the fit (a TPS's is always "
                   "zero): judge on the check points."),
                lambda task: task.table["fitting RMS (px)"].idxmin()),
        Mistake(N_("That is the lowest RMS of a fit on ALL the points; the check points must "
                   "stay out of the fit."),
                lambda task: accuracy.compare_models(task.src, task.dst, None, task.models)[
                    "fitting RMS (px)"].idxmin()),
    ))


@declare(MODEL_CHOICE)
def check_model_choice(model, src, dst, is_check, name="model"):
    """The model (a label of ``rsgeo.transforms.GEOREFERENCER_MODELS``) with the lowest check-point RMS.

    Parameters
    ----------
    model : str
        The student's answer, e.g. "polynomial 1".
    src, dst : (n, 2) array_like
        All points (map -> image).
    is_check : (n,) array_like of bool
        The check points; the others are fitted.
    name : str, optional
        The name of the student's variable, which the verdict quotes
        (``"choice"`` in exercise 3b.3).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``model`` is still ``...``.

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> gcps = synthetic.distorted_pair(seed=2).gcps
    >>> print(check_model_choice("affine", gcps.map_xy, gcps.image_xy,
    ...                          np.arange(16) % 3 == 0).message)
    `model` is 'affine': the model is one of 'linear', 'helmert', 'polynomial 1', 'polynomial 2', 'projective' or 'tps'.
    """  # noqa: E501  (a doctest's expected line)
    fitted = int((~np.asarray(is_check, dtype=bool)).sum())
    labels = [label for label, kind, order in transforms.GEOREFERENCER_MODELS
              if fitted > transforms.min_gcps(kind, order)]
    try:
        model = require(model, name)
        if not isinstance(model, str):
            raise WrongForm(_("`{name}` is `{value!r}`; the check needs the model's name "
                               "as text, e.g. 'polynomial 1'.").format(name=name, value=model))
        if model not in labels:
            raise WrongForm(_("`{name}` is {value!r}: the model is one of {listed}.").format(
                name=name, value=model, listed=listed(labels, repr)))
    except WrongForm as form:
        return form.verdict(_(MODEL_CHOICE.general))
    task = MODEL_CHOICE.task(src=src, dst=dst, is_check=is_check)
    check = task.table["check RMS (px)"]
    if model == task.right:
        return Verdict(True, _("`{name}` is {value!r}: check-point RMS {rms:.2f} px, the "
                               "lowest.").format(name=name, value=model,
                                                 rms=prose_number(check[model])))
    hints = MODEL_CHOICE.hints(model, task, lambda answer, wrong: answer == wrong,
                               exclude_right=False, first=True)
    return Verdict(False, _("`{name}` is {value!r}, whose check-point RMS is {rms:.2f} px; "
                            "another model does better on the check points.").format(
                                name=name, value=model, rms=prose_number(check[model])),
                   hints[0] if hints else _(MODEL_CHOICE.general))
