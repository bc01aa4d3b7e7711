"""Accuracy standards: the Brazilian PEC-PCD's classes at a map scale; ASPRS's horizontal and
vertical accuracy, by Edition 2 (2023, the current one) and by Edition 1 (2014) and the NSSDA as
history; CE90 and LE90.
"""

from dataclasses import dataclass

import numpy as np

from ..errors import GCPError, RsgeoError
from ..language import N_, _, prose_number
from ..validation import as_finite, as_number, as_points, check_choice

__all__ = [
    "MAP_SCALES", "PEC_CLASSES", "LE90_FACTOR", "VERTICAL_95_FACTOR", "CE90_FACTOR",
    "CE90_RADIAL_FACTOR", "NSSDA_95_FACTOR", "NSSDA_95_RADIAL_FACTOR", "pec_thresholds",
    "PECResult", "classify", "largest_scale", "HorizontalAccuracy", "asprs_horizontal",
    "VerticalAccuracy", "asprs_vertical", "ASPRS_MIN_CHECKPOINTS", "ASPRS_CHECKPOINT_RATIO",
    "HorizontalAccuracy2023", "asprs_horizontal_2023", "VerticalAccuracy2023",
    "asprs_vertical_2023",
]

# --- Accuracy standards --------------------------------------------------------------------------

#: The map scales (denominators) of Brazil's mapping series, the columns of the PEC-PCD's
#: tables: 1:1,000 to 1:250,000.
MAP_SCALES = (1_000, 2_000, 5_000, 10_000, 25_000, 50_000, 100_000, 250_000)

#: Planimetric classes, (PEC, EP) in millimetres at the map's scale. "PEC-PCD": the Brazilian
#: Army's Directorate of Geographic Service (DSG) for digital products (ET-ADGV 2.0, 2011;
#: ET-CQDG, 2016); "Decreto 89.817": the 1984 decree's classes for printed maps (art. 9). The
#: PEC-PCD's classes B, C and D are the decree's A, B and C; its class A is new and stricter.
PEC_CLASSES = {
    "PEC-PCD": {"A": (0.28, 0.17), "B": (0.5, 0.3), "C": (0.8, 0.5), "D": (1.0, 0.6)},
    "Decreto 89.817": {"A": (0.5, 0.3), "B": (0.8, 0.5), "C": (1.0, 0.6)},
}

#: LE90 = 1.6449 RMSE_z: 90 % of one-dimensional normal errors lie within 1.6449 σ (the normal
#: distribution's 95th percentile). Decreto 89.817, art. 8 §2, defines its PEC with it too.
LE90_FACTOR = 1.6449
#: Vertical accuracy at 95 % confidence = 1.9600 RMSE_z (NSSDA, ASPRS 2014).
VERTICAL_95_FACTOR = 1.9600
#: CE90 = 2.1460 RMSE_x for circular normal errors (RMSE_x = RMSE_y = σ): the Rayleigh
#: distribution's 90th percentile, σ sqrt(-2 ln 0.1).
CE90_FACTOR = 2.1460
#: The same CE90 in terms of RMSE_r = sqrt(2) σ, as ASPRS prints it: 2.1460 / sqrt(2) (the
#: unrounded ratio is 1.51743).
CE90_RADIAL_FACTOR = 1.5175
#: NSSDA's and ASPRS 2014's horizontal accuracy at 95 % = 2.4477 RMSE_x (RMSE_x = RMSE_y):
#: σ sqrt(-2 ln 0.05).
NSSDA_95_FACTOR = 2.4477
#: The same in terms of RMSE_r: 2.4477 / sqrt(2).
NSSDA_95_RADIAL_FACTOR = 1.7308
#: ASPRS Edition 2 (2023): the fewest checkpoints a product's accuracy may be tested on (Edition 1
#: and the NSSDA asked for 20).
ASPRS_MIN_CHECKPOINTS = 30
#: ASPRS Edition 2 (2023): checkpoints at least this many times more accurate than the accuracy
#: class they test (Edition 1 asked three times for checkpoints).
ASPRS_CHECKPOINT_RATIO = 2


def _as_scale(scale):
    """The scale's denominator as a number (25000 for 1:25,000)."""
    return as_number(scale, "scale", low=1,
                     why=N_("the scale's denominator: 25000 for 1:25,000"))


def _as_standard(standard):
    return check_choice(standard, "standard", tuple(PEC_CLASSES))


def _check_point_distances(errors):
    """Check-point errors as distances: (n,) lengths, or the lengths of (n, 2) (dx, dy)."""
    try:
        kind = np.asarray(errors).dtype.kind
    except (TypeError, ValueError):
        kind = "O"
    if kind in "cbUS":
        raise TypeError(_("errors must hold real numbers (metres on the ground), got {kind} "
                          "values").format(kind={"c": "complex", "b": "bool"}.get(kind, "text")))
    if np.ndim(errors) == 2:
        vectors = as_points(errors, "errors")
        distances = np.hypot(vectors[:, 0], vectors[:, 1])
    else:
        try:
            distances = np.asarray(errors, dtype=np.float64)
        except (TypeError, ValueError) as error:
            raise GCPError(_("errors must be numbers: (n, 2) discrepancies (dx, dy) or (n,) "
                             "distances ({error})").format(error=error)) from None
        if distances.ndim != 1:
            raise GCPError(_("errors must be (n, 2) discrepancies (dx, dy) or (n,) distances, "
                             "got shape {shape}").format(shape=distances.shape))
        if not np.isfinite(distances).all() or (distances < 0).any():
            raise GCPError(_("errors given as distances must be finite and not negative"))
    if len(distances) == 0:
        raise GCPError(_("errors holds no check point; the standards need at least one "
                         "(ASPRS Edition 2 asks for {asprs}, the NSSDA for 20)").format(
                             asprs=ASPRS_MIN_CHECKPOINTS))
    return distances


def _check_point_vectors(errors):
    """Check-point discrepancies as an (n, 2) float array of (dx, dy), n >= 1."""
    if np.ndim(errors) == 1 and np.size(errors) != 2:
        raise GCPError(_("errors must be (n, 2) discrepancies (dx, dy): RMSE_x and RMSE_y need "
                         "both components, got {size} distances").format(size=np.size(errors)))
    if np.ndim(errors) == 1:
        # [3, 4] is one check point's (dx, dy) or two checks' distances: refused, not guessed
        raise GCPError(_("errors must be an (n, 2) array of (dx, dy), one row per check point; "
                         "a flat pair {errors!r} could be one point or two distances: give "
                         "[[dx, dy]] for one check point").format(errors=np.asarray(errors)
                                                                    .tolist()))
    vectors = as_points(errors, "errors")
    if len(vectors) == 0:
        raise GCPError(_("errors holds no check point; the standards need at least one "
                         "(ASPRS Edition 2 asks for {asprs}, the NSSDA for 20)").format(
                             asprs=ASPRS_MIN_CHECKPOINTS))
    return vectors


def _ninety_percent_error(distances):
    """The smallest error that at least 90 % of the check points do not exceed: the k-th
    smallest, k = ceil(0.9 n), so that it is <= PEC exactly when 90 % of the errors are."""
    k = (9 * len(distances) + 9) // 10             # ceil(0.9 n) in integers
    return float(np.sort(distances)[k - 1])


def pec_thresholds(scale, standard="PEC-PCD"):
    """Each class's PEC and EP in metres on the ground at a map scale.

    Parameters
    ----------
    scale : float
        The scale's denominator: 25000 for 1:25,000.
    standard : {"PEC-PCD", "Decreto 89.817"}
        The DSG's classes A-D for digital products, or the 1984 decree's
        classes A-C for printed maps (``PEC_CLASSES``).

    Returns
    -------
    dict of str to (float, float)
        Class -> (PEC, EP) in metres: millimetres at the map's scale times
        ``scale / 1000``.

    Raises
    ------
    rsgeo.errors.RsgeoError
        For a scale below 1 or an unknown standard.
    TypeError
        If ``scale`` is not a number.

    References
    ----------
    Brasil, Decreto nº 89.817, de 20 de junho de 1984, arts. 8 and 9 (90 % of
    well-defined points within the PEC; the standard error, equivalent to the RMS
    error, at most the class's EP).
    Diretoria de Serviço Geográfico (DSG), *Especificação Técnica para a Aquisição de
    Dados Geoespaciais Vetoriais (ET-ADGV)*, version 2.0, 2011, and *Especificação
    Técnica para o Controle de Qualidade de Dados Geoespaciais (ET-CQDG)*, 2016: the
    PEC-PCD's classes A-D for digital products.

    Examples
    --------
    >>> pec_thresholds(25_000)["D"]
    (25.0, 15.0)
    >>> pec_thresholds(25_000, "Decreto 89.817")["C"]
    (25.0, 15.0)
    """
    scale = _as_scale(scale)
    classes = PEC_CLASSES[_as_standard(standard)]
    # rounding drops the binary noise of 0.28 × 25000 (7000.000000000001)
    return {name: (round(pec * scale / 1000, 9), round(ep * scale / 1000, 9))
            for name, (pec, ep) in classes.items()}


@dataclass
class PECResult:
    """The class of a set of check-point errors at a map scale (:func:`classify`).

    Attributes
    ----------
    standard : str
        "PEC-PCD" or "Decreto 89.817".
    scale : float
        The scale's denominator.
    n_points : int
        Number of check points.
    rms : float
        RMS of the errors' lengths, sqrt(Σ d_i² / n), metres: the standard
        error (EP) the decree takes as equivalent to the RMS error, and ASPRS's
        RMSE_r (Edition 1) or RMSE_H1 (Edition 2).
    percentile_90 : float
        The smallest error that at least 90 % of the check points do not
        exceed, metres: a class's 90 % test passes when it is <= the PEC.
    thresholds : dict of str to (float, float)
        Class -> (PEC, EP) in metres at this scale.
    within : dict of str to float
        Class -> share of the check points whose error is <= its PEC.
    pec_test, ep_test : dict of str to bool
        Class -> whether at least 90 % are within its PEC; whether ``rms`` <= its
        EP.
    best : str or None
        The strictest class whose two tests pass, None if none does.
    """

    standard: str
    scale: float
    n_points: int
    rms: float
    percentile_90: float
    thresholds: dict
    within: dict
    pec_test: dict
    ep_test: dict
    best: str | None

    @property
    def meets(self):
        """Whether each class passes both tests.

        Returns
        -------
        dict of str to bool
            Class -> ``pec_test[class] and ep_test[class]``.
        """
        return {name: self.pec_test[name] and self.ep_test[name] for name in self.thresholds}

    def table(self):
        """One row per class: PEC and EP (mm and m), the share within the PEC, both tests.

        Returns
        -------
        pandas.DataFrame
            Index the classes; columns ``PEC (mm)``, ``EP (mm)``, ``PEC (m)``,
            ``EP (m)``, ``within PEC``, ``90 % within PEC``, ``RMS <= EP``, ``meets``.
        """
        import pandas as pd

        millimetres = PEC_CLASSES[self.standard]
        rows = {name: {"PEC (mm)": millimetres[name][0], "EP (mm)": millimetres[name][1],
                       "PEC (m)": pec, "EP (m)": ep, "within PEC": self.within[name],
                       "90 % within PEC": self.pec_test[name], "RMS <= EP": self.ep_test[name],
                       "meets": self.meets[name]}
                for name, (pec, ep) in self.thresholds.items()}
        return pd.DataFrame.from_dict(rows, orient="index")


def classify(errors, scale, standard="PEC-PCD"):
    """The planimetric class a set of check-point errors meets at a map scale (PEC-PCD).

    A class is met when both of Decreto 89.817's tests pass (art. 8): at least
    90 % of the check points are within the class's PEC, and the standard
    error - the RMS of the errors, which the decree takes as equivalent - is
    at most its EP. The errors must come from check points (well-defined
    points measured independently, of higher accuracy, not used in the fit):
    the residuals of the GCPs a model was fitted to flatter it. ASPRS's
    Edition 2 asks for at least 30 check points (Edition 1 and the NSSDA for
    20); with fewer the 90 % test lets fewer errors through (with 13, one may
    exceed the PEC).

    Parameters
    ----------
    errors : (n, 2) or (n,) array_like
        The check points' discrepancies on the ground in metres: (dx, dy),
        product minus reference, or their lengths.
    scale : float
        The scale's denominator: 25000 for 1:25,000.
    standard : {"PEC-PCD", "Decreto 89.817"}
        The DSG's classes A-D for digital products (default), or the 1984
        decree's A-C for printed maps.

    Returns
    -------
    PECResult
        ``best`` (the strictest class met, or None), each class's thresholds
        in metres and both tests, the 90 % error and the RMS.

    Raises
    ------
    GCPError
        If ``errors`` is empty, not (n, 2) or (n,), or holds NaN, infinite or
        (as distances) negative values.
    TypeError
        If ``errors`` holds text, booleans or complex numbers, or ``scale`` is
        not a number.
    rsgeo.errors.RsgeoError
        For a scale below 1 or an unknown standard.

    References
    ----------
    Brasil, Decreto nº 89.817, de 20 de junho de 1984, arts. 8 and 9 (90 % of
    well-defined points within the PEC; the standard error, equivalent to the RMS
    error, at most the class's EP).
    Diretoria de Serviço Geográfico (DSG), *Especificação Técnica para a Aquisição de
    Dados Geoespaciais Vetoriais (ET-ADGV)*, version 2.0, 2011, and *Especificação
    Técnica para o Controle de Qualidade de Dados Geoespaciais (ET-CQDG)*, 2016: the
    PEC-PCD's classes A-D for digital products.

    Examples
    --------
    >>> distances = [4, 5, 6, 6, 7, 8, 9, 10, 11, 30]     # metres; one of ten beyond 25 m
    >>> result = classify(distances, 50_000)
    >>> result.best, round(result.rms, 2), result.percentile_90
    ('B', 11.95, 11.0)
    >>> result.pec_test["A"], result.ep_test["A"]         # A: 90 % within 14 m, RMS > 8.5 m
    (True, False)
    >>> classify(distances, 10_000).best is None          # two of ten beyond class D's 10 m
    True
    """
    distances = _check_point_distances(errors)
    thresholds = pec_thresholds(scale, standard)
    rms = float(np.sqrt(np.mean(distances**2)))
    percentile_90 = _ninety_percent_error(distances)
    n = len(distances)
    within = {name: float(np.mean(distances <= pec)) for name, (pec, _ep) in thresholds.items()}
    # at least 90 %, counted in integers: 10 × (count within) >= 9 n
    pec_test = {name: bool(10 * np.count_nonzero(distances <= pec) >= 9 * n)
                for name, (pec, _ep) in thresholds.items()}
    ep_test = {name: rms <= ep for name, (_pec, ep) in thresholds.items()}
    best = next((name for name in thresholds if pec_test[name] and ep_test[name]), None)
    return PECResult(_as_standard(standard), _as_scale(scale), n, rms, percentile_90,
                     thresholds, within, pec_test, ep_test, best)


def largest_scale(errors, standard="PEC-PCD", scales=MAP_SCALES):
    """For each class, the largest map scale of a series at which the errors meet it.

    Both thresholds grow with the scale's denominator, so each class is met
    from some denominator on: this is the smallest such denominator among
    ``scales``.

    Parameters
    ----------
    errors : (n, 2) or (n,) array_like
        Check-point discrepancies (dx, dy) in metres, or their lengths.
    standard : {"PEC-PCD", "Decreto 89.817"}
    scales : sequence of float
        Candidate denominators; default ``MAP_SCALES``, 1:1,000 to 1:250,000.

    Returns
    -------
    dict of str to float or None
        Class -> the smallest denominator of ``scales`` at which the class is
        met, None if it is met at none of them.

    Raises
    ------
    GCPError, TypeError, rsgeo.errors.RsgeoError
        As :func:`classify`, or for an empty ``scales``.

    References
    ----------
    Brasil, Decreto nº 89.817, de 20 de junho de 1984, arts. 8 and 9 (90 % of
    well-defined points within the PEC; the standard error, equivalent to the RMS
    error, at most the class's EP).
    Diretoria de Serviço Geográfico (DSG), *Especificação Técnica para a Aquisição de
    Dados Geoespaciais Vetoriais (ET-ADGV)*, version 2.0, 2011, and *Especificação
    Técnica para o Controle de Qualidade de Dados Geoespaciais (ET-CQDG)*, 2016: the
    PEC-PCD's classes A-D for digital products.

    Examples
    --------
    >>> largest_scale([4, 5, 6, 6, 7, 8, 9, 10, 11, 30])
    {'A': 100000, 'B': 50000, 'C': 25000, 'D': 25000}
    """
    distances = _check_point_distances(errors)
    denominators = sorted(_as_scale(scale) for scale in scales)
    if not denominators:
        raise GCPError(_("scales is empty; give at least one scale's denominator"))
    found = {name: None for name in PEC_CLASSES[_as_standard(standard)]}
    for denominator in denominators:
        meets = classify(distances, denominator, standard).meets
        for name in found:
            if found[name] is None and meets[name]:
                found[name] = int(denominator) if float(denominator).is_integer() else denominator
    return found


@dataclass
class HorizontalAccuracy:
    """Horizontal accuracy of check points as ASPRS Edition 1 (2014) and the NSSDA report it.

    Edition 2 (2023) replaced these figures: see :class:`HorizontalAccuracy2023`.

    Attributes
    ----------
    n_points : int
        Number of check points.
    rmse_x, rmse_y : float
        RMS of the discrepancies along x (east) and y (north).
    rmse_r : float
        sqrt(RMSE_x² + RMSE_y²), the radial RMS error.
    accuracy_95 : float
        The radius containing 95 % of the errors if they are normal: 2.4477 ×
        (RMSE_x + RMSE_y) / 2, which is 1.7308 RMSE_r when RMSE_x = RMSE_y; NaN
        when RMSE_min / RMSE_max < 0.6, where the standards give no formula.
    ce90 : float
        1.5175 RMSE_r (= 2.1460 RMSE_x when RMSE_x = RMSE_y), the 90 % radius
        of circular normal errors; NaN like ``accuracy_95``.
    axis_ratio : float
        RMSE_min / RMSE_max (1 for circular errors).
    """

    n_points: int
    rmse_x: float
    rmse_y: float
    rmse_r: float
    accuracy_95: float
    ce90: float
    axis_ratio: float


def asprs_horizontal(errors):
    """RMSE_x, RMSE_y, RMSE_r, the 95 % horizontal accuracy and CE90 of check-point errors.

    The figures of ASPRS's Edition 1 (2014) and the NSSDA (1998), kept as
    history and for CE90: ASPRS's Edition 2 (2023) reports accuracy as an RMS
    error alone, with the checkpoints' own accuracy added, on at least 30
    checkpoints (:func:`asprs_horizontal_2023`). The formulas assume normally
    distributed errors with no systematic part; ``accuracy_95`` and ``ce90``
    are RMS errors times a constant, not counts of the errors (compare
    :attr:`PECResult.percentile_90`, which counts).

    Parameters
    ----------
    errors : (n, 2) array_like
        Check-point discrepancies (dx, dy), product minus reference, in map
        units.

    Returns
    -------
    HorizontalAccuracy

    Raises
    ------
    GCPError
        If ``errors`` is empty or not (n, 2) finite numbers (distances alone cannot give
        RMSE_x and RMSE_y); a flat pair such as ``[3, 4]`` is refused too, being
        either one check point or two distances (give ``[[3, 4]]`` for one point).

    References
    ----------
    ASPRS, *ASPRS Positional Accuracy Standards for Digital Geospatial Data*,
    Edition 1, Version 1.0, November 2014, Photogrammetric Engineering & Remote
    Sensing 81(3): A1-A26, doi:10.14358/PERS.81.3.A1-A26 (section 7, Annex D).
    FGDC, *Geospatial Positioning Accuracy Standards, Part 3: National Standard
    for Spatial Data Accuracy*, FGDC-STD-007.3-1998 (section 3.2.1, appendix 3-D:
    CMAS = 2.1460 RMSE_x).

    Examples
    --------
    >>> result = asprs_horizontal([[3, 4], [-3, -4], [4, -3], [-4, 3]])
    >>> round(result.rmse_r, 4), round(result.accuracy_95, 2), round(result.ce90, 2)
    (5.0, 8.65, 7.59)
    """
    vectors = _check_point_vectors(errors)
    rmse_x, rmse_y = np.sqrt(np.mean(vectors**2, axis=0))
    rmse_r = float(np.hypot(rmse_x, rmse_y))
    larger, smaller = max(rmse_x, rmse_y), min(rmse_x, rmse_y)
    ratio = float(smaller / larger) if larger > 0 else 1.0
    if ratio >= 0.6:
        accuracy_95 = NSSDA_95_FACTOR * 0.5 * float(rmse_x + rmse_y)
        ce90 = CE90_RADIAL_FACTOR * rmse_r
    else:
        accuracy_95 = ce90 = float("nan")
    return HorizontalAccuracy(len(vectors), float(rmse_x), float(rmse_y), rmse_r, accuracy_95,
                              ce90, ratio)


@dataclass
class VerticalAccuracy:
    """Vertical accuracy of check points by ASPRS Edition 1 (2014) (:func:`asprs_vertical`).

    Attributes
    ----------
    n_points : int
    rmse_z : float
        RMS of the height discrepancies.
    le90 : float
        1.6449 RMSE_z: 90 % of normal errors are within it.
    accuracy_95 : float
        1.9600 RMSE_z, ASPRS's and the NSSDA's vertical accuracy at 95 %.
    """

    n_points: int
    rmse_z: float
    le90: float
    accuracy_95: float


def asprs_vertical(dz):
    """RMSE_z, LE90 and the 95 % vertical accuracy of check-point height errors.

    The figures of ASPRS's Edition 1 (2014) and the NSSDA, kept as history and
    for LE90; Edition 2 (2023) reports RMSE_V alone (:func:`asprs_vertical_2023`).

    Parameters
    ----------
    dz : (n,) array_like
        Height discrepancies, product minus reference.

    Returns
    -------
    VerticalAccuracy

    Raises
    ------
    GCPError
        If ``dz`` is empty, not one-dimensional, or holds NaN or infinity.

    References
    ----------
    ASPRS 2014 (see :func:`asprs_horizontal`), section 7 and Annex D; FGDC-STD-007.3-1998,
    appendix 3-D (VMAS = 1.6449 RMSE_z).

    Examples
    --------
    >>> result = asprs_vertical([1.0, -1.0, 1.0, -1.0])
    >>> result.rmse_z, result.le90, result.accuracy_95
    (1.0, 1.6449, 1.96)
    """
    # text, booleans and complex numbers are refused (TypeError), not read as numbers
    heights = as_finite(dz, "dz", error=GCPError)
    if heights.ndim != 1 or len(heights) == 0:
        raise GCPError(_("dz must be a non-empty (n,) array of finite height errors, got shape "
                         "{shape}").format(shape=heights.shape))
    rmse_z = float(np.sqrt(np.mean(heights**2)))
    return VerticalAccuracy(len(heights), rmse_z, LE90_FACTOR * rmse_z,
                            VERTICAL_95_FACTOR * rmse_z)



# --- ASPRS Edition 2 (2023) ----------------------------------------------------------------------

def _as_survey_rmse(value, name):
    return as_number(value, name, low=0, why=N_(
        "the checkpoints' own survey accuracy as an RMSE, in the errors' units; 0 takes them "
        "as exact"))


def _edition2_class(n_points, checkpoint_rmse, accuracy_class, symbol):
    """The class as a number, once an Edition 2 statement about it may be made at all."""
    accuracy_class = as_number(accuracy_class, "accuracy_class")
    if accuracy_class <= 0:
        raise RsgeoError(_("accuracy_class must be a positive RMSE in the errors' units (25 for "
                           "a 25 m class when the errors are in metres), got {value!r}").format(
                               value=accuracy_class))
    if n_points < ASPRS_MIN_CHECKPOINTS:
        raise GCPError(_("an ASPRS Edition 2 accuracy class needs at least {minimum} "
                         "checkpoints, got {n}: test on {more} more, or report {symbol} as an "
                         "estimate without claiming a class").format(
                             minimum=ASPRS_MIN_CHECKPOINTS, n=n_points,
                             more=ASPRS_MIN_CHECKPOINTS - n_points, symbol=symbol))
    limit = accuracy_class / ASPRS_CHECKPOINT_RATIO
    if checkpoint_rmse > limit:
        raise GCPError(_("checkpoints surveyed to {symbol} {survey:g} cannot test a class of "
                         "{accuracy_class:g}: ASPRS Edition 2 asks for checkpoints at least "
                         "{ratio} times more accurate than the class they test ({symbol} at "
                         "most {limit:g})").format(
                             symbol=symbol, survey=prose_number(checkpoint_rmse),
                             accuracy_class=prose_number(accuracy_class),
                             ratio=ASPRS_CHECKPOINT_RATIO, limit=prose_number(limit)))
    return accuracy_class


@dataclass
class HorizontalAccuracy2023:
    """Horizontal accuracy by ASPRS Edition 2 (:func:`asprs_horizontal_2023`).

    Attributes
    ----------
    n_points : int
        Number of checkpoints.
    rmse_x, rmse_y : float
        RMS of the discrepancies along x (east) and y (north).
    rmse_h1 : float
        sqrt(RMSE_x² + RMSE_y²): the product tested against the checkpoints
        (Edition 1's RMSE_r).
    checkpoint_rmse_h : float
        RMSE_H2, the checkpoints' own horizontal accuracy as surveyed (0: taken
        as exact).
    rmse_h : float
        The product's horizontal accuracy, sqrt(RMSE_H1² + RMSE_H2²).
    enough_checkpoints : bool
        Whether there are at least ``ASPRS_MIN_CHECKPOINTS`` (30), so that
        ``rmse_h`` may be stated as Edition 2 accuracy; with fewer it is an
        estimate, and :meth:`meets` refuses.
    """

    n_points: int
    rmse_x: float
    rmse_y: float
    rmse_h1: float
    checkpoint_rmse_h: float
    rmse_h: float
    enough_checkpoints: bool

    def meets(self, accuracy_class):
        """Whether the product meets a horizontal accuracy class: RMSE_H <= the class.

        Edition 2 names a class by its RMSE_H, "horizontal accuracy class
        X cm" for RMSE_H <= X, with no map scale attached.

        Parameters
        ----------
        accuracy_class : float
            The class's RMSE_H, in the errors' units (25 for a 25 m class
            when the errors are in metres).

        Returns
        -------
        bool
            ``rmse_h <= accuracy_class``.

        Raises
        ------
        GCPError
            With fewer than 30 checkpoints (it says how many there are), or
            checkpoints surveyed less than two times more accurately than the
            class (``checkpoint_rmse_h > accuracy_class / 2``).
        rsgeo.errors.RsgeoError
            If ``accuracy_class`` is not a positive number.
        TypeError
            If ``accuracy_class`` is not a number.
        """
        accuracy_class = _edition2_class(self.n_points, self.checkpoint_rmse_h,
                                         accuracy_class, "RMSE_H")
        return bool(self.rmse_h <= accuracy_class)


def asprs_horizontal_2023(errors, *, checkpoint_rmse_h=0.0):
    """Horizontal accuracy of check-point errors by ASPRS Edition 2 (2023): RMSE_H.

    Edition 2 states accuracy as an RMS error alone (Edition 1's and the
    NSSDA's 95 % figures are gone), and it counts the checkpoints' own error:
    the product's RMSE_H1, measured against the checkpoints, is combined with
    RMSE_H2, the accuracy of the checkpoints' survey, as
    RMSE_H = sqrt(RMSE_H1² + RMSE_H2²). So a product is never stated more
    accurate than the checkpoints that tested it.

    Computed for any number of checkpoints, so that a small test (a course's
    leave-one-out GCPs) still shows its figure; ``enough_checkpoints`` says
    whether Edition 2's minimum of 30 is met, and
    :meth:`HorizontalAccuracy2023.meets` refuses a class below it.

    Parameters
    ----------
    errors : (n, 2) array_like
        Check-point discrepancies (dx, dy), product minus reference, in map
        units.
    checkpoint_rmse_h : float, keyword-only
        RMSE_H2, the checkpoints' horizontal accuracy from their survey
        (radial, like RMSE_H: sqrt(2) σ for a survey of σ per axis), in the
        units of ``errors``. Default 0: the checkpoints are assumed exact.

    Returns
    -------
    HorizontalAccuracy2023

    Raises
    ------
    GCPError
        If ``errors`` is empty or not (n, 2) finite numbers (a flat pair such
        as ``[3, 4]`` is refused too, as by :func:`asprs_horizontal`).
    rsgeo.errors.RsgeoError
        If ``checkpoint_rmse_h`` is negative or not finite.
    TypeError
        If ``errors`` holds text, booleans or complex numbers, or
        ``checkpoint_rmse_h`` is not a number.

    References
    ----------
    ASPRS, *ASPRS Positional Accuracy Standards for Digital Geospatial Data*,
    Edition 2, Version 1.0, August 2023 (Version 2.0, June 2024, adds
    best-practice addenda), American Society for Photogrammetry and Remote
    Sensing. Q. Abdullah, "The ASPRS Positional Accuracy Standards, Edition 2:
    the geospatial mapping industry guide to best practices", Photogrammetric
    Engineering & Remote Sensing 89(10): 581-588, 2023,
    doi:10.14358/PERS.89.10.581.

    Examples
    --------
    Thirty checkpoints off by (±3, ±4) m, surveyed to RMSE_H2 = 12 m:

    >>> errors = [[3, 4], [-3, -4], [3, -4]] * 10
    >>> result = asprs_horizontal_2023(errors, checkpoint_rmse_h=12)
    >>> result.rmse_h1, result.rmse_h, result.enough_checkpoints
    (5.0, 13.0, True)
    >>> result.meets(25)          # 12 m checkpoints can test classes from 24 m
    True
    >>> result.meets(20)          # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rsgeo.errors.GCPError: checkpoints surveyed to RMSE_H 12 cannot test a class of 20: ...
    """
    vectors = _check_point_vectors(errors)
    survey = _as_survey_rmse(checkpoint_rmse_h, "checkpoint_rmse_h")
    rmse_x, rmse_y = (float(value) for value in np.sqrt(np.mean(vectors**2, axis=0)))
    rmse_h1 = float(np.hypot(rmse_x, rmse_y))
    return HorizontalAccuracy2023(len(vectors), rmse_x, rmse_y, rmse_h1, survey,
                                  float(np.hypot(rmse_h1, survey)),
                                  len(vectors) >= ASPRS_MIN_CHECKPOINTS)


@dataclass
class VerticalAccuracy2023:
    """Vertical accuracy by ASPRS Edition 2 (:func:`asprs_vertical_2023`).

    Attributes
    ----------
    n_points : int
        Number of checkpoints.
    rmse_v1 : float
        RMS of the height discrepancies: the product tested against the
        checkpoints (Edition 1's RMSE_z).
    checkpoint_rmse_v : float
        RMSE_V2, the checkpoints' own vertical accuracy as surveyed (0: taken as
        exact).
    rmse_v : float
        The product's vertical accuracy, sqrt(RMSE_V1² + RMSE_V2²).
    enough_checkpoints : bool
        Whether there are at least ``ASPRS_MIN_CHECKPOINTS`` (30).
    """

    n_points: int
    rmse_v1: float
    checkpoint_rmse_v: float
    rmse_v: float
    enough_checkpoints: bool

    def meets(self, accuracy_class):
        """Whether the product meets a vertical accuracy class: RMSE_V <= the class.

        Parameters
        ----------
        accuracy_class : float
            The class's RMSE_V, in the units of the height errors.

        Returns
        -------
        bool
            ``rmse_v <= accuracy_class``.

        Raises
        ------
        GCPError
            With fewer than 30 checkpoints, or checkpoints surveyed less than
            two times more accurately than the class.
        rsgeo.errors.RsgeoError
            If ``accuracy_class`` is not a positive number.
        TypeError
            If ``accuracy_class`` is not a number.
        """
        accuracy_class = _edition2_class(self.n_points, self.checkpoint_rmse_v,
                                         accuracy_class, "RMSE_V")
        return bool(self.rmse_v <= accuracy_class)


def asprs_vertical_2023(dz, *, checkpoint_rmse_v=0.0):
    """Vertical accuracy of check-point height errors by ASPRS Edition 2 (2023): RMSE_V.

    RMSE_V = sqrt(RMSE_V1² + RMSE_V2²): RMSE_V1 measured against the
    checkpoints, RMSE_V2 the accuracy of their survey. No 95 % figure, and no
    LE90 (:func:`asprs_vertical` keeps those).

    Parameters
    ----------
    dz : (n,) array_like
        Height discrepancies, product minus reference.
    checkpoint_rmse_v : float, keyword-only
        RMSE_V2, the checkpoints' vertical accuracy from their survey, in the
        units of ``dz``. Default 0: the checkpoints are assumed exact.

    Returns
    -------
    VerticalAccuracy2023

    Raises
    ------
    GCPError
        If ``dz`` is empty, not one-dimensional, or holds NaN or infinity.
    rsgeo.errors.RsgeoError
        If ``checkpoint_rmse_v`` is negative or not finite.
    TypeError
        If ``dz`` holds text, booleans or complex numbers, or
        ``checkpoint_rmse_v`` is not a number.

    References
    ----------
    ASPRS, *ASPRS Positional Accuracy Standards for Digital Geospatial Data*,
    Edition 2, Version 1.0, August 2023 (Version 2.0, June 2024, adds
    best-practice addenda), American Society for Photogrammetry and Remote
    Sensing. Q. Abdullah, "The ASPRS Positional Accuracy Standards, Edition 2:
    the geospatial mapping industry guide to best practices", Photogrammetric
    Engineering & Remote Sensing 89(10): 581-588, 2023,
    doi:10.14358/PERS.89.10.581.

    Examples
    --------
    A surface 1.5 cm off at 30 checkpoints surveyed to 2 cm is a 2.5 cm product:

    >>> result = asprs_vertical_2023([1.5, -1.5] * 15, checkpoint_rmse_v=2.0)
    >>> result.rmse_v1, result.rmse_v, result.meets(5.0)
    (1.5, 2.5, True)
    """
    heights = as_finite(dz, "dz", error=GCPError)
    if heights.ndim != 1 or len(heights) == 0:
        raise GCPError(_("dz must be a non-empty (n,) array of finite height errors, got shape "
                         "{shape}").format(shape=heights.shape))
    survey = _as_survey_rmse(checkpoint_rmse_v, "checkpoint_rmse_v")
    rmse_v1 = float(np.sqrt(np.mean(heights**2)))
    return VerticalAccuracy2023(len(heights), rmse_v1, survey, float(np.hypot(rmse_v1, survey)),
                                len(heights) >= ASPRS_MIN_CHECKPOINTS)
