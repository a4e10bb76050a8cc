"""Example 1 of the RocketPy paper (Ceotto et al. 2021): a first trajectory, its summary and
plots. Run: python first_trajectory.py [--mission FILE] [--out DIR]."""

from __future__ import annotations

from _common import arguments, load, pyplot


def main() -> None:
    args = arguments(__doc__)
    mission = load(args.mission)
    flight = mission.simulate()
    print(f"{flight.name}: {flight.termination} after {flight.t[-1]:.1f} s")
    for key in (
        "out_of_rail_time_s",
        "out_of_rail_velocity_mps",
        "initial_static_margin",
        "out_of_rail_stability_margin",
        "apogee_agl_m",
        "apogee_time_s",
        "max_speed_mps",
        "max_mach",
        "impact_time_s",
        "impact_velocity_mps",
    ):
        value = getattr(flight, key)
        print(f"  {key:<30} {value:12.3f}" if value is not None else f"  {key:<30} {'—':>12}")
    for event in flight.events:
        print(f"  event {event['name']:<20} at {event['time_s']:9.3f} s")
    flight.export_csv(args.out / "trajectory.csv")
    flight.export_kml(args.out / "flight.kml")
    if pyplot() is not None:
        figures = flight.plot(path=str(args.out / "{name}.png"))
        print(f"figures: {', '.join(sorted(figures))} in {args.out}")


if __name__ == "__main__":
    main()
