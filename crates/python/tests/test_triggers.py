"""Parachute triggers written in Python (`Mission.simulate(triggers=...)`): RocketPy's
`trigger(p, h, y[, sensors])` called at the parachute's sampling instants; a function equal to
a trigger expression flies the expression's flight bit for bit; bad functions and names are
refused; an exception is raised when the flight returns."""

from __future__ import annotations

import math

import pytest

import karman
from conftest import EXAMPLE

# The main parachute fires below 300 m above ground on the way down, and at once after 500 m.
EXPRESSION = "vz < 0.0 && h < 300.0"


def python_trigger(p, h, y):
    return y[5] < 0.0 and h < 300.0


def with_expression():
    mission = karman.load(EXAMPLE)
    mission.set("rocket.parachutes.main.trigger", {"expression": EXPRESSION})
    return mission


def test_a_python_trigger_flies_as_the_same_expression():
    by_expression = with_expression().simulate(seed=5)
    by_python = karman.load(EXAMPLE).simulate(seed=5, triggers={"main": python_trigger})
    assert by_python.to_dict() == by_expression.to_dict()
    for series in ("altitude_agl", "vz", "x"):
        assert (by_python[series] == by_expression[series]).all(), series


def test_the_function_sees_pressure_height_and_state():
    calls = []

    def record(p, h, y):
        calls.append((p, h, list(y)))
        return False

    flight = karman.load(EXAMPLE).simulate(triggers={"main": record})
    assert len(calls) > 100, "called at every sampling instant, ascent included"
    p, h, y = calls[len(calls) // 2]
    assert 1e4 < p < 1.2e5 and math.isfinite(h) and len(y) == 13
    assert "parachute:main" not in [e["name"] for e in flight.events]


def test_sensors_reach_a_four_parameter_trigger():
    mission = karman.load(EXAMPLE)
    mission.set(
        "rocket.sensors",
        [{"name": "baro", "kind": "barometer", "sampling_rate": 50.0, "position": 0.5}],
    )
    seen = []

    def with_sensors(p, h, y, sensors):
        seen.append(sensors[0].measurement)
        return False

    mission.simulate(triggers={"main": with_sensors})
    readings = [m for m in seen if m is not None]
    assert readings, "the barometer's readings reach the trigger"
    assert all(isinstance(m, float) and 1e4 < m < 1.2e5 for m in readings)


def test_bad_triggers_are_refused():
    mission = karman.load(EXAMPLE)
    with pytest.raises(karman.MissionError, match="no parachute"):
        mission.simulate(triggers={"nonesuch": python_trigger})
    with pytest.raises(TypeError, match="3 or 4"):
        mission.simulate(triggers={"main": lambda p, h: True})
    with pytest.raises(TypeError, match="not callable"):
        mission.simulate(triggers={"main": 3})


def test_an_exception_is_raised_when_the_flight_returns():
    def broken(p, h, y):
        return 1 / 0

    with pytest.raises(ZeroDivisionError):
        karman.load(EXAMPLE).simulate(triggers={"main": broken})
