"""Checks of exercises 6 (chapter 6, the genetic-algorithm paper): fitness, decoding, a sub-optimal
run.

References
----------
The GA paper: *Homologous regions by genetic algorithms for the registration of multi-sensor
images* (GEOSAFRAS programme).
"""

import numpy as np

from rsgeo.registration import BITS_PER_GENE, decode, fitness

from .._i18n import N_, _
from .engine import (
    Declaration,
    Mistake,
    Verdict,
    WrongForm,
    declare,
    first_hint,
    integer,
    require,
)

__all__ = ["check_fitness", "check_decode", "check_suboptimal_segment"]


def _one_to_one(task):
    """The solution's reordered areas and distances, when it matches one to one (else None)."""
    solution = np.asarray(task.solution)
    reference, adjustment = task.reference, task.adjustment
    if sorted(solution.tolist()) != list(range(1, len(reference) + 1)):
        return {"pairs": None}
    order = np.argsort(solution)                  # adjustment segment of each reference label
    pairs = np.triu_indices(len(reference), 1)
    s_r, s_a = reference.areas, adjustment.areas[order]
    d_r, d_a = reference.distances[pairs], adjustment.distances[order][:, order][pairs]
    return {"pairs": pairs, "s_r": s_r, "s_a": s_a, "d_r": d_r, "d_a": d_a,
            "fs": 1 - np.abs(s_r - s_a).sum() / s_r.sum(),
            "fe": 1 - np.abs(d_r - d_a).sum() / d_r.sum()}


def _variant(fs, fe):
    """A mistake in FS or FE (``fs(task)``, ``fe(task)``; None: the right one), combined as FA;
    for a one-to-one solution only."""
    def wrong(task):
        if task.pairs is None:
            return None
        got_fs = task.fs if fs is None else fs(task)
        got_fe = task.fe if fe is None else fe(task)
        return task.alpha * got_fs + (1 - task.alpha) * got_fe
    return wrong


def _identity_fitness(task):
    if len(task.adjustment) > len(task.reference):
        return float("nan")
    return fitness(np.arange(1, len(task.adjustment) + 1), task.reference, task.adjustment,
                   task.alpha)


FITNESS = Declaration(
    check="check_fitness", answer="value", inputs=("solution", "reference", "adjustment", "alpha"),
    derive=_one_to_one,
    right=lambda task: fitness(task.solution, task.reference, task.adjustment, task.alpha),
    general=N_("FA = a·FS + (1 − a)·FE with FS = 1 − Σ|S_R − S_A| / Σ S_R and FE = 1 − "
               "Σ|D_R − D_A| / Σ D_R (chapter 6, section 'The fitness and the genetic "
               "algorithm')."),
    mistakes=(
        Mistake(N_("That is FS alone; FA also weighs the layout, FE."),
                lambda task: fitness(task.solution, task.reference, task.adjustment, 1.0)),
        Mistake(N_("That is FE alone; FA also weighs the sizes, FS."),
                lambda task: fitness(task.solution, task.reference, task.adjustment, 0.0)),
        Mistake(N_("That is a·DMS + (1 − a)·DME, the errors: FS = 1 − DMS and FE = 1 − DME."),
                lambda task: 1 - task.right),
        Mistake(N_("That is the fitness of the identity matching [1, 2, 3 ...]; pair segments as "
                   "`solution` says."), _identity_fitness),
        Mistake(N_("Normalise by the REFERENCE's sums, Σ S_R and Σ D_R."),
                _variant(lambda t: 1 - np.abs(t.s_r - t.s_a).sum() / t.s_a.sum(),
                         lambda t: 1 - np.abs(t.d_r - t.d_a).sum() / t.d_a.sum())),
        Mistake(N_("Normalise DMS by Σ S_R, the reference's areas."),
                _variant(lambda t: 1 - np.abs(t.s_r - t.s_a).sum() / t.s_a.sum(), None)),
        Mistake(N_("Normalise DME by Σ D_R, the reference's distances."),
                _variant(None, lambda t: 1 - np.abs(t.d_r - t.d_a).sum() / t.d_a.sum())),
        Mistake(N_("Compare each reference segment's area with the area of ITS matched "
                   "adjustment segment."),
                _variant(lambda t: 1 - np.abs(t.s_r - t.adjustment.areas).sum() / t.s_r.sum(),
                         None)),
        Mistake(N_("Reorder the adjustment's distances by the matching too: D_A between the "
                   "segments matched to reference j and j'."),
                _variant(None, lambda t: 1 - np.abs(
                    t.d_r - t.adjustment.distances[t.pairs]).sum() / t.d_r.sum())),
        Mistake(N_("DMS and DME are normalised: divide the summed differences by Σ S_R and "
                   "Σ D_R."),
                _variant(lambda t: 1 - np.abs(t.s_r - t.s_a).mean(),
                         lambda t: 1 - np.abs(t.d_r - t.d_a).mean())),
    ))


@declare(FITNESS)
def check_fitness(value, solution, reference, adjustment, alpha=0.5):
    """The paper's FA for a given solution, computed by hand.

    Parameters
    ----------
    value : float
        The student's answer.
    solution : (n,) array_like of int
        solution[k] = reference label of adjustment segment k (1-based).
    reference, adjustment : Mesh
    alpha : float

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``value`` is still ``...``.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), eqs. 1-7.

    Examples
    --------
    >>> from rsgeo.registration import Mesh
    >>> mesh = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> check_fitness(1.0, [1, 2, 3], mesh, mesh)
    Correct: `value` = 1.
    """
    return FITNESS.judge(value, FITNESS.task(solution=solution, reference=reference,
                                             adjustment=adjustment, alpha=alpha))


def _decode_derived(task):
    bits = np.asarray(task.chromosome, dtype=np.int64)
    return {"bits": bits, "genes": bits.reshape(-1, BITS_PER_GENE)}


DECODE = Declaration(
    check="check_decode", answer="decoded", inputs=("chromosome",),
    derive=_decode_derived,
    right=lambda task: decode(task.bits),
    general=N_("Split the bits in groups of 8, most significant bit first, and read each group "
               "as an integer: bit k from the right weighs 2^k."),
    mistakes=(
        Mistake(N_("You read the least significant bit first; the first bit of a gene is the "
                   "MOST significant."),
                lambda task: task.genes[:, ::-1] @ 2 ** np.arange(BITS_PER_GENE - 1, -1, -1)),
        Mistake(N_("Labels are 1-based as they are: do not subtract 1 (0 means 'no match')."),
                lambda task: task.right - 1),
        Mistake(N_("Do not add 1: the bits already encode the 1-based label."),
                lambda task: task.right + 1),
        Mistake(N_("You counted the 1 bits; each bit has a weight, 2^k, by its position."),
                lambda task: task.genes.sum(axis=1)),
    ))


def _decoded_form(answer, bits, genes, expected):
    """``answer`` as an array of labels; raises WrongForm for any other form."""
    answer = require(answer, "decoded")
    if isinstance(answer, (str, bytes)):
        raise WrongForm(_("`decoded` is the text {value!r}; the check needs an array of "
                           "integers.").format(value=answer))
    try:
        array = np.asarray(answer, dtype=float)
    except (TypeError, ValueError):
        raise WrongForm(_("`decoded` is not an array of numbers.")) from None
    if array.ndim == 0:
        if np.isfinite(array) and int(array) == int(bits @ 2 ** np.arange(bits.size - 1, -1, -1)):
            raise WrongForm(_("`decoded` is one integer: you read the whole chromosome as one "
                               "number. Each gene of 8 bits is one label."))
        raise WrongForm(_("`decoded` is one number; the check needs one label per gene, "
                           "{count} of them.").format(count=len(expected)))
    if array.shape == genes.shape:
        raise WrongForm(_("`decoded` has shape {shape}: the bits are grouped but not read as "
                           "integers yet.").format(shape=array.shape))
    if array.shape == bits.shape and np.array_equal(array, bits):
        raise WrongForm(_("`decoded` is the chromosome's bits themselves; decode them into "
                           "labels."))
    if array.ndim != 1:
        raise WrongForm(_("`decoded` has shape {shape}; the check needs a flat array of "
                           "{count} labels.").format(shape=array.shape, count=len(expected)))
    if array.shape != expected.shape:
        groups = {size: bits.reshape(-1, size) @ 2 ** np.arange(size - 1, -1, -1)
                  for size in range(1, bits.size + 1) if bits.size % size == 0}
        size = next((s for s, g in groups.items() if g.shape == array.shape
                     and np.array_equal(g, array)), None)
        if size:
            raise WrongForm(_("`decoded` has {count} labels (groups of {size} bits; a gene has "
                               "{gene}); {bits} bits at {gene} per gene make {expected}.").format(
                                   count=array.size, size=size, gene=BITS_PER_GENE,
                                   bits=bits.size, expected=len(expected)))
        raise WrongForm(_("`decoded` has {count} labels; {bits} bits at {gene} per gene make "
                           "{expected}.").format(count=array.size, gene=BITS_PER_GENE,
                                                 bits=bits.size, expected=len(expected)))
    if not np.all(array == np.round(array)):
        raise WrongForm(_("`decoded` holds fractions; labels are whole numbers."))
    return array


@declare(DECODE)
def check_decode(solution, chromosome):
    """A binary chromosome (8 bits per gene, most significant first) decoded to reference labels.

    Parameters
    ----------
    solution : (n,) array_like of int
        The student's answer (``decoded`` in the exercise, the name its messages use).
    chromosome : (8n,) array_like of 0 and 1

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``decoded`` is still ``...``.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 3 (8 bits per gene).

    Examples
    --------
    >>> check_decode([3, 5], [0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 1])
    Correct: decoded [3, 5].
    """
    task = DECODE.task(chromosome=chromosome)
    expected = task.right
    try:
        array = _decoded_form(solution, task.bits, task.genes, expected)
    except WrongForm as form:
        return form.verdict(_(DECODE.general))
    if np.array_equal(array, expected):
        return Verdict(True, _("decoded {labels}.").format(labels=expected.tolist()))
    hints = DECODE.hints(array, task, np.array_equal)
    wrong = np.flatnonzero(array != expected) + 1
    return Verdict(False, (_("`decoded` is not what these bits encode: gene {genes} differs.")
                           if len(wrong) == 1 else
                           _("`decoded` is not what these bits encode: genes {genes} differ.")
                           ).format(genes=", ".join(map(str, wrong))),
                   first_hint(hints, DECODE.general))


SUBOPTIMAL_SEGMENT = Declaration(
    check="check_suboptimal_segment", answer="segment", inputs=("result", "truth"),
    derive=lambda task: {"result": np.asarray(task.result), "truth": np.asarray(task.truth)},
    right=lambda task: [k + 1 for k in range(len(task.truth))
                        if task.result[k] != task.truth[k]],
    general=N_("Compare the GA's solution with the true one position by position; segments "
               "count from 1."),
    mistakes=(
        Mistake(N_("Did you count from 0 (np.flatnonzero gives 0-based positions)? Segments are "
                   "numbered from 1: add 1."),
                lambda task: [k - 1 for k in task.right], many=True),
    ))


@declare(SUBOPTIMAL_SEGMENT)
def check_suboptimal_segment(segment, result, truth):
    """Which adjustment segment (1-based) a sub-optimal GA run matched wrongly.

    The right answers are every wrongly matched segment; any one of them is correct.

    Parameters
    ----------
    segment : int
        The student's answer, an adjustment segment numbered from 1.
    result, truth : (n,) array_like of int
        The GA's solution and the true one.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``segment`` is still ``...``.

    Examples
    --------
    >>> check_suboptimal_segment(2, [1, 3, 3], [1, 2, 3])
    Correct: segment 2 is matched to 3, not 2.
    """
    n = len(np.asarray(truth))
    generic = SUBOPTIMAL_SEGMENT.general
    try:
        segment = integer(segment, "segment", _("a segment number"), many=_(
            "`segment` holds several values; the check needs ONE segment number (any one of "
            "the wrongly matched)."))
        if not 1 <= segment <= n:
            message = _("`segment` is {segment}: the adjustment segments are numbered 1 to "
                        "{n}.").format(segment=segment, n=n)
            if segment == 0:
                message += " " + _("Segments are numbered from 1, not from 0.")
            raise WrongForm(message)
    except WrongForm as form:
        return form.verdict(_(generic))
    task = SUBOPTIMAL_SEGMENT.task(result=result, truth=truth)
    if segment in task.right:
        return Verdict(True, _("segment {segment} is matched to {got}, not {true}.").format(
            segment=segment, got=task.result[segment - 1], true=task.truth[segment - 1]))
    hints = SUBOPTIMAL_SEGMENT.hints(segment, task, lambda answer, wrong: answer == wrong,
                                     exclude_right=False)
    return Verdict(False, _("segment {segment} is matched correctly.").format(segment=segment),
                   first_hint(hints, generic))
