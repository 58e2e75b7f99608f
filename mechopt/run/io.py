"""The one place where mechopt writes files: atomically, or not at all, and only its own.

Every file is written under a temporary name in its destination folder and
renamed over the final name (``os.replace`` is atomic on POSIX), so a killed
run never leaves a truncated CSV, JSON or PNG under its final name.

What a run may touch (file safety):

* it removes or replaces only files it can prove it wrote: the names of its
  folder's :data:`MANIFEST`, which is authenticated with the user's key
  (:mod:`mechopt.run.keys`); each name is a plain name inside the folder (no
  ``/``, ``..`` or absolute path), matches the run's output names, is a regular
  file (never a link or a folder) and, for a finished output, still has the
  sha256 the manifest recorded. A manifest that is not authenticated (written
  by hand, by another user, by an older mechopt) vouches for nothing;
* temporary names carry the run's tag (:func:`run_tag`), and the sweep removes
  only the temporaries of this run and of the dead run whose lock it takes over;
* a folder is removed (:func:`remove_created`) only if this process created it
  and it is empty: results are never deleted because a run failed;
* every file read back is checked first to be a regular file of bounded size
  (:func:`read_bytes`): a FIFO, a device or a sparse giant is refused with one
  line, never read.
"""
from __future__ import annotations

import contextlib
import errno
import fnmatch
import hashlib
import json
import math
import os
import shutil
import socket
import stat
import tempfile
import time
import uuid
from pathlib import Path

# bounded reads live in the core layer (user inputs, such as a task's points, are read there too)
from mechopt.core.reading import read_bytes

__all__ = ["plain_json", "atomic_path", "write_text", "write_csv", "write_json", "save_figure", "prepare_out_dir",
           "out_lock", "sweep_temporaries", "LOCK_NAME", "MANIFEST", "read_manifest", "claim_out",
           "output_set", "own", "run_in", "sha256_file", "differences", "read_bytes", "read_json",
           "run_tag", "remove_created", "created_folders", "write_manifest", "authentic",
           "MAX_JSON_BYTES", "TAG_ENV"]

#: the lock file a run keeps in its output folder (an OS lock, ``fcntl.flock``, on it;
#: its text names the holder: pid, host, start time and run tag)
LOCK_NAME = ".mechopt.lock"
#: the environment variable that carries the run's tag to the processes it starts
TAG_ENV = "MECHOPT_RUN_TAG"
#: the largest JSON file mechopt reads back (manifest, run.json, stamps) [bytes]
MAX_JSON_BYTES = 16 << 20
#: how deep below an output folder the sweep looks for its temporaries (a
#: reproduction writes ``out/<paper>/<run>/.staging-*/``)
SWEEP_DEPTH = 4


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def run_tag() -> str:
    """The tag of this run's temporary names: the one :func:`out_lock` set (inherited
    by the worker processes through :data:`TAG_ENV`), else ``p<pid>``.

    Returns
    -------
    str
        The tag.
    """
    tag = os.environ.get(TAG_ENV, "")
    return tag if tag.isalnum() and len(tag) <= 40 else f"p{os.getpid()}"


def _tmp_prefix(name: str) -> str:
    return f".{name}.{run_tag()}."


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path next to ``path``; rename it to ``path`` on success.

    Parameters
    ----------
    path : str or Path
        The final path.

    Yields
    ------
    Path
        The temporary path to write.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=_tmp_prefix(path.name), suffix=".tmp", dir=path.parent)
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
    """Write ``text`` to ``path`` atomically (:func:`atomic_path`).

    Parameters
    ----------
    path : str or Path
        The file.
    text : str
        Its content.

    Returns
    -------
    Path
        The file written.
    """
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def write_csv(df, path, **kw) -> Path:
    """A DataFrame as CSV, no index, every float in full precision: the shortest text
    that reads back as the same double (Python's ``repr``, pandas' default), so that
    ``pandas.read_csv`` of the file gives the written numbers bit for bit (a margin
    re-read from ``front.csv`` is the computed one, not one rounded to 10 digits).
    Written atomically (:func:`atomic_path`).

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    path : str or Path
        The file.
    **kw
        More keywords of :meth:`pandas.DataFrame.to_csv` (``index`` defaults to False).

    Returns
    -------
    Path
        The file written.
    """
    kw.setdefault("index", False)
    with atomic_path(path) as tmp:
        df.to_csv(tmp, **kw)
    return Path(path)


def plain_json(x):
    """``x`` as plain JSON data: mappings with string keys, lists for tuples, NumPy
    scalars as Python numbers, NaN and infinities as None (JSON has none).

    Parameters
    ----------
    x : object
        Nested data.

    Returns
    -------
    object
        Plain JSON data.
    """
    import numpy as np

    if isinstance(x, dict):
        return {str(k): plain_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [plain_json(v) for v in x]
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, np.bool_):
        return bool(x)
    return x


def write_json(obj, path) -> Path:
    """Write ``obj`` as indented JSON with sorted keys to ``path`` atomically.

    Parameters
    ----------
    obj : object
        Plain JSON data (NumPy numbers are written as floats).
    path : str or Path
        The file.

    Returns
    -------
    Path
        The file written.
    """
    return write_text(path, json.dumps(obj, indent=2, sort_keys=True, default=float) + "\n")


def save_figure(fig, path, dpi: int = 120) -> Path:
    """Save a matplotlib figure atomically (and close it if pyplot manages it).

    Parameters
    ----------
    fig : Figure
        The figure.
    path : str or Path
        The image file.
    dpi : int
        Resolution.

    Returns
    -------
    Path
        The file written.
    """
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=path.suffix.lstrip(".") or "png", bbox_inches="tight")
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close(fig)
    return path


# ------------------------------------------------------------ bounded reads
def read_json(path, what: str | None = None, limit: int = MAX_JSON_BYTES, root=None):
    """The JSON value of a regular file (:func:`read_bytes`); anything unreadable or not
    JSON (bad UTF-8, nesting too deep, a number too large) is a one-line ValueError;
    FileNotFoundError passes.

    Parameters
    ----------
    path : str or Path
        The file.
    what : str, optional
        What it is, for the message.
    limit : int
        The largest size [bytes].
    root : str or Path, optional
        A folder the file must lie inside.

    Returns
    -------
    object
        The JSON value.

    Raises
    ------
    FileNotFoundError
        When it does not exist.
    ValueError
        One line, for anything unreadable or not JSON.
    """
    what = what or repr(str(path))
    data = read_bytes(path, limit, what, root)
    try:
        return json.loads(data.decode("utf-8"))
    except (ValueError, RecursionError) as exc:  # UnicodeDecodeError is a ValueError
        raise ValueError(f"{what} is not valid JSON ({type(exc).__name__})") from None


# ------------------------------------------------------------ output folders
#: the folders this process created (:func:`prepare_out_dir`), resolved, in order
_CREATED: list = []


def created_folders() -> list:
    """The folders this process created for output so far (resolved paths, outermost first).

    Returns
    -------
    list of Path
        The folders.
    """
    return list(_CREATED)


def prepare_out_dir(path) -> Path:
    """Create the output folder if needed and check that it is writable.

    Each missing folder is made by its own ``mkdir``; only those this process made
    count as its own (:func:`created_folders`, :func:`remove_created`): a folder
    another run made meanwhile is never taken for ours. Raises ValueError (one line)
    when it cannot be created or written; the empty folders it made are then removed.

    Parameters
    ----------
    path : str or Path
        The folder.

    Returns
    -------
    Path
        The folder.

    Raises
    ------
    ValueError
        One line, when it cannot be made or written to.
    """
    text = str(path)
    if not text.strip() or "\0" in text:
        raise ValueError(f"--out must name a folder, got {text!r}")
    path = Path(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        st = None
    except OSError as exc:
        raise ValueError(f"--out {text!r} is not writable: {exc.strerror or type(exc).__name__}") from None
    if st is not None and not stat.S_ISDIR(st.st_mode):
        raise ValueError(f"--out must be a folder, got the file {text!r}")
    made = []
    try:
        if st is None:
            cur = Path(path.anchor) if path.is_absolute() else Path(".")
            for part in path.parts[1 if path.is_absolute() else 0:]:
                cur = cur / part
                try:
                    os.mkdir(cur)
                except FileExistsError:
                    continue
                made.append(os.path.realpath(cur))
            if not os.path.isdir(path):
                raise NotADirectoryError(errno.ENOTDIR, "not a folder")
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        for p in reversed(made):
            with contextlib.suppress(OSError):
                os.rmdir(p)
        raise ValueError(f"--out {text!r} is not writable: {exc.strerror or type(exc).__name__}") from None
    _CREATED.extend(made)
    return path


def remove_created(since: int = 0) -> list:
    """Remove the folders this process created (those after the first ``since`` of
    :func:`created_folders`) if they are empty, and the empty folders inside them
    (e.g. a paper's folder a worker made); a folder holding anything (another run's
    files, finished results) stays, and nothing below a folder holding a run's lock
    (:data:`LOCK_NAME`: a run started there meanwhile may be about to write into its
    empty folders) is touched. Links are not followed. Returns the folders removed.

    Parameters
    ----------
    since : int
        How many of :func:`created_folders` to keep.

    Returns
    -------
    list of Path
        The folders removed.
    """
    removed = []
    for top in reversed(_CREATED[since:]):
        if not os.path.isdir(top) or os.path.islink(top):
            continue
        empty_candidates = []
        for here, dirs, files in os.walk(top, followlinks=False):
            if LOCK_NAME in files:
                dirs[:] = []
                continue
            dirs[:] = [d for d in dirs if not os.path.islink(os.path.join(here, d))]
            empty_candidates += [os.path.join(here, d) for d in dirs]
        for p in reversed(empty_candidates):  # innermost first
            with contextlib.suppress(OSError):
                os.rmdir(p)
                removed.append(p)
        with contextlib.suppress(OSError):
            os.rmdir(top)
            removed.append(top)
    del _CREATED[since:]
    return removed


def sweep_temporaries(folder, tag: str | None = None) -> int:
    """Remove the temporaries of the run tagged ``tag`` (default: this run's,
    :func:`run_tag`) in ``folder`` and up to :data:`SWEEP_DEPTH` folders below:
    files ``.<name>.<tag>.<random>.tmp`` (:func:`atomic_path`) and staging folders
    ``.staging-<tag>-<random>`` (:func:`output_set`). Nothing else is removed (another
    program's or another run's temporaries stay); links are not followed. Returns how
    many were removed.

    Parameters
    ----------
    folder : str or Path
        The output folder.
    tag : str, optional
        The run's tag (default: this run's).

    Returns
    -------
    int
        The number of temporaries removed.
    """
    tag = tag or run_tag()
    if not tag.isalnum():
        return 0
    folder = Path(folder)
    n = 0
    staging = f"{_STAGING}{tag}-"
    base_depth = str(folder).rstrip(os.sep).count(os.sep)
    for here, dirs, files in os.walk(folder, followlinks=False):
        for d in list(dirs):
            p = os.path.join(here, d)
            if d.startswith(staging) and not os.path.islink(p):
                shutil.rmtree(p, ignore_errors=True)
                dirs.remove(d)
                n += 1
        if here.rstrip(os.sep).count(os.sep) - base_depth >= SWEEP_DEPTH:
            dirs[:] = []
        for f in files:
            if f.startswith(".") and f.endswith(".tmp") and f".{tag}." in f:
                p = os.path.join(here, f)
                with contextlib.suppress(OSError):
                    if stat.S_ISREG(os.lstat(p).st_mode):
                        os.unlink(p)
                        n += 1
    return n


# ------------------------------------------------------------ run manifests
#: the file that says which run an output folder holds and whether its outputs are
#: complete: written when a run starts (``"status": "running"``) and, once every
#: output is in place, rewritten last (``"complete"``, with each file's sha256);
#: authenticated (``"mac"``) with the user's key (:mod:`mechopt.run.keys`)
MANIFEST = "manifest.json"
_STAGING = ".staging-"
_MAC_CONTEXT = b"mechopt-manifest 1\n"


def sha256_file(path) -> str:
    """The SHA-256 of a file's bytes.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    str
        The digest (hex).
    """
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _plain_name(name) -> bool:
    """A file name inside the folder: a non-empty string without ``/`` or NUL, not ``.``
    or ``..``."""
    return (isinstance(name, str) and 0 < len(name) <= 255 and "/" not in name and "\0" not in name
            and name not in (".", ".."))


def _is_digest(v) -> bool:
    return isinstance(v, str) and len(v) == 64 and all(c in "0123456789abcdef" for c in v)


def read_manifest(folder) -> dict | None:
    """The folder's :data:`MANIFEST`, or None if it has none. An unreadable one (not a
    regular file, too large, not JSON, not of the manifest's shape: names that are
    not plain file names, ``files`` not a mapping of names to sha256 ...) is a
    one-line ValueError (it is never guessed at). Whether it is authentic is
    :func:`authentic`.

    Parameters
    ----------
    folder : str or Path
        The output folder.

    Returns
    -------
    dict or None
        The manifest.

    Raises
    ------
    ValueError
        One line, for an unreadable manifest.
    """
    path = Path(folder) / MANIFEST
    where = repr(str(path))
    try:
        data = read_json(path, where)
    except FileNotFoundError:
        return None
    except ValueError as exc:
        raise ValueError(f"{exc}; move it away") from None
    ok = (isinstance(data, dict) and {"kind", "key", "status", "run_id"} <= set(data)
          and isinstance(data["kind"], str) and isinstance(data["key"], dict)
          and data["status"] in ("running", "complete") and isinstance(data["run_id"], str)
          and isinstance(data.get("files", {}), dict)
          and all(_plain_name(k) and _is_digest(v) for k, v in data.get("files", {}).items())
          and isinstance(data.get("owned", []), list) and all(_plain_name(n) for n in data.get("owned", []))
          and isinstance(data.get("mac", ""), str))
    if not ok:
        raise ValueError(f"{where} is not a mechopt run manifest; move it away")
    return data


def _manifest_mac(manifest: dict, key: bytes) -> str:
    from mechopt.run import keys

    body = {k: v for k, v in manifest.items() if k != "mac"}
    text = json.dumps(body, sort_keys=True, separators=(",", ":"), default=float, allow_nan=True)
    return keys.mac(key, _MAC_CONTEXT, text.encode("utf-8"))


def authentic(manifest: dict | None) -> bool:
    """Whether ``manifest`` was written by mechopt under this user's key (its ``mac``).

    Parameters
    ----------
    manifest : dict or None
        A manifest.

    Returns
    -------
    bool
        Whether its MAC verifies.
    """
    import hmac as _hmac

    from mechopt.run import keys

    if not isinstance(manifest, dict) or not isinstance(manifest.get("mac"), str):
        return False
    key = keys.load_key(create=False)
    if key is None:
        return False
    try:
        want = _manifest_mac(manifest, key)
    except (TypeError, ValueError, RecursionError):
        return False
    return _hmac.compare_digest(want, manifest["mac"])


def write_manifest(manifest: dict, folder) -> Path:
    """Write ``manifest`` (updated in place with its ``mac``) as the folder's
    :data:`MANIFEST`, authenticated with the user's key (made if missing).

    Parameters
    ----------
    manifest : dict
        The manifest (its ``mac`` is set).
    folder : str or Path
        The output folder.

    Returns
    -------
    Path
        The manifest file.
    """
    from mechopt.run import keys

    key = keys.load_key(create=True)
    plain = json.loads(json.dumps({k: v for k, v in manifest.items() if k != "mac"}, default=float))
    manifest["mac"] = _manifest_mac(plain, key)
    return write_json({**plain, "mac": manifest["mac"]}, Path(folder) / MANIFEST)


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
    dictionaries differ (nested keys dotted), for one-line messages.

    Parameters
    ----------
    old : dict
        Settings.
    new : dict
        Other settings.
    limit : int
        The most keys named.

    Returns
    -------
    str
        The differences.
    """
    a, b = _flat(old), _flat(new)
    diff = [f"{k} {a.get(k, '(none)')} -> {b.get(k, '(none)')}"
            for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    more = f", and {len(diff) - limit} more" if len(diff) > limit else ""
    return ", ".join(diff[:limit]) + more


def _present(folder: Path, patterns) -> list[str]:
    return sorted(p.name for p in folder.iterdir()
                  if any(fnmatch.fnmatch(p.name, pat) for pat in patterns)) if folder.is_dir() else []


def _remove_ours(folder: Path, name: str, digest: str | None, outputs) -> bool:
    """Remove ``folder/name`` if it is one of the run's outputs: a plain name matching
    ``outputs``, a regular file (not a link or folder) and, with ``digest``, of that
    sha256. Returns whether it was removed."""
    if not _plain_name(name) or not any(fnmatch.fnmatch(name, pat) for pat in outputs):
        return False
    p = folder / name
    try:
        if not stat.S_ISREG(os.lstat(p).st_mode):
            return False
        if digest is not None and sha256_file(p) != digest:
            return False
        os.unlink(p)
    except OSError:
        return False
    return True


def claim_out(folder, kind: str, key: dict, outputs, overwrite: bool = False) -> dict:
    """Take ``folder`` for a run of ``kind`` whose result is fixed by ``key`` (plain
    data: the problem, its settings, the algorithm, the seed ...); returns the run's
    manifest, written with ``"status": "running"``.

    * A folder whose authentic manifest holds the same kind and key is the same run:
      its files are replaced as the run writes them (a rerun gives the same result).
    * A manifest of another run is refused with the differences, unless ``overwrite``:
      then the files it lists are removed first, if it is authentic (see the module
      docstring: plain names matching ``outputs``, regular files, the recorded
      sha256); a manifest that is not authentic is replaced and nothing it lists is
      removed.
    * Files matching ``outputs`` (glob patterns: the names this kind writes) that no
      authentic manifest accounts for (another program's, an older mechopt's, a
      foreign ``checkpoint.pkl``) are refused, never removed.

    The user's key is loaded (made if missing) first: an unsafe key, or a key folder
    where none can be made, is refused before the run does any work.

    Parameters
    ----------
    folder : str or Path
        The output folder.
    kind : str
        The run's kind (``"optimize"``, ``"design"``, ...).
    key : dict
        What fixes the run's result.
    outputs : sequence of str
        Glob patterns of the files this kind writes.
    overwrite : bool
        Replace another run's files.

    Returns
    -------
    dict
        The run's manifest.

    Raises
    ------
    ValueError
        One line, for a folder holding another run (without ``overwrite``), foreign files,
        or an unsafe key.
    """
    from mechopt.run import keys

    keys.load_key(create=True)  # one line now rather than at the first checkpoint
    folder = Path(folder)
    key = json.loads(json.dumps(key, sort_keys=True, default=str))  # as the manifest will hold it
    old = read_manifest(folder)
    trusted = authentic(old)
    present = [n for n in _present(folder, outputs) if n != MANIFEST]
    mine = (set(old.get("files", {})) | set(old.get("owned", []))) if trusted else set()
    foreign = [n for n in present if n not in mine]
    if foreign:
        why = (f" (its {MANIFEST} is not authenticated by your key: written by hand, by another "
               f"user or an older mechopt)" if old is not None and not trusted else "")
        raise ValueError(f"--out {str(folder)!r} holds {', '.join(foreign)}, which no mechopt run "
                         f"manifest accounts for{why}; move them away or choose another folder")
    if old is not None and (not trusted or old["kind"] != kind or old["key"] != key):
        what = ("a run manifest not authenticated by your key" if not trusted
                else f"{'an' if old['kind'][:1] in 'aeiou' else 'a'} {old['kind']} run" if old["kind"] != kind
                else f"another {kind} run ({differences(old['key'], key)})")
        if not overwrite:
            raise ValueError(f"--out {str(folder)!r} holds {what}; pass --overwrite to replace it, "
                             f"or choose another folder")
        if trusted:
            for name, digest in old.get("files", {}).items():
                _remove_ours(folder, name, digest, outputs)
            for name in old.get("owned", []):
                _remove_ours(folder, name, None, outputs)
        old = None
    manifest = {"kind": kind, "key": key, "status": "running", "run_id": uuid.uuid4().hex,
                "started": time.strftime("%Y-%m-%dT%H:%M:%S%z")}
    if old is not None:  # the same run again: the earlier files stay ours until replaced
        manifest["files"] = old.get("files", {})
        manifest["owned"] = old.get("owned", [])
    from mechopt import __version__

    manifest["mechopt"] = __version__
    write_manifest(manifest, folder)
    return manifest


@contextlib.contextmanager
def run_in(folder, kind: str, key: dict, outputs, overwrite: bool = False):
    """:func:`claim_out` for the length of a block, yielding the manifest. If the block
    fails (an error, an interrupt) before the run has written anything it owns (a
    checkpoint) or completed its set, the folder's manifest is put back as it was
    (removed if there was none): a run that failed leaves nothing. A run killed
    outright leaves its ``running`` manifest, which ``--resume`` recognises.

    Parameters
    ----------
    folder : str or Path
        The output folder.
    kind : str
        The run's kind.
    key : dict
        What fixes the run's result.
    outputs : sequence of str
        Glob patterns of the files this kind writes.
    overwrite : bool
        Replace another run's files.

    Yields
    ------
    dict
        The run's manifest.

    Raises
    ------
    ValueError
        As :func:`claim_out`.
    """
    path = Path(folder) / MANIFEST
    try:
        before = read_bytes(path, MAX_JSON_BYTES, repr(str(path)))
    except FileNotFoundError:
        before = None
    except ValueError as exc:
        raise ValueError(f"{exc}; move it away") from None
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
    may not.

    Parameters
    ----------
    folder : str or Path
        The output folder.
    manifest : dict
        The run's manifest.
    name : str
        The file's name.

    Raises
    ------
    ValueError
        For a name that is not a plain file name.
    """
    if not _plain_name(name):
        raise ValueError(f"not a plain file name: {name!r}")
    if name not in manifest.setdefault("owned", []):
        manifest["owned"].append(name)
        write_manifest(manifest, folder)


@contextlib.contextmanager
def output_set(folder, manifest: dict):
    """Write a run's outputs as one set: yields a staging folder inside ``folder``;
    when the block ends without error, every file written there is renamed into
    ``folder`` and the manifest is rewritten last with ``"status": "complete"`` and
    each file's sha256. On an error (no space, a kill) the staging folder is removed
    and nothing of the set reaches ``folder``; the manifest still says ``running``,
    so a set cut short by a kill between the renames never reads as complete.

    Parameters
    ----------
    folder : str or Path
        The output folder.
    manifest : dict
        The run's manifest (:func:`claim_out`).

    Yields
    ------
    Path
        The staging folder to write the outputs into.
    """
    folder = Path(folder)
    stage = Path(tempfile.mkdtemp(prefix=f"{_STAGING}{run_tag()}-", dir=folder))
    try:
        yield stage
        names = sorted(p.name for p in stage.iterdir() if p.is_file() and not p.is_symlink())
        files = {n: sha256_file(stage / n) for n in names}
        for n in names:
            os.replace(stage / n, folder / n)
        _fsync(folder)
        manifest.update(status="complete", files={**manifest.get("files", {}), **files},
                        finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
        write_manifest(manifest, folder)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


# ------------------------------------------------------------ the folder's lock
def _holder(fd) -> dict:
    """What a lock file says of its holder: ``{"pid", "host", "started", "tag"}``
    (strings; empty when unreadable)."""
    try:
        text = os.pread(fd, 4096, 0).decode("utf-8", "replace")
    except OSError:
        text = ""
    fields = text.split()
    return dict(zip(("pid", "host", "started", "tag"), fields + [""] * 4))


def _take_lock(lock: Path, folder: Path):
    """Open ``lock`` and take its OS lock (``fcntl.flock``, exclusive, without
    waiting); returns ``(fd, previous holder)``. A lock file whose holder is gone
    (killed: the OS released its lock) is taken over, whatever pid it names; one
    held by a live process, on this host or another sharing the filesystem, is a
    one-line ValueError."""
    import fcntl

    flags = os.O_RDWR | os.O_CREAT | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    for _ in range(20):
        try:
            fd = os.open(lock, flags, 0o644)
        except OSError as exc:
            why = "is a symbolic link" if exc.errno == errno.ELOOP else f"cannot be opened ({exc.strerror})"
            raise ValueError(f"the lock {str(lock)!r} {why}; remove it") from None
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise ValueError(f"the lock {str(lock)!r} is not a regular file; remove it")
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                if exc.errno not in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                    raise ValueError(f"the lock {str(lock)!r} cannot be taken ({exc.strerror})") from None
                who = _holder(fd)
                pid = who["pid"] if who["pid"].isdigit() and len(who["pid"]) < 12 else "?"
                host = f" on {who['host']}" if who["host"] else ""
                raise ValueError(f"--out {str(folder)!r} is in use by another mechopt run (pid {pid}{host}); "
                                 f"wait for it or choose another folder") from None
            try:  # the name may have been removed (or replaced) by the holder we waited on
                same = os.stat(lock, follow_symlinks=False).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if same:
                return fd, _holder(fd)
        except BaseException:
            os.close(fd)
            raise
        os.close(fd)
    raise ValueError(f"--out {str(folder)!r} is in use by another mechopt run")  # pragma: no cover


@contextlib.contextmanager
def out_lock(folder):
    """Hold the output folder for one run: a second run on the same folder fails at
    once with one line (ValueError). The lock is the OS's (``fcntl.flock`` on
    :data:`LOCK_NAME`, released by the kernel when its holder dies, also across hosts
    on a shared filesystem that supports it); the file's text names the holder (pid,
    host, start time, run tag) for the message. The run's tag (:func:`run_tag`) is set
    for the block; the temporaries of the dead run whose lock is taken over, and this
    run's own, are swept (:func:`sweep_temporaries`) when the lock is taken and on
    every exit.

    Parameters
    ----------
    folder : str or Path
        The output folder.

    Yields
    ------
    Path
        The folder, while it is held.

    Raises
    ------
    ValueError
        One line, when another run holds the folder.
    """
    folder = prepare_out_dir(folder)  # one-line ValueError if it cannot be made or written
    lock = folder / LOCK_NAME
    fd, before = _take_lock(lock, folder)
    tag = uuid.uuid4().hex[:20]
    try:
        text = f"{os.getpid()} {socket.gethostname() or '-'} {int(time.time())} {tag}\n".encode()
        os.ftruncate(fd, 0)
        if os.pwrite(fd, text, 0) != len(text):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(lock))
    except BaseException:  # a full disk: no empty lock file is left behind
        with contextlib.suppress(OSError):
            os.unlink(lock)
        os.close(fd)
        raise
    previous = os.environ.get(TAG_ENV)
    os.environ[TAG_ENV] = tag
    try:
        if before["tag"].isalnum():
            sweep_temporaries(folder, before["tag"])  # the killed run's leftovers
        yield folder
    finally:
        with contextlib.suppress(OSError):
            sweep_temporaries(folder, tag)
        if previous is None:
            os.environ.pop(TAG_ENV, None)
        else:
            os.environ[TAG_ENV] = previous
        try:
            if os.stat(lock, follow_symlinks=False).st_ino == os.fstat(fd).st_ino:
                os.unlink(lock)
        except OSError:
            pass
        os.close(fd)
