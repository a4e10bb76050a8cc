"""What the examples share: the mission they fly and where figures go.

The examples fly RocketPy's Calisto (its documentation rocket) from the validation flights
($KARMAN_VALIDATION_DATA, the repository's fixtures/validation, or ../shared/validation
beside the repository) and fall back to the repository's fixtures/example.toml.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import karman

ROOT = Path(__file__).resolve().parents[3]


def mission_path() -> Path:
    for folder in (
        os.environ.get("KARMAN_VALIDATION_DATA"),
        ROOT / "fixtures" / "validation",
        ROOT.parent / "shared" / "validation",
    ):
        if folder and (Path(folder) / "calisto" / "mission.toml").is_file():
            return Path(folder) / "calisto" / "mission.toml"
    return ROOT / "fixtures" / "example.toml"


def arguments(description: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--mission", type=Path, default=None, help="mission file")
    parser.add_argument("--out", type=Path, default=Path("."), help="folder for the figures")
    parser.add_argument("--samples", type=int, default=1000, help="Monte Carlo samples")
    args = parser.parse_args()
    args.mission = args.mission or mission_path()
    args.out.mkdir(parents=True, exist_ok=True)
    return args


def pyplot():
    """matplotlib's pyplot, or None when it is not installed (the examples then only print)."""
    try:
        import matplotlib

        matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figures")
        return None
    return plt


def load(path: Path) -> karman.Mission:
    return karman.load(path)
