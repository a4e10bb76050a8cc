"""Reference values of tests/rocketpy_surfaces.rs, from RocketPy 1.13.0.

Run: python3 rocketpy_surfaces.py   (needs `pip install rocketpy==1.13.0`)
Prints each quantity with repr() precision; the test module copies them verbatim.
"""

import warnings

import numpy as np
from rocketpy import EllipticalFins, FreeFormFins, NoseCone, TrapezoidalFins

warnings.simplefilter("ignore")


def show(label, value):
    print(f"{label} = {float(value)!r}")


# Noses as Rocket.add_nose builds them (base radius = reference radius), bluffness 0.3.
for kind in ["ogive", "vonkarman", "lvhaack", "conical", "elliptical", "parabolic"]:
    n = NoseCone(0.55829, kind, base_radius=0.0635, rocket_radius=0.0635, bluffness=0.3)
    show(f"nose {kind} bluff 0.3 length", n.length)
    show(f"nose {kind} bluff 0.3 cpz", n.cpz)
n = NoseCone(0.4, "powerseries", base_radius=0.05, rocket_radius=0.05, power=0.5)
show("nose powerseries 0.5 cpz", n.cpz)

# Elliptical fins, span larger and smaller than the body radius, cant 1 deg.
for span in [0.1, 0.05]:
    f = EllipticalFins(3, 0.12, span, 0.0635, cant_angle=1.0)
    p = f"elliptical span {span}"
    for mach in [0.0, 0.5, 0.9, 1.5]:
        show(f"{p} cnalpha({mach})", f.clalpha(mach))
    show(f"{p} cpz", f.cpz)
    show(f"{p} Yma", f.Yma)
    show(f"{p} Kd", f.roll_damping_interference_factor)
    show(f"{p} Kf", f.roll_forcing_interference_factor)
    show(f"{p} G", f.roll_geometrical_constant)
    show(f"{p} clf_delta(0)", f.roll_parameters[0](0))
    show(f"{p} cld_omega(0)", f.roll_parameters[1](0))

# Free-form fins: a swept trapezoid and a clipped-delta pentagon, cant 0.5 deg.
shapes = {
    "trapezoid": [(0, 0), (0.08, 0.1), (0.12, 0.1), (0.2, 0)],
    "pentagon": [(0, 0), (0.05, 0.06), (0.1, 0.09), (0.16, 0.09), (0.18, 0)],
}
for name, pts in shapes.items():
    f = FreeFormFins(4, pts, 0.0635, cant_angle=0.5)
    p = f"freeform {name}"
    show(f"{p} Af", f.Af)
    show(f"{p} gamma_c", f.gamma_c)
    show(f"{p} Yma", f.Yma)
    show(f"{p} cpz", f.cpz)
    show(f"{p} Kd", f.roll_damping_interference_factor)
    show(f"{p} G", f.roll_geometrical_constant)
    for mach in [0.0, 0.95, 2.0]:
        show(f"{p} cnalpha({mach})", f.clalpha(mach))
    show(f"{p} clf_delta(0)", f.roll_parameters[0](0))
    show(f"{p} cld_omega(0)", f.roll_parameters[1](0))

# Six trapezoidal fins with a sweep angle (fin-count factor 2.74).
f = TrapezoidalFins(6, 0.15, 0.05, 0.08, 0.05, sweep_angle=30)
for mach in [0.0, 0.7, 1.2]:
    show(f"trapezoidal six cnalpha({mach})", f.clalpha(mach))
show("trapezoidal six cpz", f.cpz)
