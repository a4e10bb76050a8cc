"""Shared fixtures: the repository's example mission, the validation flights, the CLI."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import karman

ROOT = Path(__file__).resolve().parents[3]
EXAMPLE = ROOT / "fixtures" / "example.toml"
TWO_STAGE = ROOT / "fixtures" / "two_stage.toml"


def validation_dir() -> Path | None:
    """The validation flights: $KARMAN_VALIDATION_DATA, the repository's copy, or the shared
    folder beside the repository (README, "Validation data")."""
    candidates = [
        os.environ.get("KARMAN_VALIDATION_DATA"),
        ROOT / "fixtures" / "validation",
        ROOT.parent / "shared" / "validation",
    ]
    for candidate in candidates:
        if candidate and (Path(candidate) / "calisto" / "mission.toml").is_file():
            return Path(candidate)
    return None


@pytest.fixture(scope="session")
def validation() -> Path:
    found = validation_dir()
    if found is None:
        pytest.skip("no validation data (set KARMAN_VALIDATION_DATA)")
    return found


@pytest.fixture()
def example() -> karman.Mission:
    return karman.load(EXAMPLE)


@pytest.fixture(scope="session")
def cli() -> str:
    """The `karman` binary: $KARMAN_CLI (set by `cargo xtask ci`) or one on PATH."""
    found = os.environ.get("KARMAN_CLI") or shutil.which("karman")
    if not found or not Path(found).is_file():
        pytest.skip("no karman binary (set KARMAN_CLI)")
    return found
