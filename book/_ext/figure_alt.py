"""A Sphinx extension for the course's book: every figure says what it shows to a reader who
cannot see it.

myst-nb writes each image a notebook's cell outputs to a file named by its hash
(``_build/jupyter_execute/<sha256>.png``) and gives its image node no ``alt``, so the page read
the file's path aloud. The build's kernels write a description of every figure they render into
its PNG (a ``Description`` text chunk, :func:`rsgeo_course.alt_text.describe_figure`, put there by
figure_audit.py); here it becomes the image's ``alt``. An alt the author gave (a cell's image
metadata) is kept. An image with neither is a warning naming its page, which fails the build
(``-W``): a figure rendered outside the audited kernel, or a cached execution from before the
descriptions existed (clear the notebook's cache entry to execute it again).

Examples
--------
>>> import io
>>> from PIL import Image
>>> from PIL.PngImagePlugin import PngInfo
>>> info = PngInfo()
>>> info.add_text("Description", "Figure “a line”: 1 line.")
>>> png = io.BytesIO()
>>> Image.new("L", (2, 2)).save(png, format="png", pnginfo=info)
>>> png_description(png)
'Figure “a line”: 1 line.'
>>> png_description(io.BytesIO(b"not an image")) is None
True
"""

from pathlib import Path

from docutils import nodes
from sphinx.transforms.post_transforms import SphinxPostTransform
from sphinx.util import logging

logger = logging.getLogger(__name__)

#: The PNG text chunk that holds a figure's description (PNG's own keyword for it).
DESCRIPTION_KEY = "Description"


def png_description(source):
    """The ``Description`` text of a PNG file, or None (no such chunk, or not a PNG).

    Parameters
    ----------
    source : str, pathlib.Path or file object
        The image.

    Returns
    -------
    str or None
        The description, stripped; None when there is none.
    """
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(source) as image:
            if image.format != "PNG":
                return None
            text = getattr(image, "text", {}).get(DESCRIPTION_KEY)
    except (OSError, UnidentifiedImageError, ValueError):
        return None
    return text.strip() if isinstance(text, str) and text.strip() else None


class FigureAltText(SphinxPostTransform):
    """Give every image of a page its figure's description as ``alt`` (after myst-nb has pasted
    the glued outputs, its priority 5); warn about an image that has none."""

    default_priority = 20

    def run(self, **kwargs):
        for node in self.document.findall(nodes.image):
            if node.get("alt", "").strip():
                continue
            # Sphinx's image collector left the file's path, relative to the source folder,
            # in candidates; an image it did not collect (a URL) has only its uri
            uri = node.get("uri", "")
            collected = node.get("candidates", {}).get("*")
            if collected:
                path = Path(self.env.srcdir, collected)
            elif uri and "://" not in uri:
                path = Path(self.env.relfn2path(uri, self.env.docname)[1])
            else:
                path = None
            description = png_description(path) if path and path.is_file() else None
            if description:
                node["alt"] = description
            else:
                logger.warning(f"image without alternative text on page {self.env.docname!r}: "
                               f"{uri} (its PNG has no Description; execute the notebook again "
                               "with the figure audit, or give the image an alt)",
                               location=node, type="figure_alt", subtype="missing")


def setup(app):
    app.add_post_transform(FigureAltText)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
