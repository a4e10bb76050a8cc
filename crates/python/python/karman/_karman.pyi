"""Type stubs of the extension module ``karman._karman`` (re-exported by ``karman``)."""

from __future__ import annotations

import os
from typing import Any, Mapping, Sequence

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
    def simulate(self, seed: int = 0) -> Flight:
        """Flies the mission once (GIL released); ``seed`` seeds the parachute trigger
        noise. The first call builds and checks the models; later calls fly them again until
        the mission changes (``set``)."""
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

