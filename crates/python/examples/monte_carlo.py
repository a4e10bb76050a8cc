"""Example 3 of the RocketPy paper (Ceotto et al. 2021): a Monte Carlo dispersion study with
the 1, 2 and 3 sigma apogee and landing ellipses. The inputs vary as in RocketPy's Monte
Carlo documentation (mass, inclination, heading, impulse, drag, parachute drag areas);
a mission with a [dispersion] table of its own uses that instead.
Run: python monte_carlo.py [--mission FILE] [--samples N] [--out DIR]."""

from __future__ import annotations

import numpy as np
from _common import arguments, load, pyplot

VARY = {
    "rocket.mass": {"std": 0.5},
    "flight.inclination": {"std": 1.0},
    "flight.heading": {"std": 2.0},
    "motor.total_impulse": {"factor": {"normal": [1.0, 0.033]}},
    "rocket.power_off_drag": {"factor": {"normal": [1.0, 0.05]}},
    "rocket.power_on_drag": {"factor": {"normal": [1.0, 0.05]}},
}


def main() -> None:
    args = arguments(__doc__)
    mission = load(args.mission)
    own = mission.to_dict().get("dispersion")
    vary = None if own else dict(VARY)
    if vary is not None:
        for name in mission.to_dict()["rocket"].get("parachutes", {}):
            vary[f"rocket.parachutes.{name}.cd_s"] = {"factor": {"normal": [1.0, 0.1]}}
    study = mission.montecarlo(samples=args.samples, seed=2022, vary=vary)
    print(f"{study.samples} flights in {study.elapsed:.2f} s ({study.rate:.0f} flights/s on"
          f" {study.threads} threads), {len(study.failures)} failed")
    apogee = study.outputs["apogee_agl_m"]
    print(f"apogee AGL: mean {np.nanmean(apogee):.1f} m, std {np.nanstd(apogee):.1f} m")
    for name, ellipse in study.ellipses.items():
        cx, cy = ellipse["center_m"]
        print(f"{name} ellipse: centre ({cx:.1f}, {cy:.1f}) m, major axis"
              f" {ellipse['orientation_deg']:.1f} deg from east")
        for contour in ellipse["k_sigma_rocketpy"]:
            print(f"  {contour['sigma']} sigma: {2 * contour['semi_major_m']:.1f} m x"
                  f" {2 * contour['semi_minor_m']:.1f} m")
    if pyplot() is not None:
        study.plot_ellipses(path=str(args.out / "ellipses.png"))
        print(f"figure: {args.out / 'ellipses.png'}")


if __name__ == "__main__":
    main()
