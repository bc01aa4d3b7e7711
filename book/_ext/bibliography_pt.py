"""Citations and the bibliography of the Portuguese book written the way a Brazilian reads them.

sphinxcontrib-bibtex formats ``{cite}`` roles and the ``{bibliography}`` page with two pybtex
plugins named in the configuration: a referencing style (``bibtex_reference_style``, the text of
a citation) and a formatting style (``bibtex_default_style``, an entry of the list). Their
words are English: "Meneses and Almeida, 2012", "n.d." for an entry without a year, "editors",
"4 edition", "pages", "In", "URL:". This extension registers two Portuguese plugins, which
``_config_pt.yml`` names:

- ``author_year_pt`` (referencing): "Meneses e Almeida, 2012", "s.d." without a year;
- ``plain_pt`` (formatting): pybtex's ``plain`` with "e" between names, "(org.)" after
  editors, "4. ed.", "p." before pages, "In:", "Disponível em:" before a URL.

A field of ``references.bib`` may also have a Portuguese version, the same name with ``_pt``
(``title_pt``, ``note_pt``, ``howpublished_pt``): when the book's ``language`` is Portuguese,
it replaces the English field in citations and in the list, so that a note written in English
for the English book is read in Portuguese here. The English book is left as it is (this
extension can be loaded by both books: the plugins are only used where the configuration names
them, and the fields are only swapped in a Portuguese book).
"""

from dataclasses import dataclass, field

import pybtex.plugin
from pybtex.richtext import Symbol
from pybtex.style.formatting import toplevel
from pybtex.style.formatting.plain import Style as PlainStyle
from pybtex.style.formatting.unsrt import date, pages
from pybtex.style.template import field as bib_field
from pybtex.style.template import (
    first_of,
    href,
    join,
    names,
    node,
    optional,
    optional_field,
    sentence,
    tag,
    words,
)
from sphinxcontrib.bibtex.plugin import register_plugin
from sphinxcontrib.bibtex.style.referencing import PersonStyle
from sphinxcontrib.bibtex.style.referencing.author_year import AuthorYearReferenceStyle
from sphinxcontrib.bibtex.style.referencing.basic_author_year import (
    BasicAuthorYearParentheticalReferenceStyle,
    BasicAuthorYearTextualReferenceStyle,
)
from sphinxcontrib.bibtex.style.referencing.extra_author import ExtraAuthorReferenceStyle
from sphinxcontrib.bibtex.style.referencing.extra_empty import ExtraEmptyReferenceStyle
from sphinxcontrib.bibtex.style.referencing.extra_label import ExtraLabelReferenceStyle
from sphinxcontrib.bibtex.style.referencing.extra_year import ExtraYearReferenceStyle
from sphinxcontrib.bibtex.style.template import join2, post_text, pre_text, reference

#: Languages whose books get the Portuguese fields (``title_pt``...) of references.bib.
PORTUGUESE_LANGUAGES = ("pt_BR", "pt")
#: The suffix of a field's Portuguese version in references.bib.
PORTUGUESE_SUFFIX = "_pt"
#: Name of the referencing style (``bibtex_reference_style``) and of the formatting style
#: (``bibtex_default_style``) this extension registers.
REFERENCE_STYLE = "author_year_pt"
FORMATTING_STYLE = "plain_pt"

#: "and" between two names and before the last of several, "et al." beyond.
NAMES_AND = " e "
#: An entry without a year: *sem data*.
NO_YEAR = "s.d."


# -- Citations -----------------------------------------------------------------------------------

def _portuguese_person():
    return PersonStyle(sep2=NAMES_AND, last_sep=NAMES_AND)


@node
def year_or_nd(children, data):
    """The entry's year, or "s.d." (a template node, like sphinxcontrib.bibtex's ``year``)."""
    assert not children
    return first_of[optional[bib_field("year")], NO_YEAR].format_data(data)


@dataclass
class _ParentheticalPt(BasicAuthorYearParentheticalReferenceStyle):
    def inner(self, role_name):
        return join2(sep1=self.pre_text_sep, sep2=self.post_text_sep)[
            pre_text,
            reference[join(sep=self.author_year_sep)[
                self.person.author_or_editor_or_title(full="s" in role_name), year_or_nd]],
            post_text,
        ]


@dataclass
class _TextualPt(BasicAuthorYearTextualReferenceStyle):
    def inner(self, role_name):
        return join(sep=self.text_reference_sep)[
            self.person.author_or_editor_or_title(full="s" in role_name),
            join[
                self.bracket.left,
                join2(sep1=self.pre_text_sep, sep2=self.post_text_sep)[
                    pre_text, reference[year_or_nd], post_text],
                self.bracket.right,
            ],
        ]


@dataclass
class _YearPt(ExtraYearReferenceStyle):
    def inner(self, role_name):
        return reference[year_or_nd]


@dataclass
class PortugueseAuthorYearReferenceStyle(AuthorYearReferenceStyle):
    """``author_year`` in Portuguese: "(Meneses e Almeida, 2012)", "(Negri, s.d.)"."""

    person: PersonStyle = field(default_factory=_portuguese_person)

    def __post_init__(self):
        self.styles.extend([
            _ParentheticalPt(bracket=self.bracket_parenthetical, person=self.person,
                             author_year_sep=self.author_year_sep,
                             pre_text_sep=self.pre_text_sep, post_text_sep=self.post_text_sep),
            _TextualPt(bracket=self.bracket_textual, person=self.person,
                       text_reference_sep=self.text_reference_sep,
                       pre_text_sep=self.pre_text_sep, post_text_sep=self.post_text_sep),
            ExtraAuthorReferenceStyle(bracket=self.bracket_author, person=self.person),
            ExtraLabelReferenceStyle(bracket=self.bracket_label),
            _YearPt(bracket=self.bracket_year),
            ExtraEmptyReferenceStyle(),
        ])
        # GroupReferenceStyle's own __post_init__ (AuthorYearReferenceStyle's would add the
        # English styles a second time)
        super(AuthorYearReferenceStyle, self).__post_init__()


# -- The bibliography's entries ------------------------------------------------------------------

class PortuguesePlainStyle(PlainStyle):
    """pybtex's ``plain`` with Portuguese words (ABNT's where it has one)."""

    def format_names(self, role, as_sentence=True):
        formatted = names(role, sep=", ", sep2=NAMES_AND, last_sep=NAMES_AND)
        return sentence[formatted] if as_sentence else formatted

    def format_editor(self, e, as_sentence=True):
        editors = self.format_names("editor", as_sentence=False)
        if "editor" not in e.persons:
            return editors            # the template raises FieldIsMissing, as pybtex's does
        result = join(sep=" ")[editors, "(org.)"]
        return sentence[result] if as_sentence else result

    def format_edition(self, e):
        return optional[join[bib_field("edition"), ". ed."]]

    def format_chapter_and_pages(self, e):
        return join(sep=", ")[
            optional[join(sep=Symbol("nbsp"))["cap.", bib_field("chapter")]],
            optional[join(sep=Symbol("nbsp"))["p.", pages]],
        ]

    def format_volume_and_series(self, e, as_sentence=True):
        volume = optional[words[join(sep=Symbol("nbsp"))["v.", bib_field("volume")],
                                optional[words["de", bib_field("series")]]]]
        number = optional[words[join(sep=Symbol("nbsp"))["n.", bib_field("number")],
                                optional[words["em", bib_field("series")]]]]
        result = first_of[volume, number, optional_field("series")]
        return sentence(capfirst=True)[result] if as_sentence else result

    def get_article_template(self, e):
        volume_and_pages = first_of[
            optional[join[bib_field("volume"), optional["(", bib_field("number"), ")"], ":",
                          pages]],
            join(sep=Symbol("nbsp"))["p.", pages],
        ]
        return toplevel[
            self.format_names("author"),
            self.format_title(e, "title"),
            sentence[tag("em")[bib_field("journal")], optional[volume_and_pages], date],
            sentence[optional_field("note")],
            self.format_web_refs(e),
        ]

    def get_inproceedings_template(self, e):
        return toplevel[
            sentence[self.format_names("author")],
            self.format_title(e, "title"),
            words[
                "In:",
                sentence[
                    optional[self.format_editor(e, as_sentence=False)],
                    self.format_btitle(e, "booktitle", as_sentence=False),
                    self.format_volume_and_series(e, as_sentence=False),
                    optional[join(sep=Symbol("nbsp"))["p.", pages]],
                ],
                self.format_address_organization_publisher_date(e),
            ],
            sentence[optional_field("note")],
            self.format_web_refs(e),
        ]

    def format_url(self, e):
        url = bib_field("url", raw=True)
        return words["Disponível em:", href(url)[url]]


# -- The Portuguese fields -----------------------------------------------------------------------

def portuguese_fields(entries):
    """Replace each field of ``entries`` by its Portuguese version (``title`` by ``title_pt``).

    Parameters
    ----------
    entries : iterable of pybtex.database.Entry
        The bibliography's entries; changed in place.

    Returns
    -------
    int
        How many fields were replaced.

    Examples
    --------
    >>> from pybtex.database import Entry
    >>> entry = Entry("misc", fields={"note": "Lecture slides", "note_pt": "Notas de aula"})
    >>> portuguese_fields([entry]), str(entry.fields["note"])
    (1, 'Notas de aula')
    """
    replaced = 0
    for entry in entries:
        for name in [name for name in entry.fields if name.lower().endswith(PORTUGUESE_SUFFIX)]:
            english = name[:-len(PORTUGUESE_SUFFIX)]
            if entry.fields.get(english) != entry.fields[name]:
                entry.fields[english] = entry.fields[name]
                replaced += 1
    return replaced


def _use_portuguese_fields(app):
    # after sphinxcontrib.bibtex's own builder-inited handler has read references.bib
    if (app.config.language or "en") not in PORTUGUESE_LANGUAGES:
        return
    bibdata = app.env.get_domain("cite").bibdata
    portuguese_fields(bibdata.data.entries.values())


def setup(app):
    register_plugin("sphinxcontrib.bibtex.style.referencing", REFERENCE_STYLE,
                    PortugueseAuthorYearReferenceStyle, force=True)
    pybtex.plugin.register_plugin("pybtex.style.formatting", FORMATTING_STYLE,
                                  PortuguesePlainStyle, force=True)
    app.connect("builder-inited", _use_portuguese_fields, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
