"""Reference values of `validate_rocket_time_tables` (crates/mission/tests/validate_rocket.rs),
from RocketPy 1.13.0: the rocket's time functions that the 6-DOF equations evaluate, for three
validation missions built exactly as their mission.toml says (Calisto: solid motor; NDRT 2020:
nose_to_tail rocket with a combustion_chamber_to_nozzle motor; Prometheus: generic motor).

Run from the validation folder: python3 rocketpy_time_tables.py /path/to/shared/validation
"""

import sys
import warnings

from rocketpy import GenericMotor, Rocket, SolidMotor

warnings.simplefilter("ignore")
root = sys.argv[1] if len(sys.argv) > 1 else "."


def calisto():
    motor = SolidMotor(
        thrust_source=f"{root}/calisto/Cesaroni_M1670.eng",
        dry_mass=1.815,
        dry_inertia=(0.125, 0.125, 0.002),
        nozzle_radius=0.033,
        grain_number=5,
        grain_density=1815,
        grain_outer_radius=0.033,
        grain_initial_inner_radius=0.015,
        grain_initial_height=0.12,
        grain_separation=0.005,
        grains_center_of_mass_position=0.397,
        center_of_dry_mass_position=0.317,
        nozzle_position=0,
        burn_time=3.9,
        throat_radius=0.011,
        coordinate_system_orientation="nozzle_to_combustion_chamber",
    )
    rocket = Rocket(0.0635, 14.426, (6.321, 6.321, 0.034), 0.5, 0.5, 0, "tail_to_nose")
    rocket.add_motor(motor, position=-1.255)
    return rocket


def ndrt():
    motor = SolidMotor(
        thrust_source=f"{root}/ndrt_2020/Cesaroni_4895L1395-P.eng",
        burn_time=3.433,
        dry_mass=1.848,
        dry_inertia=(0, 0, 0),
        center_of_dry_mass_position=-0.35,
        grains_center_of_mass_position=-0.35,
        grain_number=5,
        grain_separation=0.003,
        grain_density=1519.708,
        grain_outer_radius=0.033,
        grain_initial_inner_radius=0.015,
        grain_initial_height=0.12,
        nozzle_radius=0.02475,
        throat_radius=0.01075,
        interpolation_method="linear",
        nozzle_position=0,
        coordinate_system_orientation="combustion_chamber_to_nozzle",
    )
    rocket = Rocket(0.1015, 18.998, (73.316, 73.316, 0.15982), 0.44, 0.44, 1.3, "nose_to_tail")
    rocket.add_motor(motor, position=3.391)
    return rocket


def prometheus():
    motor = GenericMotor(
        thrust_source=f"{root}/prometheus_2022/Cesaroni_7579M1520-P.eng",
        burn_time=4.897,
        chamber_radius=0.064,
        chamber_height=0.548,
        chamber_position=0.274,
        propellant_initial_mass=3.737,
        nozzle_radius=0.027,
        dry_mass=2.981,
        center_of_dry_mass_position=0.274,
        dry_inertia=(0, 0, 0),
        nozzle_position=0,
    )
    rocket = Rocket(0.06985, 13.93, (4.87, 4.87, 0.05), 0.4, 0.4, 0.9549, "tail_to_nose")
    rocket.add_motor(motor, position=0)
    return rocket


TIMES = [0.0, 0.37, 1.0, 1.234, 2.5, 3.3, 3.61, 4.5]
for name, build in [("calisto", calisto), ("ndrt_2020", ndrt), ("prometheus_2022", prometheus)]:
    r = build()
    rows = []
    for t in TIMES:
        rows.append(
            [
                t,
                r.total_mass(t),
                r.total_mass_flow_rate(t),
                r.total_mass_flow_rate.differentiate_complex_step(t),
                r.com_to_cdm_function(t),
                r.com_to_cdm_function.differentiate_complex_step(t),
                r.I_11(t),
                r.I_11.differentiate_complex_step(t),
                r.I_33(t),
                r.I_33.differentiate_complex_step(t),
                r.center_of_mass(t),
            ]
        )
    print(f'("{name}", &[')
    for row in rows:
        print("    [" + ", ".join(repr(float(v)) for v in row) + "],")
    print("]),")
