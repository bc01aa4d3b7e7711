"""Atomic file writing: a file rsgeo writes is replaced whole, or left as it was.

Writing a file in place (``open(path, "w")``, ``rasterio.open(path, "w")``)
empties it first: a writer that fails, is killed or loses its power half-way
leaves a partial file under the final name, which may even open without an
error (a GeoTIFF of zeros, a ``.points`` file missing most of its GCPs), and
two writers of one name interleave their bytes. :func:`replacing` writes a
temporary file in the same folder instead, flushes it to the disk
(``os.fsync``) and renames it onto the final name with ``os.replace``, which
is atomic on POSIX and Windows: a reader, or a second writer, sees the old
file or the new one, never a mix. The temporary file is removed on any
exception; only a process killed outright (``SIGKILL``, a power cut) leaves
it behind, as a hidden ``.<name>.<random>.tmp`` beside the final file.

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> target = Path(tempfile.mkdtemp()) / "notes.txt"
>>> with replacing(target) as temporary:
...     _ = Path(temporary).write_text("complete")
>>> target.read_text()
'complete'
>>> try:
...     with replacing(target) as temporary:
...         _ = Path(temporary).write_text("half")
...         raise RuntimeError("the writer failed")
... except RuntimeError:
...     pass
>>> target.read_text(), sorted(path.name for path in target.parent.iterdir())
('complete', ['notes.txt'])
"""

import os
import secrets
import stat
from contextlib import contextmanager
from pathlib import Path

from .errors import DataError
from .language import _

__all__ = ["replacing"]

# a file name is at most 255 bytes on the common file systems: the temporary name keeps a part
_NAME_PART = 80


@contextmanager
def replacing(file):
    """Yield a temporary path beside ``file``; when the block ends, it becomes ``file``.

    The caller writes the whole file to the temporary path. If the block
    ends without an exception, the temporary file is flushed to the disk,
    given the final file's permissions and renamed onto ``file`` in one
    atomic step; if it raises, the temporary file is removed and ``file``
    is left as it was (absent, or its old complete content).

    Parameters
    ----------
    file : str or path-like
        The file to write. A symbolic link is followed: the file it points
        to is replaced, as a plain ``open(file, "w")`` would write it.

    Yields
    ------
    pathlib.Path
        The temporary file, created empty in ``file``'s folder (so that the
        rename stays on one file system) with a hidden name,
        ``.<name>.<random>.tmp``.

    Raises
    ------
    rsgeo.errors.DataError
        If ``file`` is a folder or a read-only file, or no file can be
        created in its folder (read-only, missing, not permitted): raised
        before anything is written.

    Notes
    -----
    Permissions: a new file gets the mode a plain ``open`` would give it
    (0o666 less the umask); a replaced file keeps its mode. A replaced file
    is a new file: hard links to the old one keep the old content.
    """
    target = Path(os.path.realpath(file)) if Path(file).is_symlink() else Path(file)
    _refuse_folder_or_read_only(target, file)
    temporary = _create_temporary(target, file)
    try:
        yield temporary
        _flush_to_disk(temporary)
        if target.exists():
            os.chmod(temporary, stat.S_IMODE(target.stat().st_mode))
        os.replace(temporary, target)
    except BaseException:
        # an interrupted or failed writer leaves nothing behind: the old file is untouched
        temporary.unlink(missing_ok=True)
        raise
    _flush_folder(target.parent)


def _refuse_folder_or_read_only(target, file):
    """Refuse a folder or a read-only file as the target, before anything is written."""
    if target.is_dir():
        raise DataError(_("file {file!r} is a folder; give the name of a file to write, e.g. "
                          "inside that folder").format(file=str(file)))
    # os.replace would replace a read-only file, which a plain open(file, "w") refuses
    if target.exists() and not os.access(target, os.W_OK):
        raise DataError(_("file {file!r} is read-only, so it is left as it is; make it "
                          "writable (e.g. chmod u+w) or write to another file").format(
                              file=str(file)))


def _create_temporary(target, file):
    """Create an empty, hidden temporary file beside ``target`` and return its path."""
    prefix = "." + target.name[:_NAME_PART] + "."
    for _attempt in range(100):
        temporary = target.parent / (prefix + secrets.token_hex(6) + ".tmp")
        try:
            # mode 0o666 with O_EXCL, as a plain open() creates a file: the umask applies
            # (tempfile.mkstemp would make it 0o600, private to its owner)
            os.close(os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
        except FileExistsError:
            continue
        except OSError as error:
            raise DataError(_(
                "cannot write file {file!r}: no file can be created in its folder {folder} "
                "({reason}); write to a folder you may write to, or change its "
                "permissions").format(file=str(file), folder=str(target.parent),
                                      reason=error.strerror or error)) from None
        return temporary
    raise FileExistsError(temporary)  # pragma: no cover - 100 random names all taken


def _flush_to_disk(path):
    """Make the file's bytes durable before the rename publishes them (``os.fsync``)."""
    # Windows flushes only through a handle open for writing; POSIX accepts a read-only one,
    # which works whatever the file's mode
    descriptor = os.open(path, os.O_RDWR if os.name == "nt" else os.O_RDONLY)
    try:
        os.fsync(descriptor)
    finally:
        os.close(descriptor)


def _flush_folder(folder):
    """Make the rename itself durable on POSIX (Windows cannot open a folder for this)."""
    if os.name == "nt":
        return
    try:
        descriptor = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(descriptor)
    except OSError:
        pass  # some file systems refuse to flush a folder; the rename has been made
    finally:
        os.close(descriptor)
