"""Air-brake controllers written in Python (RocketPy's ``controller_function``): called where
the mission's Rhai controller would be, so the same controller in Python flies the Rhai
controller's flight bit for bit; an exception ends the flight with its traceback."""

from __future__ import annotations

import pytest

import karman
from conftest import ROOT

CAMOES = ROOT / "fixtures" / "validation" / "camoes" / "mission.toml"
CALISTO_BRAKES = ROOT / "fixtures" / "airbrakes" / "calisto_apogee.toml"


def camoes_controller(time, sampling_rate, state, state_history, observed_variables, air_brakes):
    """The notebook's Camoes replay (camoes_controller.rhai), as RocketPy users write it."""
    if time <= 11.4:
        new_deployment_level = 1.0
    else:
        new_deployment_level = (
            -0.002906 * time**3.0 + 0.1497 * time**2.0 + -2.563 * time + 14.96
        )
    if time > 19.6:
        new_deployment_level = 0.0
    if time < 3.8:
        new_deployment_level = 0.0
    air_brakes.deployment_level = new_deployment_level
    return [time, air_brakes.deployment_level]


def test_camoes_in_python_flies_the_rhai_flight_bit_for_bit():
    mission = karman.load(CAMOES)
    rhai = mission.simulate()
    python = mission.simulate(controller=camoes_controller)
    assert rhai.to_dict() == python.to_dict()
    assert (rhai.t == python.t).all()
    for series in ("z_asl", "vz", "e0", "omega1"):
        assert (rhai[series] == python[series]).all(), series


def test_the_arguments_are_rocketpy_s():
    seen = {}

    def controller(time, sampling_rate, state, state_history, observed_variables, air_brakes, sensors):
        if not seen:
            seen.update(
                time=time,
                rate=sampling_rate,
                state=list(state),
                history=[list(row) for row in state_history],
                observed=list(observed_variables),
                sensors=list(sensors),
                clamp=air_brakes.clamp,
            )
        # Clipped as the brakes clamp.
        air_brakes.deployment_level = 5.0
        assert air_brakes.deployment_level == 1.0
        air_brakes.deployment_level = 0.0
        return None if time < 1.0 else time

    karman.load(CALISTO_BRAKES).simulate(controller=controller)
    assert seen["time"] == 0.0 and seen["rate"] == 100.0
    assert len(seen["state"]) == 13 and len(seen["history"]) == 1 and len(seen["history"][0]) == 14
    assert seen["observed"] == [] and seen["sensors"] == [] and seen["clamp"] is True


def test_observed_variables_keep_what_the_function_returned():
    calls = []

    def controller(time, sampling_rate, state, state_history, observed_variables, air_brakes):
        calls.append(len(observed_variables))
        return time if len(observed_variables) < 3 else None

    karman.load(CAMOES).simulate(controller=controller)
    assert calls[:5] == [0, 1, 2, 3, 3]


def test_an_exception_ends_the_flight_with_its_traceback():
    def controller(time, sampling_rate, state, state_history, observed_variables, air_brakes):
        if time > 2.0:
            raise RuntimeError("lost the IMU")

    with pytest.raises(karman.MissionError) as error:
        karman.load(CAMOES).simulate(controller=controller)
    text = str(error.value)
    assert "rocket.air_brakes.controller" in text
    assert "Traceback" in text and "RuntimeError: lost the IMU" in text
    assert "the call at t = 2.1 s" in text


def test_a_bad_controller_is_a_type_error():
    with pytest.raises(TypeError, match="not callable"):
        karman.load(CAMOES).simulate(controller=42)
    with pytest.raises(TypeError, match="takes 2 parameters"):
        karman.load(CAMOES).simulate(controller=lambda t, s: None)

    def returns_a_string(time, sampling_rate, state, state_history, observed_variables, air_brakes):
        air_brakes.deployment_level = "open"

    with pytest.raises(karman.MissionError, match="TypeError"):
        karman.load(CAMOES).simulate(controller=returns_a_string)
