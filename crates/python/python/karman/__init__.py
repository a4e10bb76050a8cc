"""karman: a 6-DOF rocket flight simulator in Rust that reproduces RocketPy 1.13.

Load a mission file (the TOML format of ``docs/mission-format.md``), or build one from a
RocketPy script with :func:`karman.rocketpy.from_rocketpy`, then fly it::

    import karman
    mission = karman.load("mission.toml", overrides={"flight.inclination": 84})
    flight = mission.simulate()
    print(flight.apogee_agl_m, flight["altitude_agl"].max())
    study = mission.montecarlo(samples=500, seed=1)
    print(study.outputs["apogee_agl_m"].std(), study.ellipses["landing"]["center_m"])

Altimeter and flight-computer logs: :func:`read_log` reads one (format detected from its
content), ``Flight.compare(log)`` sets it against a flight and ``Mission.fit(log, vary=...)``
fits the mission's inputs to it, as ``karman log show``, ``karman compare`` and ``karman fit``
do::

    log = karman.read_log("flight.csv")
    print(log.apogee_agl_m, log.altitude.max())
    print(flight.compare(log)["apogee_error_m"])
    print(mission.fit(log, vary=["rocket.power_off_drag"])["phases"])

Every error about a mission is a :class:`MissionError` carrying the command-line
interface's message (file, line, column and key); every error about a log a
:class:`LogError` naming the file and line. Both are ``ValueError``\ s.
"""

from ._karman import (
    SERIES,
    SUMMARY_KEYS,
    Flight,
    FlightLog,
    LogError,
    Mission,
    MissionError,
    Study,
    load,
    read_log,
)

__all__ = [
    "SERIES",
    "SUMMARY_KEYS",
    "Flight",
    "FlightLog",
    "LogError",
    "Mission",
    "MissionError",
    "Study",
    "load",
    "read_log",
]
