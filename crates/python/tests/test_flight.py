"""One flight: summary attributes, series as numpy arrays with units, exports, determinism."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import karman
from conftest import EXAMPLE


@pytest.fixture()
def flight(example):
    return example.simulate(seed=3)


def test_summary_attributes_and_dict(flight):
    summary = flight.to_dict()
    for key in karman.SUMMARY_KEYS:
        assert key in summary
        assert getattr(flight, key) == summary[key]
    assert flight.termination == "impact"
    assert flight.seed == 3
    assert flight.apogee_agl_m > 100.0
    assert [e["name"] for e in flight.events][0] == "rail_exit"
    with pytest.raises(AttributeError):
        flight.no_such_value


def test_summary_matches_the_cli_json(flight, cli):
    out = subprocess.run(
        [cli, "simulate", str(EXAMPLE), "--json", "--seed", "3"],
        check=True, capture_output=True, text=True,
    ).stdout
    assert json.loads(out) == flight.to_dict()


def test_series_are_float_arrays_of_one_length(flight):
    n = flight.t.shape[0]
    assert n > 100
    assert list(flight.series) == list(karman.SERIES)
    for name in karman.SERIES:
        values = flight[name]
        assert values.dtype == np.float64 and values.shape == (n,), name
    assert np.all(np.diff(flight.t) >= 0)
    assert flight.units["altitude_agl"] == "m"
    assert flight.units["vz"] == "mps"
    assert flight.units["mach"] == ""
    # Units: SI heights, degrees for angles.
    assert flight["altitude_agl"].max() == pytest.approx(flight.apogee_agl_m, rel=1e-3)
    assert np.all(np.abs(flight["attitude_angle"]) <= 90.0)
    assert flight.static_margin(0.0) == pytest.approx(flight.initial_static_margin)
    with pytest.raises(KeyError, match="no series `height`"):
        flight["height"]


def test_same_seed_same_arrays(example):
    a, b = example.simulate(seed=5), example.simulate(seed=5)
    for name in karman.SERIES:
        assert np.array_equal(a[name], b[name]), name
    assert a.to_dict() == b.to_dict()


def test_exports_equal_the_cli_files(flight, cli, tmp_path):
    subprocess.run(
        [cli, "simulate", str(EXAMPLE), "--seed", "3", "--out", str(tmp_path / "cli")],
        check=True, capture_output=True,
    )
    flight.export_csv(tmp_path / "trajectory.csv")
    flight.export_kml(tmp_path / "flight.kml")
    for name in ("trajectory.csv", "flight.kml"):
        assert (tmp_path / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_to_pandas_when_installed(flight):
    pandas = pytest.importorskip("pandas")
    frame = flight.to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    assert "altitude_agl_m" in frame.columns and len(frame) == flight.t.shape[0]


def test_plots_when_matplotlib_is_installed(flight, tmp_path):
    pytest.importorskip("matplotlib")
    figures = flight.plot(path=str(tmp_path / "{name}.png"))
    assert set(figures) == {"altitude", "ground_track", "speed_mach", "attitude", "stability"}
    assert (tmp_path / "altitude.png").stat().st_size > 0
