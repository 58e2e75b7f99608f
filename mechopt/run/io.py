"""The one place where mechopt writes files: atomically, or not at all.

Every file is written under a temporary name in its destination folder and
renamed over the final name (``os.replace`` is atomic on POSIX), so a killed
run never leaves a truncated CSV, JSON or PNG under its final name.
"""
from __future__ import annotations

import contextlib
import fnmatch
import hashlib
import json
import os
import shutil
import tempfile
import time
import uuid
from pathlib import Path

__all__ = ["atomic_path", "write_text", "write_csv", "write_json", "save_figure", "prepare_out_dir",
           "out_lock", "sweep_temporaries", "LOCK_NAME", "MANIFEST", "read_manifest", "claim_out",
           "output_set", "own", "run_in", "sha256_file", "differences"]

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
    a run was killed (``.<name>.<random>.tmp``) and the staging folders of
    :func:`output_set` (``.staging-<random>``); returns how many. Only runs holding
    the folder's lock call it, so no live writer's file is removed."""
    n = 0
    folder = Path(folder)
    if folder.is_dir():
        for p in folder.glob(f"{_STAGING}*"):
            if p.is_dir():
                shutil.rmtree(p, ignore_errors=True)
                n += 1
        for p in folder.rglob(".*.tmp"):
            if p.is_file():
                with contextlib.suppress(OSError):
                    p.unlink()
                    n += 1
    return n


# ------------------------------------------------------------ run manifests
#: the file that says which run an output folder holds and whether its outputs are
#: complete: written when a run starts (``"status": "running"``) and, once every
#: output is in place, rewritten last (``"complete"``, with each file's sha256)
MANIFEST = "manifest.json"
_STAGING = ".staging-"


def sha256_file(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def read_manifest(folder) -> dict | None:
    """The folder's :data:`MANIFEST`, or None if it has none. An unreadable one is a
    one-line ValueError (it is never guessed at)."""
    path = Path(folder) / MANIFEST
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        return None
    except (OSError, ValueError) as exc:
        raise ValueError(f"{str(path)!r} is unreadable ({type(exc).__name__}); move it away") from None
    if not isinstance(data, dict) or not {"kind", "key", "status", "run_id"} <= set(data):
        raise ValueError(f"{str(path)!r} is not a mechopt run manifest; move it away")
    return data


def _flat(d, prefix=""):
    out = {}
    for k, v in (d.items() if isinstance(d, dict) else ()):
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flat(v, name + "."))
        else:
            out[name] = v
    return out


def differences(old: dict, new: dict, limit: int = 6) -> str:
    """``"seed 3 -> 4, algorithm.pop_size 20 -> 40"``: the keys where two settings
    dictionaries differ (nested keys dotted), for one-line messages."""
    a, b = _flat(old), _flat(new)
    diff = [f"{k} {a.get(k, '(none)')} -> {b.get(k, '(none)')}"
            for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    more = f", and {len(diff) - limit} more" if len(diff) > limit else ""
    return ", ".join(diff[:limit]) + more


def _present(folder: Path, patterns) -> list[str]:
    return sorted(p.name for p in folder.iterdir()
                  if any(fnmatch.fnmatch(p.name, pat) for pat in patterns)) if folder.is_dir() else []


def claim_out(folder, kind: str, key: dict, outputs, overwrite: bool = False) -> dict:
    """Take ``folder`` for a run of ``kind`` whose result is fixed by ``key`` (plain
    data: the problem, its settings, the algorithm, the seed ...); returns the run's
    manifest, written with ``"status": "running"``.

    * A folder whose manifest holds the same kind and key is the same run: its files
      are replaced as the run writes them (a rerun gives the same result).
    * A manifest of another run is refused with the differences, unless ``overwrite``:
      then the files it lists (those mechopt wrote, checked by their sha256) are
      removed first.
    * Files matching ``outputs`` (glob patterns: the names this kind writes) that no
      manifest accounts for (another program's, an older mechopt's, a foreign
      ``checkpoint.pkl``) are refused, never removed.
    """
    folder = Path(folder)
    key = json.loads(json.dumps(key, sort_keys=True, default=str))  # as the manifest will hold it
    old = read_manifest(folder)
    present = [n for n in _present(folder, outputs) if n != MANIFEST]
    mine = set((old or {}).get("files", {})) | set((old or {}).get("owned", []))
    foreign = [n for n in present if n not in mine]
    if foreign:
        raise ValueError(f"--out {str(folder)!r} holds {', '.join(foreign)}, which no mechopt run "
                         f"manifest accounts for; move them away or choose another folder")
    if old is not None and (old["kind"] != kind or old["key"] != key):
        what = (f"a {old['kind']} run" if old["kind"] != kind
                else f"another {kind} run ({differences(old['key'], key)})")
        if not overwrite:
            raise ValueError(f"--out {str(folder)!r} holds {what}; pass --overwrite to replace it, "
                             f"or choose another folder")
        for name, digest in old.get("files", {}).items():
            p = folder / name
            if p.is_file() and sha256_file(p) == digest:
                p.unlink()
        for name in old.get("owned", []):
            with contextlib.suppress(FileNotFoundError):
                (folder / name).unlink()
        old = None
    manifest = {"kind": kind, "key": key, "status": "running", "run_id": uuid.uuid4().hex,
                "started": time.strftime("%Y-%m-%dT%H:%M:%S%z")}
    if old is not None:  # the same run again: the earlier files stay ours until replaced
        manifest["files"] = old.get("files", {})
        manifest["owned"] = old.get("owned", [])
    from mechopt import __version__

    manifest["mechopt"] = __version__
    write_json(manifest, folder / MANIFEST)
    return manifest


@contextlib.contextmanager
def run_in(folder, kind: str, key: dict, outputs, overwrite: bool = False):
    """:func:`claim_out` for the length of a block, yielding the manifest. If the block
    fails (an error, an interrupt) before the run has written anything it owns (a
    checkpoint) or completed its set, the folder's manifest is put back as it was
    (removed if there was none): a run that failed leaves nothing. A run killed
    outright leaves its ``running`` manifest, which ``--resume`` recognises."""
    path = Path(folder) / MANIFEST
    before = path.read_bytes() if path.is_file() else None
    manifest = claim_out(folder, kind, key, outputs, overwrite)
    owned = list(manifest.get("owned", []))
    try:
        yield manifest
    except BaseException:
        if manifest.get("status") != "complete" and manifest.get("owned", []) == owned:
            if before is None:
                with contextlib.suppress(FileNotFoundError):
                    path.unlink()
            else:
                with atomic_path(path) as tmp:
                    tmp.write_bytes(before)
        raise


def own(folder, manifest: dict, name: str) -> None:
    """Record in the manifest that the run wrote ``name`` outside :func:`output_set`
    (its checkpoint): a later run may then remove it, a foreign file of that name it
    may not."""
    if name not in manifest.setdefault("owned", []):
        manifest["owned"].append(name)
        write_json(manifest, Path(folder) / MANIFEST)


@contextlib.contextmanager
def output_set(folder, manifest: dict):
    """Write a run's outputs as one set: yields a staging folder inside ``folder``;
    when the block ends without error, every file written there is renamed into
    ``folder`` and the manifest is rewritten last with ``"status": "complete"`` and
    each file's sha256. On an error (no space, a kill) the staging folder is removed
    and nothing of the set reaches ``folder``; the manifest still says ``running``,
    so a set cut short by a kill between the renames never reads as complete."""
    folder = Path(folder)
    stage = Path(tempfile.mkdtemp(prefix=_STAGING, dir=folder))
    try:
        yield stage
        names = sorted(p.name for p in stage.iterdir() if p.is_file())
        files = {n: sha256_file(stage / n) for n in names}
        for n in names:
            os.replace(stage / n, folder / n)
        _fsync(folder)
        manifest.update(status="complete", files={**manifest.get("files", {}), **files},
                        finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
        write_json(manifest, folder / MANIFEST)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


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
