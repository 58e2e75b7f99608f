"""The compiled kernels' cache: one directory per state of the package's sources.

numba checks a cached kernel against its own source file only; the five-bar kernels
call formulas of other modules (the LCI of ``mechopt.core.indices``). These tests
copy the package, edit a formula module in the copy, and show the copy's cache
directory moves (so an edited formula is compiled afresh), while an unedited copy
keeps the directory of the original.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import mechopt
from mechopt.core import jit

PACKAGE = Path(mechopt.__file__).resolve().parent


def _cache_dir_of(root: Path, env_extra: dict) -> str:
    """``cache_dir()`` as a fresh interpreter computes it for the package under ``root``."""
    env = dict(os.environ, PYTHONPATH=str(root), **env_extra)
    code = "import mechopt.core.jit as j; print(j.cache_dir())"
    return subprocess.run([sys.executable, "-c", code], env=env, cwd=root, check=True,
                          capture_output=True, text=True).stdout.strip()


@pytest.fixture()
def package_copy(tmp_path):
    root = tmp_path / "copy"
    shutil.copytree(PACKAGE, root / "mechopt", ignore=shutil.ignore_patterns("__pycache__"))
    return root


def test_an_edited_formula_module_moves_the_cache(package_copy, tmp_path):
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    before = _cache_dir_of(package_copy, env)
    assert before == str(Path(env["NUMBA_CACHE_DIR"]) / Path(before).name)
    assert before == _cache_dir_of(package_copy, env)  # deterministic
    indices = package_copy / "mechopt" / "core" / "indices.py"
    indices.write_text(indices.read_text().replace("return 2.0 * abs(a * d - b * c)",
                                                   "return 2.00 * abs(a * d - b * c)"))
    after = _cache_dir_of(package_copy, env)
    assert after != before and Path(after).parent == Path(before).parent


def test_an_unedited_copy_shares_the_cache_of_the_package(package_copy, tmp_path):
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    here = dict(os.environ, **env)
    code = "import mechopt.core.jit as j; print(j.cache_dir())"
    original = subprocess.run([sys.executable, "-c", code], env=here, check=True,
                              capture_output=True, text=True).stdout.strip()
    assert _cache_dir_of(package_copy, env) == original


def test_without_numba_cache_dir_the_cache_is_under_the_user_cache(monkeypatch, tmp_path):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    d = jit.cache_dir()
    assert d.parent == tmp_path / "mechopt" and d.name.startswith("numba-")
