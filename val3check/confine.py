"""Which files a run may read, and reading them safely: the one gate every reader goes through.

A path written in a file (a project's `<Program file=>`, a library's `Disk://` path, a user
type's path...) may only lead into the allowed roots of the run (`Roots`): the folders the
user named, the repository that holds them (git top level, else the folder named), the
configured disk roots, and the `Disk://` folder and controller tree of each application
checked. Symbolic links are resolved before the check, so a link cannot lead out either.
A path the user typed (`--scenario`, `--config`, `--robot`, a lint target) is read wherever it
is (`Roots.user_given()`), but only if it is a regular file.

`read_bytes` then refuses what is not a regular file (FIFO, device, socket, folder) and
anything under /proc, /sys or /dev (they report a size of 0 and can be endless or reveal the
process environment), checks the size before reading, and opens without blocking and without
following a link swapped in after the check. It never raises anything but `Refused`.
"""

from __future__ import annotations

import errno
import os
import stat

from .rules import codes

# Pseudo file systems: sizes are wrong (0), content is endless or secret (/proc/self/environ).
_SPECIAL_TREES = ("/proc", "/sys", "/dev")
_OPEN_FLAGS = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)


class Refused(Exception):
    """A file that is not read. `code`: F001 (cannot be read: missing, not a regular file,
    special), F002 (too large), F014 (outside the allowed roots)."""

    def __init__(self, code: str, reason: str) -> None:
        super().__init__(reason)
        self.code = code
        self.reason = reason


def _inside(real: str, top: str) -> bool:
    return real == top or real.startswith(top.rstrip(os.sep) + os.sep)


def is_special(real: str) -> bool:
    return any(_inside(real, t) for t in _SPECIAL_TREES)


class Roots:
    """The folders that paths written in files may lead into (resolved real paths)."""

    def __init__(self, folders=(), *, anywhere: bool = False) -> None:
        self.anywhere = anywhere
        self._real: list[str] = []
        for f in folders:
            self.add(f)

    @classmethod
    def user_given(cls) -> "Roots":
        """For a path the user typed: no root applies (the kind and size checks still do)."""
        return cls(anywhere=True)

    def add(self, folder: str) -> None:
        if "\x00" in str(folder):  # no folder has one: nothing is allowed through it
            return
        real = os.path.realpath(folder)
        if real not in self._real and not is_special(real):
            self._real.append(real)

    @property
    def folders(self) -> list[str]:
        return list(self._real)

    def allows(self, path: str) -> bool:
        """`path`, symbolic links resolved, lies in one of the roots."""
        if self.anywhere:
            return True
        if "\x00" in str(path):
            return False
        real = os.path.realpath(path)
        return any(_inside(real, r) for r in self._real)

    def holds(self, path: str) -> bool:
        """`path`, taken as it is written (absolute, normalised, no link resolved), lies in a root."""
        return self.anywhere or any(_inside(path, r) for r in self._real)

    def containing(self, path: str) -> list[str]:
        """The roots that hold `path` (symbolic links resolved)."""
        if "\x00" in str(path):
            return []
        real = os.path.realpath(path)
        return [r for r in self._real if _inside(real, r)]


def _reason(exc: OSError) -> str:
    if isinstance(exc, PermissionError):
        return "permission denied"
    if exc.errno == errno.ELOOP:
        return "too many levels of symbolic links"
    if exc.strerror:
        return exc.strerror.lower()
    return type(exc).__name__


def human_size(n: int) -> str:
    if n >= 1024 * 1024:
        return f"{n / (1024 * 1024):.1f} MB"
    if n >= 1024:
        return f"{n / 1024:.1f} KB"
    return f"{n} bytes"


def check(path: str, roots: Roots) -> str:
    """The real path of a file that may be read, or `Refused` (nothing is opened)."""
    if "\x00" in str(path):
        raise Refused(codes.FILE_NOT_FOUND, "cannot be read: the path holds a NUL character")
    real = os.path.realpath(path)
    if is_special(real):
        raise Refused(codes.FILE_NOT_FOUND, "a special file (under /proc, /sys or /dev): not read")
    if not roots.allows(real):
        raise Refused(codes.PATH_OUTSIDE_ROOTS, "outside the application and the configured roots: not read")
    try:
        st = os.stat(real)
    except FileNotFoundError:
        if os.path.lexists(path):
            raise Refused(codes.FILE_NOT_FOUND, "cannot be read: a broken symbolic link") from None
        raise Refused(codes.FILE_NOT_FOUND, "file not found") from None
    except (OSError, ValueError) as exc:
        raise Refused(codes.FILE_NOT_FOUND, f"cannot be read: {_reason(exc) if isinstance(exc, OSError) else exc}") from None
    if stat.S_ISDIR(st.st_mode):
        raise Refused(codes.FILE_NOT_FOUND, "expected a file but this is a folder")
    if not stat.S_ISREG(st.st_mode):
        raise Refused(codes.FILE_NOT_FOUND, f"{kind_of(st.st_mode)}, not a regular file: not read")
    return real


def kind_of(mode: int) -> str:
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a special file"


def read_bytes(path: str, roots: Roots, max_size: int, overlay: dict[str, bytes] | None = None) -> bytes:
    """The bytes of a file that may be read and is at most `max_size` bytes; else `Refused`.

    `overlay` maps absolute paths to their unsaved text (an editor's buffer, standard input): such
    a file passes the same checks (inside the roots, a regular file on disk, not special) and
    its text is taken instead of the disk's."""
    real = check(path, roots)
    if overlay:
        text = overlay.get(os.path.abspath(path))
        if text is None:
            text = overlay.get(real)
        if text is not None:
            if len(text) > max_size:
                raise Refused(
                    codes.FILE_TOO_LARGE,
                    f"file too large ({human_size(len(text))}, limit {human_size(max_size)}): not read",
                )
            return bytes(text)
    try:
        st = os.stat(real)
        if st.st_size > max_size:
            raise Refused(
                codes.FILE_TOO_LARGE,
                f"file too large ({human_size(st.st_size)}, limit {human_size(max_size)}): not read",
            )
        # O_NONBLOCK: a FIFO swapped in after the check cannot block the open; O_NOFOLLOW: nor
        # can a symbolic link swapped in for the last component.
        fd = os.open(real, _OPEN_FLAGS | getattr(os, "O_NOFOLLOW", 0))
    except Refused:
        raise
    except (OSError, ValueError) as exc:
        raise Refused(
            codes.FILE_NOT_FOUND, f"cannot be read: {_reason(exc) if isinstance(exc, OSError) else exc}"
        ) from None
    try:
        fst = os.fstat(fd)
        if not stat.S_ISREG(fst.st_mode) or (fst.st_dev, fst.st_ino) != (st.st_dev, st.st_ino):
            raise Refused(codes.FILE_NOT_FOUND, "cannot be read: the file changed while it was opened")
        chunks, left = [], max_size + 1
        while left > 0:
            chunk = os.read(fd, min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
    except OSError as exc:
        raise Refused(codes.FILE_NOT_FOUND, f"cannot be read: {_reason(exc)}") from None
    finally:
        os.close(fd)
    data = b"".join(chunks)
    if len(data) > max_size:  # grew while reading
        raise Refused(codes.FILE_TOO_LARGE, f"file too large (more than {human_size(max_size)}): not read")
    return data


def git_top_level(folder: str) -> str | None:
    """The nearest folder at or above `folder` holding a `.git` entry (folder or file, as in a
    worktree), found without running git; None outside any repository."""
    cur = os.path.abspath(folder)
    while True:
        if os.path.lexists(os.path.join(cur, ".git")):
            return cur
        parent = os.path.dirname(cur)
        if parent == cur:
            return None
        cur = parent


def repository_root(target: str) -> str:
    """The repository of a lint target: its git top level, else the target's folder."""
    folder = target if os.path.isdir(target) else os.path.dirname(os.path.abspath(target))
    return git_top_level(folder) or os.path.abspath(folder)
