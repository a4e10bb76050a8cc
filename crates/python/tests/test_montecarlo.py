"""Monte Carlo in memory: arrays, determinism across threads, the CLI's bytes, the GIL,
Ctrl-C."""

from __future__ import annotations

import _thread
import csv
import json
import subprocess
import threading
import time

import numpy as np
import pytest

import karman
from conftest import EXAMPLE, TWO_STAGE


def test_inputs_and_outputs_are_arrays(example):
    study = example.montecarlo(samples=24, seed=11, threads=2, progress=False)
    assert study.samples == 24 and study.seed == 11
    assert np.array_equal(study.index, np.arange(24))
    assert set(study.outputs) == set(karman.SUMMARY_KEYS)
    for values in [*study.inputs.values(), *study.outputs.values()]:
        assert values.dtype == np.float64 and values.shape == (24,)
    assert study.failures == []
    stats = study.statistics["apogee_agl_m"]
    assert stats["mean"] == pytest.approx(np.mean(study.outputs["apogee_agl_m"]))
    landing = study.ellipses["landing"]
    assert [c["sigma"] for c in landing["k_sigma_rocketpy"]] == [1, 2, 3]
    assert landing["center_m"][0] == pytest.approx(np.mean(study.outputs["impact_x_m"]))


def test_a_multi_stage_study_has_each_bodys_results():
    mission = karman.load(TWO_STAGE)
    one = mission.montecarlo(samples=6, seed=5, threads=1, progress=False)
    two = mission.montecarlo(samples=6, seed=5, threads=2, progress=False)
    assert one.failures == []
    # The sustainer's columns as in a single-stage study, then the booster's own.
    assert set(karman.SUMMARY_KEYS) <= set(one.outputs)
    for key in ("booster.separation_time_s", "booster.apogee_agl_m", "booster.impact_x_m",
                "booster.impact_y_m", "booster.impact_time_s"):
        assert one.outputs[key].shape == (6,) and np.isfinite(one.outputs[key]).all(), key
    assert "stages.0.rocket.mass" in one.inputs
    # Two bodies, two landings: the booster comes down first, elsewhere.
    assert (one.outputs["booster.impact_time_s"] < one.outputs["impact_time_s"]).all()
    assert not np.array_equal(one.outputs["booster.impact_x_m"], one.outputs["impact_x_m"])
    # Each body's landing ellipse is centred on its own points.
    for prefix in ("", "booster."):
        landing = one.ellipses[f"{prefix}landing"]
        assert landing["outputs"] == [f"{prefix}impact_x_m", f"{prefix}impact_y_m"]
        assert landing["center_m"][0] == pytest.approx(np.mean(one.outputs[f"{prefix}impact_x_m"]))
    # The thread count changes nothing.
    for name in one.outputs:
        assert np.array_equal(one.outputs[name], two.outputs[name], equal_nan=True), name
    assert one.to_dict() == two.to_dict()


def test_vary_replaces_the_mission_inputs(example):
    study = example.montecarlo(
        samples=16, seed=1, vary={"rocket.mass": {"std": 0.5}}, progress=False
    )
    assert list(study.inputs) == ["rocket.mass"]
    mass = example.to_dict()["rocket"]["mass"]
    assert abs(np.mean(study.inputs["rocket.mass"]) - mass) < 0.5
    with pytest.raises(karman.MissionError, match="rocket.mas"):
        example.montecarlo(samples=4, vary={"rocket.mas": {"std": 0.5}}, progress=False)


def test_threads_do_not_change_the_arrays(example):
    one = example.montecarlo(samples=20, seed=4, threads=1, progress=False)
    two = example.montecarlo(samples=20, seed=4, threads=2, progress=False)
    for name in one.inputs:
        assert np.array_equal(one.inputs[name], two.inputs[name])
    for name in one.outputs:
        assert np.array_equal(one.outputs[name], two.outputs[name], equal_nan=True)
    assert one.to_dict() == two.to_dict()


def test_out_writes_the_cli_bytes(example, cli, tmp_path):
    example.montecarlo(samples=12, seed=9, threads=2, out=tmp_path / "py", progress=False)
    subprocess.run(
        [cli, "montecarlo", str(EXAMPLE), "--samples", "12", "--seed", "9", "--threads", "1",
         "--out", str(tmp_path / "cli"), "--quiet"],
        check=True, capture_output=True,
    )
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir())
    for name in names:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_a_study_in_memory_is_the_cli_study(example, cli, tmp_path, monkeypatch):
    """No folder is written (not even a temporary one: the temporary directory does not
    exist), and the arrays and the summary are exactly the CLI's samples.csv and
    summary.json."""
    monkeypatch.setenv("TMPDIR", str(tmp_path / "absent"))
    study = example.montecarlo(samples=12, seed=9, threads=2, progress=False)
    assert study.out is None
    monkeypatch.undo()
    subprocess.run(
        [cli, "montecarlo", str(EXAMPLE), "--samples", "12", "--seed", "9", "--threads", "1",
         "--out", str(tmp_path / "cli"), "--quiet"],
        check=True, capture_output=True,
    )
    assert study.to_dict() == json.loads((tmp_path / "cli" / "summary.json").read_text())
    with open(tmp_path / "cli" / "samples.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    assert [int(r["index"]) for r in rows] == list(study.index)
    for columns in (study.inputs, study.outputs):
        for name, values in columns.items():
            written = np.array([float(r[name]) if r[name] else np.nan for r in rows])
            assert np.array_equal(written, values, equal_nan=True), name
    assert study.failures == [
        (int(r["index"]), f"{r['status']}: {r['error']}" if r["status"] != "failed"
         else r["error"]) for r in rows if r["status"] != "ok"
    ]


def test_a_python_thread_runs_during_a_study(example):
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=count)
    thread.start()
    time.sleep(0.05)
    started = time.perf_counter()
    example.montecarlo(samples=1500, seed=2, threads=1, progress=False)
    finished = time.perf_counter()
    stop.set()
    thread.join()
    during = [t for t in ticks if started < t < finished]
    assert finished - started > 0.1, "the study is long enough to observe"
    assert len(during) > 10, f"{len(during)} ticks of the Python thread during the study"


def test_ctrl_c_stops_a_study_that_then_resumes(example, tmp_path):
    out = tmp_path / "study"

    def interrupt_once_flying():
        # Ctrl-C while samples are being flown: once samples.csv holds rows (a fixed delay
        # could land before the run starts on a slow machine).
        csv = out / "samples.csv"
        deadline = time.monotonic() + 30.0
        while time.monotonic() < deadline:
            if csv.exists() and csv.stat().st_size > 4096:
                break
            time.sleep(0.01)
        _thread.interrupt_main()

    timer = threading.Thread(target=interrupt_once_flying)
    timer.start()
    started = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        example.montecarlo(samples=100_000, seed=3, threads=2, out=out, progress=False)
    assert time.perf_counter() - started < 60.0
    timer.join()
    rows = (out / "samples.csv").read_text().count("\n") - 1
    assert 0 < rows < 100_000
    assert not (out / "summary.json").exists()


def test_progress_reports_to_the_python_helper(example, monkeypatch):
    import karman._progress as progress

    seen = []

    class Recorder:
        def __init__(self, total):
            seen.append(("total", total))

        def update(self, done):
            seen.append(("update", done))

        def close(self, done):
            seen.append(("close", done))

    monkeypatch.setattr(progress, "Progress", Recorder)
    example.montecarlo(samples=8, seed=1, progress=True)
    assert seen[0] == ("total", 8) and seen[-1] == ("close", 8)


def test_progress_without_tqdm_is_a_text_line(example, monkeypatch, capsys):
    import sys

    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    example.montecarlo(samples=8, seed=1, threads=1, progress=True)
    lines = capsys.readouterr().err.splitlines()
    assert lines and lines[-1].startswith("karman Monte Carlo: 8/8 samples (100 %)"), lines


def test_plot_ellipses_when_matplotlib_is_installed(example, tmp_path):
    pytest.importorskip("matplotlib")
    study = example.montecarlo(samples=30, seed=5, progress=False)
    study.plot_ellipses(path=str(tmp_path / "ellipses.png"))
    assert (tmp_path / "ellipses.png").stat().st_size > 0


def test_sensitivity_is_rocketpys_sensitivity_model(example):
    """`Study.sensitivity` against RocketPy 1.13's SensitivityModel fitted on the same
    arrays (the completed samples' inputs and output)."""
    study = example.montecarlo(samples=60, seed=11, threads=2, progress=False)
    result = study.sensitivity(["apogee_agl_m", "impact_x_m"])
    assert set(result) == {"apogee_agl_m", "impact_x_m"}
    names = list(study.inputs)
    for output, decomposition in result.items():
        assert decomposition["inputs"] == names
        assert decomposition["samples"] == 60
        share = decomposition["share"]
        assert share.dtype == np.float64 and share.shape == (len(names),)
        assert share.sum() + decomposition["unexplained"] == pytest.approx(1, abs=1e-12)
    sensitivity = pytest.importorskip("rocketpy.sensitivity")
    pytest.importorskip("statsmodels")
    x = np.column_stack([study.inputs[n] for n in names])
    for output, decomposition in result.items():
        model = sensitivity.SensitivityModel(names, [output])
        model.fit(x, study.outputs[output])
        info = model.target_variables_info[output]
        expected = [info["sensitivity"][n] for n in names]
        assert decomposition["share"] == pytest.approx(expected, abs=1e-9)
        assert decomposition["unexplained"] == pytest.approx(info["LAE"], abs=1e-9)
        assert decomposition["output_std"] == pytest.approx(info["sd"], rel=1e-9)
    with pytest.raises(ValueError, match="not an output"):
        study.sensitivity(["apogee_feet"])


def test_wilks_tolerance_bounds_are_order_statistics(example):
    study = example.montecarlo(samples=100, seed=3, threads=2, progress=False)
    bounds = study.tolerance(["apogee_agl_m"], coverage=0.95, confidence=0.95)["apogee_agl_m"]
    # n = 100 >= 93: the second largest and second smallest (Wilks' second order).
    apogees = np.sort(study.outputs["apogee_agl_m"])
    assert bounds["rank"] == 2
    assert bounds["upper"] == apogees[-2] and bounds["lower"] == apogees[1]
    few = study.tolerance(["apogee_agl_m"])["apogee_agl_m"]
    assert few["upper"] is None and few["samples_needed"] == 299
    with pytest.raises(ValueError, match="strictly between 0 and 1"):
        study.tolerance(coverage=1.5)
