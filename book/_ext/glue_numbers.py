"""Glued numbers written the way the book's readers write numbers.

The prose's numbers are glued from the notebooks' executions (myst-nb's ``{glue:text}`` role,
with a format spec such as ``:.2f`` or ``:,d``): Python formats them with a decimal point and a
thousands comma. A Brazilian reads "1.478 s" as one thousand four hundred and seventy-eight
seconds and "10,000 pares" as ten pairs; the Portuguese book (``language: pt_BR``) writes them
"1,478 s" and "10.000 pares", and "8.5e-08" as "8,5 × 10⁻⁸". Only the glued text is changed
(myst-nb's ``pasted-text`` spans, every one of which is a number, a percentage or a sum of
numbers); code, code spans, maths and printed output keep the point, as the first page's note
says. The English book is left as Python prints it.
"""

import re

from docutils import nodes
from sphinx.transforms.post_transforms import SphinxPostTransform

#: Languages whose decimal separator is a comma and thousands separator a point.
DECIMAL_COMMA_LANGUAGES = ("pt_BR", "pt")

_NUMBER = re.compile(r"(?<![\w.,])(\d{1,3}(?:,\d{3})+|\d+)(\.\d+)?(?:e([-+]\d+))?(?![\w])")
_SUPERSCRIPT = str.maketrans("-+0123456789", "⁻⁺⁰¹²³⁴⁵⁶⁷⁸⁹")


def _brazilian(match):
    whole, fraction, exponent = match.groups()
    text = whole.replace(",", ".") + (fraction or "").replace(".", ",")
    if exponent is not None:
        power = str(int(exponent)).translate(_SUPERSCRIPT)
        text = f"10{power}" if text == "1" else f"{text} × 10{power}"
    return text


def brazilian_number(text):
    """``text`` (a number as Python formats it) with Brazilian separators.

    Parameters
    ----------
    text : str
        A glued value: a number, a percentage, a sum of numbers ("≈ 50 + 25").

    Returns
    -------
    str
        The same text, each number with a decimal comma and a thousands point, and
        exponents written as powers of ten.

    Examples
    --------
    >>> brazilian_number("1.478")
    '1,478'
    >>> brazilian_number("7,370,120")
    '7.370.120'
    >>> brazilian_number("-1,234.5%")
    '-1.234,5%'
    >>> brazilian_number("8.5e-08"), brazilian_number("1e-08")
    ('8,5 × 10⁻⁸', '10⁻⁸')
    >>> brazilian_number("≈ 50 + 25")
    '≈ 50 + 25'
    """
    return _NUMBER.sub(_brazilian, text)


class LocalGlueNumbers(SphinxPostTransform):
    """Rewrite every glued number of a page in the book's language (after myst-nb has resolved
    the glue references to other pages, its priority 5)."""

    default_priority = 10

    def run(self, **kwargs):
        if (self.config.language or "en") not in DECIMAL_COMMA_LANGUAGES:
            return
        for node in list(self.document.findall(nodes.inline)):
            if "pasted-text" not in node.get("classes", []):
                continue
            text = node.astext()
            local = brazilian_number(text)
            if local != text:
                node.children = [nodes.Text(local)]


def setup(app):
    app.add_post_transform(LocalGlueNumbers)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
