"""The one place where mechopt writes files: atomically, or not at all.

Every file is written under a temporary name in its destination folder and
renamed over the final name (``os.replace`` is atomic on POSIX), so a killed
run never leaves a truncated CSV, JSON or PNG under its final name.
"""
from __future__ import annotations

import contextlib
import json
import os
import tempfile
from pathlib import Path

__all__ = ["atomic_path", "write_text", "write_csv", "write_json", "save_figure", "prepare_out_dir",
           "out_lock", "sweep_temporaries", "LOCK_NAME"]

#: the lock file a run keeps in its output folder (holds the owner's pid)
LOCK_NAME = ".mechopt.lock"


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path next to ``path``; rename it to ``path`` on success."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; give the usual mode
        _fsync(tmp)  # the data is on disk before the name points at it (power loss)
        os.replace(tmp, path)
        _fsync(path.parent)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def _fsync(path):
    """fsync a file or a folder (best effort where the OS does not allow it)."""
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_text(path, text: str) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def write_csv(df, path, **kw) -> Path:
    """A DataFrame as CSV (floats with full precision, no index)."""
    kw.setdefault("index", False)
    kw.setdefault("float_format", "%.10g")
    with atomic_path(path) as tmp:
        df.to_csv(tmp, **kw)
    return Path(path)


def write_json(obj, path) -> Path:
    return write_text(path, json.dumps(obj, indent=2, sort_keys=True, default=float) + "\n")


def save_figure(fig, path, dpi: int = 120) -> Path:
    """Save a matplotlib figure atomically (and close it if pyplot manages it)."""
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=path.suffix.lstrip(".") or "png", bbox_inches="tight")
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close(fig)
    return path


def prepare_out_dir(path) -> Path:
    """Create the output folder if needed and check that it is writable.

    Raises ValueError (one line) when it cannot be created or written; nothing
    is left behind in that case.
    """
    if not str(path).strip():
        raise ValueError(f"--out must name a folder, got {str(path)!r}")
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"--out must be a folder, got the file {str(path)!r}")
    created = []  # the folders mkdir makes, innermost first
    p = path.absolute()
    while not p.exists() and p != p.parent:
        created.append(p)
        p = p.parent
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        for p in created:
            with contextlib.suppress(OSError):
                p.rmdir()
        raise ValueError(f"--out {str(path)!r} is not writable: {exc.strerror}") from None
    return path


def sweep_temporaries(folder) -> int:
    """Remove the temporary files :func:`atomic_path` left in ``folder`` (and below) when
    a run was killed (``.<name>.<random>.tmp``); returns how many. Only runs holding
    the folder's lock call it, so no live writer's file is removed."""
    n = 0
    folder = Path(folder)
    if folder.is_dir():
        for p in folder.rglob(".*.tmp"):
            if p.is_file():
                with contextlib.suppress(OSError):
                    p.unlink()
                    n += 1
    return n


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # alive, another user's
        return True
    return True


@contextlib.contextmanager
def out_lock(folder):
    """Hold the output folder for one run: a second run on the same folder fails at
    once with one line (ValueError). The lock file holds the owner's pid; a lock
    whose owner is dead (a killed run) is stale and taken over. Temporary files of
    killed runs are swept when the lock is taken and on every exit."""
    folder = prepare_out_dir(folder)  # one-line ValueError if it cannot be made or written
    lock = folder / LOCK_NAME
    for _ in range(2):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            try:
                pid = int(lock.read_text().strip() or "0")
            except (OSError, ValueError):
                pid = 0
            if pid and pid != os.getpid() and _pid_alive(pid):
                raise ValueError(f"--out {str(folder)!r} is in use by another mechopt run (pid "
                                 f"{pid}); wait for it or choose another folder") from None
            with contextlib.suppress(FileNotFoundError):
                lock.unlink()  # stale: its owner is gone
            continue
        with os.fdopen(fd, "w") as fh:
            fh.write(f"{os.getpid()}\n")
        break
    else:  # pragma: no cover - a race with another run taking over the same stale lock
        raise ValueError(f"--out {str(folder)!r} is in use by another mechopt run")
    sweep_temporaries(folder)
    try:
        yield folder
    finally:
        sweep_temporaries(folder)
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()
