"""karman: a 6-DOF rocket flight simulator in Rust that reproduces RocketPy 1.13.

Load a mission file (the TOML format of ``docs/mission-format.md``), or build one from a
RocketPy script with :func:`karman.rocketpy.from_rocketpy`, then fly it::

    import karman
    mission = karman.load("mission.toml", overrides={"flight.inclination": 84})
    flight = mission.simulate()
    print(flight.apogee_agl_m, flight["altitude_agl"].max())
    study = mission.montecarlo(samples=500, seed=1)
    print(study.outputs["apogee_agl_m"].std(), study.ellipses["landing"]["center_m"])

Every error about a mission is a :class:`MissionError` carrying the command-line
interface's message (file, line, column and key).
"""

from ._karman import SERIES, SUMMARY_KEYS, Flight, Mission, MissionError, Study, load

__all__ = [
    "SERIES",
    "SUMMARY_KEYS",
    "Flight",
    "Mission",
    "MissionError",
    "Study",
    "load",
]
