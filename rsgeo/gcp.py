"""Ground control points: GCP sets, their CRS, and QGIS Georeferencer's ``.points`` files.

A :class:`GCPSet` holds map (x, y) beside image (col, row) coordinates, with ids, notes,
enabled flags and the map coordinates' CRS; :func:`read_points` and :func:`write_points` read
and write the files QGIS's Georeferencer saves. The models fitted to GCPs live in
:mod:`rsgeo.transforms`, the statistics of their accuracy in :mod:`rsgeo.accuracy`.

Image coordinates follow GDAL: (col, row) = (pixel, line), continuous, with the image's top-left
corner at (0, 0); QGIS's ``sourceY`` is minus the row.
"""

import csv
import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._atomic import replacing
from .accuracy import residuals
from .errors import CRSError, DataError, GCPError
from .language import _
from .transforms import fit_transform, registered
from .validation import as_flags, as_points

__all__ = ["GCPSet", "read_points", "write_points"]


@dataclass
class GCPSet:  # numpydoc ignore=PR02
    """Ground control points: map (x, y) beside image (col, row), with ids and flags.

    Parameters
    ----------
    map_xy : (n, 2) array_like
        Map coordinates (easting, northing) of each GCP.
    image_xy : (n, 2) array_like
        Image coordinates (col, row) of the same GCP, rows counted downwards.
    enabled : (n,) array_like of bool, optional
        False for GCPs left out of the fit (QGIS's "enable" column).
    ids : sequence of str, optional
        A name per GCP; "1", "2", ... by default.
    crs : str, optional
        The map coordinates' CRS (WKT or "EPSG:..."), written to .points files.
    notes : sequence of str, optional
        What each GCP is on the ground ("road crossing", "field corner").
    reliability : pandas.DataFrame, optional
        Set by :func:`rsgeo.registration.correlation_tiepoints`: per window, the
        correlation peak, its reliability, error, contrast and last shift.
    passes : list of dict, optional
        Set by :func:`rsgeo.registration.correlation_tiepoints`: per pass, the
        reliable points and the median shift, pixels.
    n_keypoints : (int, int), optional
        Set by :func:`rsgeo.registration.feature_tiepoints`: keypoints found in
        the reference and in the moving image.
    n_matches : int, optional
        Set by :func:`rsgeo.registration.feature_tiepoints`: descriptor matches
        before RANSAC.
    candidates : GCPSet, optional
        Set by :func:`rsgeo.registration.feature_tiepoints`: every match, with
        ``enabled`` flagging RANSAC's inliers.
    """

    map_xy: np.ndarray
    image_xy: np.ndarray
    enabled: np.ndarray = None
    ids: list = None
    crs: str = None
    notes: list = None
    # what found the GCPs says how (rsgeo.registration); None for GCPs picked by hand or read
    reliability: object = None
    passes: list = None
    n_keypoints: tuple = None
    n_matches: int = None
    candidates: "GCPSet" = None

    def __post_init__(self):
        # copies: editing the caller's arrays afterwards must not move these GCPs
        self.map_xy = np.array(as_points(self.map_xy, "map_xy"))
        self.image_xy = np.array(as_points(self.image_xy, "image_xy"))
        n = len(self.map_xy)
        if len(self.image_xy) != n:
            raise GCPError(_("map_xy and image_xy must hold the same GCPs, got {n} and "
                             "{n_values}").format(n=n, n_values=len(self.image_xy)))
        self.enabled = (np.ones(n, bool) if self.enabled is None
                        else np.array(as_flags(self.enabled, "enabled")))
        if self.enabled.shape != (n,):
            raise GCPError(_("enabled must have one flag per GCP ({n}), got shape "
                             "{shape}").format(n=n, shape=self.enabled.shape))
        self.ids = ([str(i + 1) for i in range(n)] if self.ids is None
                    else [str(i) for i in self.ids])
        self.notes = [""] * n if self.notes is None else [str(note) for note in self.notes]
        if len(self.ids) != n or len(self.notes) != n:
            raise GCPError(_("ids and notes must have one entry per GCP ({n})").format(n=n))

    def __len__(self):
        return len(self.map_xy)

    def fit(self, order, kind=None):
        """A model map -> image (u = f(x, y), v = g(x, y)) fitted on the enabled GCPs.

        Parameters
        ----------
        order : {1, 2, 3} or str or None
            Degree of the polynomial, or the name of another kind of
            :func:`rsgeo.transforms.fit_transform` ("helmert", "tps", ...).
        kind : str, optional
            A kind of :data:`rsgeo.transforms.REGISTRY`; then ``order`` is only
            for ``kind="polynomial"``.

        Returns
        -------
        GeometricModel
            Map (x, y) -> image (col, row); a
            :class:`~rsgeo.transforms.PolynomialModel` for a degree.

        Raises
        ------
        GCPError
            As :func:`rsgeo.transforms.fit_transform` (too few or collinear
            enabled GCPs).
        """
        entry = registered(order, None, "fit") if kind is None else registered(kind, order)
        return fit_transform(self.map_xy[self.enabled], self.image_xy[self.enabled], entry.kind,
                             entry.order)

    def to_crs(self, crs):
        """The same GCPs with their map coordinates transformed to ``crs`` by PROJ.

        Image coordinates, flags, ids and notes are kept. The datum transformation
        is :func:`rsgeo.crs.transform_points`' (the same PROJ with rsgeo's grids:
        SAD69 -> SIRGAS 2000 by IBGE's grid, EPSG:5528, where it applies); points
        outside the CRSs' areas of use are not refused.

        Parameters
        ----------
        crs : str, int or rasterio.crs.CRS
            The target CRS ("EPSG:31981", 31981, a WKT).

        Returns
        -------
        GCPSet
            With ``crs`` set to the target's WKT.

        Raises
        ------
        CRSError
            If this set has no CRS, or PROJ does not know either CRS.
        """
        from ._proj import transformer  # georef's PROJ, not GDAL's: it finds the grids

        if self.crs is None:
            raise CRSError(_("these GCPs have no CRS (crs=None): set the CRS their map "
                             "coordinates are in before transforming them"))
        source, target = _as_crs(self.crs, "the GCPs' crs"), _as_crs(crs, "crs")
        xs, ys = transformer(source.to_wkt(version="WKT2_2019"),
                             target.to_wkt(version="WKT2_2019")).transform(
                                 self.map_xy[:, 0], self.map_xy[:, 1])
        return GCPSet(np.column_stack([xs, ys]), self.image_xy.copy(), self.enabled.copy(),
                      list(self.ids), target.to_wkt(), list(self.notes))

    def combine(self, other):
        """This set followed by ``other``; refuses to mix map coordinates of two CRSs.

        Parameters
        ----------
        other : GCPSet
            More GCPs of the same image, in the same CRS (or both without one).

        Returns
        -------
        GCPSet

        Raises
        ------
        CRSError
            If the CRSs differ (transform one with :meth:`to_crs` first) or
            only one of the sets has a CRS.
        TypeError
            If ``other`` is not a GCPSet.
        """
        if not isinstance(other, GCPSet):
            raise TypeError(_("other must be a GCPSet, got {kind}").format(
                    kind=type(other).__name__))
        if (self.crs is None) != (other.crs is None) or (
                self.crs is not None and _as_crs(self.crs) != _as_crs(other.crs)):
            names = [_crs_name(self.crs), _crs_name(other.crs)]
            raise CRSError(_("cannot mix GCPs in {value} with GCPs in {value2}: "
                             "transform one set with .to_crs() first").format(
                    value=names[0], value2=names[1]))
        return GCPSet(np.vstack([self.map_xy, other.map_xy]),
                      np.vstack([self.image_xy, other.image_xy]),
                      np.concatenate([self.enabled, other.enabled]),
                      list(self.ids) + list(other.ids), self.crs,
                      list(self.notes) + list(other.notes))

    def table(self, model=None):
        """The GCP table as a pandas DataFrame; with a model, residuals in pixels.

        Columns: id, map x/y, image col/row, enabled, and with a model dx, dy
        (model - GCP, pixels), residual R_i (pixels), and ``residual_map``: the
        residual of the separately fitted reverse model (image -> map), in map units.

        Parameters
        ----------
        model : GeometricModel, optional
            A map -> image model with ``kind`` (and ``order`` for a
            polynomial), e.g. from :meth:`fit`.

        Returns
        -------
        pandas.DataFrame
            Indexed by id.

        Raises
        ------
        GCPError
            If the enabled GCPs cannot determine the reverse model.
        """
        import pandas as pd

        table = pd.DataFrame({
            "id": self.ids, "map_x": self.map_xy[:, 0], "map_y": self.map_xy[:, 1],
            "col": self.image_xy[:, 0], "row": self.image_xy[:, 1], "enabled": self.enabled,
        })
        if any(self.notes):
            table["note"] = self.notes
        if model is not None:
            dx, dy, distance = residuals(model, self.map_xy, self.image_xy)
            table["dx"], table["dy"], table["residual"] = dx, dy, distance
            reverse = fit_transform(self.image_xy[self.enabled], self.map_xy[self.enabled],
                                    model.kind, getattr(model, "order", None))
            table["residual_map"] = residuals(reverse, self.image_xy, self.map_xy)[2]
        return table.set_index("id")


def _as_crs(crs, name="crs"):
    """A rasterio CRS, or CRSError for one that PROJ does not know."""
    from rasterio.crs import CRS
    from rasterio.errors import CRSError as RasterioCRSError

    if isinstance(crs, CRS):
        return crs
    try:
        if isinstance(crs, (int, np.integer)):
            return CRS.from_epsg(crs)
        return CRS.from_user_input(crs)
    except (RasterioCRSError, TypeError, ValueError) as error:
        raise CRSError(_("{name} {value!r} is not a CRS that PROJ knows ({error}); give "
                         "an EPSG code such as 'EPSG:31983', a WKT or a PROJ string").format(
                name=name, value=str(crs)[:60], error=error)) from None


def _crs_name(crs):
    """A short name for a CRS in messages: 'EPSG:29191', or 'no CRS'."""
    if crs is None:
        return "no CRS"
    value = _as_crs(crs)
    epsg = value.to_epsg()
    return f"EPSG:{epsg}" if epsg else value.to_string()[:40]


_TRUE = ("1", "true", "yes")
_FALSE = ("0", "false", "no")


def _as_enabled(value, path, number):
    """QGIS's enable column: 0/1, true/false or yes/no in any case; anything else refused."""
    text = str(value if value is not None else "1").strip().lower()
    if text in _TRUE or text == "":
        return True
    if text in _FALSE:
        return False
    raise DataError(_("{path}, line {number}: enable must be 1 or 0 (or true/false, yes/no), got "
                      "{value!r}").format(path=path, number=number, value=value))


def read_points(path):
    """Read a QGIS Georeferencer ``.points`` file into a :class:`GCPSet`.

    Format (QGIS Georeferencer, ``QgsGCPList::saveGcps``): an optional first
    line ``#CRS: <WKT>``, a header ``mapX,mapY,sourceX,sourceY,enable,dX,dY,residual``
    (older files: ``mapX,mapY,pixelX,pixelY,enable``), comma- or tab-separated,
    UTF-8 with or without a byte-order mark. ``sourceY`` is the negative line
    number; rsgeo's rows count downwards, so row = -sourceY. ``enable`` is 1 or
    0 (true/false and yes/no in any case are read too). The extra columns
    ``id`` and ``note`` that :func:`write_points` adds (QGIS reads only the
    first five columns) give the GCPs' ids and notes as written, empty ones
    included; a file without an ``id`` column numbers its GCPs "1", "2", ...

    Parameters
    ----------
    path : str or path-like
        The ``.points`` file.

    Returns
    -------
    GCPSet
        With ``crs`` from the ``#CRS:`` line, if any.

    Raises
    ------
    DataError
        If the file is not text, the header lacks the needed columns, a line
        has fewer fields than the header (a file cut short ends so), a value
        is not a number, an ``enable`` value is not a flag, or the file holds
        no GCP. The message names the file and the line, counted in the file.
    """
    try:
        with open(path, encoding="utf-8-sig") as handle:
            text = handle.read()
    except UnicodeDecodeError:
        raise DataError(_("{path} is not a text .points file (it is not UTF-8 text); give the "
                          "file QGIS's Georeferencer saved").format(path=path)) from None
    if "\0" in text:
        raise DataError(_("{path} is not a text .points file (it holds NUL bytes); give the "
                          "file QGIS's Georeferencer saved").format(path=path))
    # line breaks as QGIS and the csv module know them: not str.splitlines's extra Unicode
    # separators (U+2028, U+0085, form feed ...), which an id or a note may hold
    # each line with its number in the file, for messages that point at it
    lines = list(enumerate((line.rstrip("\r\n") for line in io.StringIO(text, newline="")),
                           start=1))
    crs = None
    if lines and lines[0][1].startswith("#CRS:"):
        crs = lines.pop(0)[1][len("#CRS:"):].strip() or None
    lines = [(number, line) for number, line in lines
             if line.strip() and not line.startswith("#")]
    if not lines:
        raise DataError(_("{path}: no header and no GCPs; a .points file needs a header "
                          "line").format(path=path))
    numbers = [number for number, _line in lines]
    delimiter = "\t" if "\t" in lines[0][1] else ","
    reader = csv.DictReader((line + "\n" for _number, line in lines), delimiter=delimiter)
    header = [name.strip() for name in reader.fieldnames]
    reader.fieldnames = header
    older = "sourceX" not in header and ("pixelX" in header or "pixelY" in header)
    source_x, source_y = ("pixelX", "pixelY") if older else ("sourceX", "sourceY")
    # the image columns are sourceX, sourceY, or pixelX, pixelY in older files: the message
    # names the set the header started (sourceX,sourceY when it has neither)
    missing = [name for name in ("mapX", "mapY", source_x, source_y) if name not in header]
    if missing:
        raise DataError(_("{path}: header {header} lacks {sorted}; a QGIS .points file's "
                          "header is mapX,mapY,sourceX,sourceY,enable (older QGIS: "
                          "mapX,mapY,pixelX,pixelY,enable)").format(
                path=path, header=header, sorted=missing))
    map_xy, image_xy, enabled, ids, notes = [], [], [], [], []
    for row in reader:
        number = numbers[reader.line_num - 1]        # the row's last line, counted in the file
        missing = [name for name in header if row.get(name) is None]
        if missing:
            # a file cut short (a writer killed, a copy interrupted) ends in such a line, whose
            # last number may be cut too: reading it would give wrong or missing GCPs
            raise DataError(_(
                "{path}, line {number}: the line has {count} of the header's {total} fields "
                "({missing} missing), as a file cut short ends; write the file again, or give "
                "the line all its fields").format(
                    path=path, number=number, count=len(header) - len(missing),
                    total=len(header), missing=", ".join(missing)))
        try:
            map_xy.append((float(row["mapX"]), float(row["mapY"])))
            image_xy.append((float(row[source_x]), -float(row[source_y])))
        except (TypeError, ValueError):
            raise DataError(_("{path}, line {number}: coordinates must be numbers, got "
                              "{dict}").format(path=path, number=number, dict=dict(row))) from None
        enabled.append(_as_enabled(row.get("enable"), path, number))
        # an id column keeps what it holds, empty included; QGIS's files have none: 1, 2, ...
        ids.append(str(len(ids) + 1) if row.get("id") is None else row["id"])
        notes.append(row.get("note") or "")
    if not map_xy:
        raise DataError(_("{path} has a header but no points: a .points file needs one line per "
                          "GCP after its header").format(path=path))
    return GCPSet(np.array(map_xy), np.array(image_xy), enabled=enabled, ids=ids, crs=crs,
                  notes=notes)


def _check_writable(path):
    """Refuse to write inside rsgeo's shipped data folder, or into a folder that does not exist."""
    folder = (Path(__file__).parent / "data").resolve()
    target = Path(path).resolve()
    if target == folder or folder in target.parents:
        raise DataError(_("{path} is inside rsgeo's own data folder ({folder}), whose files ship "
                          "with the package; write your .points file somewhere else").format(
                              path=path, folder=folder))
    if not target.parent.is_dir():
        # the words of rsgeo.data.save's refusal (one message to translate)
        raise DataError(_(
            "the folder of file {file!r} does not exist ({folder}); create it first, e.g. "
            "Path({folder_text!r}).mkdir(parents=True)").format(
                file=str(path), folder=str(target.parent), folder_text=str(Path(path).parent)))


# one GCP per line: QGIS's Georeferencer (QgsGCPList::loadGcps) reads the file line by line and
# calls a line of fewer than four fields malformed; read_points refuses NUL bytes
_LINE_BREAKS = "\r\n\0"


def _check_one_line(gcps):
    """Refuse an empty GCPSet, and ids or notes that would break a GCP's line."""
    if not len(gcps):
        raise GCPError(_("gcps holds no GCP, and a .points file needs at least one: read_points "
                         "refuses a file with a header and no points; add GCPs before writing"))
    for name, texts in (("ids", gcps.ids), ("notes", gcps.notes)):
        for index, text in enumerate(texts):
            if any(character in _LINE_BREAKS for character in text):
                raise GCPError(_(
                    "{name}[{index}] is {text!r}, which holds a line break or a NUL character: "
                    "a .points file holds one GCP per line, which QGIS's Georeferencer reads "
                    "line by line; replace it (e.g. with a space) before writing").format(
                        name=name, index=index, text=text[:60]))


def write_points(path, gcps, model=None):
    """Write a :class:`GCPSet` as a QGIS Georeferencer ``.points`` file.

    With a model (map -> image, as :meth:`GCPSet.fit` returns), the dX, dY and
    residual columns hold its residuals in pixels; QGIS's dY, like sourceY,
    points up, so dY = -(model row - GCP row). The CRS goes on the ``#CRS:``
    line as one line (QGIS reads only that line). Ids and notes follow in two
    extra columns, ``id`` and ``note``: QGIS's reader
    (``QgsGCPList::loadGcps``) takes only the first five columns and ignores
    them, :func:`read_points` reads them back, empty ones included. An id or
    a note holding a comma or a quote is quoted as Python's ``csv`` module does;
    one holding a line break is refused, since QGIS reads the file line by line.

    Parameters
    ----------
    path : str or path-like
        The file to write.
    gcps : GCPSet
    model : callable, optional
        Map -> image model whose residuals fill dX, dY and residual: given
        the (n, 2) map (x, y), it returns the (n, 2) image (col, row).

    Returns
    -------
    None

    Raises
    ------
    TypeError
        If ``gcps`` is not a :class:`GCPSet`, or ``model`` is not callable.
    GCPError
        If ``gcps`` holds no GCP (:func:`read_points` refuses a file without
        points), an id or a note holds a line break (``"\\n"``, ``"\\r"``)
        or a NUL character, or ``model`` returns anything but (n, 2) numbers.
    DataError
        If ``path`` lies inside rsgeo's own data folder, its folder does not
        exist or no file can be created in it, or ``path`` is a folder or a
        read-only file.

    Notes
    -----
    Nothing is lost: every argument is checked first, and the file is written
    whole to a hidden temporary file beside ``path`` and then renamed onto it
    in one atomic step (``os.replace``). A refused call, a failure or an
    interrupted process leaves an existing ``path`` as it was; two processes
    writing one ``path`` leave one of their files, complete, never a mix.
    """
    if not isinstance(gcps, GCPSet):
        raise TypeError(_("gcps must be a GCPSet (map_xy, image_xy, enabled), got {kind}").format(
                kind=type(gcps).__name__))
    _check_one_line(gcps)
    if model is not None:
        dx, dy = _model_residuals(model, gcps)
        distance = np.hypot(dx, dy)
    else:
        dx = dy = distance = np.zeros(len(gcps))
    _check_writable(path)
    # written whole beside the target, then renamed onto it: a killed writer leaves the old file,
    # and of two writers of one name the last rename wins with its complete file
    with replacing(path) as temporary, open(temporary, "w", encoding="utf-8",
                                            newline="") as handle:
        if gcps.crs:
            # QGIS reads the CRS from the first line only: a multi-line WKT goes on one line
            one_line = " ".join(part.strip() for part in str(gcps.crs).splitlines())
            handle.write(f"#CRS: {one_line.strip()}\n")
        handle.write("mapX,mapY,sourceX,sourceY,enable,dX,dY,residual,id,note\n")
        writer = csv.writer(handle, lineterminator="\n")
        for i in range(len(gcps)):
            values = (gcps.map_xy[i, 0], gcps.map_xy[i, 1], gcps.image_xy[i, 0],
                      -gcps.image_xy[i, 1])
            writer.writerow([repr(float(v)) for v in values]
                            + [int(gcps.enabled[i]), repr(float(dx[i])), repr(float(-dy[i])),
                               repr(float(distance[i])), gcps.ids[i], gcps.notes[i]])


def _model_residuals(model, gcps):
    """dx, dy (model - GCP, pixels) of a map -> image model, whose output must be (n, 2)."""
    if not callable(model):
        raise TypeError(_("model must be a map -> image model (a callable, as GCPSet.fit "
                          "returns), got {kind}").format(kind=type(model).__name__))
    predicted = model(gcps.map_xy)
    try:
        # a wrong shape would broadcast against the GCPs into residuals that mean nothing
        predicted = np.asarray(predicted, dtype=np.float64)
    except (TypeError, ValueError):
        predicted = None
    expected = (len(gcps), 2)
    if predicted is None or predicted.shape != expected:
        got = (_("values that are not numbers") if predicted is None
               else _("shape {shape}").format(shape=predicted.shape))
        raise GCPError(_(
            "model returned {got} for the {n} GCPs' map (x, y); write_points needs their image "
            "(col, row), shape {expected}: give a map -> image model such as "
            "gcps.fit(order) returns").format(got=got, n=len(gcps), expected=expected))
    difference = predicted - gcps.image_xy
    return difference[:, 0], difference[:, 1]
