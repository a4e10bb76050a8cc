"""Apogee by mass: how heavy may the rocket be to reach a target apogee? The apogee over a
range of masses, and the mass that gives each of a few target apogees found by
`Mission.solve` (Brent's bracketing root finder, a flight per step).
Run: python apogee_by_mass.py [--mission FILE] [--out DIR]."""

from __future__ import annotations

import karman
from _common import arguments, load, pyplot


def main() -> None:
    args = arguments(__doc__)
    mission = load(args.mission)
    nominal = mission.to_dict()["rocket"]["mass"]
    nominal_apogee = mission.simulate().apogee_agl_m
    print(f"nominal mass {nominal:.3f} kg: apogee {nominal_apogee:.1f} m")
    masses = [nominal * (0.8 + 0.1 * k) for k in range(5)]
    apogees = []
    for mass in masses:
        flight = karman.load(args.mission, {"rocket.mass": mass}).simulate()
        apogees.append(flight.apogee_agl_m)
        print(f"  mass {mass:8.3f} kg  apogee {flight.apogee_agl_m:9.1f} m")
    solved = []
    for target in (0.9 * nominal_apogee, nominal_apogee, 1.1 * nominal_apogee):
        target = round(target, -1)
        result = mission.solve({"apogee_agl_m": target}, "rocket.mass", tolerance=0.05)
        solved.append((result["value"], result["achieved"]))
        print(
            f"target apogee {target:8.1f} m: mass {result['value']:.4f} kg "
            f"(apogee {result['achieved']:.3f} m, {result['flights']} flights)"
        )
    plt = pyplot()
    if plt is not None:
        figure, axes = plt.subplots()
        axes.plot(masses, apogees, "o-", label="simulated")
        axes.plot(*zip(*solved), "x", markersize=10, label="solved for a target")
        axes.set_xlabel("rocket mass without motor (kg)")
        axes.set_ylabel("apogee above ground (m)")
        axes.legend()
        figure.savefig(args.out / "apogee_by_mass.png", dpi=120)
        print(f"figure: apogee_by_mass.png in {args.out}")


if __name__ == "__main__":
    main()
