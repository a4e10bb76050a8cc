"""Example 2 of the RocketPy paper (Ceotto et al. 2021): dynamic stability. The fin set is
moved to 0.5, 0.7, 0.9, 1.1 and 1.3 times its distance from the rocket's centre of mass
without motor; each variant flies vertically to apogee (at most 5 s, steps of at most
0.01 s) and the attitude angles are compared in one figure, with the static margins at
t = 0, at rail exit and at the end of each flight.
Run: python dynamic_stability.py [--mission FILE] [--out DIR]."""

from __future__ import annotations

import numpy as np
from _common import arguments, load, pyplot

FACTORS = (0.5, 0.7, 0.9, 1.1, 1.3)


def fin_set(data: dict) -> str:
    """The name of the mission's (first) fin set."""
    for name, surface in data["rocket"]["surfaces"].items():
        if surface["type"].endswith("fins"):
            return name
    raise SystemExit("the mission has no fins")


def main() -> None:
    args = arguments(__doc__)
    base = load(args.mission)
    data = base.to_dict()
    fins = fin_set(data)
    reference = data["rocket"]["center_of_mass_without_motor"]
    distance = data["rocket"]["surfaces"][fins]["position"] - reference
    results = []
    for factor in FACTORS:
        variant = base.copy()
        variant.set(f"rocket.surfaces.{fins}.position", reference + distance * factor)
        variant.set("flight.inclination", 90)
        variant.set("flight.heading", 0)
        variant.set("flight.max_time_step", 0.01)
        variant.set("flight.max_time", 5)
        variant.set("flight.terminate_on_apogee", True)
        flight = variant.simulate()
        end = flight.t[-1]
        rail_exit = flight.out_of_rail_time_s
        margins = (
            flight.static_margin(0.0),
            flight.static_margin(rail_exit) if rail_exit is not None else float("nan"),
            flight.static_margin(end),
        )
        results.append((factor, flight, margins))
        print(
            f"factor {factor:.1f}: static margin {margins[0]:6.3f} (t=0), {margins[1]:6.3f}"
            f" (rail exit), {margins[2]:6.3f} (t={end:.2f} s); attitude angle"
            f" {np.min(flight['attitude_angle']):.2f} to {np.max(flight['attitude_angle']):.2f} deg"
        )
    plt = pyplot()
    if plt is not None:
        figure, axes = plt.subplots()
        for factor, flight, margins in results:
            axes.plot(
                flight.t, flight["attitude_angle"],
                label=f"factor {factor}: SM {margins[0]:.2f} / {margins[1]:.2f} / {margins[2]:.2f}",
            )
        axes.set(title="Dynamic stability: attitude angle", xlabel="time (s)",
                 ylabel="attitude angle (deg)")
        axes.grid(True)
        axes.legend(title="static margin at 0 / rail exit / end")
        figure.tight_layout()
        figure.savefig(args.out / "dynamic_stability.png")
        print(f"figure: {args.out / 'dynamic_stability.png'}")


if __name__ == "__main__":
    main()
