"""Figures of flights and studies with matplotlib (an optional dependency): the figures
``karman simulate --out`` and ``karman montecarlo`` write as SVG."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from ._karman import Flight, Study

FLIGHT_FIGURES = ("altitude", "ground_track", "speed_mach", "attitude", "stability")


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError as error:  # pragma: no cover - depends on the environment
        raise ImportError(
            "plotting needs matplotlib: pip install matplotlib (or karman[plot])"
        ) from error
    return plt


def _finish(plt: Any, figures: dict[str, Any], path: str | None, show: bool) -> None:
    for name, figure in figures.items():
        figure.tight_layout()
        if path is not None:
            figure.savefig(path.replace("{name}", name) if "{name}" in path else path)
    if show:
        plt.show()


def plot_flight(
    flight: Flight, which: list[str] | None, path: str | None, show: bool
) -> dict[str, Any]:
    """The flight's figures by name; ``path`` must contain ``{name}`` to save several."""
    plt = _pyplot()
    names = list(FLIGHT_FIGURES if which is None else which)
    unknown = [n for n in names if n not in FLIGHT_FIGURES]
    if unknown:
        raise ValueError(f"unknown figures {unknown}; choose from {list(FLIGHT_FIGURES)}")
    if path is not None and len(names) > 1 and "{name}" not in path:
        raise ValueError("path must contain {name} to save several figures")
    t = flight.t
    apogee_time = flight.apogee_time_s
    ascent = t <= (apogee_time if apogee_time is not None else np.inf)
    figures: dict[str, Any] = {}
    for name in names:
        figure, axes = plt.subplots()
        if name == "altitude":
            axes.plot(t, flight["altitude_agl"], label="altitude")
            axes.set(title="Altitude", xlabel="time (s)", ylabel="altitude AGL (m)")
        elif name == "ground_track":
            axes.plot(flight["x"], flight["y"], label="track")
            axes.set(
                title="Ground track",
                xlabel="east of the pad (m)",
                ylabel="north of the pad (m)",
            )
        elif name == "speed_mach":
            axes.plot(t, flight["speed"], label="speed (m/s)")
            axes.plot(t, 100 * flight["mach"], label="Mach × 100")
            axes.set(title="Speed and Mach", xlabel="time (s)", ylabel="speed (m/s), Mach × 100")
        elif name == "attitude":
            for series, label in (
                ("attitude_angle", "attitude angle"),
                ("path_angle", "path angle"),
                ("angle_of_attack", "angle of attack"),
            ):
                axes.plot(t[ascent], flight[series][ascent], label=label)
            axes.set(
                title="Attitude and angle of attack (ascent)",
                xlabel="time (s)",
                ylabel="angle (deg)",
            )
        else:
            axes.plot(t[ascent], flight["static_margin"][ascent], label="static margin")
            axes.plot(t[ascent], flight["stability_margin"][ascent], label="stability margin")
            axes.set(
                title="Static and stability margin (ascent)",
                xlabel="time (s)",
                ylabel="margin (calibres)",
            )
        axes.grid(True)
        axes.legend()
        figures[name] = figure
    _finish(plt, figures, path, show)
    return figures


def ellipse_boundary(ellipse: dict[str, Any], sigma: int, points: int = 200) -> np.ndarray:
    """The (x, y) points of an ellipse's RocketPy ``sigma``-contour, shape (points, 2)."""
    contour = ellipse["k_sigma_rocketpy"][sigma - 1]
    angle = np.radians(ellipse["orientation_deg"])
    s = np.linspace(0.0, 2.0 * np.pi, points)
    u = contour["semi_major_m"] * np.cos(s)
    v = contour["semi_minor_m"] * np.sin(s)
    x = ellipse["center_m"][0] + u * np.cos(angle) - v * np.sin(angle)
    y = ellipse["center_m"][1] + u * np.sin(angle) + v * np.cos(angle)
    return np.column_stack([x, y])


def plot_ellipses(study: Study, path: str | None, show: bool) -> Any:
    """The landing and apogee points of the study with their 1/2/3-sigma ellipses."""
    plt = _pyplot()
    figure, axes = plt.subplots()
    colours = {"apogee": "tab:blue", "landing": "tab:red"}
    for name, ellipse in study.ellipses.items():
        x_key, y_key = ellipse["outputs"]
        colour = colours.get(name, "tab:gray")
        axes.scatter(
            study.outputs[x_key], study.outputs[y_key], s=4, color=colour, alpha=0.5,
            label=f"{name} points",
        )
        for sigma in (1, 2, 3):
            boundary = ellipse_boundary(ellipse, sigma)
            axes.plot(boundary[:, 0], boundary[:, 1], color=colour, linewidth=1.0 + 0.5 * (3 - sigma),
                      label=f"{name} {sigma}σ" if sigma == 1 else None)
    axes.plot([0.0], [0.0], marker="^", color="black", linestyle="none", label="launch")
    axes.set(
        title="Apogee and landing dispersion",
        xlabel="east of the pad (m)",
        ylabel="north of the pad (m)",
    )
    axes.set_aspect("equal", adjustable="datalim")
    axes.grid(True)
    axes.legend()
    _finish(plt, {"ellipses": figure}, path, show)
    return figure
