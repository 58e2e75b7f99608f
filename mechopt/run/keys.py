"""The per-user secret that authenticates what a later run must trust.

Two things a run reads back are authenticated with it (HMAC-SHA256): checkpoints
(:mod:`mechopt.run.checkpoint`: unpickling runs code) and run manifests
(:mod:`mechopt.run.io`: the files a manifest lists are the only ones a run may
remove). The key lives in the user's configuration folder (:func:`key_path`:
``$MECHOPT_CONFIG_DIR``, else ``$XDG_CONFIG_HOME/mechopt``, else
``~/.config/mechopt``; the file ``checkpoint.key``, 32 random bytes in hex).

It is made on first use with mode 0600, written whole under a temporary name and
linked to its final name (a full disk leaves no empty key). A key that is empty,
shorter than :data:`KEY_BYTES`, not hex, a symbolic link, not a regular file, owned
by another user or readable/writable by group or others is refused with one line
(ValueError): an empty or public key would let anyone forge a checkpoint.
"""
from __future__ import annotations

import errno
import hashlib
import hmac
import os
import secrets
import stat
import tempfile
from pathlib import Path

__all__ = ["KEY_BYTES", "key_path", "load_key", "mac"]

#: length of a key [bytes]; a shorter one is refused
KEY_BYTES = 32
_KEY_NAME = "checkpoint.key"
#: a key file longer than this is not ours [bytes]
_MAX_KEY_FILE = 4096


def key_path() -> Path:
    """Where the key lives (see the module docstring).

    Returns
    -------
    Path
        The key file.
    """
    base = os.environ.get("MECHOPT_CONFIG_DIR")
    if not base:
        xdg = os.environ.get("XDG_CONFIG_HOME")
        base = os.path.join(xdg, "mechopt") if xdg else os.path.join(os.path.expanduser("~"), ".config",
                                                                      "mechopt")
    return Path(base) / _KEY_NAME


def _refuse(path, why: str) -> ValueError:
    return ValueError(f"the checkpoint key {str(path)!r} {why}; remove it (a new one is made at the next "
                      f"run; checkpoints written with it can then no longer be resumed)")


def load_key(create: bool) -> bytes | None:
    """The user's key; with ``create`` made if missing (None if missing otherwise).

    Parameters
    ----------
    create : bool
        Make the key when it is missing.

    Returns
    -------
    bytes or None
        The key (None when missing and not created).

    Raises
    ------
    ValueError
        One line, for a key that is unsafe or unusable (see the module docstring) or a
        key folder where no key can be made.
    """
    path = key_path()
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        return _create(path) if create else None
    except OSError as exc:
        if exc.errno == errno.ENOTDIR:  # its folder cannot exist: no key
            return _create(path) if create else None
        if exc.errno == errno.ELOOP:
            raise _refuse(path, "is a symbolic link") from None
        raise _refuse(path, f"is unreadable ({exc.strerror})") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _refuse(path, "is not a regular file")
        if st.st_uid != os.geteuid():
            raise _refuse(path, "belongs to another user")
        if st.st_mode & 0o077:
            raise _refuse(path, f"is open to group or others (mode {stat.S_IMODE(st.st_mode):04o}, "
                                f"must be 0600)")
        data = os.read(fd, _MAX_KEY_FILE + 1)
    finally:
        os.close(fd)
    text = data.decode("ascii", "replace").strip()
    if not text:
        raise _refuse(path, "is empty")
    try:
        key = bytes.fromhex(text)
    except ValueError:
        raise _refuse(path, "is not a hex key") from None
    if len(key) < KEY_BYTES:
        raise _refuse(path, f"is too short ({len(key)} bytes, at least {KEY_BYTES})")
    return key


def _create(path: Path) -> bytes:
    """A new key, written whole before its name appears (os.link fails if another
    process made one meanwhile: then that one is used)."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".new", dir=path.parent)  # mode 0600
    except OSError as exc:
        raise ValueError(f"cannot create the checkpoint key {str(path)!r}: {exc.strerror}; set "
                         f"MECHOPT_CONFIG_DIR to a writable folder") from None
    key = secrets.token_bytes(KEY_BYTES)
    try:
        try:
            with os.fdopen(fd, "w") as fh:
                fh.write(key.hex() + "\n")
                fh.flush()
                os.fsync(fh.fileno())
            os.link(tmp, path)
        except FileExistsError:  # another run made it meanwhile
            return load_key(create=False)
        except OSError as exc:
            raise ValueError(f"cannot create the checkpoint key {str(path)!r}: {exc.strerror}; set "
                             f"MECHOPT_CONFIG_DIR to a writable folder") from None
    finally:
        try:
            os.unlink(tmp)
        except OSError:
            pass
    return key


def mac(key: bytes, *parts: bytes) -> str:
    """HMAC-SHA256 (hex) of the concatenated ``parts`` under ``key``.

    Parameters
    ----------
    key : bytes
        The key.
    *parts : bytes
        The data.

    Returns
    -------
    str
        The MAC (hex).
    """
    h = hmac.new(key, b"", hashlib.sha256)
    for p in parts:
        h.update(p)
    return h.hexdigest()
