"""Type stubs of the extension module ``karman._karman`` (re-exported by ``karman``)."""

from __future__ import annotations

import os
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
PathLike = str | os.PathLike[str]

#: The trajectory series of a flight, in the column order of ``trajectory.csv``.
SERIES: list[str]
#: The scalar summary keys of ``karman simulate --json`` (a study's outputs).
SUMMARY_KEYS: list[str]

class MissionError(ValueError):
    """A mission that cannot be read, overridden, validated, built or flown; the message is
    the command-line interface's, with file, line, column and key."""

class LogError(ValueError):
    """A flight log that cannot be read or compared with a flight; the message names the
    file and, where one line is at fault, the line."""

def load(path: PathLike, overrides: Mapping[str, Any] | None = None) -> Mission:
    """Reads a mission file, applies ``overrides`` (``{"flight.inclination": 84}``: the
    dotted paths of ``--set``, values as Python data) and validates it."""

class Mission:
    """A validated mission: the TOML text, the overrides applied to it, the result."""

    @staticmethod
    def from_toml(text: str, path: PathLike | None = None) -> Mission:
        """A mission from TOML text; ``path`` names it in messages and its folder resolves
        relative data paths (default: the working directory)."""
    @staticmethod
    def from_dict(data: Mapping[str, Any], path: PathLike | None = None) -> Mission:
        """A mission from Python data shaped like the TOML file."""
    def set(self, path: str, value: Any) -> None:
        """Sets one input by dotted path and validates again; on error nothing changes."""
    def copy(self) -> Mission:
        """An independent copy."""
    def __copy__(self) -> Mission: ...
    def __deepcopy__(self, memo: Any) -> Mission: ...
    def to_toml(self) -> str:
        """The mission, overrides applied, as TOML text (defaults written out)."""
    def to_dict(self) -> dict[str, Any]:
        """The mission, overrides applied, as Python data (the shape ``from_dict`` takes)."""
    @property
    def name(self) -> str | None:
        """The mission's ``name``."""
    @property
    def path(self) -> str:
        """The mission file (or the name given to ``from_toml``/``from_dict``)."""
    @property
    def overrides(self) -> list[str]:
        """The overrides applied, as ``PATH=VALUE`` texts."""
    def inspect(
        self, heights: Sequence[float] | None = None, times: Sequence[float] | None = None
    ) -> dict[str, Any]:
        """The environment, motor and rocket as ``karman inspect --json`` shows them, tables
        as numpy arrays; ``heights`` (m ASL) and ``times`` (s) choose the sample points."""
    def set_trigger(self, name: str, function: Callable[..., Any] | None) -> None:
        """Fires parachute ``name`` by RocketPy's ``trigger(p, h, y[, sensors])`` written in
        Python in every later ``simulate`` (its ``triggers`` argument wins for the names it
        gives); the mission's TOML keeps its own trigger. ``None`` removes the function."""
    def simulate(
        self,
        seed: int = 0,
        controller: Callable[..., Any] | None = None,
        triggers: Mapping[str, Callable[..., Any]] | None = None,
    ) -> Flight:
        """Flies the mission once (GIL released); ``seed`` seeds the parachute trigger
        noise. The first call builds and checks the models; later calls fly them again until
        the mission changes (``set``). ``controller`` is RocketPy's
        ``controller_function(time, sampling_rate, state, state_history,
        observed_variables, air_brakes[, sensors])``: it drives ``[rocket.air_brakes]`` in
        place of the mission's Rhai script; an exception it raises ends the flight with a
        ``MissionError`` holding its traceback. ``triggers`` (``{"main": f}``) fires the named
        parachutes by RocketPy's ``trigger(p, h, y[, sensors])`` instead of their mission
        triggers, called at each sampling instant (ascent included); an exception it raises
        is raised when the flight returns."""
    def montecarlo(
        self,
        samples: int | None = None,
        seed: int | None = None,
        threads: int | None = None,
        vary: Mapping[str, Any] | None = None,
        out: PathLike | None = None,
        progress: bool = True,
    ) -> Study:
        """A Monte Carlo study in memory, no folder written (``samples``/``seed`` default to
        ``[dispersion]``; ``vary`` replaces ``[dispersion.vary]``; ``out`` writes the CLI's
        files there). The GIL is released; Ctrl-C raises ``KeyboardInterrupt`` between
        samples; ``progress`` shows tqdm's bar when tqdm is installed, else a text line."""
    def solve(
        self,
        target: dict[str, float],
        vary: str,
        bounds: tuple[float, float] | None = None,
        tolerance: float | None = None,
        max_flights: int | None = None,
        seed: int = 0,
    ) -> dict[str, Any]:
        """The value of the input ``vary`` (``"rocket.mass"``) at which the output of
        ``target`` (``{"apogee_agl_m": 3048}``) reaches its value, as ``karman solve`` finds it
        (Brent's bracketing root finder within ``bounds``, default the nominal ∓ 50 %;
        tolerance 0.01 in the output's units and 30 flights unless told). Returns the dict of
        ``karman solve --json``; raises ``MissionError`` when no value within the bounds
        reaches the target."""
    def fit(
        self,
        log: FlightLog,
        vary: str | Sequence[str],
        max_flights: int = 100,
        seed: int = 0,
        out: PathLike | None = None,
    ) -> dict[str, Any]:
        """Fits the inputs of ``vary`` (dotted paths: ``rocket.power_off_drag``,
        ``motor.total_impulse``, ``rocket.parachutes.Main.cd_s``, ``rocket.mass``) to the log
        as ``karman fit`` does, within ``max_flights`` flights (GIL released). Returns the
        dict of ``karman fit --json`` (``flights``, ``converged``, ``termination``,
        ``clock_offset_s``, ``correlation_inflation``, ``warnings``, ``inputs``, ``phases``);
        ``out`` writes the mission with the fitted values (a commented copy). Raises
        ``MissionError`` for an input that cannot be fitted, ``LogError`` for a log that
        cannot be compared with the flight."""

class AirBrakes:
    """The ``air_brakes`` argument of a Python controller (RocketPy's ``AirBrakes``)."""
    deployment_level: float
    """The level, 0 shut to 1 open; clipped to [0, 1] when set if ``clamp``."""
    @property
    def clamp(self) -> bool: ...
    @property
    def reference_area(self) -> float: ...
    @property
    def override_rocket_drag(self) -> bool: ...

class SensorReading:
    """An item of a Python controller's ``sensors``: a sensor's latest reading."""
    @property
    def measurement(self) -> float | tuple[float, float, float] | None: ...
    @property
    def time(self) -> float | None: ...

class Flight:
    """A flown mission. Summary keys (``apogee_agl_m``, ``out_of_rail_velocity_mps``, ...)
    are attributes; series are items (``flight["altitude_agl"]``)."""

    def __getitem__(self, name: str) -> FloatArray:
        """One trajectory series (``karman.SERIES``), one value per stored point."""
    def __getattr__(self, name: str) -> Any:
        """A summary value (``None`` for what did not happen)."""
    @property
    def t(self) -> FloatArray:
        """Times of the stored points, s."""
    @property
    def series(self) -> list[str]:
        """The series names."""
    @property
    def units(self) -> dict[str, str]:
        """The unit of each series (``""`` for pure numbers)."""
    def to_dict(self) -> dict[str, Any]:
        """The summary as ``karman simulate --json`` prints it."""
    @property
    def events(self) -> list[dict[str, Any]]:
        """The events (``name``, ``time_s``)."""
    @property
    def warnings(self) -> list[str]:
        """The mission's warnings, each starting with the key it concerns."""
    @property
    def termination(self) -> str:
        """``"impact"``, ``"apogee"``, ``"max_time"``, ``"stuck_on_rail"``, ``"terminated"``
        or ``"separation"``."""
    @property
    def seed(self) -> int:
        """The seed of the parachute trigger noise."""
    @property
    def name(self) -> str:
        """The mission's name."""
    @property
    def integration(self) -> dict[str, int]:
        """Integrator counters."""
    def static_margin(self, t: float) -> float:
        """The rocket's static margin at time ``t``, calibres."""
    def compare(self, log: FlightLog) -> dict[str, Any]:
        """The flight set against a log on one time axis from liftoff: one entry of the
        ``logs`` list of ``karman compare --json`` (``apogee_m``, ``apogee_error_m``,
        ``apogee_error_pct``, ``apogee_time_error_s``, ``max_velocity_error_pct``,
        ``ascent_rms_altitude_m``, ``ascent_rms_velocity_mps``, ``descent_rate_error_pct``,
        ``descent``, ``landing`` or ``None``, ...). Errors are simulated minus measured, the
        simulated altitude counted from the pad."""
    def to_pandas(self) -> Any:
        """Every series as a pandas DataFrame (columns with units); needs pandas."""
    def export_csv(self, path: PathLike) -> None:
        """Writes ``trajectory.csv`` as ``karman simulate --out`` does."""
    def export_kml(self, path: PathLike) -> None:
        """Writes the flight path as KML as ``karman simulate --out`` does."""
    def plot(
        self, which: Sequence[str] | None = None, path: str | None = None, show: bool = False
    ) -> dict[str, Any]:
        """The CLI's figures with matplotlib (``altitude``, ``ground_track``, ``speed_mach``,
        ``attitude``, ``stability``); ``path`` with ``{name}`` saves them."""

class Study:
    """A finished Monte Carlo study."""

    @property
    def seed(self) -> int: ...
    @property
    def samples(self) -> int: ...
    @property
    def index(self) -> npt.NDArray[np.uint64]:
        """Sample indices in row order."""
    @property
    def inputs(self) -> dict[str, FloatArray]:
        """Sampled inputs by ``samples.csv`` column (the path, ``:factor``/``:offset``
        appended for factors and offsets)."""
    @property
    def outputs(self) -> dict[str, FloatArray]:
        """Outputs by summary key, NaN where a sample failed or the quantity did not occur."""
    @property
    def failures(self) -> list[tuple[int, str]]:
        """Failed samples as ``(index, message)``."""
    def to_dict(self) -> dict[str, Any]:
        """``summary.json`` of ``karman montecarlo``."""
    @property
    def statistics(self) -> dict[str, dict[str, float] | None]:
        """Statistics of every input and output column."""
    def tolerance(
        self, outputs: list[str] | None = None, coverage: float = 0.99, confidence: float = 0.95
    ) -> dict[str, dict[str, Any]]:
        """Wilks' one-sided tolerance bounds per output (``karman tolerance --json``):
        ``upper`` is the value a fraction ``coverage`` of flights stays below with
        ``confidence`` (None with too few samples), ``lower`` the one it stays above."""
    def sensitivity(self, outputs: list[str] | None = None) -> dict[str, dict[str, Any]]:
        """RocketPy 1.13's ``SensitivityModel`` (linear regression variance decomposition)
        on the completed samples: per output, ``inputs`` (names) and the arrays ``share``,
        ``coefficient``, ``effect_per_std``, ``mean``, ``std`` in their order, the
        ``unexplained`` share, ``output_mean``, ``output_std`` and ``samples``."""
    @property
    def ellipses(self) -> dict[str, dict[str, Any]]:
        """The ``apogee`` and ``landing`` ellipses with their 1/2/3-sigma contours; a lower
        stage's named after it (``"booster.landing"``) in a study of a multi-stage rocket."""
    @property
    def threads(self) -> int: ...
    @property
    def elapsed(self) -> float:
        """Wall time of the flights, s."""
    @property
    def rate(self) -> float:
        """Samples flown per second of wall time."""
    @property
    def out(self) -> str | None:
        """The output folder given as ``out=``."""
    def to_pandas(self) -> Any:
        """Inputs and outputs as one pandas DataFrame indexed by sample."""
    def plot_ellipses(self, path: str | None = None, show: bool = False) -> Any:
        """The landing/apogee points and their 1/2/3-sigma ellipses with matplotlib."""


def read_log(
    path: PathLike, format: str | None = None, mapping: str | None = None
) -> FlightLog:
    """Reads an altimeter or flight-computer log: the format detected from its content, or
    named (``"altusmetrum"``, ``"raven-fip"``, ``"blueraven"``, ``"perfectflite-pf2"``,
    ``"stratologger-txt"``, ``"rrc3"``, ``"eggtimer"``, ``"cats-vega"``), or a generic CSV
    through a column mapping (``"time=ts,altitude=alt_ft:ft"``). Raises ``LogError`` naming
    the file and line."""

class FlightLog:
    """A flight log read and normalised: SI units, time from liftoff, heights above the
    ground. ``len(log)`` is the number of samples; the series are float64 arrays of that
    length, NaN where a sample lacks the channel."""

    @property
    def path(self) -> str:
        """The file read."""
    @property
    def format(self) -> str:
        """The format read (``"rrc3"``, ``"altusmetrum"``, ..., ``"generic"``)."""
    @property
    def device(self) -> str:
        """The device (family, model, serial as the file says)."""
    def __len__(self) -> int: ...
    @property
    def sample_rate_hz(self) -> float:
        """Median sampling rate of the altitude, Hz."""
    @property
    def velocity_source(self) -> str:
        """``"device"`` or ``"derivative"`` (of the altitude)."""
    @property
    def liftoff_time_s(self) -> float:
        """Liftoff on the device's clock, s (the samples' time zero)."""
    @property
    def apogee_agl_m(self) -> float:
        """The highest altitude above the ground, m."""
    @property
    def apogee_time_s(self) -> float:
        """Its time from liftoff, s."""
    @property
    def max_vertical_velocity_mps(self) -> float:
        """The highest vertical velocity, m/s."""
    @property
    def max_vertical_velocity_time_s(self) -> float:
        """Its time from liftoff, s."""
    @property
    def events(self) -> list[dict[str, Any]]:
        """The events (``kind``, ``time_s``, ``source``: ``"device"`` or ``"derived"``)."""
    @property
    def reported(self) -> dict[str, float | None]:
        """The device's own figures (``apogee_agl_m``, ``ground_elevation_m``,
        ``max_velocity_mps``)."""
    @property
    def metadata(self) -> dict[str, str]:
        """Everything else the header says, by lower-case key."""
    @property
    def warnings(self) -> list[str]:
        """What the reading rules changed or could not read."""
    def to_dict(self) -> dict[str, Any]:
        """The log as ``karman log show --json`` prints it."""
    @property
    def time(self) -> FloatArray:
        """Time from liftoff, s."""
    @property
    def altitude(self) -> FloatArray:
        """Height above the ground, m."""
    @property
    def vertical_velocity(self) -> FloatArray:
        """Vertical velocity, m/s."""
    @property
    def acceleration(self) -> FloatArray:
        """Acceleration as the device writes it, m/s²."""
    @property
    def pressure(self) -> FloatArray:
        """Static pressure, Pa."""
    @property
    def temperature(self) -> FloatArray:
        """Temperature, K."""
    @property
    def latitude(self) -> FloatArray:
        """GNSS latitude, degrees north (NaN without a fix)."""
    @property
    def longitude(self) -> FloatArray:
        """GNSS longitude, degrees east (NaN without a fix)."""
    @property
    def gnss_altitude(self) -> FloatArray:
        """GNSS altitude above sea level, m (NaN without one)."""
