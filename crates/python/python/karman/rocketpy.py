"""``from_rocketpy``: the RocketPy 1.13 objects of an existing script as a karman mission.

Build the ``Environment``, the motor (``SolidMotor`` or ``GenericMotor``) and the ``Rocket``
with its surfaces, rail buttons and parachutes as usual, then call
``from_rocketpy(env, rocket, rail_length=..., inclination=..., heading=...)`` with the
arguments that would go to RocketPy's ``Flight``. The result is a :class:`karman.Mission`
that flies the same model (docs/physics.md follows RocketPy 1.13's conventions one to one), with
RocketPy 1.13's form of the equations of motion (``flight.equations = "rocketpy_1_13"``).

What the adapter reads (attributes of RocketPy 1.13's objects):

- ``Environment``: ``latitude``, ``longitude``, ``elevation``, ``datum``, ``date`` (UTC),
  ``gravity`` (RocketPy's default Somigliana table or a constant), the atmospheric model
  (``atmospheric_model_type``: standard atmosphere, custom atmosphere from tables or
  constants, Wyoming/NOAA soundings, reanalysis/forecast/ensemble netCDF files with
  ``atmospheric_model_file`` and ``atmospheric_model_dict``).
- Motors: the processed thrust curve (``motor.thrust``, already clipped to the burn window and
  reshaped), ``burn_time``, ``interpolate``, dry mass and inertia, positions, nozzle and throat
  radii, coordinate system, ``reference_pressure``; BATES grains (``SolidMotor``) or the
  chamber and propellant mass (``GenericMotor``).
- ``Rocket``: radius, mass and inertia without motor, centre of mass, coordinate system, the
  drag inputs as given (file, points, constant or a tabulated ``Function``), the motor
  position, rail buttons, nose cones, trapezoidal/elliptical/free-form fins (with airfoils),
  tails and parachutes in the order they were added.
- ``Flight``'s arguments: rail length, inclination, heading, ``max_time``, ``max_time_step``,
  ``terminate_on_apogee``, tolerances and ``simulation_mode`` (``"3 DOF"`` with the rocket's
  ``weathercock_coeff`` attribute, which RocketPy's 3-DOF equations read).

A parachute trigger given as a Python function (RocketPy's ``trigger(p, h, y[, sensors])``) is
flown as it is: the mission holds the function (``Mission.set_trigger``) and its TOML a
trigger that never fires on its own (``{ expression = "false" }``). Eccentricities become
``cm_eccentricity``, ``cp_eccentricity`` and ``thrust_eccentricity``.

Anything else that would change the flight — callables (a thrust, drag or gravity given as
Python code), hybrid/liquid motors, air brakes, non-default solver options — raises
:class:`UnsupportedError` naming the attribute.
"""

from __future__ import annotations

import datetime as _datetime
import math
import os
from typing import Any

import numpy as np

from . import Mission

__all__ = ["UnsupportedError", "from_rocketpy", "mission_dict"]


class UnsupportedError(ValueError):
    """A RocketPy input the adapter cannot translate; ``attribute`` names it
    (``rocket.power_off_drag``, ``environment.gravity``)."""

    def __init__(self, attribute: str, reason: str) -> None:
        super().__init__(f"{attribute}: {reason}")
        self.attribute = attribute
        self.reason = reason


# Flight's keyword arguments and what karman calls them; the ones with no karman key must
# keep RocketPy's default.
_FLIGHT_KEYS = {
    "rail_length": "rail_length",
    "inclination": "inclination",
    "heading": "heading",
    "terminate_on_apogee": "terminate_on_apogee",
    "max_time": "max_time",
    "max_time_step": "max_time_step",
    "rtol": "rtol",
    "atol": "atol",
}
_FLIGHT_DEFAULTS: dict[str, Any] = {
    "initial_solution": None,
    "min_time_step": 0,
    "time_overshoot": True,
    "equations_of_motion": "standard",
    "ode_solver": "LSODA",
}
_FLIGHT_IGNORED = ("verbose", "name")


def _number(value: Any, attribute: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise UnsupportedError(attribute, f"{value!r} is not a number") from None
    if not math.isfinite(number) and not (attribute.endswith("max_time_step") and number > 0):
        raise UnsupportedError(attribute, f"{value!r} is not a finite number")
    return number


def _points(source: Any, attribute: str) -> list[list[float]]:
    array = np.asarray(source, dtype=float)
    if array.ndim != 2 or array.shape[1] != 2:
        raise UnsupportedError(
            attribute, f"a table of shape {array.shape}; karman takes curves of one variable"
        )
    return array.tolist()


def _path(text: str) -> str:
    return os.path.abspath(text)


def _function_curve(function: Any, attribute: str) -> Any:
    """A tabulated RocketPy ``Function`` of one variable as inline points."""
    source = getattr(function, "source", None)
    if isinstance(source, np.ndarray):
        return _points(source, attribute)
    raise UnsupportedError(
        attribute, "a Function of a Python callable; give points, a file or a constant"
    )


def _drag(value: Any, attribute: str) -> tuple[Any, str | None, str | None]:
    """A drag input as given to RocketPy's ``Rocket`` and the interpolation and extrapolation
    RocketPy 1.13 gives it (``Rocket.__process_drag_input``): a headerless two-column CSV
    file is linear, other files, lists of pairs and Functions built from them are RocketPy
    ``Function`` defaults (spline), all hold their end values; a constant has neither."""
    if isinstance(value, (str, os.PathLike)):
        path = _path(os.fspath(value))
        if path.lower().endswith(".csv"):
            with open(path, newline="") as file:
                first = file.readline().split(",")
            try:
                numeric = len(first) == 2 and all(math.isfinite(float(c)) for c in first)
            except ValueError:
                numeric = False
            if not numeric:
                raise UnsupportedError(
                    attribute,
                    f"{path} has a header: RocketPy reads it as a table of several variables",
                )
            return path, "linear", "constant"
        return path, "spline", "constant"
    if isinstance(value, bool):
        raise UnsupportedError(attribute, f"{value!r} is not a curve")
    if isinstance(value, (int, float, np.number)):
        return _number(value, attribute), None, None
    if isinstance(value, (list, tuple)):
        return _points(value, attribute), "spline", "constant"
    if type(value).__name__ == "Function":
        if getattr(value, "__dom_dim__", 1) != 1:
            raise UnsupportedError(attribute, "a drag Function of several variables")
        return (
            _function_curve(value, attribute),
            _interpolation(value, attribute),
            str(getattr(value, "__extrapolation__", "constant") or "constant"),
        )
    if callable(value):
        raise UnsupportedError(attribute, "a Python callable cannot be translated")
    raise UnsupportedError(attribute, f"a {type(value).__name__} is not a curve")


def _interpolation(function: Any, attribute: str) -> str:
    method = getattr(function, "__interpolation__", "linear") or "linear"
    if method not in ("linear", "spline", "akima", "polynomial"):
        raise UnsupportedError(attribute, f"interpolation {method!r}")
    return method


def _inertia(obj: Any, prefix: str, suffix: str, attribute: str) -> list[float]:
    names = ("11", "22", "33", "12", "13", "23")
    values = [_number(getattr(obj, f"{prefix}{n}{suffix}", 0.0), attribute) for n in names]
    return values if any(values[3:]) else values[:3]


def _environment(env: Any) -> dict[str, Any]:
    out: dict[str, Any] = {
        "latitude": _number(env.latitude, "environment.latitude"),
        "longitude": _number(env.longitude, "environment.longitude"),
        "elevation": _number(env.elevation, "environment.elevation"),
        "datum": str(env.datum),
    }
    date = getattr(env, "datetime_date", None)
    if date is not None:
        # RocketPy keeps the launch time in UTC; a naive one is UTC.
        if date.tzinfo is None:
            date = date.replace(tzinfo=_datetime.timezone.utc)
        out["date"] = date.astimezone(_datetime.timezone.utc)
    out.update(_gravity(env))
    out["atmosphere"] = _atmosphere(env)
    return out


def _gravity(env: Any) -> dict[str, Any]:
    source = getattr(env.gravity, "source", None)
    if not isinstance(source, np.ndarray):
        raise UnsupportedError("environment.gravity", "a gravity Function of a Python callable")
    heights, values = source[:, 0], source[:, 1]
    if np.all(values == values[0]):
        return {"gravity": float(values[0])}
    somigliana = np.array([env.somigliana_gravity(h) for h in heights])
    if not np.allclose(values, somigliana, rtol=1e-12, atol=0.0):
        raise UnsupportedError("environment.gravity", "a gravity table of height")
    if not math.isclose(float(heights[-1]), 80000.0):
        raise UnsupportedError(
            "environment.max_expected_height",
            f"gravity sampled up to {heights[-1]:g} m; karman samples RocketPy's Somigliana "
            "gravity on 0-80000 m (the Environment default)",
        )
    return {}


def _atmosphere(env: Any) -> dict[str, Any]:
    kind = str(env.atmospheric_model_type)
    if kind == "standard_atmosphere":
        return {"model": "standard"}
    if kind == "custom_atmosphere":
        atmosphere: dict[str, Any] = {"model": "custom"}
        # RocketPy 1.13 keeps the custom winds as `wind_velocity_x` (east, karman's `wind_u`)
        # and `wind_velocity_y` (north, `wind_v`).
        for key, name in (
            ("pressure", "pressure"),
            ("temperature", "temperature"),
            ("wind_u", "wind_velocity_x"),
            ("wind_v", "wind_velocity_y"),
        ):
            function = getattr(env, name)
            attribute = f"environment.{name}"
            atmosphere[key] = _function_curve(function, attribute)
        return atmosphere
    file = getattr(env, "atmospheric_model_file", None)
    if kind in ("wyoming_sounding", "NOAARucSounding"):
        if not isinstance(file, str) or not os.path.isfile(file):
            raise UnsupportedError(
                "environment.atmospheric_model_file", "the sounding must be a local file"
            )
        return {
            "model": "sounding",
            "file": _path(file),
            "format": "wyoming" if kind == "wyoming_sounding" else "noaa_ruc",
        }
    if kind in ("Reanalysis", "Forecast", "Ensemble"):
        if not isinstance(file, str) or not os.path.isfile(file):
            raise UnsupportedError(
                "environment.atmospheric_model_file",
                f"{file!r}: karman reads weather grids from local netCDF files only",
            )
        atmosphere = {"model": kind.lower(), "file": _path(file)}
        dictionary = getattr(env, "atmospheric_model_dict", None)
        if isinstance(dictionary, str):
            atmosphere["dictionary"] = dictionary
        if kind == "Ensemble":
            atmosphere["member"] = int(env.ensemble_member)
        return atmosphere
    raise UnsupportedError("environment.atmospheric_model_type", f"{kind!r} is not supported")


def _motor(motor: Any) -> dict[str, Any]:
    kind = type(motor).__name__
    if kind not in ("SolidMotor", "GenericMotor"):
        raise UnsupportedError(
            "rocket.motor", f"a {kind}; karman translates SolidMotor and GenericMotor"
        )
    thrust = _function_curve(motor.thrust, "motor.thrust")
    start, end = (float(t) for t in motor.burn_time)
    out: dict[str, Any] = {
        "kind": "solid" if kind == "SolidMotor" else "generic",
        "thrust": thrust,
        "burn_time": [start, end],
        "interpolation": _interpolation(motor.thrust, "motor.thrust"),
        "dry_mass": _number(motor.dry_mass, "motor.dry_mass"),
        "dry_inertia": _inertia(motor, "dry_I_", "", "motor.dry_inertia"),
        "center_of_dry_mass_position": _number(
            motor.center_of_dry_mass_position, "motor.center_of_dry_mass_position"
        ),
        "nozzle_position": _number(motor.nozzle_position, "motor.nozzle_position"),
        "nozzle_radius": _number(motor.nozzle_radius, "motor.nozzle_radius"),
        "coordinate_system": str(motor.coordinate_system_orientation),
    }
    if getattr(motor, "reference_pressure", None) is not None:
        out["reference_pressure"] = _number(motor.reference_pressure, "motor.reference_pressure")
    if kind == "SolidMotor":
        out["throat_radius"] = _number(motor.throat_radius, "motor.throat_radius")
        for name in (
            "grain_number",
            "grain_separation",
            "grain_density",
            "grain_outer_radius",
            "grain_initial_inner_radius",
            "grain_initial_height",
            "grains_center_of_mass_position",
        ):
            value = getattr(motor, name)
            out[name] = int(value) if name == "grain_number" else _number(value, f"motor.{name}")
        if getattr(motor, "only_radial_burn", False):
            raise UnsupportedError("motor.only_radial_burn", "only radial burning grains")
    else:
        for name in (
            "propellant_initial_mass",
            "chamber_radius",
            "chamber_height",
            "chamber_position",
        ):
            out[name] = _number(getattr(motor, name), f"motor.{name}")
    return out


def _position(position: Any) -> float:
    return float(position[2])


def _airfoil(fins: Any, name: str) -> dict[str, Any] | None:
    airfoil = getattr(fins, "_airfoil", None)
    if airfoil is None:
        return None
    data, unit = airfoil
    attribute = f"rocket.surfaces.{name}.airfoil"
    if isinstance(data, (str, os.PathLike)):
        return {"file": _path(os.fspath(data)), "unit": unit}
    return {"curve": _points(data, attribute), "unit": unit}


def _surface(surface: Any, position: Any, name: str) -> dict[str, Any]:
    kind = type(surface).__name__
    at = f"rocket.surfaces.{name}"
    z = _position(position)
    if kind == "NoseCone":
        out: dict[str, Any] = {
            "type": "nose",
            "length": _number(surface.length, f"{at}.length"),
            "kind": str(surface.kind),
            "position": z,
            "base_radius": _number(surface.base_radius, f"{at}.base_radius"),
        }
        if surface.bluffness:
            out["bluffness"] = _number(surface.bluffness, f"{at}.bluffness")
        if str(surface.kind).lower().replace(" ", "") == "powerseries":
            out["power"] = _number(surface.power, f"{at}.power")
        return out
    if kind in ("TrapezoidalFins", "EllipticalFins", "FreeFormFins"):
        out = {
            "type": {
                "TrapezoidalFins": "trapezoidal_fins",
                "EllipticalFins": "elliptical_fins",
                "FreeFormFins": "free_form_fins",
            }[kind],
            "n": int(surface.n),
            "position": z,
            "radius": _number(surface.rocket_radius, f"{at}.rocket_radius"),
        }
        if kind == "FreeFormFins":
            out["shape_points"] = _points(surface.shape_points, f"{at}.shape_points")
        else:
            out["root_chord"] = _number(surface.root_chord, f"{at}.root_chord")
            out["span"] = _number(surface.span, f"{at}.span")
        if kind == "TrapezoidalFins":
            out["tip_chord"] = _number(surface.tip_chord, f"{at}.tip_chord")
            out["sweep_length"] = _number(surface.sweep_length, f"{at}.sweep_length")
        if surface.cant_angle:
            out["cant_angle"] = _number(surface.cant_angle, f"{at}.cant_angle")
        airfoil = _airfoil(surface, name)
        if airfoil is not None:
            out["airfoil"] = airfoil
        return out
    if kind == "Tail":
        return {
            "type": "tail",
            "top_radius": _number(surface.top_radius, f"{at}.top_radius"),
            "bottom_radius": _number(surface.bottom_radius, f"{at}.bottom_radius"),
            "length": _number(surface.length, f"{at}.length"),
            "position": z,
        }
    raise UnsupportedError(at, f"a {kind} surface is not supported")


def _surface_name(surface: Any, taken: set[str]) -> str:
    base = {
        "NoseCone": "nose",
        "TrapezoidalFins": "fins",
        "EllipticalFins": "fins",
        "FreeFormFins": "fins",
        "Tail": "tail",
    }.get(type(surface).__name__, "surface")
    name, k = base, 2
    while name in taken:
        name, k = f"{base}{k}", k + 1
    taken.add(name)
    return name


def _parachute(chute: Any) -> dict[str, Any]:
    at = f"rocket.parachutes.{chute.name}"
    trigger = chute.trigger
    if isinstance(trigger, str):
        if trigger.lower() != "apogee":
            raise UnsupportedError(f"{at}.trigger", f"{trigger!r}")
        trigger_value: Any = "apogee"
    elif isinstance(trigger, (int, float, np.number)) and not isinstance(trigger, bool):
        trigger_value = _number(trigger, f"{at}.trigger")
    elif callable(trigger):
        # A Python trigger: from_rocketpy hands the function itself to the mission
        # (Mission.set_trigger); the mission's own trigger is one that never fires.
        trigger_value = {"expression": "false"}
    else:
        raise UnsupportedError(f"{at}.trigger", f"{trigger!r} is not a trigger")
    out = {
        "cd_s": _number(chute.cd_s, f"{at}.cd_s"),
        "trigger": trigger_value,
        "sampling_rate": _number(chute.sampling_rate, f"{at}.sampling_rate"),
        "lag": _number(chute.lag, f"{at}.lag"),
        "noise": [_number(v, f"{at}.noise") for v in chute.noise],
    }
    for name in ("radius", "height", "porosity"):
        value = getattr(chute, name, None)
        if value is not None:
            out[name] = _number(value, f"{at}.{name}")
    return out


def _eccentricities(rocket: Any) -> dict[str, list[float]]:
    """The rocket's eccentricities as karman's keys.

    RocketPy's ``add_cm_eccentricity(x, y)`` sets the CP and thrust eccentricities to ``(-x,
    -y)`` and moves the surfaces it places afterwards (``surfaces_cp_to_cdm``): when every
    surface sits at ``(-x csys, -y)`` and both eccentricities are ``(-x, -y)``, that is
    karman's ``cm_eccentricity``; when the surfaces were placed before it (not moved), the
    flight RocketPy flies is that of its CP and thrust eccentricities alone.
    """

    def pair(kind: str) -> tuple[float, float]:
        return (
            _number(getattr(rocket, f"{kind}_eccentricity_x", 0), f"rocket.{kind}_eccentricity_x"),
            _number(getattr(rocket, f"{kind}_eccentricity_y", 0), f"rocket.{kind}_eccentricity_y"),
        )

    cm, cp, thrust = pair("cm"), pair("cp"), pair("thrust")
    out: dict[str, list[float]] = {}
    csys = getattr(rocket, "_csys", 1)
    positions = list(getattr(rocket, "surfaces_cp_to_cdm", {}).values())
    moved = any(cm) and all(
        abs(p[0] + cm[0] * csys) < 1e-12 and abs(p[1] + cm[1]) < 1e-12 for p in positions
    )
    if moved:
        opposite = (-cm[0], -cm[1])
        if cp != opposite or thrust != opposite:
            raise UnsupportedError(
                "rocket.cp_eccentricity_x",
                "a centre-of-mass eccentricity with other CP or thrust eccentricities set after"
                " it (karman takes add_cm_eccentricity alone, or the two others)",
            )
        out["cm_eccentricity"] = list(cm)
        return out
    if any(abs(p[0]) > 1e-12 or abs(p[1]) > 1e-12 for p in positions):
        raise UnsupportedError(
            "rocket.surfaces_cp_to_cdm",
            "surfaces off the rocket's axis other than by add_cm_eccentricity",
        )
    if any(cp):
        out["cp_eccentricity"] = list(cp)
    if any(thrust):
        out["thrust_eccentricity"] = list(thrust)
    return out


def _rocket(rocket: Any) -> dict[str, Any]:
    if type(rocket).__name__ == "PointMassRocket":
        raise UnsupportedError(
            "rocket",
            "a PointMassRocket (no surfaces or inertia); karman's 3-DOF mode flies a Rocket:"
            ' pass simulation_mode="3 DOF"',
        )
    if getattr(rocket, "air_brakes", None):
        raise UnsupportedError("rocket.air_brakes", "air brakes and controllers")
    if getattr(rocket, "_controllers", None):
        raise UnsupportedError("rocket._controllers", "controllers")
    motor = getattr(rocket, "motor", None)
    if motor is None or type(motor).__name__ == "EmptyMotor":
        raise UnsupportedError("rocket.motor", "the rocket has no motor (add_motor)")
    out: dict[str, Any] = {
        "radius": _number(rocket.radius, "rocket.radius"),
        "mass": _number(rocket.mass, "rocket.mass"),
        "inertia": _inertia(rocket, "I_", "_without_motor", "rocket.inertia"),
        "center_of_mass_without_motor": _number(
            rocket.center_of_mass_without_motor, "rocket.center_of_mass_without_motor"
        ),
        "coordinate_system": str(rocket.coordinate_system_orientation),
        "motor_position": _number(rocket.motor_position, "rocket.motor_position"),
    }
    out.update(_eccentricities(rocket))
    shapes: dict[str, tuple[str, str]] = {}
    for name in ("power_off_drag", "power_on_drag"):
        curve, interpolation, extrapolation = _drag(
            getattr(rocket, f"_{name}_input"), f"rocket.{name}"
        )
        out[name] = curve
        if interpolation is not None and extrapolation is not None:
            shapes[name] = (interpolation, extrapolation)
    if len(set(shapes.values())) > 1:
        raise UnsupportedError(
            "rocket.power_on_drag",
            f"interpolated {shapes['power_on_drag']}, power_off_drag "
            f"{shapes['power_off_drag']}: karman shapes both drag curves alike",
        )
    if shapes:
        interpolation, extrapolation = next(iter(shapes.values()))
        out["interpolation"] = interpolation
        out["extrapolation"] = extrapolation
    buttons = list(rocket.rail_buttons)
    if len(buttons) > 1:
        raise UnsupportedError("rocket.rail_buttons", "more than one pair of rail buttons")
    if buttons:
        button, position = buttons[0]
        lower = _position(position)
        sign = 1.0 if rocket.coordinate_system_orientation == "tail_to_nose" else -1.0
        out["rail_buttons"] = {
            "upper_position": lower + sign * _number(
                button.buttons_distance, "rocket.rail_buttons.buttons_distance"
            ),
            "lower_position": lower,
            "angular_position": _number(
                button.angular_position, "rocket.rail_buttons.angular_position"
            ),
        }
    surfaces: dict[str, Any] = {}
    taken: set[str] = set()
    for surface, position in rocket.aerodynamic_surfaces:
        if type(surface).__name__ == "RailButtons":
            continue
        name = _surface_name(surface, taken)
        surfaces[name] = _surface(surface, position, name)
    out["surfaces"] = surfaces
    chutes: dict[str, Any] = {}
    for chute in rocket.parachutes:
        if chute.name in chutes:
            raise UnsupportedError(
                f"rocket.parachutes.{chute.name}", "two parachutes with the same name"
            )
        chutes[chute.name] = _parachute(chute)
    if chutes:
        out["parachutes"] = chutes
    return out


def _flight(kwargs: dict[str, Any], rocket: Any) -> dict[str, Any]:
    if "rail_length" not in kwargs:
        raise UnsupportedError("flight.rail_length", "Flight needs rail_length")
    out: dict[str, Any] = {}
    for key, value in kwargs.items():
        if key == "simulation_mode":
            if value not in ("6 DOF", "3 DOF"):
                raise UnsupportedError("flight.simulation_mode", f"{value!r}")
            if value == "3 DOF":
                out["simulation_mode"] = value
                # RocketPy's 3-DOF equations read the rocket's attribute (PointMassRocket's
                # argument) with getattr, default 0.
                weathercock = getattr(rocket, "weathercock_coeff", 0.0)
                if weathercock != 0.0:
                    out["weathercock_coeff"] = _number(weathercock, "rocket.weathercock_coeff")
        elif key in _FLIGHT_KEYS:
            if value is None and key == "atol":
                continue
            if key == "terminate_on_apogee":
                out[key] = bool(value)
            elif key == "atol":
                out[key] = (
                    [_number(v, "flight.atol") for v in value]
                    if isinstance(value, (list, tuple, np.ndarray))
                    else _number(value, "flight.atol")
                )
            else:
                out[_FLIGHT_KEYS[key]] = _number(value, f"flight.{key}")
        elif key in _FLIGHT_DEFAULTS:
            if value != _FLIGHT_DEFAULTS[key]:
                raise UnsupportedError(
                    f"flight.{key}", f"{value!r}; karman flies RocketPy's default"
                    f" {_FLIGHT_DEFAULTS[key]!r}"
                )
        elif key not in _FLIGHT_IGNORED:
            raise UnsupportedError(f"flight.{key}", "not a Flight argument karman knows")
    if math.isinf(out.get("max_time_step", 0.0)):
        out.pop("max_time_step")
    # RocketPy's `equations_of_motion="standard"` is the form karman calls "rocketpy_1_13"
    # (the mass flow -T/v_e whatever the motor, docs/physics.md §15.3): the translated objects fly
    # as RocketPy flies them.
    out["equations"] = "rocketpy_1_13"
    return out


def mission_dict(environment: Any, rocket: Any, **flight_kwargs: Any) -> dict[str, Any]:
    """The mission (as Python data, the shape of the TOML file) that :func:`from_rocketpy`
    builds."""
    mission: dict[str, Any] = {
        "environment": _environment(environment),
        "motor": _motor(rocket.motor),
        "rocket": _rocket(rocket),
        "flight": _flight(flight_kwargs, rocket),
    }
    name = flight_kwargs.get("name")
    if isinstance(name, str) and name != "Flight":
        mission = {"name": name, **mission}
    return mission


def from_rocketpy(environment: Any, rocket: Any, **flight_kwargs: Any) -> Mission:
    """The karman mission of RocketPy 1.13 objects: ``environment`` (``Environment``),
    ``rocket`` (``Rocket`` with its motor, surfaces, rail buttons and parachutes) and the
    keyword arguments of RocketPy's ``Flight`` (``rail_length``, ``inclination``,
    ``heading``, ...). Data files are referred to by absolute path.

    Raises :class:`UnsupportedError` naming the first attribute that cannot be translated.
    """
    mission = Mission.from_dict(mission_dict(environment, rocket, **flight_kwargs))
    for chute in rocket.parachutes:
        if callable(chute.trigger):
            mission.set_trigger(chute.name, chute.trigger)
    return mission
