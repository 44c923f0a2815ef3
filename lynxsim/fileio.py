"""Writing files safely: inside the asked folder, to a temporary name, renamed when complete.

Names that come from files (a task's ``name``) never choose where output goes:
:func:`safe_stem` turns them into a plain file stem, and :func:`output_path`
places that stem inside the folder the user gave. :func:`atomic_path` writes
beside the destination and renames only after the writer succeeded; it never
replaces anything that is not a regular file (a folder, a FIFO, a device, a
symbolic link). :func:`atomic_folder` does the same for a folder written whole
(a dataset): a hidden temporary folder, renamed only when complete.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import shutil
import stat
import tempfile
import unicodedata
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

from lynxsim.errors import OutputPathError

__all__ = [
    "MAX_STEM",
    "atomic_folder",
    "atomic_path",
    "check_destination",
    "check_new_folder",
    "file_stem",
    "output_path",
    "safe_stem",
    "unique_stems",
    "write_json",
]

MAX_STEM = 80
"""Longest file stem made from a name (characters)."""

_UNSAFE = re.compile(r"[^A-Za-z0-9._+-]+|\.{2,}")


def safe_stem(name: str, fallback: str = "output") -> str:
    """A file stem made from free text: ASCII letters, digits, ``. _ + -`` only.

    Path separators, ``..``, control characters and everything else become ``_``;
    accents are dropped (``é`` -> ``e``); leading dots and dashes are removed (no
    hidden files, no names that read as options); at most :data:`MAX_STEM`
    characters. Empty results give ``fallback``.

    Args:
        name: Any text, e.g. a task's name.
        fallback: Stem used when nothing of ``name`` is left.
    """
    ascii_text = unicodedata.normalize("NFKD", name).encode("ascii", "ignore").decode("ascii")
    stem = _UNSAFE.sub("_", ascii_text).lstrip(".-_")[:MAX_STEM].rstrip("._")
    return stem or fallback


def file_stem(*parts: str) -> str:
    """Name pieces made safe (:func:`safe_stem`) and joined by ``_``, e.g. ``pick_quintic``."""
    return "_".join(safe_stem(p) for p in parts)[: 2 * MAX_STEM]


def unique_stems(stems: Sequence[str]) -> list[str]:
    """``stems`` with a repeat made distinct: the second ``x`` becomes ``x_2``, and so on.

    Names made safe can coincide (``arm/one`` and ``arm_one``, two names of
    other scripts, long names cut short); files named after them must not
    overwrite each other.
    """
    taken: set[str] = set()
    out = []
    for stem in stems:
        name, n = stem, 1
        while name in taken:
            n += 1
            name = f"{stem}_{n}"
        taken.add(name)
        out.append(name)
    return out


def output_path(folder: str | os.PathLike[str], *parts: str, suffix: str) -> Path:
    """``folder / file_stem(*parts) + suffix``: always a file directly inside ``folder``.

    Args:
        folder: The folder the user gave (created on writing, not here).
        parts: Name pieces, e.g. ``(task.name, "quintic")``; each made safe.
        suffix: File suffix including the dot, e.g. ``".mp4"``.
    """
    return Path(folder) / f"{file_stem(*parts)}{suffix}"


def check_destination(dest: str | os.PathLike[str]) -> Path:
    """Refuse a destination that exists and is not a regular file, or whose folder cannot be.

    Called before long work, so that a wrong ``--out`` fails in a second, and
    again by :func:`atomic_path` just before writing.

    Raises:
        OutputPathError: ``dest`` is a folder, FIFO, device, socket or symbolic
            link, or a part of its folder exists and is not a folder.
    """
    dest = Path(dest)
    try:
        mode = os.lstat(dest).st_mode
    except (FileNotFoundError, NotADirectoryError):
        mode = None
    except OSError as exc:
        raise OutputPathError(f"cannot write {dest}: {exc.strerror}") from None
    if mode is not None and not stat.S_ISREG(mode):
        kind = (
            "a folder"
            if stat.S_ISDIR(mode)
            else "a symbolic link"
            if stat.S_ISLNK(mode)
            else "not a regular file"
        )
        raise OutputPathError(f"will not replace {dest}: it is {kind}")
    for parent in dest.parents:
        if parent.exists() or parent.is_symlink():
            if not parent.is_dir():
                raise OutputPathError(f"cannot write {dest}: {parent} is not a folder")
            break
    return dest


_WRITE_ERRNOS = frozenset({errno.ENOSPC, errno.EFBIG, errno.EDQUOT, errno.EIO, errno.EROFS})
"""Errors of a write that :func:`atomic_path` reports as its destination's."""


def _make_folders(folder: Path) -> list[Path]:
    """Create ``folder`` and its missing parents; the ones created, outermost first."""
    missing = []
    for part in (folder, *folder.parents):
        if os.path.lexists(part):
            break
        missing.append(part)
    folder.mkdir(parents=True, exist_ok=True)
    return missing[::-1]


def _remove_made(made: list[Path]) -> None:
    """Remove the folders :func:`_make_folders` created, innermost first, where still empty."""
    for folder in reversed(made):
        try:
            folder.rmdir()
        except OSError:  # something else was written there meanwhile: it stays
            return


@contextlib.contextmanager
def atomic_path(dest: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path beside ``dest``; rename it to ``dest`` on success.

    The temporary name keeps ``dest``'s suffix (writers such as matplotlib and
    imageio pick the format from it). On any exception (``KeyboardInterrupt``
    and the CLI's SIGTERM included) the partial file is removed, and so are the
    folders made for it (if still empty); ``dest`` is left as it was.

    Raises:
        OutputPathError: See :func:`check_destination`; also a write that
            failed for want of space or of a writable disk (``cannot write DEST:
            No space left on device``), named after ``dest``, not its temporary name.
    """
    dest = check_destination(dest)
    made = _make_folders(dest.parent)
    try:
        fd, name = tempfile.mkstemp(
            prefix=f".{dest.stem[:MAX_STEM]}.", suffix=f".tmp{dest.suffix}", dir=dest.parent
        )
    except BaseException:
        _remove_made(made)
        raise
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        # mkstemp creates the file private (0600); give it the usual permissions.
        umask = os.umask(0)
        os.umask(umask)
        tmp.chmod(0o666 & ~umask)
        check_destination(dest)  # it may have changed while we wrote
        os.replace(tmp, dest)
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        _remove_made(made)
        if exc.errno in _WRITE_ERRNOS:  # named after dest: the temporary name is ours
            raise OutputPathError(f"cannot write {dest}: {os.strerror(exc.errno)}") from None
        raise
    except BaseException:
        tmp.unlink(missing_ok=True)
        _remove_made(made)
        raise


def write_json(dest: str | os.PathLike[str], data: Any) -> Path:
    """Write ``data`` as indented JSON, atomically; returns the path."""
    with atomic_path(dest) as tmp:
        tmp.write_text(json.dumps(data, indent=2) + "\n")
    return Path(dest)


def check_new_folder(dest: str | os.PathLike[str], hint: str = "remove it") -> Path:
    """Refuse a destination that exists (of any kind), or whose parent cannot be a folder.

    Args:
        dest: The folder to create.
        hint: What the error suggests doing instead.

    Raises:
        OutputPathError: ``dest`` exists, or a part of its path is not a folder.
    """
    dest = Path(dest)
    if os.path.lexists(dest):
        raise OutputPathError(f"will not replace {dest}: it exists ({hint})")
    return check_destination(dest)


@contextlib.contextmanager
def atomic_folder(dest: str | os.PathLike[str], hint: str = "remove it") -> Iterator[Path]:
    """Yield a new temporary folder beside ``dest``; rename it to ``dest`` on success.

    On any exception (``KeyboardInterrupt`` and the CLI's SIGTERM included) the
    temporary folder and everything in it are removed, and so are the folders
    made for it (if still empty); ``dest`` never appears.

    Raises:
        OutputPathError: ``dest`` exists (checked before and again just before
            the rename), or a part of its path is not a folder.
    """
    dest = check_new_folder(dest, hint)
    made = _make_folders(dest.parent)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{dest.name}.", suffix=".tmp", dir=dest.parent))
    except BaseException:
        _remove_made(made)
        raise
    try:
        yield tmp
        # mkdtemp creates the folder private (0700); give it the usual permissions.
        umask = os.umask(0)
        os.umask(umask)
        tmp.chmod(0o777 & ~umask)
        # dest may have appeared while we wrote, and a rename replaces an empty folder.
        check_new_folder(dest, hint)
        os.rename(tmp, dest)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        _remove_made(made)
        raise
