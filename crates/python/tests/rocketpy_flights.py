"""Three validation flights built with RocketPy 1.13's API, as their sources do (RocketPy's
first-simulation page for Calisto, the Valetudo and Prometheus notebooks), with the data
files of the validation folder. Each builder returns (environment, rocket, flight kwargs)."""

from __future__ import annotations

import datetime
from pathlib import Path


def calisto(data: Path):
    from rocketpy import Environment, Rocket, SolidMotor

    d = data / "calisto"
    env = Environment(latitude=32.990254, longitude=-106.974998, elevation=1400)
    env.set_atmospheric_model(type="standard_atmosphere")
    motor = SolidMotor(
        thrust_source=str(d / "Cesaroni_M1670.eng"),
        dry_mass=1.815,
        dry_inertia=(0.125, 0.125, 0.002),
        nozzle_radius=33 / 1000,
        grain_number=5,
        grain_density=1815,
        grain_outer_radius=33 / 1000,
        grain_initial_inner_radius=15 / 1000,
        grain_initial_height=120 / 1000,
        grain_separation=5 / 1000,
        grains_center_of_mass_position=0.397,
        center_of_dry_mass_position=0.317,
        nozzle_position=0,
        burn_time=3.9,
        throat_radius=11 / 1000,
        coordinate_system_orientation="nozzle_to_combustion_chamber",
    )
    rocket = Rocket(
        radius=127 / 2000,
        mass=14.426,
        inertia=(6.321, 6.321, 0.034),
        power_off_drag=str(d / "powerOffDragCurve.csv"),
        power_on_drag=str(d / "powerOnDragCurve.csv"),
        center_of_mass_without_motor=0,
        coordinate_system_orientation="tail_to_nose",
    )
    rocket.add_motor(motor, position=-1.255)
    rocket.set_rail_buttons(
        upper_button_position=0.0818, lower_button_position=-0.6182, angular_position=45
    )
    rocket.add_nose(length=0.55829, kind="von karman", position=1.278)
    rocket.add_trapezoidal_fins(
        n=4, root_chord=0.120, tip_chord=0.060, span=0.110, position=-1.04956,
        cant_angle=0.5, airfoil=(str(d / "NACA0012-radians.txt"), "radians"),
    )
    rocket.add_tail(top_radius=0.0635, bottom_radius=0.0435, length=0.060, position=-1.194656)
    for name, cd_s, trigger in (("main", 10.0, 800), ("drogue", 1.0, "apogee")):
        rocket.add_parachute(
            name=name, cd_s=cd_s, trigger=trigger, sampling_rate=105, lag=1.5,
            noise=(0, 8.3, 0.5), radius=1.5, height=1.5, porosity=0.0432,
        )
    return env, rocket, {"rail_length": 5.2, "inclination": 85, "heading": 0}


def valetudo(data: Path):
    from rocketpy import Environment, Rocket, SolidMotor

    d = data / "valetudo"
    env = Environment(
        latitude=-23.363611, longitude=-48.011389, elevation=668,
        date=datetime.datetime(2019, 8, 10, 21, 0),
    )
    env.set_atmospheric_model(type="standard_atmosphere")
    motor = SolidMotor(
        thrust_source=str(d / "keron_thrust_curve.csv"),
        burn_time=5.274,
        reshape_thrust_curve=False,
        grain_number=6,
        grain_separation=0.006,
        grain_outer_radius=0.0214,
        grain_initial_inner_radius=0.00965,
        grain_initial_height=0.12,
        grain_density=1707,
        nozzle_radius=0.021642,
        throat_radius=0.008,
        interpolation_method="linear",
        grains_center_of_mass_position=0.42,
        nozzle_position=0,
        dry_mass=0.001,
        dry_inertia=(0, 0, 0),
        center_of_dry_mass_position=0.42,
    )
    rocket = Rocket(
        radius=0.04045,
        mass=8.257,
        inertia=(3.675, 3.675, 0.007),
        power_off_drag=str(d / "Cd_PowerOff_RASAero.csv"),
        power_on_drag=str(d / "Cd_PowerOn_RASAero.csv"),
        center_of_mass_without_motor=0,
    )
    rocket.add_motor(motor, position=-1.024)
    rocket.set_rail_buttons(0.224, -0.93, 30)
    rocket.add_nose(length=0.274, kind="tangent", position=1.134)
    rocket.add_trapezoidal_fins(
        n=3, span=0.077, root_chord=0.058, tip_chord=0.018, position=-0.906
    )
    rocket.add_parachute(
        "Drogue", cd_s=0.349 * 1.3, trigger="apogee", sampling_rate=105, lag=1,
        noise=(0, 8.3, 0.5),
    )
    return env, rocket, {"rail_length": 5.7, "inclination": 84.7, "heading": 53}


def prometheus(data: Path):
    import math

    from rocketpy import Environment, GenericMotor, Rocket

    d = data / "prometheus_2022"
    env = Environment(
        latitude=32.939377, longitude=-106.911986, elevation=1401,
        date=(2023, 6, 24, 9), timezone="America/Denver",
    )
    env.set_atmospheric_model(type="standard_atmosphere")
    motor = GenericMotor(
        thrust_source=str(d / "Cesaroni_7579M1520-P.eng"),
        burn_time=4.897,
        chamber_radius=0.064,
        chamber_height=0.548,
        chamber_position=0.274,
        propellant_initial_mass=3.737,
        nozzle_radius=0.027,
        dry_mass=2.981,
    )
    off = [(0.15, 0.422), (0.45, 0.38), (0.77, 0.32), (0.82, 0.3), (0.88, 0.3), (0.94, 0.32),
           (0.99, 0.37), (1.04, 0.44), (1.24, 0.43), (1.33, 0.42), (1.49, 0.39)]
    rocket = Rocket(
        radius=0.06985,
        mass=13.93,
        inertia=(4.87, 4.87, 0.05),
        power_off_drag=[list(p) for p in off],
        power_on_drag=[[m, cd * 1.02] for m, cd in off],
        center_of_mass_without_motor=0.9549,
        coordinate_system_orientation="tail_to_nose",
    )
    rocket.add_motor(motor, position=0)
    rocket.set_rail_buttons(0.69, 0.21, 60)
    rocket.add_nose(length=0.742, kind="Von Karman", position=2.229)
    rocket.add_trapezoidal_fins(
        n=3, span=0.13, root_chord=0.268, tip_chord=0.136, position=0.273, sweep_length=0.066
    )
    rocket.add_parachute("Drogue", cd_s=1.6 * math.pi * 0.3048**2, trigger="apogee")
    rocket.add_parachute("Main", cd_s=2.2 * math.pi * 0.9144**2, trigger=457.2)
    return env, rocket, {"rail_length": 5.18, "inclination": 80, "heading": 75}


def juno3(data: Path):
    from rocketpy import Environment, Rocket, SolidMotor

    d = data / "juno3"
    env = Environment(
        latitude=32.939377, longitude=-106.911986, elevation=1480,
        date=(2023, 6, 23, 17), timezone="America/Denver",
    )
    env.set_atmospheric_model(type="standard_atmosphere")
    motor = SolidMotor(
        thrust_source=str(d / "mandioca_thrust_curve.csv"),
        reshape_thrust_curve=(5.8, 8800),
        interpolation_method="linear",
        dry_mass=1e-11,
        dry_inertia=(1e-13, 1e-13, 1e-13),
        center_of_dry_mass_position=-0.683,
        nozzle_position=-1.294,
        nozzle_radius=0.0335,
        throat_radius=0.0114,
        grain_number=5,
        grain_separation=0.006,
        grain_density=1748.9,
        grain_outer_radius=0.0465,
        grain_initial_inner_radius=0.016,
        grain_initial_height=0.156,
        grains_center_of_mass_position=-0.683,
    )
    rocket = Rocket(
        radius=0.0655,
        mass=24.05,
        inertia=(15.07, 15.07, 0.067),
        power_off_drag=str(d / "drag_curve.csv"),
        power_on_drag=str(d / "drag_curve.csv"),
        center_of_mass_without_motor=0,
        coordinate_system_orientation="tail_to_nose",
    )
    rocket.add_motor(motor, position=0)
    rocket.set_rail_buttons(0.24, -1.17, 45)
    rocket.add_nose(length=0.565, kind="vonKarman", position=1.477)
    rocket.add_trapezoidal_fins(
        n=4, root_chord=0.2, tip_chord=0.12, span=0.13, position=-0.928, cant_angle=0,
        airfoil=([[0, 0.0002], [2, 0.332], [4, 0.6335], [6, 0.6877]], "degrees"),
    )
    rocket.add_tail(top_radius=0.0655, bottom_radius=0.0535, length=0.068, position=-1.226)
    rocket.add_parachute(
        "Drogue", cd_s=0.885, trigger="apogee", sampling_rate=105, lag=0.5,
        noise=(0, 8.3, 0.5),
    )
    kwargs = {"rail_length": 5.2, "inclination": 85, "heading": 105, "max_time": 600,
              "rtol": 1e-6, "atol": 1e-6}
    return env, rocket, kwargs
