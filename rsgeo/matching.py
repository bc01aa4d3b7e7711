"""Homologous regions by a genetic algorithm over relational meshes (paper 001).

Forest remnants change little between dates and sensors; their segments in a
reference image and in an adjustment image form two relational meshes (a
label, a centroid and an area per segment; distances between centroids).
Matching = choosing, for each adjustment segment k, the reference segment
``solution[k]`` it corresponds to (0 = none), e.g. [3, 1, 1, 2, 4, 5]. The
paper searches this space with a genetic algorithm whose fitness rewards
similar sizes and similar spatial layout.

Reading of the paper's equations (the OCR of eqs. 2 and 6 is garbled)
----------------------------------------------------------------------
Several adjustment segments may belong to one reference segment (the paper's
optimum [1 1 1 2 2 2 3 3 3 4 4 4 5]), so sizes and positions are compared per
reference label j, over the group G_j = {k : solution[k] = j}:

* size:   DMS = Σ_j |S_R(j) − Σ_{k∈G_j} S_A(k)| / Σ_j S_R(j)   (eq. 2), FS = 1 − DMS (eq. 3);
  an unmatched reference segment counts with its whole area;
* layout: the group's centroid is the area-weighted mean of its members'
  centroids; over the pairs of matched labels (j, j'),
  DME = Σ |D_R(j, j') − D_A(j, j')| / Σ D_R(j, j')   (eqs. 4-6), FE = 1 − DME (eq. 7);
* FA = a·FS + (1 − a)·FE (eq. 1), with FS and FE floored at 0 so FA is in [0, 1].

Distances and areas are in map units (pixels × pixel size), which accounts for
the images' different resolutions as the paper asks.
"""

from dataclasses import dataclass, field
from itertools import permutations, product

import numpy as np

from ._checks import as_points, check_choice, check_range

BITS_PER_GENE = 8


@dataclass
class Mesh:
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
        Fewer than 3 segments, arrays of different lengths, non-positive areas.
    """

    centroids: np.ndarray
    areas: np.ndarray
    pixel_size: float = 1.0
    distances: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        self.centroids = as_points(self.centroids, "centroids") * float(self.pixel_size)
        self.areas = np.asarray(self.areas, dtype=np.float64).ravel() * float(self.pixel_size) ** 2
        if len(self.centroids) < 3:
            raise ValueError(f"a relational mesh needs at least 3 segments, got {len(self.centroids)}")
        if len(self.areas) != len(self.centroids):
            raise ValueError(f"centroids and areas must describe the same segments, got {len(self.centroids)} "
                             f"centroids and {len(self.areas)} areas")
        if not (np.isfinite(self.areas).all() and (self.areas > 0).all()):
            raise ValueError("every segment area must be a positive number")
        difference = self.centroids[:, np.newaxis] - self.centroids[np.newaxis]
        self.distances = np.hypot(difference[..., 0], difference[..., 1])

    def __len__(self):
        return len(self.areas)


def _as_solutions(solutions, n, m):
    solutions = np.asarray(solutions)
    if solutions.ndim == 1:
        solutions = solutions[np.newaxis]
    if solutions.shape[1] != n:
        raise ValueError(f"a solution needs one label per adjustment segment ({n}), got {solutions.shape[1]}")
    if solutions.min() < 0 or solutions.max() > m:
        raise ValueError(f"labels must be 0 (no match) to {m} (the reference segments), "
                         f"got {solutions.min()} to {solutions.max()}")
    return solutions.astype(np.intp)


def fitness_batch(solutions, reference, adjustment, alpha=0.5):
    """FA of many solutions at once; see :func:`fitness`. Returns an array of shape (P,)."""
    alpha = check_range(alpha, "alpha", 0, 1, "the weight of size against layout")
    m, n = len(reference), len(adjustment)
    solutions = _as_solutions(solutions, n, m)
    # membership[p, k, j]: adjustment segment k assigned to reference label j + 1
    membership = (solutions[:, :, np.newaxis] == np.arange(1, m + 1)).astype(np.float64)
    group_area = np.einsum("pkj,k->pj", membership, adjustment.areas)
    dms = np.abs(reference.areas - group_area).sum(axis=1) / reference.areas.sum()
    size_fitness = np.clip(1.0 - dms, 0.0, 1.0)

    used = group_area > 0
    weighted = np.einsum("pkj,k,kd->pjd", membership, adjustment.areas, adjustment.centroids)
    group_centroid = weighted / np.where(used, group_area, 1.0)[..., np.newaxis]
    difference = group_centroid[:, :, np.newaxis] - group_centroid[:, np.newaxis]
    adjustment_distance = np.hypot(difference[..., 0], difference[..., 1])
    pairs = used[:, :, np.newaxis] & used[:, np.newaxis] & np.triu(np.ones((m, m), bool), 1)
    reference_sum = (reference.distances * pairs).sum(axis=(1, 2))
    error_sum = (np.abs(reference.distances - adjustment_distance) * pairs).sum(axis=(1, 2))
    dme = np.where(reference_sum > 0, error_sum / np.where(reference_sum > 0, reference_sum, 1.0), 1.0)
    layout_fitness = np.clip(1.0 - dme, 0.0, 1.0)
    return alpha * size_fitness + (1 - alpha) * layout_fitness


def fitness(solution, reference, adjustment, alpha=0.5):
    """The paper's fitness FA = a·FS + (1 − a)·FE of one solution (paper 001, eq. 1).

    Parameters
    ----------
    solution : (n,) array_like of int
        solution[k] = reference label (1 to m) of adjustment segment k, 0 = no match.
    reference, adjustment : Mesh
    alpha : float
        a, the weight of size similarity (FS) against layout similarity (FE), in [0, 1].

    Returns
    -------
    float
        1 for a perfect match; see the module's docstring for FS and FE.

    Raises
    ------
    ValueError
        For alpha outside [0, 1], a solution of the wrong length or with labels outside 0..m.

    Examples
    --------
    >>> ref = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> fitness([1, 2, 3], ref, ref)
    1.0
    >>> round(fitness([2, 1, 3], ref, ref), 4)
    0.7587
    """
    return float(fitness_batch(solution, reference, adjustment, alpha)[0])


def encode(solution, bits=BITS_PER_GENE):
    """A solution as a chromosome of bits, ``bits`` per gene, most significant first.

    Examples
    --------
    >>> encode([3, 1]).tolist()
    [0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1]
    """
    solution = np.asarray(solution, dtype=np.int64)
    if solution.min() < 0 or solution.max() >= 2**bits:
        raise ValueError(f"labels must fit in {bits} bits (0 to {2**bits - 1})")
    powers = 2 ** np.arange(bits - 1, -1, -1)
    return ((solution[..., np.newaxis] // powers) % 2).reshape(solution.shape[:-1] + (-1,)).astype(np.uint8)


def decode(chromosome, bits=BITS_PER_GENE):
    """Integers encoded by a chromosome, ``bits`` per gene, most significant bit first.

    Examples
    --------
    >>> decode([0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 1]).tolist()
    [3, 5]
    """
    chromosome = np.asarray(chromosome, dtype=np.int64)
    if chromosome.shape[-1] % bits:
        raise ValueError(f"a chromosome holds {bits} bits per gene; {chromosome.shape[-1]} bits is not a multiple")
    if not np.isin(chromosome, (0, 1)).all():
        raise ValueError("a chromosome holds only 0 and 1")
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
        Per generation: ``best`` and ``mean`` fitness, ``diversity`` (mean
        share of genes that differ from the population's most common value)
        and ``best_solution``. Empty for exhaustive search.
    evaluations : int
        Number of fitness evaluations.
    """

    solution: np.ndarray
    fitness: float
    history: list
    evaluations: int


def _diversity(population):
    mode_share = [np.bincount(column).max() / len(column) for column in population.T]
    return float(1.0 - np.mean(mode_share))


def genetic_match(reference, adjustment, alpha=0.5, seed=None, population_size=100, generations=400,
                  elite_fraction=0.05, selection="tournament", crossover_rate=0.9, mutation_rate=None,
                  tournament_size=3, target_fitness=None, encoding="binary"):
    """The paper's genetic algorithm: the adjustment segments' reference labels that maximise FA.

    Paper 001, section 3: one gene per adjustment segment holding a reference
    label (0 = no match), each coded in 8 bits; a random initial population;
    elitism (about 5 %); roulette or tournament selection; crossover; bit-flip
    mutation; stop on a fitness criterion or a generation limit (Goldberg 1989).
    A decoded value above m wraps around (value mod (m + 1)), so every
    chromosome is a valid solution.

    Parameters
    ----------
    reference, adjustment : Mesh
    alpha : float
        Weight of size against layout in FA.
    seed : int, optional
        Seed of the random generator; the same seed gives the same run.
    population_size, generations : int
    elite_fraction : float
        Share of the best individuals copied unchanged to the next generation.
    selection : {"tournament", "roulette"}
    crossover_rate : float
        Probability that two parents are recombined (one-point crossover).
    mutation_rate : float, optional
        Probability of flipping each bit (binary) or resetting each gene
        (integer); default 0.04 per bit (binary) or 0.1 per gene (integer),
        which found the exhaustive optimum in 30 of 30 seeded runs on 5- and
        8-segment meshes, where 1/length converged too early in 1 to 3 of 30.
    tournament_size : int
    target_fitness : float, optional
        Stop as soon as the best fitness reaches this value.
    encoding : {"binary", "integer"}
        "binary" is the paper's; "integer" keeps one integer per gene, with
        one-point crossover and random-reset mutation (beyond the paper).

    Returns
    -------
    MatchResult
    """
    check_range(alpha, "alpha", 0, 1)
    check_choice(selection, "selection", ("tournament", "roulette"))
    check_choice(encoding, "encoding", ("binary", "integer"))
    check_range(elite_fraction, "elite_fraction", 0, 1)
    if int(population_size) < 2 or int(generations) < 1:
        raise ValueError("population_size must be at least 2 and generations at least 1")
    rng = np.random.default_rng(seed)
    m, n = len(reference), len(adjustment)
    genes_per_individual = n * BITS_PER_GENE if encoding == "binary" else n
    if mutation_rate is None:
        mutation_rate = 0.04 if encoding == "binary" else 0.1
    check_range(mutation_rate, "mutation_rate", 0, 1)

    def labels_of(population):
        return (decode(population) if encoding == "binary" else population) % (m + 1)

    if encoding == "binary":
        population = rng.integers(0, 2, (population_size, genes_per_individual), dtype=np.uint8)
    else:
        population = rng.integers(0, m + 1, (population_size, n))
    elite_count = max(1, int(round(elite_fraction * population_size))) if elite_fraction > 0 else 0
    history, evaluations = [], 0
    best_solution, best_fitness = None, -np.inf
    for _ in range(generations):
        labels = labels_of(population)
        scores = fitness_batch(labels, reference, adjustment, alpha)
        evaluations += len(scores)
        order = np.argsort(-scores, kind="stable")
        if scores[order[0]] > best_fitness:
            best_fitness, best_solution = float(scores[order[0]]), labels[order[0]].copy()
        history.append({"best": best_fitness, "mean": float(scores.mean()),
                        "diversity": _diversity(labels), "best_solution": best_solution.copy()})
        if target_fitness is not None and best_fitness >= target_fitness:
            break
        children = [population[order[:elite_count]]]
        parent_count = population_size - elite_count
        parents = _select(rng, scores, parent_count + parent_count % 2, selection, tournament_size)
        mothers, fathers = population[parents[0::2]], population[parents[1::2]]
        cross = rng.random(len(mothers)) < crossover_rate
        points = rng.integers(1, genes_per_individual, len(mothers))
        mask = (np.arange(genes_per_individual) < points[:, np.newaxis]) | ~cross[:, np.newaxis]
        offspring = np.concatenate([np.where(mask, mothers, fathers), np.where(mask, fathers, mothers)])
        offspring = offspring[:parent_count]
        flips = rng.random(offspring.shape) < mutation_rate
        if encoding == "binary":
            offspring = np.where(flips, 1 - offspring, offspring).astype(np.uint8)
        else:
            offspring = np.where(flips, rng.integers(0, m + 1, offspring.shape), offspring)
        children.append(offspring)
        population = np.concatenate(children)
    return MatchResult(best_solution, best_fitness, history, evaluations)


def _select(rng, scores, count, selection, tournament_size):
    if selection == "roulette":
        weights = scores - scores.min() + 1e-12
        return rng.choice(len(scores), size=count, p=weights / weights.sum())
    contestants = rng.integers(0, len(scores), (count, tournament_size))
    return contestants[np.arange(count), np.argmax(scores[contestants], axis=1)]


def exhaustive_match(reference, adjustment, alpha=0.5, one_to_one=None, batch=200_000):
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

    Returns
    -------
    MatchResult
        With an empty history; ``evaluations`` is the number of solutions tried.
    """
    m, n = len(reference), len(adjustment)
    if one_to_one is None:
        one_to_one = (m + 1) ** n > 5_000_000
    if one_to_one and n > m:
        raise ValueError(f"a one-to-one match needs no more adjustment segments ({n}) than reference ones ({m})")
    candidates = permutations(range(1, m + 1), n) if one_to_one else product(range(m + 1), repeat=n)
    best_solution, best_fitness, evaluations = None, -np.inf, 0
    while True:
        chunk = np.array([c for _, c in zip(range(batch), candidates)], dtype=np.intp)
        if chunk.size == 0:
            break
        scores = fitness_batch(chunk, reference, adjustment, alpha)
        evaluations += len(chunk)
        top = int(np.argmax(scores))
        if scores[top] > best_fitness:
            best_fitness, best_solution = float(scores[top]), chunk[top].copy()
    return MatchResult(best_solution, best_fitness, [], evaluations)


def qap_match(reference, adjustment, alpha=0.5, seed=None, restarts=20):
    """A one-to-one match by SciPy's quadratic assignment (FAQ with random restarts).

    Beyond the paper: the layout part of the problem is a quadratic assignment
    between the two distance matrices; SciPy's FAQ solver maximises their
    agreement. Each restart's permutation is scored with the paper's FA and
    the best kept. Needs as many adjustment as reference segments.
    """
    from scipy.optimize import quadratic_assignment

    m, n = len(reference), len(adjustment)
    if m != n:
        raise ValueError(f"qap_match pairs segments one to one: it needs as many reference ({m}) as "
                         f"adjustment ({n}) segments")
    rng = np.random.default_rng(seed)
    best_solution, best_fitness = None, -np.inf
    for _ in range(restarts):
        result = quadratic_assignment(adjustment.distances, reference.distances, method="faq",
                                      options={"maximize": True, "P0": "randomized", "rng": rng})
        solution = result.col_ind + 1
        score = fitness(solution, reference, adjustment, alpha)
        if score > best_fitness:
            best_fitness, best_solution = score, solution
    return MatchResult(best_solution, best_fitness, [], restarts)


def matched_centroids(solution, reference, adjustment):
    """GCP pairs from a solution: (adjustment group centroid, reference centroid) per matched label.

    Returns
    -------
    adjustment_xy, reference_xy : ndarray, shape (k, 2)
        In each mesh's units (divide by the pixel size for pixels).
    labels : ndarray
        The reference labels that were matched.
    """
    solution = _as_solutions(solution, len(adjustment), len(reference))[0]
    labels = np.unique(solution[solution > 0])
    adjustment_xy = np.array([np.average(adjustment.centroids[solution == j], axis=0,
                                         weights=adjustment.areas[solution == j]) for j in labels])
    return adjustment_xy, reference.centroids[labels - 1], labels


def success_table(sizes=(5, 8), seeds=range(30), alpha=0.5, shrink=None):
    """Success rate of each matcher over seeded synthetic meshes (beyond the paper).

    For every size n and seed, :func:`rsgeo.synthetic.synthetic_meshes` makes
    a reference mesh and a noisy, shuffled copy with a known true matching;
    the paper's binary GA, the integer-coded GA and SciPy's QAP solver each
    search it. A run succeeds when it returns the true matching.

    Parameters
    ----------
    shrink : (int, float), optional
        Passed to ``synthetic_meshes``: one segment keeps only this share of its area.

    Returns
    -------
    pandas.DataFrame
        One row per (n, matcher): exact-match rate, mean share of segments
        matched right, mean and worst seconds per run.
    """
    import time

    import pandas as pd

    from .synthetic import synthetic_meshes

    matchers = {
        "GA, binary (the paper)": lambda ref, adj, seed: genetic_match(ref, adj, alpha, seed=seed),
        "GA, integer": lambda ref, adj, seed: genetic_match(ref, adj, alpha, seed=seed, encoding="integer"),
        "QAP (SciPy FAQ, 20 restarts)": lambda ref, adj, seed: qap_match(ref, adj, alpha, seed=seed),
    }
    rows = []
    for n in sizes:
        for name, matcher in matchers.items():
            exact, share, seconds = [], [], []
            for seed in seeds:
                reference, adjustment, truth = synthetic_meshes(n, seed=seed, shrink=shrink)
                start = time.perf_counter()
                result = matcher(reference, adjustment, seed)
                seconds.append(time.perf_counter() - start)
                exact.append(np.array_equal(result.solution, truth))
                share.append(np.mean(result.solution == truth))
            rows.append({"n": n, "matcher": name, "exact matches (%)": 100 * np.mean(exact),
                         "segments right (%)": 100 * np.mean(share), "mean s/run": np.mean(seconds),
                         "worst s/run": np.max(seconds)})
    return pd.DataFrame(rows).set_index(["n", "matcher"])


@dataclass
class Registration:
    """The outcome of :func:`register_by_regions`.

    Attributes
    ----------
    match : MatchResult
        The GA's matching of adjustment segments to reference labels.
    map_xy, image_xy : ndarray, shape (k, 2)
        The GCPs: matched reference centroids (map units) and adjustment
        centroids (adjustment pixels), one per matched reference label.
    model : rsgeo.gcp.PolynomialModel
        Affine model map -> adjustment image, fitted on the kept GCPs.
    kept : ndarray of bool
        GCPs that survived refinement.
    rms_all, rms_kept : float
        Lecture's RMS (pixels) of the affine fit on all GCPs, and of the refined model on the kept ones.
    """

    match: MatchResult
    map_xy: np.ndarray
    image_xy: np.ndarray
    model: object
    kept: np.ndarray
    rms_all: float
    rms_kept: float


def register_by_regions(reference, adjustment, reference_transform, reference_pixel, adjustment_pixel,
                        alpha=0.5, seed=None, tolerance=1.0, min_gcps=4):
    """The paper's registration: match forest segments by the GA, then an affine model from centroids.

    Paper 001, section 4: the matched centroids are GCPs for an affine
    transformation; GCPs with large errors are removed (here exactly as
    ``gdalwarp -refine_gcps tolerance min_gcps``) until the RMS is under a pixel.

    Parameters
    ----------
    reference, adjustment : rsgeo.regions.Segments
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

    Returns
    -------
    Registration
    """
    from . import gcp

    reference_mesh = Mesh(reference.centroids, reference.areas, pixel_size=reference_pixel)
    adjustment_mesh = Mesh(adjustment.centroids, adjustment.areas, pixel_size=adjustment_pixel)
    match = genetic_match(reference_mesh, adjustment_mesh, alpha, seed=seed)
    adjustment_xy, _, labels = matched_centroids(match.solution, reference_mesh, adjustment_mesh)
    image_xy = adjustment_xy / adjustment_pixel
    map_xy = reference.map_centroids(reference_transform)[labels - 1]
    if len(labels) < 3:
        raise ValueError(f"only {len(labels)} segments were matched; an affine model needs at least 3")
    rms_all = gcp.rms_error(gcp.fit_polynomial(map_xy, image_xy, 1)(map_xy), image_xy)
    model, kept = gcp.refine_gcps(map_xy, image_xy, 1, tolerance, min(min_gcps, len(labels)))
    rms_kept = gcp.rms_error(model(map_xy[kept]), image_xy[kept])
    return Registration(match, map_xy, image_xy, model, kept, rms_all, rms_kept)
