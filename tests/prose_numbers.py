"""Find the numbers a notebook's Markdown states by hand (not glued from the computation).

Every number a chapter's prose states is computed and inserted with myst-nb's glue
(``{glue:text}`name:.2f` ``). What may stay typed is what defines rather than reports: years,
chapter, section, equation, task and EPSG numbers, map scales, names that contain digits
(Landsat 7, WGS 84, RPC00B), small integers that count or order things (degree 2, 6 GCPs, a 4 × 4
window), and what sits in code or maths. Anything else is reported with its sentence, so that it is
either glued or named in ``ALLOWED`` below with the reason it is a definition.

Run ``python tests/prose_numbers.py`` for the list per notebook, and
``python tests/prose_numbers.py --check book/04_resampling.ipynb`` to execute one notebook and
check, besides, that every glue role of its Markdown names a value the notebook glues and that
the role's format applies to it (what the book's ``-W`` build would otherwise report).
"""

import re
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]

# Where prose hides no stated result: code, maths, glue roles, links' targets, citations, HTML,
# MyST directives' options and labels.
_NOT_PROSE = [
    r"```.*?```",                                   # fenced blocks (code, directives' bodies kept
    r"\$\$.*?\$\$",                                 #   out only when they are code)
    r"\$[^$\n]+\$",
    r"\{[a-z:-]+\}`[^`]*`",                         # any role: {glue:text}, {cite}, {ref}, {math}
    r"`[^`]*`",                                     # inline code
    r"\]\([^)]*\)",                                 # a link's target
    r"<[^>]+>",                                     # HTML tags and their attributes
    r"^\s*:[a-z-]+:[^\n]*$",                            # directive options (:label:, :width: ...)
    r"\([a-zA-Z_]+-[a-zA-Z0-9_-]+\)=",              # MyST targets (label)=
    r"^#+ [^\n]*$",                                 # headings: numbered by the table of contents
]
NOT_PROSE = re.compile("|".join(_NOT_PROSE), flags=re.S | re.M)

NUMBER = re.compile(r"(?<![\w.])[-−+±]?\d+(?:,\d{3})*(?:\.\d+)?(?![\w])")

# Contexts that make a number a definition or a name, not a result.
_DEFINITIONS = [
    r"(?:chapters?|sections?|equations?|eqs?\.|tasks?|exercises?|figures?|tables?|steps?|"
    r"parts?|pages?|items?|capítulos?|seções|equaç(?:ão|ões)|tarefas?)\s+NUM",
    r"EPSG:?\s*NUM", r"1\s*:\s*NUM",                 # EPSG codes, map scales 1:25,000
    r"(?:Landsat|CBERS|WGS|SAD|SIRGAS|Sentinel|SPOT|GDAL|PROJ|Python|NumPy|ISO|UTM|zone|EGM|"
    r"MAPGEO|Jupyter Book|myst-nb|Sphinx|ETM\+?|OLI|band|bands|banda|bandas|R\.PR|"
    r"scikit-image|rasterio|matplotlib|SciPy|Numba|OpenCV|pydata-sphinx-theme|"
    r"sphinx-book-theme|axe-core|version|versão|RFC|IEEE|Keys|MODIS|ASTER)[\s-]?NUM",
    r"NUM\s*(?:st|nd|rd|th)\b",
    r"(?:Time to learn|Tempo de estudo):\s*NUM",     # the author's estimate, not a result
]
DEFINITION = [re.compile(pattern.replace("NUM", r"(?P<num>[\d.,]+)"), flags=re.I)
              for pattern in _DEFINITIONS]

# Numbers a notebook states as definitions, each with why (notebook -> list of exact snippets of
# the sentence that contain the number). Keep this short: a measured number is glued, not listed.
ALLOWED: dict[str, list[str]] = {
    "04_resampling.ipynb": [
        # the parameters of benchmarks/resample.py, whose saved table the chapter reads
        "(a 3° rotation and a 1.02 zoom)",
    ],
    "05_contrast_regression.ipynb": [
        # the range of 8-bit pixels, a definition
        "kept within 0–255",
    ],
    "04b_relief_orthorectification.ipynb": [
        # a licence's name and a GDAL issue and pull request: references, not results
        "Apache-2.0",
    ],
    "01_systematic_distortions.ipynb": [
        # the lecture's own words, quoted to be checked against each sensor's field of view
        "together at ±7.5°",
        "The lecture's \"±7.5°",
        # a journal reference: volume, issue and pages
        "53(7), 3847–3854",
    ],
    "02b_crs_datums.ipynb": [
        "SAD69(96)",                         # the 1996 realization's name (EPSG:5527)
        "the epoch 2000.4",                  # SIRGAS 2000's reference epoch, a definition
    ],
    "03_evaluating_models.ipynb": [
        "the row by 0.5",                                  # half a pixel: corner vs centre
        "30 m pixels (Landsat TM), lecture | RMS < 2 pixels (60 m)",   # the lecture's rule
        "≈ 0.2–0.5 pixel",                                 # Townshend et al.'s targets
        "Decreto 89.817/1984",                             # the decree's number
        "90 %",                                            # the PEC's definition
        "95 %",                                            # ASPRS's confidence level
        "20 check points",                                 # ASPRS's and the NSSDA's minimum
        "1:25,000 map, lecture | ≈ 20 m",                  # the lecture's rule
    ],
}


def is_small_count(text):
    # 0-12 without a decimal point: orders, degrees, counts of GCPs or windows, kernel sizes
    return re.fullmatch(r"[-−+]?\d{1,2}", text) is not None and abs(int(text.lstrip("-−+"))) <= 12


def is_year(text):
    return re.fullmatch(r"(1[89]|20)\d\d", text) is not None


def markdown_of(path):
    notebook = nbformat.read(path, as_version=4)
    return [(index, cell.source) for index, cell in enumerate(notebook.cells)
            if cell.cell_type == "markdown"]


def typed_numbers(path):
    """(cell index, number, sentence) for every number the notebook's Markdown types by hand."""
    allowed = ALLOWED.get(path.name, [])
    found = []
    for index, source in markdown_of(path):
        prose = NOT_PROSE.sub(lambda match: " " * len(match.group(0)), source)
        defined = set()
        for pattern in DEFINITION:
            for match in pattern.finditer(prose):
                defined.add(match.start("num"))
        for match in NUMBER.finditer(prose):
            text = match.group(0)
            digits = text.lstrip("-−+±")
            start = match.start() + len(text) - len(digits)
            if start in defined or is_small_count(digits) or is_year(digits):
                continue
            sentence = _sentence(source, prose, match.start())
            if any(snippet in source and text in snippet for snippet in allowed):
                continue
            found.append((index, text, sentence))
    return found


def _sentence(source, prose, position):
    stop = prose.rfind(". ", 0, position)
    start = max(stop + 2 if stop >= 0 else 0, prose.rfind("\n", 0, position) + 1)
    end = min([i for i in (prose.find(". ", position), prose.find("\n", position)) if i >= 0]
              or [len(prose)])
    return " ".join(source[start:end + 1].split())[:160]


GLUE_ROLE = re.compile(r"\{glue(?::(?:text|any|md|figure|math))?\}`([^`]*)`")


def glued_values(notebook):
    """``{key: text/plain}`` of the values the executed ``notebook`` glues (myst-nb's glue)."""
    values = {}
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            scrapbook = output.get("metadata", {}).get("scrapbook")
            if scrapbook:
                prefix = scrapbook.get("mime_prefix", "")
                values[scrapbook["name"]] = output.get("data", {}).get(prefix + "text/plain")
    return values


def glue_problems(path, notebook):
    """What the book build would warn about this notebook's glue roles, given its execution."""
    from myst_nb.core.variables import format_plain_text

    values = glued_values(notebook)
    problems = []
    for index, source in markdown_of(path):
        for role in GLUE_ROLE.finditer(source):
            content = role.group(1)
            key, _, spec = content.rpartition(":") if ":" in content else (content, "", "s")
            if "::" in key:
                document, key = key.split("::", 1)
                if Path(document).name != path.name:
                    continue                          # another notebook's value: not checked here
            if key not in values:
                problems.append(f"cell {index}: {role.group(0)}: nothing glued as {key!r}")
                continue
            try:
                format_plain_text(values[key], spec or "s")
            except Exception as error:                # what myst-nb reports, whatever it is
                problems.append(f"cell {index}: {role.group(0)}: {values[key]!r}: {error}")
    return problems


def chapters():
    """The numbered chapters (reference pages such as the data gallery are not chapters)."""
    return sorted(path for path in (ROOT / "book").glob("[0-9]*.ipynb"))


def check(path):
    """Execute ``path``; print its typed numbers and glue problems; return how many."""
    sys.path.insert(0, str(ROOT / "tests"))
    from notebook_runner import execute_notebook

    path = Path(path).resolve()
    numbers, problems = typed_numbers(path), glue_problems(path, execute_notebook(path))
    for index, text, sentence in numbers:
        print(f"typed number, cell {index}: {text!r}  {sentence}")
    for problem in problems:
        print(f"glue: {problem}")
    print(f"{path.name}: {len(numbers)} typed numbers, {len(problems)} glue problems")
    return len(numbers) + len(problems)


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--check":
        sys.exit(1 if sum(check(path) for path in sys.argv[2:]) else 0)
    total = 0
    for path in chapters():
        numbers = typed_numbers(path)
        total += len(numbers)
        if numbers and (len(sys.argv) < 2 or path.name.startswith(sys.argv[1])):
            print(f"## {path.name}: {len(numbers)}")
            for index, text, sentence in numbers:
                print(f"  cell {index}: {text!r:>10}  {sentence}")
    print("total", total)
