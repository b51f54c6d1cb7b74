"""Output folders tvtrack replaces (a site, a reproduce run): never emptied unless tvtrack made them, and replaced
through a temporary folder and a rename, so no file tvtrack did not write is ever deleted.

A folder tvtrack builds holds the marker :data:`MARKER` (JSON: what it is and the relative path of every file
written there). Before ``-o DIR`` is written, :func:`check_replaceable` refuses, with one line naming the
parameter, a symbolic link (the rename would replace the link, not the folder it leads to), a folder that is not
empty and has no marker, or one that holds a file the marker does not list (a file the user added). The new content
is built in a sibling ``.tmp-<name>-<random>`` folder (its owner's process id in ``.owner``, so a killed build's
folder is removed by the next one), marked (:func:`mark`), then put in place by :func:`replace_folder`: the old
folder is renamed aside, the new one renamed in (should that fail, the old one is renamed back), and of the old one
only the files its marker lists are deleted (a file that appeared meanwhile is left in the renamed folder and
named). A listed name is deleted only if it is a relative path inside the folder (:func:`listed_inside`); a marker
listing another is refused, and a damaged ``run.json`` deletes nothing. :func:`build_folder` does all of this for a
builder, and a write that fails midway (a full disk) is one line, with the temporary folder removed.
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import socket
import uuid
from collections.abc import Callable
from pathlib import Path

from .preflight import UsageError

__all__ = [
    "MARKER",
    "check_replaceable",
    "mark",
    "marked_files",
    "listed_inside",
    "temporary_beside",
    "replace_folder",
    "replace_text",
    "build_folder",
    "disk_refused",
]

MARKER = ".tvtrack-output.json"
OWNER_FILE = ".owner"  # "<host> <pid>" of the process building a temporary folder (as the runner's)


def listed_inside(folder: Path, rel: object) -> bool:
    """Whether ``rel``, a file name listed in a record of ``folder`` (a marker's or ``run.json``'s ``files``,
    ``results.json``'s figures and recording), names a file inside ``folder``: a non-empty relative path without a
    ``..`` part that, symbolic links followed, stays in ``folder``.

    Parameters
    ----------
    folder : Path
        The folder the record describes.
    rel : object
        The entry as the record holds it (anything but a string is refused).

    Returns
    -------
    bool
        ``False`` for an absolute path, one with ``..``, one resolving outside ``folder``, or not a string.
    """
    if not isinstance(rel, str) or not rel.strip() or "\0" in rel:
        return False
    path = Path(rel)
    if path.is_absolute() or ".." in path.parts or path == Path("."):
        return False
    try:
        return (Path(folder) / path).resolve().is_relative_to(Path(folder).resolve())
    except (OSError, RuntimeError):  # a symbolic link loop
        return False


def _listing(folder: Path) -> tuple[Path, list] | None:
    """The record of ``folder`` listing the files tvtrack wrote there (its marker, else its ``run.json``) and its
    ``files`` as written; ``None`` when neither is a JSON object with a ``files`` list."""
    for name in (MARKER, "run.json"):
        try:
            data = json.loads((Path(folder) / name).read_text())
        except (OSError, ValueError):
            continue
        if isinstance(data, dict) and isinstance(data.get("files"), list):
            return Path(folder) / name, data["files"]
    return None


def marked_files(folder: Path) -> set[str] | None:
    """The relative paths tvtrack wrote in ``folder``: those its marker lists, or for a run folder those its
    ``run.json`` lists (``files``); ``None`` when neither says.

    Raises
    ------
    UsageError
        One line naming the record and its first entry that is not a file inside ``folder``
        (:func:`listed_inside`): such a record was not written by tvtrack, and nothing it lists is deleted.
    """
    listing = _listing(folder)
    if listing is None:
        return None
    record, files = listing
    outside = [f for f in files if not listed_inside(folder, f)]
    if outside:
        raise UsageError(
            f"{record}: 'files' lists {outside[0]!r}, which is not a file inside {Path(folder)} (allowed: relative "
            "paths without '..'); tvtrack did not write this record: move the folder aside or give another one"
        )
    return set(files)


def _files(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in Path(folder).rglob("*") if not p.is_dir()}


def check_replaceable(folder: Path, parameter: str, kind: str) -> None:
    """Refuse ``folder`` as the output of a ``kind`` (e.g. "site") unless it is absent, empty or one tvtrack built.

    Raises
    ------
    UsageError
        One line naming ``parameter`` (e.g. ``-o``) and the folder: a symbolic link (the folder is replaced by
        renames, which would replace the link itself: the folder it leads to is to be given); a file; a non-empty
        folder without the marker (not built here); a marked folder holding a file tvtrack did not write (named,
        with how many more); a marker listing a file outside the folder (:func:`marked_files`).
    """
    folder = Path(folder)
    if folder.is_symlink():
        raise UsageError(
            f"{parameter} {folder}: a symbolic link (to {os.readlink(folder)}); the {kind} folder is replaced by "
            "renames, which would replace the link: give the folder it leads to, or another one"
        )
    if not folder.exists():
        return
    if not folder.is_dir():
        raise UsageError(
            f"{parameter} {folder}: cannot write the {kind} folder there: it is a file; give an empty or new folder"
        )
    present = _files(folder)
    if not present:
        return
    listed = marked_files(folder)
    if listed is None:
        raise UsageError(
            f"{parameter} {folder}: not a {kind} built here (no {MARKER}) and not empty; tvtrack never empties a "
            "folder it did not make: give an empty or new folder"
        )
    foreign = sorted(present - listed - {MARKER})
    if foreign:
        more = f" and {len(foreign) - 1} more" if len(foreign) > 1 else ""
        raise UsageError(
            f"{parameter} {folder}: holds {foreign[0]}{more}, which tvtrack did not write; move it out, or give "
            "another folder (tvtrack never deletes a file it did not write)"
        )


def temporary_beside(final: Path) -> Path:
    """A new, empty ``.tmp-<name>-<random>`` folder beside ``final`` (owned by this process); stale ones of the same
    name whose process is gone are removed first."""
    final = Path(final)
    final.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_builds(final)
    tmp = final.parent / f".tmp-{final.name}-{uuid.uuid4().hex[:8]}"
    tmp.mkdir()
    try:
        (tmp / OWNER_FILE).write_text(f"{socket.gethostname()} {os.getpid()}")
    except BaseException:  # a full disk: without its owner file the folder would never be removed
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return tmp


def remove_stale_builds(final: Path) -> int:
    """Remove ``.tmp-<name>-*`` folders beside ``final`` whose owner file names a process of this host that is gone;
    returns how many. A folder without an owner file is never touched (it may be the user's)."""
    from .runner import owner_gone

    n = 0
    for tmp in Path(final).parent.glob(f".tmp-{Path(final).name}-*"):
        if tmp.is_dir() and (tmp / OWNER_FILE).is_file() and owner_gone(tmp):
            shutil.rmtree(tmp, ignore_errors=True)
            n += 1
    return n


def mark(folder: Path, kind: str) -> None:
    """Write the marker of ``folder``: its kind and every file in it now (the owner file is removed first)."""
    folder = Path(folder)
    (folder / OWNER_FILE).unlink(missing_ok=True)
    files = sorted(_files(folder) - {MARKER})
    (folder / MARKER).write_text(json.dumps({"kind": kind, "written_by": "tvtrack", "files": files}, indent=0))


def replace_folder(new: Path, final: Path, legacy_run: bool = False) -> list[str]:
    """Put the marked folder ``new`` in place of ``final`` by renames; of the old ``final``, delete only the files its
    marker lists (with ``legacy_run``, a run folder from before runs listed their files, told by its ``run.json``:
    all its files). Returns the files left (ones tvtrack did not write, kept in ``.old-<name>-<random>`` beside
    it). Should ``new`` not go in place, the old ``final`` is put back before the error is raised."""
    new, final = Path(new), Path(final)
    if not final.exists():
        os.replace(new, final)
        return []
    old = final.parent / f".old-{final.name}-{uuid.uuid4().hex[:8]}"
    listed = _deletable(final, legacy_run)
    os.replace(final, old)
    try:
        os.replace(new, final)
    except BaseException:
        os.replace(old, final)
        raise
    for rel in sorted(listed | {MARKER}):
        path = old / rel
        if path.is_file() or path.is_symlink():
            try:
                path.unlink()
            except OSError:  # the new folder is in place: what cannot be deleted is left aside, and named
                pass
    for folder in sorted((p for p in old.rglob("*") if p.is_dir()), key=lambda p: -len(p.parts)):
        try:
            folder.rmdir()
        except OSError:
            pass
    try:
        old.rmdir()
    except OSError:
        return [str(old / rel) for rel in sorted(_files(old))]
    return []


def _deletable(final: Path, legacy_run: bool) -> set[str]:
    """The files of ``final`` that :func:`replace_folder` may delete: those its record lists that lie inside it
    (:func:`listed_inside`; any other entry is ignored), or with ``legacy_run`` and a ``run.json`` that is a JSON
    object without ``files`` (a run from before runs listed them), all of its files. A damaged ``run.json`` (not
    JSON, ``files`` not a list) deletes nothing."""
    listing = _listing(final)
    if listing is not None:
        return {f for f in listing[1] if listed_inside(final, f)}
    if not legacy_run:
        return set()
    try:
        record = json.loads((final / "run.json").read_text())
    except (OSError, ValueError):
        return set()
    return _files(final) if isinstance(record, dict) and "files" not in record else set()


def replace_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` whole or not at all: into a sibling ``.tmp-<name>-<random>`` file, then renamed over
    ``path`` (its permission bits kept). A full disk, a write error or a Ctrl-C midway leaves ``path`` as it was
    (the README, ``REPRODUCTION.md``, a finished run's ``run.json``), never truncated; the partial file is removed.
    A ``path`` that is a symbolic link stays one: the file it leads to is written."""
    path = Path(path)
    if path.is_symlink():
        path = Path(os.path.realpath(path))
    tmp = path.parent / f".tmp-{path.name}-{uuid.uuid4().hex[:8]}"
    try:
        with open(tmp, "x", encoding="utf-8") as f:
            f.write(text)
        if path.exists():
            shutil.copymode(path, tmp)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


#: The errors of a write the file system refuses (no room left, a quota, a file too large, read-only), whatever
#: was being read.
DISK_REFUSALS = (errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EROFS)


def disk_refused(exc: BaseException) -> bool:
    """Whether ``exc`` is a write the file system refused (a full disk, a quota, a read-only file system): a
    failure to write the output, never a sign that what was being read is damaged."""
    return isinstance(exc, OSError) and exc.errno in DISK_REFUSALS


def build_folder(final: Path, kind: str, build: Callable[[Path], None]) -> None:
    """Build a ``kind`` folder (e.g. "site") with ``build(folder)`` in a temporary folder beside ``final``, mark it
    (:func:`mark`) and put it in place of ``final`` (:func:`replace_folder`).

    Raises
    ------
    UsageError
        The temporary folder cannot be made (one line naming ``final``), before anything is built.
    WriteFailed
        A write failed midway (a full disk, a read-only file system): one line naming ``final``, the file where
        known and the system's reason. The temporary folder is removed and ``final`` is left as it was.
    """
    from .runner import WriteFailed

    final = Path(final)
    try:
        tmp = temporary_beside(final)
    except OSError as exc:
        raise UsageError(f"cannot write the {kind} folder {final}: {exc.strerror or exc}") from exc
    try:
        build(tmp)
        mark(tmp, kind)
        replace_folder(tmp, final)
    except OSError as exc:
        shutil.rmtree(tmp, ignore_errors=True)
        name = exc.filename if isinstance(exc.filename, str) else None
        if name and Path(name).is_relative_to(tmp):  # a file of the new folder, as it would have been named
            name = str(final / Path(name).relative_to(tmp))
        where = f"{name}: " if name else ""
        raise WriteFailed(
            f"cannot write the {kind} folder {final}: {where}{exc.strerror or exc}; nothing of the new {kind} is "
            f"kept, {final} is as it was"
        ) from exc
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
