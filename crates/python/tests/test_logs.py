"""Flight logs: read_log's figures and arrays, Flight.compare and Mission.fit against the
command-line interface's `log show`, `compare` and `fit` JSON, and located errors."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import karman

PROMETHEUS_LOG = "prometheus_2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv"
JUNO3_LOG = "juno3/cots_altimeter.csv"
SERIES = ("time", "altitude", "vertical_velocity", "acceleration", "pressure",
          "temperature", "latitude", "longitude", "gnss_altitude")
#: The keys of one entry of `karman compare --json`'s `logs` list.
COMPARE_KEYS = {
    "file", "format", "device", "apogee_m", "apogee_time_s", "apogee_error_m",
    "apogee_error_pct", "apogee_time_error_s", "max_vertical_velocity_mps",
    "max_velocity_error_pct", "ascent_samples", "ascent_rms_altitude_m",
    "ascent_rms_velocity_mps", "landing_time_s", "landing_time_error_s",
    "descent_rate_error_pct", "descent", "landing", "warnings",
}
#: The keys of `karman fit --json`.
FIT_KEYS = {"log", "flights", "converged", "termination", "clock_offset_s",
            "correlation_inflation", "warnings", "inputs", "phases"}


def run_json(cli, *args):
    out = subprocess.run([cli, *map(str, args)], check=True, capture_output=True,
                         text=True).stdout
    return json.loads(out)


@pytest.fixture(scope="module")
def juno3_log(validation):
    return karman.read_log(validation / JUNO3_LOG)


@pytest.fixture(scope="module")
def prometheus(validation):
    return (karman.load(validation / "prometheus_2022" / "mission.toml"),
            karman.read_log(validation / PROMETHEUS_LOG))


def test_read_log_figures_and_arrays(juno3_log):
    log = juno3_log
    assert log.format == "rrc3"
    assert isinstance(log.device, str) and log.device
    n = len(log)
    assert n > 100
    for name in SERIES:
        values = getattr(log, name)
        assert values.dtype == np.float64 and values.shape == (n,), name
    assert np.all(np.diff(log.time) > 0)
    assert log.apogee_agl_m == pytest.approx(3213, abs=5)
    assert log.apogee_agl_m == log.altitude.max()
    assert log.apogee_time_s == log.time[np.argmax(log.altitude)]
    assert log.max_vertical_velocity_mps == log.vertical_velocity.max()
    # The RRC3 writes no acceleration and no GNSS: NaN throughout.
    assert np.all(np.isnan(log.latitude)) and np.all(np.isnan(log.longitude))
    assert np.all(np.isnan(log.acceleration))
    assert np.all(np.isfinite(log.pressure))
    # Its temperature column turns to "-" partway through the flight: NaN on those samples.
    temperature = log.temperature
    assert np.isfinite(temperature[0]) and np.isnan(temperature).any()
    assert 250.0 < np.nanmin(temperature) and np.nanmax(temperature) < 330.0
    kinds = [e["kind"] for e in log.events]
    assert kinds[0] == "launch" and "apogee" in kinds
    assert set(log.events[0]) == {"kind", "time_s", "source"}
    assert set(log.reported) == {"apogee_agl_m", "ground_elevation_m", "max_velocity_mps"}
    assert isinstance(log.metadata, dict) and isinstance(log.warnings, list)
    assert "rrc3" in repr(log)


def test_gnss_series_of_a_telemetrum(prometheus):
    _, log = prometheus
    assert log.format == "altusmetrum"
    assert np.isfinite(log.latitude).any() and np.isfinite(log.longitude).any()
    assert np.nanmax(log.latitude) == pytest.approx(32.94, abs=0.1)
    assert np.isfinite(log.acceleration).all()
    assert log.apogee_agl_m == log.altitude.max()


def test_read_log_equals_log_show_json(juno3_log, validation, cli):
    expected = run_json(cli, "log", "show", validation / JUNO3_LOG, "--json")
    assert juno3_log.to_dict() == expected
    for key in ("format", "device", "liftoff_time_s", "apogee_agl_m", "apogee_time_s",
                "max_vertical_velocity_mps", "events", "reported", "metadata", "warnings"):
        assert getattr(juno3_log, key) == expected[key], key


def test_read_log_format_and_mapping(validation, tmp_path):
    named = karman.read_log(validation / JUNO3_LOG, format="rrc3")
    assert named.apogee_agl_m == karman.read_log(validation / JUNO3_LOG).apogee_agl_m
    path = tmp_path / "generic.csv"
    rows = ["t,alt_ft"] + [f"{t / 10},{max(0.0, 300 * (t / 10) - 10 * (t / 10) ** 2) / 0.3048}"
                           for t in range(0, 300)]
    path.write_text("\n".join(rows) + "\n")
    generic = karman.read_log(path, mapping="time=t:s,altitude=alt_ft:ft")
    assert generic.format == "generic"
    assert generic.apogee_agl_m == pytest.approx(2250.0, abs=1.0)
    with pytest.raises(karman.LogError, match="unknown format name 'nope'"):
        karman.read_log(path, format="nope")
    with pytest.raises(karman.LogError, match="column mapping"):
        karman.read_log(path, mapping="time")


@pytest.mark.parametrize(
    ("mission", "log", "cli_error_m"),
    [("prometheus_2022", PROMETHEUS_LOG, 172.0), ("juno3", JUNO3_LOG, -60.2)],
)
def test_compare_equals_the_cli(validation, cli, mission, log, cli_error_m):
    flight = karman.load(validation / mission / "mission.toml").simulate()
    read = karman.read_log(validation / log)
    result = flight.compare(read)
    assert set(result) == COMPARE_KEYS
    # The simulated apogee counted from the pad (its first point) minus the log's.
    altitude = flight["altitude_agl"]
    simulated_apogee = altitude.max() - altitude[0]
    assert result["apogee_m"] == read.apogee_agl_m
    assert result["apogee_error_m"] == pytest.approx(simulated_apogee - read.apogee_agl_m,
                                                     abs=1e-6)
    assert result["apogee_error_m"] == pytest.approx(cli_error_m, abs=0.05)
    assert result["apogee_error_pct"] == pytest.approx(
        100 * result["apogee_error_m"] / read.apogee_agl_m)
    for name, pct in result["descent_rate_error_pct"].items():
        assert any(p["parachute"] == name for p in result["descent"]), name
        assert pct is None or np.isfinite(pct)
    report = run_json(cli, "compare", validation / mission / "mission.toml",
                      validation / log, "--json")
    assert set(report["logs"][0]) == COMPARE_KEYS
    assert result == report["logs"][0]


def test_compare_landing_points_with_gnss(prometheus):
    mission, log = prometheus
    result = mission.simulate().compare(log)
    assert result["landing"] is not None
    assert set(result["landing"]) == {"measured_m", "simulated_m", "measured_drift_m",
                                      "simulated_drift_m", "distance_m"}


def test_fit_drag_reduces_the_ascent_rms(prometheus, validation, cli, tmp_path):
    mission, log = prometheus
    out = tmp_path / "fitted.toml"
    result = mission.fit(log, vary=["rocket.power_off_drag"], max_flights=100, seed=0, out=out)
    assert set(result) == FIT_KEYS
    assert result["flights"] <= 100
    phase = result["phases"][0]
    assert phase["phase"] == "ascent"
    assert phase["rms_after"] < phase["rms_before"]
    assert phase["rms_before"] == pytest.approx(229.25, abs=0.05)
    assert phase["rms_after"] == pytest.approx(14.16, abs=0.05)
    assert [i["path"] for i in result["inputs"]] == ["rocket.power_off_drag"]
    expected = run_json(cli, "fit", validation / "prometheus_2022" / "mission.toml",
                        validation / PROMETHEUS_LOG, "--vary", "rocket.power_off_drag",
                        "--json")
    assert result == expected
    # The fitted copy loads and flies closer to the log.
    assert out.read_text().startswith("# Fitted by `karman fit`")
    fitted = karman.load(out).simulate().compare(log)
    before = mission.simulate().compare(log)
    assert abs(fitted["apogee_error_m"]) < abs(before["apogee_error_m"])


def test_fit_takes_one_path_as_a_string(example, tmp_path):
    flight = example.simulate()
    path = tmp_path / "synthetic.csv"
    t, h = flight.t, flight["altitude_agl"] - flight["altitude_agl"][0]
    keep = np.searchsorted(t, np.arange(0.0, t[-1], 0.05))
    keep = keep[keep < len(t)]
    path.write_text("t,h\n" + "".join(f"{t[i]},{h[i]}\n" for i in keep))
    log = karman.read_log(path, mapping="time=t:s,altitude=h:m")
    result = example.fit(log, vary="rocket.mass", max_flights=30)
    assert result["inputs"][0]["factor"] == pytest.approx(1.0, abs=0.01)
    assert result["phases"][0]["rms_after"] <= result["phases"][0]["rms_before"] + 1e-9


def test_log_errors_name_the_file_and_line(tmp_path):
    missing = tmp_path / "no_such_log.csv"
    with pytest.raises(karman.LogError, match="no_such_log.csv: cannot read"):
        karman.read_log(missing)
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    with pytest.raises(ValueError, match="empty.csv: the file is empty"):
        karman.read_log(empty)
    unknown = tmp_path / "odd.csv"
    unknown.write_text("\n\nfoo,bar\n1,2\n")
    with pytest.raises(karman.LogError, match=r"odd.csv:3: unknown log format"):
        karman.read_log(unknown)


def test_fit_errors_name_the_input(prometheus, tmp_path):
    mission, log = prometheus
    with pytest.raises(karman.MissionError, match="rocket.no_such_input"):
        mission.fit(log, vary=["rocket.no_such_input"])
    with pytest.raises(karman.MissionError, match="would replace the mission"):
        mission.fit(log, vary=["rocket.power_off_drag"], out=mission.path)
    with pytest.raises(TypeError):
        mission.fit(log, vary=[1])
