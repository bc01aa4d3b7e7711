"""Homologous regions by a genetic algorithm over relational meshes (the GA paper).

The GA paper is *Homologous regions by genetic algorithms for the registration
of multi-sensor images* (GEOSAFRAS programme; Lapa, Paraná; see the book's
bibliography), taught in the book's chapter 6.

Forest remnants change little between dates and sensors; their segments in a
reference image and in an adjustment image form two relational meshes (a
label, a centroid and an area per segment; distances between centroids).
Matching = choosing, for each adjustment segment k, the reference segment
``solution[k]`` it corresponds to (0 = none), e.g. [3, 1, 1, 2, 4, 5]. The
paper searches this space with a genetic algorithm whose fitness rewards
similar sizes and similar spatial layout.

Notes
-----
**Reading of the paper's equations** (the OCR of eqs. 2 and 6 is garbled).
Several adjustment segments may belong to one reference segment (the paper's
optimum [1 1 1 2 2 2 3 3 3 4 4 4 5]), so sizes and positions are compared per
reference label j, over the group G_j = {k : solution[k] = j}:

* size:   ``DMS = Σ_j |S_R(j) − Σ_{k∈G_j} S_A(k)| / Σ_j S_R(j)``   (eq. 2), FS = 1 − DMS (eq. 3);
  an unmatched reference segment counts with its whole area;
* layout: the group's centroid is the area-weighted mean of its members'
  centroids; over the pairs of matched labels (j, j'),
  ``DME = Σ |D_R(j, j') − D_A(j, j')| / Σ D_R(j, j')``   (eqs. 4-6), FE = 1 − DME (eq. 7);
* FA = a·FS + (1 − a)·FE (eq. 1), with FS and FE floored at 0 so FA is in [0, 1].

Distances and areas are in map units (pixels × pixel size), which accounts for
the images' different resolutions as the paper asks.

**Beyond the paper: the "compact" fitness.**
The paper's size term rewards piling unrelated segments onto a reference
segment that is short of area (each one fills part of the shortfall), while
leaving a segment unmatched (0) never helps it. ``variant="compact"`` keeps FA
but asks that a group be one forest seen in pieces: its members, each taken as
a disk of its area, must have a polar moment about the group centroid of at
most ``COMPACT_SPREAD`` times that of a single disk of the group's area (two
halves of a disk: 0.86; two touching equal disks: 1.5). A group that is not
compact is a wrong match: it costs S_R(j) + S_G(j) in DMS (more than leaving
its members unmatched, which costs S_R(j)) and is left out of the layout term.
Solutions without many-to-one groups score the same with both variants.
"""

from dataclasses import dataclass, field, replace
from itertools import permutations
from math import factorial

import numpy as np
from numba import njit

from .. import gcp
from .._numba_cache import CACHE
from ..errors import GCPError, GridError, RsgeoError
from ..language import N_, _
from ..validation import as_finite, as_integer, as_number, as_points, check_choice
from ._pipeline import register

__all__ = [
    "BITS_PER_GENE",
    "COMPACT_SPREAD",
    "VARIANTS",
    "MatchResult",
    "Mesh",
    "decode",
    "encode",
    "exhaustive_match",
    "fitness",
    "fitness_batch",
    "genetic_match",
    "group_spread",
    "matched_centroids",
    "optimum_match",
    "qap_match",
    "register_by_regions",
    "true_matching",
]

BITS_PER_GENE = 8
COMPACT_SPREAD = 2.0
VARIANTS = ("paper", "compact")


@dataclass
class Mesh:  # numpydoc ignore=PR02
    """A relational mesh: segment centroids and areas, distances derived.

    Parameters
    ----------
    centroids : (n, 2) array_like
        Centroid (x, y) of each segment, in pixels or map units.
    areas : (n,) array_like
        Area of each segment, in pixels (or map units²).
    pixel_size : float
        Size of a pixel in map units; centroids and areas are scaled by it
        (1 when they are already in map units).

    Raises
    ------
    ValueError
        Fewer than 3 segments, arrays of different lengths, non-positive areas;
        ``GridError`` for a pixel size that is not positive.
    TypeError
        If ``pixel_size`` or an area is a bool or text.
    """

    centroids: np.ndarray
    areas: np.ndarray
    pixel_size: float = 1.0
    distances: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        self.pixel_size = as_number(self.pixel_size, "pixel_size")
        if not self.pixel_size > 0:
            raise GridError(_("pixel_size must be a positive size of a pixel in map units (1 "
                              "when centroids and areas are already in map units), got "
                              "{value!r}").format(value=self.pixel_size))
        self.centroids = as_points(self.centroids, "centroids") * self.pixel_size
        self.areas = as_finite(self.areas, "areas").ravel() * self.pixel_size ** 2
        if len(self.centroids) < 3:
            raise RsgeoError(_("a relational mesh needs at least 3 segments, got "
                               "{n_values}").format(n_values=len(self.centroids)))
        if len(self.areas) != len(self.centroids):
            raise RsgeoError(_("centroids and areas must describe the same segments, "
                               "got {n_values} centroids and {n_values2} areas").format(
                    n_values=len(self.centroids), n_values2=len(self.areas)))
        if not (np.isfinite(self.areas).all() and (self.areas > 0).all()):
            raise RsgeoError(_("every segment area must be a positive number"))
        difference = self.centroids[:, np.newaxis] - self.centroids[np.newaxis]
        self.distances = np.hypot(difference[..., 0], difference[..., 1])

    def __len__(self):
        return len(self.areas)


def _check_meshes(**meshes):
    """Refuse anything but a :class:`Mesh` for each named argument (TypeError naming it)."""
    for name, mesh in meshes.items():
        if not isinstance(mesh, Mesh):
            raise TypeError(_("{name} must be a rsgeo.registration.Mesh, got {kind}; make one "
                              "with Mesh(centroids, areas), e.g. from forest_segments' segments: "
                              "Mesh(segments.centroids, segments.areas)").format(
                                  name=name, kind=type(mesh).__name__))


def _as_solutions(solutions, n, m):
    solutions = np.asarray(solutions)
    if solutions.ndim == 1:
        solutions = solutions[np.newaxis]
    if solutions.shape[1] != n:
        raise RsgeoError(_("a solution needs one label per adjustment segment ({n}), "
                           "got {value}").format(n=n, value=solutions.shape[1]))
    if solutions.min() < 0 or solutions.max() > m:
        raise RsgeoError(_("labels must be 0 (no match) to {m} (the reference "
                           "segments), got {min} to {max}").format(
                m=m, min=solutions.min(), max=solutions.max()))
    return solutions.astype(np.intp)


def fitness_batch(solutions, reference, adjustment, alpha=0.5, variant="paper"):
    """FA of many solutions at once; see :func:`fitness`.

    Parameters
    ----------
    solutions : (P, n) array_like of int
        One solution per row (a single (n,) solution is taken as P = 1).
    reference, adjustment : Mesh
    alpha : float
    variant : {"paper", "compact"}

    Returns
    -------
    ndarray, shape (P,)

    Raises
    ------
    ValueError
        As :func:`fitness`.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), eqs. 1-7.

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> fitness_batch([[1, 2, 3], [2, 1, 3]], ref, ref).round(4).tolist()
    [1.0, 0.7587]
    """
    _check_meshes(reference=reference, adjustment=adjustment)
    alpha = as_number(alpha, "alpha", 0, 1, N_("the weight of size against layout"))
    check_choice(variant, "variant", VARIANTS)
    m, n = len(reference), len(adjustment)
    solutions = _as_solutions(solutions, n, m)
    return _fitness_kernel(solutions, reference.areas, reference.distances, adjustment.areas,
                           adjustment.centroids, alpha, variant == "compact",
                           COMPACT_SPREAD * (1 + 1e-9))


# -- compiled fitness (Numba): the same sums as the module docstring, one solution at a time --

_TWO_PI = 2 * np.pi


@njit(cache=CACHE)
def _score_groups(group_area, group_x, group_y, group_moment, members, reference_areas,
                  reference_distances, alpha, compact, spread_limit):
    """FA from per-label group sums (area, area·x, area·y, polar moment, member count).

    Overwrites group_x and group_y with the groups' centroids and marks a
    label unused by a group area of 0.
    """
    m = len(reference_areas)
    size_error, total = 0.0, 0.0
    for j in range(m):
        total += reference_areas[j]
        if group_area[j] <= 0:
            size_error += reference_areas[j]
            continue
        cx, cy = group_x[j] / group_area[j], group_y[j] / group_area[j]
        group_x[j], group_y[j] = cx, cy
        error = abs(reference_areas[j] - group_area[j])
        if compact and members[j] > 1:
            moment = max(group_moment[j] - group_area[j] * (cx * cx + cy * cy), 0.0)
            if moment / (group_area[j] * group_area[j] / _TWO_PI) > spread_limit:
                error = reference_areas[j] + group_area[j]
                group_area[j] = 0.0                 # a wrong match: out of the layout term
        size_error += error
    size_fitness = min(max(1.0 - size_error / total, 0.0), 1.0)
    reference_sum, error_sum = 0.0, 0.0
    for i in range(m):
        if group_area[i] <= 0:
            continue
        for j in range(i + 1, m):
            if group_area[j] > 0:
                distance = np.sqrt((group_x[i] - group_x[j]) ** 2 + (group_y[i] - group_y[j]) ** 2)
                reference_sum += reference_distances[i, j]
                error_sum += abs(reference_distances[i, j] - distance)
    layout_error = error_sum / reference_sum if reference_sum > 0 else 1.0
    layout_fitness = min(max(1.0 - layout_error, 0.0), 1.0)
    return alpha * size_fitness + (1 - alpha) * layout_fitness


@njit(cache=CACHE)
def _fitness_kernel(solutions, reference_areas, reference_distances, adjustment_areas,
                    adjustment_xy, alpha, compact, spread_limit):
    count, n = solutions.shape
    m = len(reference_areas)
    scores = np.empty(count)
    area, gx, gy = np.zeros(m), np.zeros(m), np.zeros(m)
    moment, members = np.zeros(m), np.zeros(m, np.int64)
    for p in range(count):
        area[:], gx[:], gy[:], moment[:], members[:] = 0.0, 0.0, 0.0, 0.0, 0
        for k in range(n):
            j = solutions[p, k] - 1
            if j >= 0:
                a, x, y = adjustment_areas[k], adjustment_xy[k, 0], adjustment_xy[k, 1]
                area[j] += a
                gx[j] += a * x
                gy[j] += a * y
                moment[j] += a * (x * x + y * y + a / _TWO_PI)
                members[j] += 1
        scores[p] = _score_groups(area, gx, gy, moment, members, reference_areas,
                                  reference_distances, alpha, compact, spread_limit)
    return scores


def _fitness_numpy(solutions, reference, adjustment, alpha=0.5, variant="paper"):
    """:func:`fitness_batch` in plain NumPy, term by term (the tests check one against the other).
    """
    m, n = len(reference), len(adjustment)
    solutions = _as_solutions(solutions, n, m)
    group_area, group_centroid, spread, members = _groups(solutions, m, adjustment)
    used = group_area > 0
    size_error = np.abs(reference.areas - group_area)
    if variant == "compact":
        wrong = used & (members > 1) & (spread > COMPACT_SPREAD * (1 + 1e-9))
        size_error = np.where(wrong, reference.areas + group_area, size_error)
        used = used & ~wrong
    dms = size_error.sum(axis=1) / reference.areas.sum()
    size_fitness = np.clip(1.0 - dms, 0.0, 1.0)
    difference = group_centroid[:, :, np.newaxis] - group_centroid[:, np.newaxis]
    adjustment_distance = np.hypot(difference[..., 0], difference[..., 1])
    pairs = used[:, :, np.newaxis] & used[:, np.newaxis] & np.triu(np.ones((m, m), bool), 1)
    reference_sum = (reference.distances * pairs).sum(axis=(1, 2))
    error_sum = (np.abs(reference.distances - adjustment_distance) * pairs).sum(axis=(1, 2))
    dme = np.where(reference_sum > 0,
                   error_sum / np.where(reference_sum > 0, reference_sum, 1.0), 1.0)
    layout_fitness = np.clip(1.0 - dme, 0.0, 1.0)
    return alpha * size_fitness + (1 - alpha) * layout_fitness


def group_spread(solution, adjustment, m=None):
    """How spread out each group of adjustment segments is, against one disk of the group's area.

    The members of group j (adjustment segments with solution[k] = j) are taken
    as disks of their areas; their polar moment about the group's area-weighted
    centroid is divided by that of a single disk of the group's total area.
    One member gives 1; the two halves of a disk 0.86; two touching equal disks
    1.5; segments far apart much more. The "compact" fitness calls a group
    compact when this is at most ``COMPACT_SPREAD``.

    Parameters
    ----------
    solution : (n,) array_like of int
        solution[k] = reference label (1 to m) of adjustment segment k, 0 = no match.
    adjustment : Mesh
    m : int, optional
        Number of reference labels (default: the largest label in ``solution``).

    Returns
    -------
    ndarray, shape (m,)
        Spread of each reference label's group; NaN where no segment is assigned.

    Raises
    ------
    ValueError
        For a solution of the wrong length or with labels outside 0..m.

    Examples
    --------
    >>> halves = Mesh([[-0.4244, 0], [0.4244, 0], [5, 5]], [np.pi / 2, np.pi / 2, 1])
    >>> group_spread([1, 1, 2], halves).round(2).tolist()
    [0.86, 1.0]
    """
    solution = np.asarray(solution)
    _check_meshes(adjustment=adjustment)
    m = int(solution.max()) if m is None else int(m)
    solutions = _as_solutions(solution, len(adjustment), max(m, 1))
    group_area, _centroid, spread, _members = _groups(solutions, m, adjustment)
    return np.where(group_area > 0, spread, np.nan)[0]


def _groups(solutions, m, adjustment):
    """Per solution and reference label: group area, centroid, spread and member count."""
    count = len(solutions)
    # one bin per (solution, label): sums over the members of each group by bincount
    index = (solutions + (m + 1) * np.arange(count)[:, np.newaxis]).ravel()

    def group_sum(values):
        weights = np.broadcast_to(values, solutions.shape).ravel()
        return np.bincount(index, weights, minlength=count * (m + 1)).reshape(count, m + 1)[:, 1:]

    areas, (x, y) = adjustment.areas, adjustment.centroids.T
    group_area = group_sum(areas)
    safe_area = np.where(group_area > 0, group_area, 1.0)
    group_centroid = (np.stack([group_sum(areas * x), group_sum(areas * y)], axis=-1)
                      / safe_area[..., None])
    # polar moment of disks of area S about the group centroid: S·(|c − c_G|² + S / 2π)
    moment = (group_sum(areas * (x**2 + y**2 + areas / (2 * np.pi)))
              - group_area * np.sum(group_centroid**2, axis=-1))
    spread = np.maximum(moment, 0.0) / (safe_area**2 / (2 * np.pi))
    members = group_sum(np.ones_like(areas))
    return group_area, group_centroid, spread, members


def fitness(solution, reference, adjustment, alpha=0.5, variant="paper"):
    """The paper's fitness FA = a·FS + (1 − a)·FE of one solution (the GA paper, eq. 1).

    Parameters
    ----------
    solution : (n,) array_like of int
        solution[k] = reference label (1 to m) of adjustment segment k, 0 = no match.
    reference, adjustment : Mesh
    alpha : float
        a, the weight of size similarity (FS) against layout similarity (FE), in [0, 1].
    variant : {"paper", "compact"}
        "paper" is the paper's FA; "compact" (beyond the paper) scores a group
        of adjustment segments that cannot be one forest in pieces (see
        :func:`group_spread`) as a wrong match, never better than leaving its
        members unmatched. Both agree on solutions without many-to-one groups.

    Returns
    -------
    float
        1 for a perfect match; see the module's docstring for FS and FE.

    Raises
    ------
    ValueError
        For alpha outside [0, 1], an unknown variant, a solution of the wrong
        length or with labels outside 0..m.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), eqs. 1-7; the "compact"
    variant is this course's.

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> fitness([1, 2, 3], ref, ref)
    1.0
    >>> round(fitness([2, 1, 3], ref, ref), 4)
    0.7587

    Piling two far-apart segments onto reference segment 3, short of area:

    >>> adj = Mesh([[0, 0], [100, 0], [0, 100], [100, 100]], [50, 80, 60, 60])
    >>> round(fitness([1, 2, 3, 3], ref, adj), 4), round(fitness([1, 2, 3, 0], ref, adj), 4)
    (0.9393, 0.88)
    >>> round(fitness([1, 2, 3, 3], ref, adj, variant="compact"), 4)
    0.52
    """
    return float(fitness_batch(solution, reference, adjustment, alpha, variant)[0])


def encode(solution, bits=BITS_PER_GENE):
    """A solution as a chromosome of bits, ``bits`` per gene, most significant first.

    Parameters
    ----------
    solution : array_like of int
        Labels, one per gene (the last axis); several solutions may be stacked
        on the leading axes.
    bits : int
        Bits per gene; the GA paper codes each gene in 8.

    Returns
    -------
    ndarray of uint8
        0s and 1s, ``bits`` per label along the last axis.

    Raises
    ------
    ValueError
        If a label is negative or does not fit in ``bits`` bits.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 3 (binary coding).

    Goldberg, D. E. (1989), *Genetic Algorithms in Search, Optimization, and
    Machine Learning*, Addison-Wesley.

    Examples
    --------
    >>> encode([3, 1]).tolist()
    [0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1]
    """
    solution = np.asarray(solution, dtype=np.int64)
    if solution.min() < 0 or solution.max() >= 2**bits:
        raise RsgeoError(_("labels must fit in {bits} bits (0 to {value})").format(
                bits=bits, value=2 ** bits - 1))
    powers = 2 ** np.arange(bits - 1, -1, -1)
    bits_of = (solution[..., np.newaxis] // powers) % 2
    return bits_of.reshape(solution.shape[:-1] + (-1,)).astype(np.uint8)


def decode(chromosome, bits=BITS_PER_GENE):
    """Integers encoded by a chromosome, ``bits`` per gene, most significant bit first.

    The inverse of :func:`encode`.

    Parameters
    ----------
    chromosome : array_like of 0 and 1
        Bits along the last axis; several chromosomes may be stacked on the
        leading axes.
    bits : int
        Bits per gene.

    Returns
    -------
    ndarray of int
        One integer per gene along the last axis.

    Raises
    ------
    ValueError
        If the length of the last axis is not a multiple of ``bits``, or the
        chromosome holds anything but 0 and 1.

    Examples
    --------
    >>> decode([0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 1]).tolist()
    [3, 5]
    """
    chromosome = np.asarray(chromosome, dtype=np.int64)
    if chromosome.shape[-1] % bits:
        raise RsgeoError(_("a chromosome holds {bits} bits per gene; {value} bits is "
                           "not a multiple").format(bits=bits, value=chromosome.shape[-1]))
    if not np.isin(chromosome, (0, 1)).all():
        raise RsgeoError(_("a chromosome holds only 0 and 1"))
    genes = chromosome.reshape(chromosome.shape[:-1] + (-1, bits))
    return genes @ (2 ** np.arange(bits - 1, -1, -1))


@dataclass
class MatchResult:
    """The outcome of a matching search.

    Attributes
    ----------
    solution : ndarray of int
        solution[k] = reference label of adjustment segment k (1-based), 0 = none.
    fitness : float
    history : list of dict
        Per generation: ``best`` (the best fitness so far), ``generation_best``
        (the best of this generation's population: it never falls when an
        elite is kept), ``mean`` fitness, ``diversity`` (mean share of genes
        that differ from the population's most common value) and
        ``best_solution``. Empty for exhaustive search.
    evaluations : int
        Number of fitness evaluations.
    optimal : bool
        True when the solution is proven to be the optimum of the fitness
        (:func:`exhaustive_match`, a finished :func:`optimum_match`).
    """

    solution: np.ndarray
    fitness: float
    history: list
    evaluations: int
    optimal: bool = False


def _diversity(labels, m):
    """Mean share of genes that differ from their column's most common label."""
    count, n = labels.shape
    counts = np.bincount((labels + (m + 1) * np.arange(n)).ravel(), minlength=n * (m + 1))
    return float(1.0 - counts.reshape(n, m + 1).max(axis=1).mean() / count)


def genetic_match(reference, adjustment, alpha=0.5, seed=None, population_size=1000,
                  generations=600, elite_fraction=0.05, selection="tournament",
                  crossover_rate=0.9, mutation_rate=None,
                  tournament_size=2, target_fitness=None, encoding="binary", variant="paper",
                  stall_generations=200, crossover=None):
    """The paper's genetic algorithm: the adjustment segments' reference labels that maximise FA.

    The GA paper, section 3: one gene per adjustment segment holding a reference
    label (0 = no match), each coded in 8 bits; a random initial population;
    elitism (about 5 %); roulette or tournament selection; crossover; bit-flip
    mutation; stop on a fitness criterion or a generation limit (Goldberg 1989).
    A decoded value above m wraps around (value mod (m + 1)), so every
    chromosome is a valid solution.

    The defaults were tuned by measurement (``python benchmarks/matching.py``,
    100 seeded synthetic meshes per size, against the optimum certified by
    :func:`optimum_match`): a large population (1000) under mild selection
    pressure (tournaments of 2) keeps the diversity that smaller, greedier
    settings lose (100 individuals and tournaments of 3 reached the optimum
    in 95 of 100 runs at n = 8); the stall rule ends a run 200 generations
    after its last improvement, which keeps runs short. The paper's binary
    coding then reaches the optimum in all 100 runs at n = 8; at n = 12 the
    integer coding does in 99, with uniform crossover (in the same sweeps,
    one-point crossover reached it less often at equal population).

    Parameters
    ----------
    reference, adjustment : Mesh
    alpha : float
        Weight of size against layout in FA.
    seed : int, optional
        Seed of the random generator; the same seed gives the same run.
    population_size : int
        Individuals per generation (at least 2).
    generations : int
        Largest number of generations.
    elite_fraction : float
        Share of the best individuals copied unchanged to the next generation.
    selection : {"tournament", "roulette"}
    crossover_rate : float
        Probability that two parents are recombined (see ``crossover``).
    mutation_rate : float, optional
        Probability of flipping each bit (binary) or resetting each gene
        (integer); default 0.04 per bit (binary) or 0.1 per gene (integer).
        Lower rates converge too early: with the old settings (100
        individuals, tournaments of 3) 0.05 per gene reached the optimum in
        30 of 100 integer runs at n = 12, 0.1 in 70.
    tournament_size : int
        Contestants per tournament (at least 1): 2 is mild pressure, more is greedier.
    target_fitness : float, optional
        Stop as soon as the best fitness reaches this value.
    encoding : {"binary", "integer"}
        "binary" is the paper's; "integer" keeps one integer per gene, with
        random-reset mutation (beyond the paper).
    variant : {"paper", "compact"}
        The fitness searched: the paper's FA, or the compact-group variant of
        :func:`fitness` (beyond the paper).
    stall_generations : int, optional
        Stop when the best fitness has not improved for this many
        generations (None: run all ``generations``).
    crossover : {"one-point", "uniform"}, optional
        One cut point, or each gene from either parent with probability 1/2.
        Default: one-point for "binary" (the paper's; uniform would mix the
        bits inside a gene), uniform for "integer".

    Returns
    -------
    MatchResult

    Raises
    ------
    ValueError
        For an unknown selection, encoding, crossover or variant, a rate
        outside [0, 1], or a population, tournament or stall count below 1,
        or the binary coding with more than 255 reference segments (use
        ``encoding="integer"``).
    TypeError
        If ``reference`` or ``adjustment`` is not a :class:`Mesh`, or a count or
        the seed is not a number (a bool, a string); 2.5 or NaN is a ValueError.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 3.

    Goldberg, D. E. (1989), *Genetic Algorithms in Search, Optimization, and
    Machine Learning*, Addison-Wesley.

    Examples
    --------
    >>> from rsgeo.synthetic import synthetic_meshes
    >>> reference, adjustment, truth = synthetic_meshes(5, seed=0)
    >>> result = genetic_match(reference, adjustment, seed=0, generations=100)
    >>> bool((result.solution == truth).all())
    True
    """
    _check_meshes(reference=reference, adjustment=adjustment)
    alpha = as_number(alpha, "alpha", 0, 1, N_("the weight of size against layout"))
    check_choice(variant, "variant", VARIANTS)
    check_choice(selection, "selection", ("tournament", "roulette"))
    check_choice(encoding, "encoding", ("binary", "integer"))
    if encoding == "binary" and len(reference) > 2**BITS_PER_GENE - 1:
        raise RsgeoError(_("the binary coding holds labels 0 to {top} in {bits} bits per gene, "
                           "and the reference has {m} segments; use the integer coding "
                           "(encoding=\"integer\")").format(
                               top=2**BITS_PER_GENE - 1, bits=BITS_PER_GENE, m=len(reference)))
    if crossover is None:
        crossover = "one-point" if encoding == "binary" else "uniform"
    check_choice(crossover, "crossover", ("one-point", "uniform"))
    as_number(elite_fraction, "elite_fraction", 0, 1)
    population_size = as_integer(population_size, "population_size", 2)
    generations = as_integer(generations, "generations", 1)
    tournament_size = as_integer(tournament_size, "tournament_size", 1)
    if stall_generations is not None:
        stall_generations = as_integer(stall_generations, "stall_generations", 1, None,
                                       _("or None to run every generation"))
    if seed is not None:
        seed = as_integer(seed, "seed", 0)
    if int(population_size) < 2 or int(generations) < 1:
        raise RsgeoError(_("population_size must be at least 2 and generations at least "
                           "1, got {population_size} and {generations}").format(
                population_size=population_size, generations=generations))
    if not 1 <= int(tournament_size) <= int(population_size):
        raise RsgeoError(_("tournament_size must be 1 to population_size "
                           "({population_size}), got {tournament_size}").format(
                population_size=population_size, tournament_size=tournament_size))
    if stall_generations is not None and int(stall_generations) < 1:
        raise RsgeoError(_("stall_generations must be at least 1 (or None to run every "
                           "generation), got {stall_generations}").format(
                stall_generations=stall_generations))
    as_number(crossover_rate, "crossover_rate", 0, 1, N_("a probability"))
    rng = np.random.default_rng(seed)
    m, n = len(reference), len(adjustment)
    genes_per_individual = n * BITS_PER_GENE if encoding == "binary" else n
    if mutation_rate is None:
        mutation_rate = 0.04 if encoding == "binary" else 0.1
    as_number(mutation_rate, "mutation_rate", 0, 1)

    spread_limit = COMPACT_SPREAD * (1 + 1e-9)

    def labels_of(population):
        # 8 bits per gene, most significant first: packbits is decode without its checks
        genes = np.packbits(population, axis=-1) if encoding == "binary" else population
        return genes.astype(np.intp) % (m + 1)

    if encoding == "binary":
        population = rng.integers(0, 2, (population_size, genes_per_individual), dtype=np.uint8)
    else:
        population = rng.integers(0, m + 1, (population_size, n))
    elite_count = max(1, int(round(elite_fraction * population_size))) if elite_fraction > 0 else 0
    history, evaluations = [], 0
    best_solution, best_fitness, improved = None, -np.inf, 0
    for _generation in range(generations):
        labels = labels_of(population)
        scores = _fitness_kernel(labels, reference.areas, reference.distances, adjustment.areas,
                                 adjustment.centroids, alpha, variant == "compact", spread_limit)
        evaluations += len(scores)
        order = np.argsort(-scores, kind="stable")
        if scores[order[0]] > best_fitness:
            best_fitness, best_solution = float(scores[order[0]]), labels[order[0]].copy()
            improved = len(history)               # the generation of the last improvement
        history.append({"best": best_fitness, "generation_best": float(scores[order[0]]),
                        "mean": float(scores.mean()),
                        "diversity": _diversity(labels, m), "best_solution": best_solution.copy()})
        if target_fitness is not None and best_fitness >= target_fitness:
            break
        if stall_generations is not None and len(history) - 1 - improved >= stall_generations:
            break
        children = [population[order[:elite_count]]]
        parent_count = population_size - elite_count
        parents = _select(rng, scores, parent_count + parent_count % 2, selection, tournament_size)
        mothers, fathers = population[parents[0::2]], population[parents[1::2]]
        cross = rng.random(len(mothers)) < crossover_rate
        if crossover == "uniform":
            mask = (rng.random((len(mothers), genes_per_individual)) < 0.5) | ~cross[:, np.newaxis]
        else:
            points = rng.integers(1, genes_per_individual, len(mothers))
            mask = ((np.arange(genes_per_individual) < points[:, np.newaxis])
                    | ~cross[:, np.newaxis])
        offspring = np.concatenate([np.where(mask, mothers, fathers),
                                    np.where(mask, fathers, mothers)])
        children.append(_mutate(rng, offspring[:parent_count], mutation_rate, encoding, m))
        population = np.concatenate(children)
    return MatchResult(best_solution, best_fitness, history, evaluations)


def _mutate(rng, offspring, rate, encoding, m):
    """Each bit flipped (binary) or each gene reset to a random label 0..m (integer), with
    probability rate."""
    flips = rng.random(offspring.shape) < rate
    if encoding == "binary":
        return np.where(flips, 1 - offspring, offspring).astype(np.uint8)
    return np.where(flips, rng.integers(0, m + 1, offspring.shape), offspring)


def _select(rng, scores, count, selection, tournament_size):
    if selection == "roulette":
        weights = scores - scores.min() + 1e-12
        return rng.choice(len(scores), size=count, p=weights / weights.sum())
    contestants = rng.integers(0, len(scores), (count, tournament_size))
    return contestants[np.arange(count), np.argmax(scores[contestants], axis=1)]


def exhaustive_match(reference, adjustment, alpha=0.5, one_to_one=None, batch=200_000,
                     variant="paper"):
    """The true optimum of FA by trying every solution.

    Parameters
    ----------
    reference, adjustment : Mesh
    alpha : float
    one_to_one : bool, optional
        Try only solutions that give every adjustment segment a different
        reference label (and no 0): n!/(m − n)! of them instead of (m + 1)^n.
        Default: all solutions when there are at most 5 million, else one-to-one.
    batch : int
        Solutions evaluated per step.
    variant : {"paper", "compact"}
        The fitness maximised; see :func:`fitness`.

    Returns
    -------
    MatchResult
        With an empty history; ``evaluations`` is the number of solutions tried.
        Among solutions of equal fitness, the first in lexicographic order.
        ``optimal`` is True for a search over all solutions (the optimum of
        the fitness), False for a one-to-one search (the best one-to-one).

    Raises
    ------
    ValueError
        For a one-to-one search with more adjustment than reference segments,
        or an unknown variant.

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> adj = Mesh([[0, 100], [0, 0], [100, 0]], [120, 50, 80])
    >>> exhaustive_match(ref, adj).solution.tolist()
    [3, 1, 2]
    """
    check_choice(variant, "variant", VARIANTS)
    _check_meshes(reference=reference, adjustment=adjustment)
    m, n = len(reference), len(adjustment)
    if one_to_one is None:
        one_to_one = (m + 1) ** n > 5_000_000
    if one_to_one and n > m:
        raise RsgeoError(_("a one-to-one match needs no more adjustment segments ({n}) "
                           "than reference ones ({m})").format(n=n, m=m))
    if one_to_one:
        candidates = permutations(range(1, m + 1), n)
        chunks = (np.array([c for _index, c in zip(range(batch), candidates)], dtype=np.intp)
                  for _chunk in range(-(-factorial(m) // factorial(m - n) // batch)))
    else:
        # every solution is a number in base m + 1, its digits the labels (most significant first)
        total, powers = (m + 1) ** n, (m + 1) ** np.arange(n - 1, -1, -1)
        chunks = ((np.arange(start, min(start + batch, total))[:, np.newaxis] // powers) % (m + 1)
                  for start in range(0, total, batch))
    best_solution, best_fitness, evaluations = None, -np.inf, 0
    for chunk in chunks:
        if chunk.size == 0:
            break
        scores = fitness_batch(chunk, reference, adjustment, alpha, variant)
        evaluations += len(chunk)
        top = int(np.argmax(scores))
        if scores[top] > best_fitness:
            best_fitness, best_solution = float(scores[top]), chunk[top].astype(np.intp)
    return MatchResult(best_solution, best_fitness, [], evaluations, not one_to_one)


def optimum_match(reference, adjustment, alpha=0.5, variant="paper", incumbent=None,
                  node_limit=2_000_000_000):
    """The true optimum of FA over all (m + 1)^n solutions, by branch and bound (beyond the paper).

    Depth-first over the adjustment segments (largest first), each given a
    reference label or 0. A branch is cut when even a perfect layout
    (FE = 1) cannot beat the best solution found so far: with the groups'
    areas G_j so far and the area R of the segments still to assign, the
    size error can only end up at least
    Σ_j max(G_j − S_R(j), 0) + max(Σ_j max(S_R(j) − G_j, 0) − R, 0),
    since a segment added to a group can only grow it, and reduces a group's
    shortfall by at most its own area. The bound holds for both variants (a
    non-compact group costs more than its size difference), so the search is
    exact: it returns the same optimum as :func:`exhaustive_match` over all
    solutions, in milliseconds where that takes minutes (n = 8) or centuries
    (n = 12).

    Parameters
    ----------
    reference, adjustment : Mesh
    alpha : float
        Weight of size against layout; the bound needs alpha > 0 to cut
        anything (alpha = 0 searches every solution, up to ``node_limit``).
    variant : {"paper", "compact"}
    incumbent : (n,) array_like of int, optional
        A good solution to start from (e.g. a GA's answer or a known truth):
        it only speeds the search up; the optimum does not depend on it.
    node_limit : int
        Largest number of partial solutions to visit before giving up.

    Returns
    -------
    MatchResult
        ``optimal`` is True when the search finished (the solution is the
        optimum, the first found among equal ones); False when it stopped at
        ``node_limit`` (then the solution is only the best found).
        ``evaluations`` counts the partial and complete solutions visited.

    Raises
    ------
    ValueError
        For alpha outside [0, 1], an unknown variant or an incumbent that is
        not a solution.

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> adj = Mesh([[0, 100], [0, 0], [100, 0]], [120, 50, 80])
    >>> best = optimum_match(ref, adj)
    >>> best.solution.tolist(), best.optimal
    ([3, 1, 2], True)
    """
    _check_meshes(reference=reference, adjustment=adjustment)
    alpha = as_number(alpha, "alpha", 0, 1, N_("the weight of size against layout"))
    check_choice(variant, "variant", VARIANTS)
    m, n = len(reference), len(adjustment)
    order = np.argsort(-adjustment.areas, kind="stable")
    # try the labels of the most similar areas first, 0 last: good solutions come early
    candidates = np.empty((n, m + 1), dtype=np.int64)
    for depth, k in enumerate(order):
        closest = np.argsort(np.abs(reference.areas - adjustment.areas[k]), kind="stable")
        candidates[depth, :m] = closest + 1
    candidates[:, m] = 0
    best_solution, best = np.zeros(n, dtype=np.int64), -np.inf
    if incumbent is not None:
        best_solution[:] = _as_solutions(incumbent, n, m)[0]
        best = fitness(best_solution, reference, adjustment, alpha, variant) - 1e-12
    best, visited, finished = _branch_and_bound(
        reference.areas, reference.distances, adjustment.areas, adjustment.centroids, order,
        candidates, alpha, variant == "compact", COMPACT_SPREAD * (1 + 1e-9), best, best_solution,
        int(node_limit))
    solution = best_solution.astype(np.intp)
    return MatchResult(solution, fitness(solution, reference, adjustment, alpha, variant), [],
                       int(visited), bool(finished))


@njit(cache=CACHE)
def _branch_and_bound(reference_areas, reference_distances, adjustment_areas, adjustment_xy, order,
                      candidates, alpha, compact, spread_limit, best, best_solution, node_limit):
    m, n = len(reference_areas), len(adjustment_areas)
    total = reference_areas.sum()
    remaining = np.zeros(n + 1)                   # area of the segments at depths d, d + 1, ...
    for depth in range(n - 1, -1, -1):
        remaining[depth] = remaining[depth + 1] + adjustment_areas[order[depth]]
    area, gx, gy = np.zeros(m), np.zeros(m), np.zeros(m)
    moment, members = np.zeros(m), np.zeros(m, np.int64)
    scratch_area, scratch_x, scratch_y = np.zeros(m), np.zeros(m), np.zeros(m)
    solution = np.zeros(n, np.int64)
    assigned = np.full(n, -1, np.int64)           # label given at each depth, -1 = none yet
    tried = np.zeros(n, np.int64)                 # candidates tried at each depth
    depth, visited = 0, 0
    while depth >= 0:
        k = order[depth]
        a, x, y = adjustment_areas[k], adjustment_xy[k, 0], adjustment_xy[k, 1]
        j = assigned[depth] - 1
        if j >= 0:                                # take back the previous choice at this depth
            members[j] -= 1
            if members[j] == 0:
                area[j], gx[j], gy[j], moment[j] = 0.0, 0.0, 0.0, 0.0
            else:
                area[j] -= a
                gx[j] -= a * x
                gy[j] -= a * y
                moment[j] -= a * (x * x + y * y + a / _TWO_PI)
        assigned[depth] = -1
        if tried[depth] > m:
            depth -= 1
            continue
        if visited >= node_limit:
            return best, visited, False
        label = candidates[depth, tried[depth]]
        tried[depth] += 1
        visited += 1
        j = label - 1
        if j >= 0:
            area[j] += a
            gx[j] += a * x
            gy[j] += a * y
            moment[j] += a * (x * x + y * y + a / _TWO_PI)
            members[j] += 1
        assigned[depth] = label
        solution[k] = label
        if depth == n - 1:
            scratch_area[:], scratch_x[:], scratch_y[:] = area, gx, gy
            score = _score_groups(scratch_area, scratch_x, scratch_y, moment, members,
                                  reference_areas, reference_distances, alpha, compact,
                                  spread_limit)
            if score > best:
                best = score
                best_solution[:] = solution
            continue
        over, short = 0.0, 0.0
        for i in range(m):
            difference = area[i] - reference_areas[i]
            if difference > 0:
                over += difference
            else:
                short -= difference
        size_error = over + max(short - remaining[depth + 1], 0.0)
        if alpha * min(max(1.0 - size_error / total, 0.0), 1.0) + (1 - alpha) <= best:
            continue
        depth += 1
        tried[depth] = 0
        assigned[depth] = -1
    return best, visited, True


def qap_match(reference, adjustment, alpha=0.5, seed=None, restarts=20, variant="paper"):
    """A one-to-one match by SciPy's quadratic assignment (FAQ with random restarts).

    Beyond the paper: the layout part of the problem is a quadratic assignment
    between the two distance matrices; SciPy's FAQ solver maximises their
    agreement. Each restart's permutation is scored with the paper's FA and
    the best kept. Needs as many adjustment as reference segments.
    ``variant`` is the fitness used to score the restarts (see :func:`fitness`).

    Parameters
    ----------
    reference, adjustment : Mesh
        Meshes with the same number of segments.
    alpha : float
        Weight of size against layout in FA, in [0, 1].
    seed : int, optional
        Seed of the random generator of the restarts' initial permutations.
    restarts : int
        Number of FAQ runs, each from a random doubly stochastic start.
    variant : {"paper", "compact"}
        The fitness that scores each restart's permutation.

    Returns
    -------
    MatchResult
        The best-scoring one-to-one solution; ``evaluations`` is ``restarts``,
        ``optimal`` is False.

    Raises
    ------
    ValueError
        If the meshes have different numbers of segments; as :func:`fitness`
        for alpha and variant.

    References
    ----------
    Vogelstein, J. T., Conroy, J. M., Lyzinski, V., Podrazik, L. J., Kratzer,
    S. G., Harley, E. T., Fishkind, D. E., Vogelstein, R. J. and Priebe, C. E.
    (2015), "Fast approximate quadratic programming for graph matching",
    PLOS ONE 10(4), e0121002.

    SciPy, ``scipy.optimize.quadratic_assignment`` (``method="faq"``).

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> adj = Mesh([[0, 100], [0, 0], [100, 0]], [120, 50, 80])
    >>> qap_match(ref, adj, seed=0, restarts=5).solution.tolist()
    [3, 1, 2]
    """
    from scipy.optimize import quadratic_assignment

    _check_meshes(reference=reference, adjustment=adjustment)
    m, n = len(reference), len(adjustment)
    if m != n:
        raise RsgeoError(_("qap_match pairs segments one to one: it needs as many "
                           "reference ({m}) as adjustment ({n}) segments").format(m=m, n=n))
    rng = np.random.default_rng(seed)
    best_solution, best_fitness = None, -np.inf
    for _restart in range(restarts):
        result = quadratic_assignment(adjustment.distances, reference.distances, method="faq",
                                      options={"maximize": True, "P0": "randomized", "rng": rng})
        solution = result.col_ind + 1
        score = fitness(solution, reference, adjustment, alpha, variant)
        if score > best_fitness:
            best_fitness, best_solution = score, solution
    return MatchResult(best_solution, best_fitness, [], restarts)


def matched_centroids(solution, reference, adjustment):
    """GCP pairs from a solution: (adjustment group centroid, reference centroid) per label.

    An adjustment group's centroid is the area-weighted mean of its members'
    centroids.

    Parameters
    ----------
    solution : (n,) array_like of int
        solution[k] = reference label (1 to m) of adjustment segment k, 0 = no match.
    reference, adjustment : Mesh
        The meshes the solution matches.

    Returns
    -------
    adjustment_xy, reference_xy : ndarray, shape (k, 2)
        In each mesh's units (divide by the pixel size for pixels).
    labels : ndarray
        The reference labels that were matched.

    Raises
    ------
    ValueError
        For a solution of the wrong length or with labels outside 0..m.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 4 (centroids of
    matched regions as GCPs).

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> adj = Mesh([[0, 0], [100, 0], [0, 90], [0, 110]], [50, 80, 60, 60])
    >>> adjustment_xy, reference_xy, labels = matched_centroids([1, 2, 3, 3], ref, adj)
    >>> adjustment_xy[2].tolist(), labels.tolist()
    ([0.0, 100.0], [1, 2, 3])
    """
    _check_meshes(reference=reference, adjustment=adjustment)
    solution = _as_solutions(solution, len(adjustment), len(reference))[0]
    labels = np.unique(solution[solution > 0])
    adjustment_xy = np.array([np.average(adjustment.centroids[solution == j], axis=0,
                                         weights=adjustment.areas[solution == j]) for j in labels])
    return adjustment_xy, reference.centroids[labels - 1], labels


def true_matching(reference_xy, adjustment_xy, tolerance):
    """The true matching, when the transform between the images is known (for checking a search).

    Each adjustment segment, its centroid already mapped into the reference
    image through the true transform, gets the label of the nearest reference
    centroid if it lies within ``tolerance``, else 0 (no counterpart among the
    reference segments).

    Parameters
    ----------
    reference_xy : (m, 2) array_like
        Reference centroids.
    adjustment_xy : (n, 2) array_like
        Adjustment centroids mapped into the reference's coordinates.
    tolerance : float
        Largest distance for a match, in the same units.

    Returns
    -------
    solution : ndarray of int, shape (n,)
        Reference label (1-based) of each adjustment segment, 0 = none.
    distance : ndarray, shape (n,)
        Distance from each mapped adjustment centroid to the nearest reference centroid.

    Raises
    ------
    ValueError
        For centroids that are not (k, 2) finite arrays or a negative tolerance.

    Examples
    --------
    >>> solution, distance = true_matching([[0, 0], [10, 0]], [[9, 1], [50, 50]], tolerance=3)
    >>> solution.tolist(), distance.round(2).tolist()
    ([2, 0], [1.41, 64.03])
    """
    reference_xy = as_points(reference_xy, "reference_xy")
    adjustment_xy = as_points(adjustment_xy, "adjustment_xy")
    tolerance = as_number(tolerance, "tolerance", 0, None, N_("a distance"))
    difference = adjustment_xy[:, np.newaxis] - reference_xy[np.newaxis]
    distances = np.hypot(difference[..., 0], difference[..., 1])
    nearest, distance = distances.argmin(axis=1), distances.min(axis=1)
    return np.where(distance <= tolerance, nearest + 1, 0).astype(np.intp), distance


def register_by_regions(reference, adjustment, reference_transform, reference_pixel,
                        adjustment_pixel, alpha=0.5, seed=None, tolerance=1.0, min_gcps=4,
                        variant="paper"):
    """The paper's registration: forest segments matched by the GA, an affine model of centroids.

    The GA paper, section 4: the matched centroids are GCPs for an affine
    transformation; GCPs with large errors are removed (here exactly as
    ``gdalwarp -refine_gcps tolerance min_gcps``) until the RMS is under a pixel.
    The last steps are :func:`rsgeo.registration.register`, which the automatic
    tie points of :mod:`rsgeo.registration` share.

    Parameters
    ----------
    reference, adjustment : rsgeo.registration.Segments
        Forest segments of the reference and adjustment images.
    reference_transform : affine.Affine
        Geotransform of the reference image (its centroids become map coordinates).
    reference_pixel, adjustment_pixel : float
        Pixel sizes (map units), to compare the meshes in the same units.
    alpha, seed
        As :func:`genetic_match`.
    tolerance : float
        Refinement tolerance, adjustment pixels.
    min_gcps : int
        Fewest GCPs refinement keeps (capped at the number matched).
    variant : {"paper", "compact"}
        As :func:`genetic_match`.

    Returns
    -------
    rsgeo.registration.Registration
        The refined affine model, the GCPs (matched reference centroids, map
        units; adjustment centroids, adjustment pixels) and the GA's ``match``.

    Raises
    ------
    ValueError
        If a mesh cannot be built from the segments (see :class:`Mesh`), fewer
        than 3 segments are matched, or as :func:`genetic_match` and
        :func:`rsgeo.accuracy.refine_gcps` for the other arguments.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 4.

    GDAL, ``gdalwarp -refine_gcps`` (``alg/gdal_crs.cpp``).
    """
    reference_mesh = Mesh(reference.centroids, reference.areas, pixel_size=reference_pixel)
    adjustment_mesh = Mesh(adjustment.centroids, adjustment.areas, pixel_size=adjustment_pixel)
    match = genetic_match(reference_mesh, adjustment_mesh, alpha, seed=seed, variant=variant)
    adjustment_xy, _reference_xy, labels = matched_centroids(match.solution, reference_mesh,
                                                             adjustment_mesh)
    image_xy = adjustment_xy / adjustment_pixel
    map_xy = reference.map_centroids(reference_transform)[labels - 1]
    if len(labels) < 3:
        raise GCPError(_("only {n_labels} segments were matched; an affine model needs "
                         "at least 3").format(n_labels=len(labels)))
    # the pipeline every registration shares: tie points -> GCPSet -> model -> refinement
    result = register(gcp.GCPSet(map_xy, image_xy), "polynomial", 1, tolerance,
                                min(min_gcps, len(labels)))
    return replace(result, match=match)
