"""Shared settings: hypothesis runs deterministically (a fixed seed via derandomize) and briefly;
the command-line binary the tests compare with."""

import os
from pathlib import Path

import pytest
from hypothesis import settings

ROOT = Path(__file__).resolve().parents[3]

settings.register_profile("shadowlab", derandomize=True, max_examples=200, deadline=None)
settings.load_profile("shadowlab")


@pytest.fixture(scope="session")
def shadowlab_binary():
    """The shadowlab binary: $SHADOWLAB_BIN, else the workspace's release or debug build."""
    for candidate in (os.environ.get("SHADOWLAB_BIN"), ROOT / "target/release/shadowlab", ROOT / "target/debug/shadowlab"):
        if candidate and Path(candidate).is_file():
            return str(candidate)
    raise AssertionError("build the shadowlab binary first (cargo build), or set SHADOWLAB_BIN")
