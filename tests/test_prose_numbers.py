"""Every number a chapter's prose states is glued from its computation (tests/prose_numbers.py)."""

import nbformat
import pytest

from notebook_runner import ROOT, executed_notebook
from prose_numbers import chapters, glue_problems, typed_numbers

CHAPTERS = chapters()


@pytest.mark.parametrize("path", CHAPTERS, ids=lambda path: path.name)
def test_prose_types_no_number(path):
    numbers = typed_numbers(path)
    assert not numbers, (
        f"{path.name} types {len(numbers)} numbers by hand; glue them from the computation "
        "({glue:text}`key:.2f`) or, for a definition, name it in prose_numbers.ALLOWED:\n"
        + "\n".join(f"  cell {index}: {text!r} in: {sentence}"
                    for index, text, sentence in numbers))


@pytest.mark.parametrize("path", CHAPTERS, ids=lambda path: path.name)
def test_every_glue_role_names_a_glued_value(path):
    problems = glue_problems(path, executed_notebook(path))
    assert not problems, "\n".join(problems)


def test_the_scanner_finds_what_it_should(tmp_path):
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell(
        "The fit leaves 1.13 px (`rms = 0.5` in code, $a = -0.5$ in maths), 84 tie points, "
        "{glue:text}`rms:.2f` px glued; chapter 14, EPSG:31983, 1:25,000, year 2015, WGS 84, "
        "degree 3, 6 GCPs.")])
    path = tmp_path / "07_planted.ipynb"
    nbformat.write(notebook, path)
    assert [text for _, text, _ in typed_numbers(path)] == ["1.13", "84"]
    executed = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        outputs=[nbformat.v4.new_output("display_data", data={"text/plain": "1.126"},
                                        metadata={"scrapbook": {"name": "other",
                                                                "mime_prefix": ""}})])])
    assert glue_problems(path, executed) == [
        "cell 0: {glue:text}`rms:.2f`: nothing glued as 'rms'"]


@pytest.mark.parametrize("path", CHAPTERS, ids=lambda path: path.name)
def test_the_translation_keeps_every_glued_number(path):
    # a translated paragraph is parsed without the notebook's glue data: its roles must name
    # the notebook, and none may be lost or typed instead
    import re

    from babel.messages.pofile import read_po

    po = ROOT / "locales" / "pt_BR" / "LC_MESSAGES" / "book" / (path.stem + ".po")
    with open(po, "rb") as handle:
        catalogue = read_po(handle)
    role = re.compile(r"\{glue(:\w+)?\}`(?:[^`:]*\.ipynb::)?([^`]*)`")
    wrong = []
    for message in catalogue:
        if not message.id or not message.string or message.fuzzy:
            continue
        english = sorted(match.group(2) for match in role.finditer(message.id))
        portuguese = sorted(match.group(2) for match in role.finditer(message.string))
        unqualified = [m.group(0) for m in role.finditer(message.string)
                       if f"{path.name}::" not in m.group(0)]
        if english != portuguese or unqualified:
            wrong.append(f"{message.id[:70]!r}: English {english}, Portuguese {portuguese}, "
                         f"not naming {path.name}: {unqualified}")
    assert not wrong, "\n".join(wrong)
