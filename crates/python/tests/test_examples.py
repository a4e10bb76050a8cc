"""The three examples of the RocketPy paper run headless and print their results."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run(script: str, tmp_path: Path, *extra: str) -> str:
    result = subprocess.run(
        [sys.executable, str(EXAMPLES / script), "--out", str(tmp_path), *extra],
        capture_output=True, text=True, timeout=600,
        env={**__import__("os").environ, "MPLBACKEND": "Agg"},
    )
    assert result.returncode == 0, result.stderr
    return result.stdout


def has_matplotlib() -> bool:
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def test_first_trajectory(tmp_path):
    out = run("first_trajectory.py", tmp_path)
    assert "apogee_agl_m" in out and "event apogee" in out
    assert (tmp_path / "trajectory.csv").stat().st_size > 0
    if has_matplotlib():
        assert (tmp_path / "altitude.png").is_file()


def test_dynamic_stability(tmp_path):
    out = run("dynamic_stability.py", tmp_path)
    lines = [l for l in out.splitlines() if l.startswith("factor")]
    assert len(lines) == 5
    # Fins further aft: a larger static margin at t = 0.
    margins = [float(l.split("static margin")[1].split()[0]) for l in lines]
    assert margins == sorted(margins) or margins == sorted(margins, reverse=True)
    assert len(set(margins)) == 5
    if has_matplotlib():
        assert (tmp_path / "dynamic_stability.png").is_file()


@pytest.mark.parametrize("samples", [200])
def test_monte_carlo(tmp_path, samples):
    out = run("monte_carlo.py", tmp_path, "--samples", str(samples))
    assert f"{samples} flights" in out
    assert "landing ellipse" in out and "3 sigma" in out
    if has_matplotlib():
        assert (tmp_path / "ellipses.png").is_file()


def test_apogee_by_mass(tmp_path):
    out = run("apogee_by_mass.py", tmp_path)
    lines = [l for l in out.splitlines() if l.startswith("target apogee")]
    assert len(lines) == 3
    for line in lines:
        target = float(line.split()[2])
        achieved = float(line.split("(apogee ")[1].split()[0])
        assert abs(achieved - target) <= 0.05
    # A lower target needs a heavier rocket.
    masses = [float(l.split("mass ")[1].split()[0]) for l in lines]
    assert masses == sorted(masses, reverse=True)
    if has_matplotlib():
        assert (tmp_path / "apogee_by_mass.png").is_file()
