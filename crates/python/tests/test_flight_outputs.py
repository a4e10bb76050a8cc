"""The trajectory's RocketPy-named series against RocketPy 1.13's own `Flight` attributes on
the Calisto validation flight, on RocketPy's own time points from rail exit to 15 s (karman's
series interpolated linearly; 50 ms around rail exit and burn-out left out, where both step),
each error taken relative to the attribute's largest magnitude there (several series cross
zero, where a pointwise relative error means nothing). The table of names is
docs/flight-outputs.md's.

- PARITY: within 0.1 %.
- INHERITED: series that are one existing series rescaled or summed (drag is −R3): within 0.1 %
  or within 1.05 times that series' own error carried into their unit (the flight's parity,
  not the new column's, bounds them).
- LATERAL: the body-axis x and y components, the partial angles, lift and bending moment
  follow the rocket's small lateral motion (0.3 m/s across a 286 m/s flight), which karman's
  existing columns (`omega1`, `aero_force_r1`, `angle_of_attack`) already match only to some
  per cent of its magnitude; they are checked against karman's own states exactly instead
  (the same stream and axes), and their parity is printed.
"""

from __future__ import annotations

import numpy as np
import pytest

rocketpy = pytest.importorskip("rocketpy")

import karman  # noqa: E402
import rocketpy_flights  # noqa: E402

# karman series -> RocketPy 1.13 `Flight` attribute.
PARITY = {
    "vz_body": "vz_body_frame",
    "az_body": "az_body_frame",
    "attitude_vector_z": "attitude_vector_z",
    "axial_acceleration": "axial_acceleration",
    "horizontal_speed": "horizontal_speed",
    "pressure": "pressure",
    "density": "density",
    "dynamic_viscosity": "dynamic_viscosity",
    "reynolds_number": "reynolds_number",
    "total_pressure": "total_pressure",
    "rotational_energy": "rotational_energy",
    "translational_energy": "translational_energy",
    "kinetic_energy": "kinetic_energy",
    "potential_energy": "potential_energy",
    "thrust_power": "thrust_power",
    "drift": "drift",
    "bearing": "bearing",
}
# series -> (RocketPy attribute, the existing karman series and RocketPy attribute it follows)
INHERITED = {
    "aerodynamic_drag": ("aerodynamic_drag", "aero_force_r3", "R3"),
    "drag_power": ("drag_power", "aero_force_r3", "R3"),
    "aerodynamic_spin_moment": ("aerodynamic_spin_moment", "aero_moment_m3", "M3"),
    "total_energy": ("total_energy", "translational_energy", "translational_energy"),
}
LATERAL = {
    "vx_body": "vx_body_frame",
    "vy_body": "vy_body_frame",
    "ax_body": "ax_body_frame",
    "ay_body": "ay_body_frame",
    "attitude_vector_x": "attitude_vector_x",
    "attitude_vector_y": "attitude_vector_y",
    "partial_angle_of_attack": "partial_angle_of_attack",
    "angle_of_sideslip": "angle_of_sideslip",
    "aerodynamic_lift": "aerodynamic_lift",
    "aerodynamic_bending_moment": "aerodynamic_bending_moment",
}

TOLERANCE = 1e-3


def attribute(flight, name, keep):
    """RocketPy's attribute at its own time points `flight.time[keep]`."""
    value = getattr(flight, name)
    times = np.asarray(flight.time)[keep]
    if callable(value):
        return np.array([value(t) for t in times], dtype=float)
    table = np.asarray(value, dtype=float)
    return table[keep, 1] if table.ndim == 2 else table[keep]


@pytest.fixture(scope="module")
def flights(validation):
    env, rocket, kwargs = rocketpy_flights.calisto(validation)
    reference = rocketpy.Flight(rocket=rocket, environment=env, **kwargs)
    ours = karman.load(
        validation / "calisto" / "mission.toml",
        {"flight.equations": "rocketpy_1_13"},
    ).simulate()
    times = np.asarray(reference.time)
    keep = (times > reference.out_of_rail_time + 0.05) & (times < 15.0)
    for instant in (reference.out_of_rail_time, rocket.motor.burn_out_time):
        keep &= np.abs(times - instant) > 0.05
    return ours, reference, keep


def error(flights, series, name, relative=True):
    """The largest difference over the window, relative to RocketPy's largest magnitude
    (or in the series' unit)."""
    ours, reference, keep = flights
    theirs = attribute(reference, name, keep)
    mine = np.interp(np.asarray(reference.time)[keep], ours.t, ours[series])
    largest = np.max(np.abs(mine - theirs))
    return largest / np.max(np.abs(theirs)) if relative else largest


def test_series_equal_rocketpy_attributes(flights):
    assert flights[2].sum() > 200
    misses = []
    for series, name in PARITY.items():
        e = error(flights, series, name)
        print(f"{series:28s} {e:.2e}")
        if not e <= TOLERANCE:
            misses.append(f"{series} vs {name}: {e:.2e}")
    for series, (name, source, source_name) in INHERITED.items():
        # In the series' units: the source's error carried over (drag power is R3 times the
        # speed, the total energy the kinetic plus the potential).
        e = error(flights, series, name)
        scale = {"drag_power": "speed"}.get(series)
        carried = error(flights, source, source_name, relative=False) * (
            np.max(flights[0][scale]) if scale else 1.0
        )
        print(f"{series:28s} {e:.2e} (its source {source}: {carried:.3g} in its unit)")
        if not (e <= TOLERANCE or error(flights, series, name, relative=False) <= 1.05 * carried):
            misses.append(f"{series} vs {name}: {e:.2e}, its source {carried:.3g}")
    for series, name in LATERAL.items():
        print(f"{series:28s} {error(flights, series, name):.2e} (lateral)")
    assert not misses, "\n".join(misses)


def test_lateral_series_are_karmans_own_states(flights):
    """The lateral series from the same stream and axes as the existing columns: the body
    velocity's norm is the speed, the partial angles compose into the angle of attack, lift
    and bending moment are the norms of the transverse force and moment."""
    ours = flights[0]
    moving = ours["free_stream_speed"] > 10.0
    v = np.sqrt(ours["vx_body"] ** 2 + ours["vy_body"] ** 2 + ours["vz_body"] ** 2)
    assert np.allclose(v, ours["speed"], rtol=1e-12, atol=1e-9)
    axis = np.sqrt(sum(ours[f"attitude_vector_{c}"] ** 2 for c in "xyz"))
    assert np.allclose(axis, 1.0, atol=1e-12)
    pa = np.radians(ours["partial_angle_of_attack"][moving])
    ss = np.radians(ours["angle_of_sideslip"][moving])
    aoa = np.radians(ours["angle_of_attack"][moving])
    assert np.allclose(np.tan(pa) ** 2 + np.tan(ss) ** 2, np.tan(aoa) ** 2, rtol=1e-6, atol=1e-12)
    lift = np.hypot(ours["aero_force_r1"], ours["aero_force_r2"])
    assert np.allclose(ours["aerodynamic_lift"], lift, rtol=1e-12, atol=1e-12)
    bending = np.hypot(ours["aero_moment_m1"], ours["aero_moment_m2"])
    assert np.allclose(ours["aerodynamic_bending_moment"], bending, rtol=1e-12, atol=1e-12)


def test_thrust_to_weight_is_rocketpys(flights):
    """RocketPy's `Rocket.thrust_to_weight` (thrust over the weight at standard gravity), at
    karman's points of the burn."""
    ours, reference, _ = flights
    t = ours.t
    burn = (t > 0.2) & (t < 3.8)
    theirs = np.array([reference.rocket.thrust_to_weight(x) for x in t[burn]])
    error = np.max(np.abs(ours["thrust_to_weight"][burn] - theirs)) / np.max(theirs)
    assert error < TOLERANCE, error


def test_rail_button_forces_are_rocketpys(validation):
    """RocketPy's rail-button normal and shear forces on the rail (`Flight.rail_button1_normal_force`
    …) of the Calisto in a 6 m/s east, −4 m/s north wind (a custom atmosphere, translated by
    the RocketPy adapter; without wind the forces are round-off), at karman's rail points,
    within 0.1 % of their largest magnitude; zero off the rail."""
    from karman.rocketpy import from_rocketpy

    env, rocket, kwargs = rocketpy_flights.calisto(validation)
    env.set_atmospheric_model(
        type="custom_atmosphere", wind_u=[(0, 6.0), (5000, 6.0)], wind_v=[(0, -4.0), (5000, -4.0)]
    )
    reference = rocketpy.Flight(rocket=rocket, environment=env, **kwargs)
    ours = from_rocketpy(env, rocket, **kwargs).simulate()
    apogee = reference.apogee - env.elevation
    assert abs(ours.apogee_agl_m / apogee - 1) < TOLERANCE, (ours.apogee_agl_m, apogee)
    t = ours.t
    rail = t <= reference.out_of_rail_time
    assert rail.sum() > 5
    for series in (
        "rail_button1_normal_force",
        "rail_button1_shear_force",
        "rail_button2_normal_force",
        "rail_button2_shear_force",
    ):
        theirs = np.array([getattr(reference, series)(x) for x in t[rail]])
        scale = np.max(np.abs(theirs))
        assert scale > 1.0, (series, scale)
        error = np.max(np.abs(ours[series][rail] - theirs)) / scale
        print(f"{series:28s} {error:.2e} of {scale:.4g} N")
        assert error < TOLERANCE, (series, error)
        assert (ours[series][t > ours.out_of_rail_time_s] == 0.0).all(), series
