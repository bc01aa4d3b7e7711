"""In Portuguese, every message rsgeo gives a student is Portuguese throughout.

Every exercise check is run with the course's own inputs (the exercise notebooks with their
worked solutions, executed the way the grader does, exercises/judge.py) and with: the right
answer, every wrong answer its declared mistakes produce, wrong forms (None, text, a tuple, a
list, arrays, NaN, infinity, a bool, a complex, an object, numbers far off), and the right answer
scaled up and down. Every message (verdict, how-far phrase, hint, the placeholder's message) is
collected under ``set_language("pt_BR")``; with code spans, quoted values and Python reprs taken
out, none may hold an English function word or a number written the English way (0.5 for 0,5).
The same holds for the RsgeoError messages of a list of wrong calls to rsgeo's public verbs.
"""

import ast
import functools
import inspect
import re
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from rsgeo import language as _i18n
from rsgeo_course import exercises

ROOT = Path(__file__).resolve().parent.parent

# English words that are not Portuguese words too ("a", "no", "as", "pixel", "zero", "array"
# and "use" are; "col" and "row" name GDAL's (col, row) in both languages): any of them outside
# code in a Portuguese message is English left untranslated
ENGLISH_WORDS = frozenset("""
    the is are was were be been has have had of and or not with without than then when
    where which what who this that these those there it its by from into onto for at on upon
    should must can cannot could would will shall your you yours we our they their got gives
    expected needs need holds holding hold check task value values number numbers image images
    too large small between times wrong yet one two three off about does did done
    written spaces lower case whole itself trailing comma tuple list string text finite yes
    function return still write hint correct right left up down looks like uses used only each
    every half more less close little slightly sign size model points point order degree shape
    dimension dimensions column columns matrix segment segments window windows
    blunder residual least squares mean distance distances height heights angle grid
    file files must unknown available got missing lies many few fit fits fitted positive
    integer integers whole above below beyond inside outside same different
""".split())


def english_words(text):
    """The English words of ``text`` outside code spans, quoted values and identifiers."""
    text = re.sub(r"`[^`]*`|'[^']*'|\"[^\"]*\"|<[^<>]*>", " ", text)       # code, quoted, reprs
    text = re.sub(r"[\w.]*[A-Za-z_][\w.]*\([^()]*\)", " ", text)            # calls: np.tan(x)
    text = re.sub(r"[\w.]*[._][\w.]+|\w+(?:-\w+)+", " ", text)              # names, scikit-image
    text = re.sub(r"\(\w+(?:, \w+)+\)", " ", text)                            # (col, row)
    return {word.lower() for word in re.findall(r"[^\W\d_]+", text)} & ENGLISH_WORDS


def english_numbers(text):
    """Numbers written the English way (a decimal point) outside code and Python values.

    A point followed by exactly three digits is Portuguese's thousands point (1:25.000,
    Decreto 89.817); a comma is Portuguese's decimal comma.
    """
    text = re.sub(r"`[^`]*`|'[^']*'|\"[^\"]*\"|<[^<>]*>|\[[^\[\]]*\]", " ", text)
    text = re.sub(r"[\w.]*[A-Za-z_][\w.]*\([^()]*\)|\([\d\s.,+-]+\)", " ", text)  # calls, shapes
    return re.findall(r"(?<![\w.,])[-−]?\d+\.(?!\d{3}(?!\d))\d+", text)


def test_the_detectors_find_english():
    assert english_words("Ainda não: `gain` is grande demais") == {"is"}
    assert english_words("Ainda não: mais da metade de the image's range") >= {"the"}
    assert not english_words("Ainda não: `gain` está grande demais, (col, row) e 'nearest'; "
                             "use np.tan(x) e o pixel do scikit-image até a borda.")
    assert english_numbers("erro de 0.1 a 1 %") == ["0.1"]
    assert english_numbers("some 0.5 aos dois") == ["0.5"]
    assert not english_numbers("erro de 0,1 %, 1:25.000, Decreto 89.817, `x = 1.5`, (2, 5), "
                               "np.cos(-23.5), [1.5] e 'a = 0.5'")


def test_an_untranslated_message_is_found(portuguese):
    # a message without a translation stays English, and the detector says so
    message = _i18n._("{name} must be a whole number of widgets, got {value!r}").format(
        name="size", value=2.5)
    assert english_words(message) >= {"must", "whole", "got"}


@pytest.fixture
def portuguese():
    before = _i18n._chosen
    _i18n.set_language("pt_BR")
    yield
    _i18n._chosen = before


# -- Every exercise check, with the course's inputs ---------------------------------------------

WRONG_FORMS = [None, "1.5", "nearest", "Nearest", "A", (1.5,), [1.5], [1.0, 2.0], (1.0, 2.0),
               (1.0, 2.0, 3.0, 4.0), np.array([1.0, 2.0]), np.array([[1.0]]), np.zeros((3, 3)),
               np.zeros((2, 5)), float("nan"), float("inf"), True, 1 + 2j, object(), 0, -1.0,
               2.5, 4, 13, 1e9]
SCALES = (1.0005, 1.005, 1.05, 1.3, 1.8, 3, 7, 30, 300, -1, -1.3, 0.7, 0.2)


def _course_calls():
    """(check, bound arguments) of every check call in the course's exercise notebooks."""
    sys.path.insert(0, str(ROOT / "exercises"))
    try:
        import grade
        import judge
    finally:
        sys.path.remove(str(ROOT / "exercises"))
    calls = []
    for course in grade.course_notebooks(ROOT / "exercises"):
        scopes = judge.course_scopes(course)
        for task in course.tasks:
            scope = dict(scopes[task.name])
            for statement in ast.parse(task.check_source).body:
                found = [node for node in ast.walk(statement) if isinstance(node, ast.Call)
                         and isinstance(node.func, ast.Name)
                         and node.func.id.startswith("check_")]
                if not (isinstance(statement, ast.Expr) and found
                        and statement.value is found[0]):
                    exec(compile(ast.Module([statement], []), "<course>", "exec"), scope)
                    continue
                call = found[0]
                check = getattr(exercises, call.func.id)
                args = [eval(compile(ast.Expression(arg), "<course>", "eval"), scope)
                        for arg in call.args]
                kwargs = {keyword.arg: eval(compile(ast.Expression(keyword.value), "<course>",
                                                    "eval"), scope)
                          for keyword in call.keywords}
                bound = inspect.signature(check).bind(*args, **kwargs)
                bound.apply_defaults()
                calls.append((check, dict(bound.arguments)))
    return calls


def _answers(check, arguments):
    """The answers to try: right, each declared mistake's, wrong forms, scaled right ones."""
    declared = check.declaration
    task = declared.task(**{name: arguments[name] for name in declared.inputs
                            if name in arguments})
    answers = [task.right]
    for mistake in declared.mistakes:
        answers.extend(mistake.answers(task))
    answers.extend(WRONG_FORMS)
    try:
        right = np.asarray(task.right, dtype=float)
    except (TypeError, ValueError):
        right = None
    if right is not None and np.isfinite(right).all():
        answers.extend(right * scale if right.ndim else float(right) * scale
                       for scale in SCALES)
    return answers + [...]


def _run(check, arguments, answer):
    """The text a student reads for ``answer``: the verdict, or the placeholder's message."""
    names = list(inspect.signature(check).parameters)
    call = dict(arguments)
    if ", " in check.declaration.answer and isinstance(answer, tuple) and len(answer) == 2:
        call[names[0]], call[names[1]] = answer            # check_gain_offset(gain, offset)
    else:
        call[names[0]] = answer
    try:
        return repr(check(**call))
    except exercises.ExerciseNotSolved as error:
        return str(error)


@functools.cache
def portuguese_verdicts():
    """{check name: [every text its verdicts gave in Portuguese]}."""
    before = _i18n._chosen
    _i18n.set_language("pt_BR")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            found = {}
            for check, arguments in _course_calls():
                texts = found.setdefault(check.__name__, [])
                for answer in _answers(check, arguments):
                    texts.append(_run(check, arguments, answer))
    finally:
        _i18n._chosen = before
    return found


def test_every_check_is_run_from_the_course():
    assert set(portuguese_verdicts()) == set(exercises.declarations())


@pytest.mark.parametrize("name", sorted(exercises.declarations()))
def test_a_portuguese_verdict_is_portuguese_throughout(name):
    texts = portuguese_verdicts()[name]
    assert any(text.startswith("Correto: ") for text in texts), name
    assert any(text.startswith("Ainda não: ") and "\nDica: " in text for text in texts), name
    english = {text: sorted(english_words(text)) for text in texts if english_words(text)}
    assert not english, english


@pytest.mark.parametrize("name", sorted(exercises.declarations()))
def test_a_portuguese_verdict_writes_numbers_with_a_decimal_comma(name):
    texts = portuguese_verdicts()[name]
    english = {text: english_numbers(text) for text in texts if english_numbers(text)}
    assert not english, english


# -- Errors from the public verbs ---------------------------------------------------------------

def _bad_calls():
    import affine

    from rsgeo import (
        accuracy,
        data,
        distortion,
        gcp,
        georef,
        matching,
        radiometry,
        resample,
        synthetic,
        tiepoints,
        transforms,
    )

    points = synthetic.distorted_pair(seed=2).gcps
    geotransform = affine.Affine(10, 0, 500000, 0, -10, 7000000)
    five_map, five_image = points.map_xy[:5], points.image_xy[:5]
    nat1 = data.load("nat1")
    return {
        "polynomial order too high": lambda: transforms.fit_polynomial(
            points.map_xy, points.image_xy, order=4),
        "too few GCPs for the order": lambda: transforms.fit_polynomial(
            five_map, five_image, order=3),
        "too few GCPs for a kind": lambda: transforms.fit_transform(
            five_map[:2], five_image[:2], "projective"),
        "unknown model kind": lambda: transforms.fit_transform(five_map, five_image, "spline"),
        "wrong pass direction": lambda: distortion.earth_rotation_skew(
            -30.0, pass_direction="sideways"),
        "warp mapping in the wrong direction": lambda: resample.warp(
            np.zeros((10, 10)), geotransform, (5, 5), geotransform),
        "scan beyond the horizon": lambda: distortion.swath_width(95.0, 833.0),
        "bands-last image": lambda: resample.interpolate(np.zeros((40, 50, 3)), [1.0], [1.0]),
        "unknown resampling method": lambda: resample.interpolate(
            np.zeros((5, 5)), [1.0], [1.0], "lanczos"),
        "nodata outside the dtype": lambda: resample.interpolate(
            np.zeros((5, 5), dtype=np.uint8), [1.0], [1.0], nodata=-1),
        "resolution not positive": lambda: georef.reproject(nat1, "EPSG:31983", resolution=0),
        "unknown dataset name": lambda: data.load("nat3"),
        "unknown GCP set": lambda: data.load_gcps("nat3"),
        "points of the wrong form": lambda: transforms.fit_polynomial(
            np.zeros((5, 3)), np.zeros((5, 3)), order=1),
        "points in 1-D": lambda: gcp.GCPSet([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]),
        "unknown CRS": lambda: georef.transform_points(five_map, "EPSG:999999", "EPSG:31983"),
        "predicted and observed of different sizes": lambda: accuracy.rms_error(
            np.zeros((5, 2)), np.zeros((4, 2))),
        "is_check of the wrong length": lambda: accuracy.fit_with_check_points(
            points.map_xy, points.image_xy, 1, np.zeros(3, dtype=bool)),
        "images of different shapes": lambda: radiometry.fit_gain_offset(
            np.zeros((5, 5)), np.zeros((4, 4))),
        "an even filter size": lambda: radiometry.mean_filter(np.zeros((9, 9)), 4),
        "a relational mesh of two segments": lambda: matching.Mesh([[0, 0], [1, 1]], [1, 1]),
        "tie-point images of 3-D": lambda: tiepoints.measure_shifts(
            np.zeros((3, 20, 20)), np.zeros((3, 20, 20))),
    }


def _read_points_errors(tmp_path):
    from rsgeo import gcp

    empty = tmp_path / "empty.points"
    empty.write_text("", encoding="utf-8")
    header_only = tmp_path / "header.points"
    header_only.write_text("mapX,mapY,sourceX,sourceY,enable\n", encoding="utf-8")
    wrong_header = tmp_path / "wrong.points"
    wrong_header.write_text("x,y,col,row\n1,2,3,4\n", encoding="utf-8")
    not_numbers = tmp_path / "text.points"
    not_numbers.write_text("mapX,mapY,sourceX,sourceY,enable\na,b,c,d,1\n", encoding="utf-8")
    return {f".points {path.stem}": functools.partial(gcp.read_points, path)
            for path in (empty, header_only, wrong_header, not_numbers)}


BAD_CALLS = ["polynomial order too high", "too few GCPs for the order", "too few GCPs for a kind",
             "unknown model kind", "wrong pass direction",
             "warp mapping in the wrong direction", "scan beyond the horizon",
             "bands-last image", "unknown resampling method", "nodata outside the dtype",
             "resolution not positive", "unknown dataset name", "unknown GCP set",
             "points of the wrong form", "points in 1-D", "unknown CRS",
             "predicted and observed of different sizes", "is_check of the wrong length",
             "images of different shapes", "an even filter size",
             "a relational mesh of two segments", "tie-point images of 3-D"]


@functools.cache
def parameter_names():
    """The names of the parameters of rsgeo's public functions and classes: an error message
    names the argument that was wrong as it is written in code ("image must be 2-D")."""
    import rsgeo

    names = set()
    for module_name in rsgeo._MODULES:
        module = getattr(rsgeo, module_name)
        for name in getattr(module, "__all__", ()):
            thing = getattr(module, name)
            for function in (thing, getattr(thing, "__init__", None)):
                try:
                    names.update(inspect.signature(function).parameters)
                except (TypeError, ValueError):
                    pass
    return frozenset(names)


def api_english_words(message):
    """The English words of an error message that are not names of rsgeo's parameters."""
    message = re.sub(r"\([^()]*PROJ:[^()]*\)", " ", message)      # PROJ's own reason, quoted
    return english_words(message) - parameter_names()


@pytest.mark.parametrize("name", BAD_CALLS)
def test_an_error_from_a_public_verb_is_portuguese(portuguese, name):
    with warnings.catch_warnings(), pytest.raises((ValueError, TypeError)) as raised:
        warnings.simplefilter("ignore")
        _bad_calls()[name]()
    message = str(raised.value)
    assert not api_english_words(message), (sorted(api_english_words(message)), message)
    assert not english_numbers(message), message


def test_the_bad_calls_are_the_listed_ones():
    assert sorted(_bad_calls()) == sorted(BAD_CALLS)


def test_a_points_file_error_is_portuguese(portuguese, tmp_path):
    for name, call in _read_points_errors(tmp_path).items():
        with pytest.raises(ValueError) as raised:
            call()
        message = str(raised.value).replace(str(tmp_path), "")
        assert not api_english_words(message), (name, sorted(api_english_words(message)),
                                                message)


def test_the_same_calls_speak_english_in_english():
    # the translation does not change the English: the same error names what was wrong
    before = _i18n._chosen
    _i18n.set_language("en")
    try:
        with pytest.raises(ValueError, match="polynomial order must be 1, 2 or 3"):
            _bad_calls()["polynomial order too high"]()
    finally:
        _i18n._chosen = before
