"""Reading a file that a stranger may have placed: a regular file of bounded size, or
a one-line ValueError, never a hang.

``open(path).read()`` blocks for ever on a FIFO without a writer, reads without end
from ``/dev/zero`` and loads a 20 GB sparse file whole; through a link it reads
whatever the link names. :func:`read_bytes` opens without following a final link
and without blocking (``O_NOFOLLOW | O_NONBLOCK``), checks with ``fstat`` that the
file is regular and within a stated size, and only then reads (and stops past the
limit should the file grow). Used for every file mechopt reads back (run manifests,
checkpoints, run.json, the report's figures) and meant for user inputs (a task's
points CSV).
"""
from __future__ import annotations

import errno
import os
import stat

__all__ = ["read_bytes", "open_regular", "inside"]


def open_regular(path, what: str, limit: int):
    """``(fd, size)`` of ``path`` opened for reading if it is a regular file (not a
    link, FIFO, device or folder) of at most ``limit`` bytes; FileNotFoundError passes,
    anything else is a one-line ValueError. Opening never blocks (O_NONBLOCK: a FIFO
    without a writer does not hang the open).

    Parameters
    ----------
    path : str or Path
        The file.
    what : str
        What it is, for the message.
    limit : int
        The largest size [bytes].

    Returns
    -------
    fd : int
        An open file descriptor (the caller closes it).
    size : int
        The size [bytes].

    Raises
    ------
    FileNotFoundError
        When it does not exist.
    ValueError
        One line, for anything but a regular file within the limit.
    """
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise ValueError(f"{what} is a symbolic link; mechopt reads only regular files") from None
        raise ValueError(f"{what} is unreadable ({exc.strerror or type(exc).__name__})") from None
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise ValueError(f"{what} is a folder, not a file")
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{what} is not a regular file (a FIFO, a device or a socket); not read")
        if st.st_size > limit:
            raise ValueError(f"{what} is larger than {limit:,} bytes ({st.st_size:,}); not read")
    except BaseException:
        os.close(fd)
        raise
    return fd, st.st_size


def inside(path, root) -> bool:
    """``path`` (its folder resolved, links followed) lies inside ``root`` (resolved).

    Parameters
    ----------
    path : str or Path
        A path.
    root : str or Path
        A folder.

    Returns
    -------
    bool
        Whether it lies inside.
    """
    base = os.path.realpath(root)
    here = os.path.realpath(os.path.dirname(os.path.abspath(path)))
    return here == base or here.startswith(base.rstrip(os.sep) + os.sep)


def read_bytes(path, limit: int, what: str | None = None, root=None) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes.

    Parameters
    ----------
    path : path
        The file; a symbolic link, FIFO, device, socket or folder is refused.
    limit : int
        The largest size read [bytes] (checked before reading, and while reading).
    what : str, optional
        How the one-line message names the file (default: the path, quoted).
    root : path, optional
        A folder the file must lie in (its folder resolved): a file reached through a
        linked folder that leads outside is refused.

    Returns
    -------
    bytes

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ValueError
        One line, for anything else that is not a small regular file.
    """
    what = what or repr(str(path))
    if root is not None and not inside(path, root):
        raise ValueError(f"{what} lies outside {str(root)!r} (through a link); not read")
    fd, _ = open_regular(path, what, limit)
    try:
        parts, n = [], 0
        while True:
            block = os.read(fd, min(1 << 20, limit + 1 - n))
            if not block:
                break
            parts.append(block)
            n += len(block)
            if n > limit:
                raise ValueError(f"{what} is larger than {limit:,} bytes; not read")
    except OSError as exc:
        raise ValueError(f"{what} is unreadable ({exc.strerror or type(exc).__name__})") from None
    finally:
        os.close(fd)
    return b"".join(parts)
