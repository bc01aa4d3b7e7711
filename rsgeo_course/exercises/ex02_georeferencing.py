"""Checks of exercises 2 (chapters 2 and 3, georeferencing and evaluating a model)."""

import numpy as np

from rsgeo import accuracy, transforms
from rsgeo.validation import as_points

from .._i18n import N_, _, prose_number
from .engine import (
    Declaration,
    Mistake,
    Verdict,
    WrongForm,
    declare,
    first_hint,
    integer,
    listed,
    one_of,
    require,
)

__all__ = ["check_design_matrix", "check_rms", "check_blunder", "check_degree_choice",
           "check_pec_class"]

_FIRST_COLUMN = N_("The first column is all ones: it multiplies the constant term a0.")


def _constant_shift(answer, task):
    shift = answer[:, 1:3] - task.right[:, 1:3]
    return np.allclose(shift, shift[0]) and not np.allclose(shift[0], 0)


DESIGN_MATRIX = Declaration(
    check="check_design_matrix", answer="matrix", inputs=("points", "order"),
    derive=lambda task: {"names": transforms.term_names(task.order),
                         "points": np.asarray(task.points, dtype=float)},
    right=lambda task: transforms.design_matrix(task.points, task.order),
    general=N_("Columns in the lecture's order: {names}; one row per GCP."),
    mistakes=(
        Mistake(N_("One ROW per GCP and one column per term: use np.column_stack, or .T."),
                recognise=lambda answer, task: answer.shape == task.right.shape[::-1]
                and np.allclose(answer.T, task.right)),
        Mistake(_FIRST_COLUMN, recognise=lambda answer, task: (
            answer.shape == (task.right.shape[0], task.right.shape[1] - 1)
            and np.allclose(answer, task.right[:, 1:])) or (
            answer.shape == task.right.shape
            and not np.isclose(answer[:, 0], task.right[:, 0]).all())),
        Mistake(N_("x and y are swapped: x (easting, `points[:, 0]`) comes before y (northing, "
                   "`points[:, 1]`)."),
                lambda task: transforms.design_matrix(task.points[:, ::-1], task.order)),
        Mistake(N_("These are not the centred coordinates of `points` (each column is off by a "
                   "constant): build the matrix from `points` itself."),
                recognise=_constant_shift),
    ))
_TRANSPOSED, _NO_ONES, _SWAPPED, _NOT_CENTRED = DESIGN_MATRIX.mistakes


@declare(DESIGN_MATRIX)
def check_design_matrix(matrix, points, order=1):
    """The linear system's matrix for the lecture's polynomial of ``order``.

    Parameters
    ----------
    matrix : (n, m) array_like
        The student's matrix.
    points : (n, 2) array_like
        The GCPs' (centred) coordinates the task gives.
    order : {1, 2, 3}

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``matrix`` is still ``...``.

    Examples
    --------
    >>> check_design_matrix([[1, 0, 0], [1, 1, 0], [1, 0, 1]], [[0, 0], [1, 0], [0, 1]])
    Correct: a 3 × 3 design matrix, columns 1, x, y.
    """
    names = ", ".join(transforms.term_names(order))
    layout = _(DESIGN_MATRIX.general).format(names=names)
    try:
        matrix = require(matrix, "matrix")
        try:
            array = np.asarray(matrix, dtype=float)
        except (TypeError, ValueError):
            raise WrongForm(_("`matrix` is not a table of numbers (rows of different lengths, "
                               "or text?).")) from None
        if array.ndim != 2:
            raise WrongForm((_("`matrix` has one dimension, shape {shape}; it needs 2: one row "
                                "per GCP, one column per term.") if array.ndim == 1 else
                              _("`matrix` has {ndim} dimensions, shape {shape}; it needs 2: one "
                                "row per GCP, one column per term.")).format(
                                   ndim=array.ndim, shape=array.shape))
        if not np.isfinite(array).all():
            raise WrongForm(_("`matrix` holds NaN or infinite values."))
    except WrongForm as form:
        return form.verdict(layout)
    task = DESIGN_MATRIX.task(points=points, order=order)
    expected = task.right
    n, m = expected.shape
    if array.shape != expected.shape:
        if _TRANSPOSED.recognise(array, task):
            return Verdict(False, _("`matrix` has shape {shape}: it is transposed.").format(
                shape=array.shape), _TRANSPOSED.text())
        if _NO_ONES.recognise(array, task):
            return Verdict(False, _("`matrix` has shape {shape}: a column is missing.").format(
                shape=array.shape), _NO_ONES.text())
        for other in transforms.ORDERS:
            if other != order and array.shape == (n, transforms.min_gcps(other)) and np.allclose(
                    array, transforms.design_matrix(task.points, other)):
                return Verdict(False, _("`matrix` is the degree-{other} matrix; the task asks "
                                        "for degree {order}.").format(other=other, order=order),
                               layout)
        return Verdict(False, _("`matrix` has shape {shape}; it needs one row per GCP and one "
                                "column per term, ({n}, {m}).").format(shape=array.shape, n=n,
                                                                       m=m), layout)
    wrong = ~np.isclose(array, expected).all(axis=0)
    if not wrong.any():
        return Verdict(True, _("a {n} × {m} design matrix, columns {names}.").format(
            n=n, m=m, names=names))
    columns = [task.names[i] for i in np.flatnonzero(wrong)]
    message = (_("the column for {names} is not right.") if len(columns) == 1 else
               _("the columns for {names} are not right.")).format(names=", ".join(columns))
    for mistake in (_SWAPPED, _NOT_CENTRED, _NO_ONES):
        if (mistake.recognise(array, task) if mistake.recognise is not None
                else np.allclose(array, mistake.wrong(task))):
            return Verdict(False, message, mistake.text())
    return Verdict(False, message, layout)


def _rms_derived(task):
    difference = as_points(task.predicted, "predicted") - as_points(task.observed, "observed")
    squares = np.sum(difference ** 2, axis=1)
    return {"difference": difference, "squares": squares, "n": len(squares)}


RMS = Declaration(
    check="check_rms", answer="rms", inputs=("predicted", "observed"),
    derive=_rms_derived,
    right=lambda task: accuracy.rms_error(task.predicted, task.observed),
    general=N_("RMS = sqrt( (1/n) Σ (dx_i² + dy_i²) ): square each residual's length, average, "
               "root."),
    mistakes=(
        Mistake(N_("You averaged dx² and dy² separately (dividing by 2n): sum them per GCP, then "
                   "divide by n."), lambda task: np.sqrt(task.squares.sum() / (2 * task.n))),
        Mistake(N_("The square root is missing: RMS = sqrt( (1/n) Σ R_i² )."),
                lambda task: task.squares.mean()),
        Mistake(N_("That is the mean of the residuals R_i; RMS squares them first, averages, "
                   "then takes the root."), lambda task: np.sqrt(task.squares).mean()),
        Mistake(N_("Divide the sum of squares by n before the square root."),
                lambda task: np.sqrt(task.squares.sum())),
        Mistake(N_("Both components count: R_i² = dx_i² + dy_i²."),
                lambda task: [np.sqrt(np.mean(task.difference[:, axis] ** 2)) for axis in (0, 1)],
                many=True),
        Mistake(N_("You divided by n − k (QGIS's 'mean error' divides by n − m); the lecture's "
                   "RMS divides by n."),
                lambda task: [np.sqrt(task.squares.sum() / (task.n - k)) for k in (1, 2, 3)
                              if task.n > k], many=True),
    ),
    rtol=1e-6, units=" px")


@declare(RMS)
def check_rms(rms, predicted, observed):
    """The lecture's RMS computed by hand.

    Parameters
    ----------
    rms : float
        The student's answer, in pixels.
    predicted, observed : (n, 2) array_like
        The model's positions of the GCPs and the GCPs' own positions.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``rms`` is still ``...``.

    Examples
    --------
    >>> check_rms(np.sqrt(125 / 4), [[3, 4], [6, 8]], [[0, 0], [0, 0]]).hint
    'You averaged dx² and dy² separately (dividing by 2n): sum them per GCP, then divide by n.'
    """
    return RMS.judge(rms, RMS.task(predicted=predicted, observed=observed))


def _blunder_derived(task):
    dx, dy, distance = accuracy.residuals(task.gcps.fit(task.order), task.gcps.map_xy,
                                     task.gcps.image_xy)
    return {"ids": list(task.gcps.ids), "dx": dx, "dy": dy, "distance": distance}


def _worst_of_degree_1(task):
    if task.order == 1:
        return None
    _dx, _dy, linear = accuracy.residuals(task.gcps.fit(1), task.gcps.map_xy, task.gcps.image_xy)
    return task.ids[int(np.argmax(linear))]


BLUNDER = Declaration(
    check="check_blunder", answer="gcp_id", inputs=("gcps", "order"),
    derive=_blunder_derived,
    right=lambda task: task.ids[int(np.argmax(task.distance))],
    general=N_("Fit the model, compute R_i for every GCP and look for the one far above the "
               "rest; a blunder also drags its neighbours' residuals up."),
    mistakes=(
        Mistake(N_("That GCP has the SMALLEST residual; the blunder has the largest."),
                lambda task: task.ids[int(np.argmin(task.distance))]),
        Mistake(N_("Its residual is high because the blunder drags its neighbours' up: look for "
                   "the one far above all the rest."),
                lambda task: task.ids[int(np.argsort(-task.distance)[1])]),
        Mistake(N_("Compare the lengths R_i = sqrt(dx² + dy²), not one component."),
                lambda task: task.ids[int(np.argmax(np.maximum(np.abs(task.dx),
                                                               np.abs(task.dy))))]),
        Mistake(N_("That is the worst GCP of a degree-1 fit; the task fits degree {order}, and a "
                   "degree-1 model cannot follow the image's curvature."), _worst_of_degree_1),
        Mistake(N_("`table['residual'].idxmax()` gives the id directly; `np.argmax` gives a "
                   "position.")),                 # a position counted from 0: _blunder_by_number
    ))
_POSITION = BLUNDER.mistakes[-1]


@declare(BLUNDER)
def check_blunder(gcp_id, gcps, order):
    """The id of the planted bad GCP in a GCPSet.

    Parameters
    ----------
    gcp_id : str
        The student's answer, an id from ``gcps.ids`` such as ``"P07"``.
    gcps : GCPSet
    order : {1, 2, 3}
        The degree of the model the task fits.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``gcp_id`` is still ``...``.

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> gcps = synthetic.distorted_pair(seed=2).gcps
    >>> print(check_blunder(13, gcps, order=2).message)      # a position, not an id
    `gcp_id` is the number 13, not a GCP id: ids are strings such as 'P01'. Counted from 0, position 13 is the blunder's row: give its id, `gcps.ids[13]`.
    """  # noqa: E501  (a doctest's expected line)
    task = BLUNDER.task(gcps=gcps, order=order)
    ids, worst, generic = task.ids, task.right, BLUNDER.general
    try:
        gcp_id = require(gcp_id, "gcp_id")
        if isinstance(gcp_id, (bool, np.bool_)):
            raise WrongForm(_("`gcp_id` is {value}; the check needs a GCP id such as "
                               "{example!r}.").format(value=gcp_id, example=ids[0]))
        if not isinstance(gcp_id, (str, np.str_)):
            return _blunder_by_number(gcp_id, ids, worst)
    except WrongForm as form:
        return form.verdict(_(generic))
    gcp_id = str(gcp_id)
    if gcp_id == worst:
        return Verdict(True, _("GCP {id} is the blunder: its residual dwarfs the others'.")
                       .format(id=gcp_id))
    if gcp_id not in ids:
        if [i for i in ids if i.upper() == gcp_id.strip().upper()]:
            return Verdict(False, _("{value!r} is spelled differently from the ids, which are "
                                    "written like {example!r} (capitals and spaces count).")
                           .format(value=gcp_id, example=ids[0]), _(generic))
        return Verdict(False, _("{value!r} is not one of the GCP ids ({first!r} to {last!r}).")
                       .format(value=gcp_id, first=ids[0], last=ids[-1]), _(generic))
    hints = BLUNDER.hints(gcp_id, task, lambda answer, wrong: answer == wrong, order=order)
    return Verdict(False, _("GCP {id} is not the blunder: its residual, {residual:.2f} px, is "
                            "not the one that stands out.").format(
                                id=gcp_id,
                                residual=prose_number(task.distance[ids.index(gcp_id)])),
                   first_hint(hints, generic))


def _blunder_by_number(answer, ids, worst):
    """A number (or array) given where a GCP id is needed: a form message, with what the number
    means."""
    generic = _(BLUNDER.general)
    if isinstance(answer, (list, tuple)) or np.ndim(answer) > 0:
        size = len(answer)
        raise WrongForm((_("`gcp_id` holds one value; the check needs ONE id, a string "
                            "such as {example!r}: take it out with `gcp_id[0]`.") if size == 1
                          else _("`gcp_id` holds {size} values; the check needs ONE id, a "
                                 "string such as {example!r}.")).format(size=size,
                                                                       example=ids[0]))
    number = integer(answer, "gcp_id", _("a position in the table"))
    intro = _("`gcp_id` is the number {number}, not a GCP id: ids are strings such as "
              "{example!r}.").format(number=number, example=ids[0])
    if 0 <= number < len(ids) and ids[number] == worst:
        return Verdict(False, intro + " " + _(
            "Counted from 0, position {number} is the blunder's row: give its id, "
            "`gcps.ids[{number}]`.").format(number=number), _POSITION.text())
    if 1 <= number <= len(ids) and ids[number - 1] == worst:
        return Verdict(False, intro + " " + _(
            "Counted from 1, GCP number {number} is the blunder: give its id, the string, as it "
            "appears in `gcps.ids`.").format(number=number), generic)
    return Verdict(False, intro + " " + _(
        "Neither the row at position {number} (from 0) nor GCP number {number} (from 1) is the "
        "blunder.").format(number=number), generic)


def _degree_derived(task):
    is_check = np.asarray(task.is_check, dtype=bool)
    offered = tuple(n for n in transforms.ORDERS if (~is_check).sum() >= transforms.min_gcps(n))
    fits = {n: accuracy.fit_with_check_points(task.gcps.map_xy, task.gcps.image_xy, n, is_check)
            for n in offered}
    return {"offered": offered, "fits": fits, "errors": {n: fit[2] for n, fit in fits.items()}}


def _best_fitting_on_all(task):
    everything = {n: accuracy.rms_error(
                      transforms.fit_polynomial(task.gcps.map_xy, task.gcps.image_xy, n)(
                          task.gcps.map_xy),
                      task.gcps.image_xy)
                  for n in task.offered}
    return min(everything, key=everything.get)


DEGREE_CHOICE = Declaration(
    check="check_degree_choice", answer="order", inputs=("gcps", "is_check"),
    derive=_degree_derived,
    right=lambda task: min(task.errors, key=task.errors.get),
    general=N_("Compare the RMS on the check points, not on the GCPs used in the fit: the "
               "fitting RMS always falls as the degree rises."),
    mistakes=(
        Mistake(N_("That degree has the lowest RMS on the GCPs used in the fit, which always "
                   "falls as the degree rises: judge on the check points."),
                lambda task: min(task.offered, key=lambda n: task.fits[n][1])),
        Mistake(N_("That is the lowest RMS of a fit on ALL the points; the check points must "
                   "stay out of the fit to judge it."), _best_fitting_on_all),
    ))


@declare(DEGREE_CHOICE)
def check_degree_choice(order, gcps, is_check):
    """The degree with the smallest error on independent check points.

    Parameters
    ----------
    order : int
        The student's answer, 1, 2 or 3.
    gcps : GCPSet
    is_check : (n,) array_like of bool
        The check points; the others are fitted.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``order`` is still ``...``.

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> gcps = synthetic.distorted_pair(seed=2).gcps
    >>> print(check_degree_choice(4, gcps, np.arange(16) % 3 == 0).message)
    `order` is 4: the degree is one of 1, 2 or 3.
    """
    is_check = np.asarray(is_check, dtype=bool)
    offered = tuple(n for n in transforms.ORDERS if (~is_check).sum() >= transforms.min_gcps(n))
    try:
        order = one_of(integer(order, "order", _("a degree")), "order", offered,
                        _("the degree"))
    except WrongForm as form:
        return form.verdict(_(DEGREE_CHOICE.general))
    task = DEGREE_CHOICE.task(gcps=gcps, is_check=is_check)
    errors, best = task.errors, task.right
    if order == best:
        return Verdict(True, _("degree {order}: check-point RMS {rms:.2f} px, the lowest.")
                       .format(order=order, rms=prose_number(errors[order])))
    hints = DEGREE_CHOICE.hints(order, task, lambda answer, wrong: answer == wrong,
                                exclude_right=False)
    message = (_("degree {order} has a check-point RMS of {rms:.2f} px; a lower degree does "
                 "better on the check points.") if best < order else
               _("degree {order} has a check-point RMS of {rms:.2f} px; a higher degree does "
                 "better on the check points.")).format(order=order,
                                                       rms=prose_number(errors[order]))
    return Verdict(False, message, first_hint(hints, DEGREE_CHOICE.general))


# -- Task 2.5: the PEC-PCD class of a product --------------------------------------------------

_PEC_ANSWERS = ("A", "B", "C", "D", "none")


def _class_name(best):
    return "none" if best is None else best


def _strictest(classes, passes):
    """The first class (strictest) for which ``passes(name)``, or 'none'."""
    return next((name for name in classes if passes(name)), "none")


def _pec_derived(task):
    check = as_points(task.check_errors, "check_errors")
    distances = np.hypot(check[:, 0], check[:, 1])
    result = accuracy.classify(check, task.scale)
    return {"check": check, "distances": distances, "result": result,
            "classes": tuple(result.thresholds)}


def _rms_against_pec(task):
    rms, thresholds = task.result.rms, task.result.thresholds
    return _strictest(task.classes, lambda name: rms <= thresholds[name][0])


def _mean_against_ep(task):
    mean, result = task.distances.mean(), task.result
    return _strictest(task.classes,
                      lambda name: result.pec_test[name] and mean <= result.thresholds[name][1])


PEC_CLASS = Declaration(
    check="check_pec_class", answer="pec_class",
    inputs=("check_errors", "fit_residuals", "scale"),
    derive=_pec_derived,
    right=lambda task: _class_name(task.result.best),
    general=N_("Both tests, on the check points, in metres at the map's scale (PEC and EP in mm "
               "× scale / 1000): at least 90 % of the errors within the class's PEC, and their "
               "RMS within its EP; the class is the strictest that passes both."),
    mistakes=(
        Mistake(N_("The RMS goes with the EP, not the PEC: the PEC is for the 90 % test, which "
                   "counts the errors."),
                _rms_against_pec),
        Mistake(N_("Both tests must pass: the check points' RMS within the class's EP too."),
                lambda task: _strictest(task.classes, lambda name: task.result.pec_test[name])),
        Mistake(N_("Both tests must pass: at least 90 % of the check points within the class's "
                   "PEC too."),
                lambda task: _strictest(task.classes, lambda name: task.result.ep_test[name])),
        Mistake(N_("Those are the GCPs' fitting residuals: the fit was bent towards them, so "
                   "they flatter the product. A class is measured on the check points."),
                lambda task: _class_name(accuracy.classify(task.fit_residuals, task.scale).best)),
        Mistake(N_("The limits are millimetres on the map: in metres on the ground they are mm × "
                   "scale / 1000 (0.5 mm at 1:25,000 is 12.5 m), not the millimetres themselves."),
                lambda task: _class_name(accuracy.classify(task.check, 1_000).best)),
        Mistake(N_("mm × scale gives millimetres on the ground: divide by 1000 for metres."),
                lambda task: _class_name(accuracy.classify(task.check, task.scale * 1000).best)),
        Mistake(N_("That letter is Decreto 89.817's (printed maps, A-C); the PEC-PCD calls "
                   "those classes B-D and adds a stricter A."),
                lambda task: _class_name(accuracy.classify(task.check, task.scale,
                                                           "Decreto 89.817").best)),
        Mistake(N_("The standard error is the errors' RMS, sqrt(Σ d_i² / n), not their mean."),
                _mean_against_ep),
    ))


@declare(PEC_CLASS)
def check_pec_class(pec_class, check_errors, fit_residuals, scale):
    """The PEC-PCD class (A-D, or 'none') a product's check points meet at a map scale.

    Parameters
    ----------
    pec_class : str
        The student's answer: "A", "B", "C", "D" or "none".
    check_errors : (n, 2) array_like
        The check points' discrepancies (dx, dy), metres on the ground.
    fit_residuals : (m, 2) array_like
        The GCPs' fitting residuals (dx, dy), metres: given to the student
        beside the check points, and a recognised mistake when used instead.
    scale : float
        The scale's denominator (25000 for 1:25,000).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``pec_class`` is still ``...``.

    Examples
    --------
    >>> errors = [[4.0, 3.0]] * 9 + [[30.0, 40.0]]      # nine of 5 m, one of 50 m
    >>> check_pec_class("C", errors, np.zeros((6, 2)), 50_000)
    Correct: class C at 1:50,000: 90 % of the check points within 5.0 m (PEC 40.0 m), RMS 16.5 m (EP 25.0 m).
    >>> print(check_pec_class("B", errors, np.zeros((6, 2)), 50_000).message)
    at 1:50,000 the check points fail class B's standard-error test.
    """  # noqa: E501  (a doctest's expected line)
    generic = _(PEC_CLASS.general)
    choices = listed(_PEC_ANSWERS, repr)
    if pec_class is None:
        return Verdict(False, _("`pec_class` is None: for a product that meets no class, write "
                                "the string 'none'; a function without `return` also gives "
                                "None."), generic)
    try:
        pec_class = require(pec_class, "pec_class")
    except WrongForm as form:
        return form.verdict(generic)
    if not isinstance(pec_class, (str, np.str_)):
        return Verdict(False, _("`pec_class` is a `{kind}`, not a class: the check needs one "
                                "of {listed}, a string.").format(kind=type(pec_class).__name__,
                                                              listed=choices), generic)
    pec_class = str(pec_class)
    if pec_class not in _PEC_ANSWERS:
        written = pec_class.strip().upper().removeprefix("CLASS").strip()
        if written in ("A", "B", "C", "D") or written == "NONE":
            wanted = written if written != "NONE" else "none"
            return Verdict(False, _("{value!r} is not written as the check needs it: write "
                                    "{wanted!r}, as in {listed}.").format(
                                        value=pec_class, wanted=wanted, listed=choices), generic)
        return Verdict(False, _("{value!r} is not a PEC-PCD class: the answer is one of "
                                "{listed}.").format(value=pec_class, listed=choices), generic)
    task = PEC_CLASS.task(check_errors=check_errors, fit_residuals=fit_residuals, scale=scale)
    result, right = task.result, task.right
    where = _("1:{scale:,.0f}").format(scale=prose_number(result.scale))
    if pec_class == right:
        if right == "none":
            return Verdict(True, _("no class at {where}: the check points fail class D's tests."
                                   ).format(where=where))
        pec, ep = result.thresholds[right]
        return Verdict(True, _("class {name} at {where}: 90 % of the check points within "
                               "{p90:.1f} m (PEC {pec:.1f} m), RMS {rms:.1f} m (EP {ep:.1f} m)."
                               ).format(name=right, where=where,
                                        p90=prose_number(result.percentile_90),
                                        pec=prose_number(pec), rms=prose_number(result.rms),
                                        ep=prose_number(ep)))
    hints = PEC_CLASS.hints(pec_class, task, lambda answer, wrong: answer == wrong)
    if pec_class == "none":
        message = _("the check points meet a class at {where}: 'none' is too strict.").format(
            where=where)
    elif right == "none" or _PEC_ANSWERS.index(pec_class) < _PEC_ANSWERS.index(right):
        fails_pec, fails_ep = not result.pec_test[pec_class], not result.ep_test[pec_class]
        message = (_("at {where} the check points fail class {name}'s 90 % test and "
                     "standard-error test.") if fails_pec and fails_ep else
                   _("at {where} the check points fail class {name}'s 90 % test.") if fails_pec
                   else _("at {where} the check points fail class {name}'s standard-error "
                          "test.")).format(where=where, name=pec_class)
    else:
        message = _("the check points meet class {name} at {where}, but also a stricter class."
                    ).format(name=pec_class, where=where)
    return Verdict(False, message, first_hint(hints, PEC_CLASS.general))
