"""The fidelity report: for each robot and model the fitted parameters, plots
of what was measured against what the fitted model gives at the same
placements, the residuals, and what was not measured (so the simulation
still runs on defaults there)."""

from __future__ import annotations

import io
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..sweep.store import atomic_write  # noqa: E402
from . import geometry  # noqa: E402

NOT_MEASURED = {
    "ir": "the sensing cone (ir.aperture) and reach (ir.range); surfaces other than white card",
    "ambient": "a dark reading per sensor (one per robot is fitted); light from more than one lamp",
    "wheels": "the speed noise (wheels.speed_noise_rel) and the bias of seed 003's eq 3; the axle "
              "(53 mm is kept); slip on other floors",
    "camera": "the rendered camera's noise; how the reach depends on the light (one room's light)",
    "colours": "the exposure (gain_g is 1: the level is the camera's automatic exposure); other colours than "
               "the detector's three and grey; light other than the room's",
    "sound": "sound.a0 (one product with the gains: they are against the scenario's a0); each microphone "
             "apart (the model's three hear the same); more than one emitter",
}


def _save(fig, path: Path):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    atomic_write(path, buf.getvalue())


def _plot_ir(fit, path):
    fig, axes = plt.subplots(2, 4, figsize=(12, 5.5), sharex=True, sharey=True)
    for s, ax in enumerate(axes.flat):
        pts = sorted((p for p in fit.points if p["sensor"] == s and p["x"] != float("inf")), key=lambda p: p["x"])
        xs = [p["x"] * 1000 for p in pts]
        ax.plot(xs, [p["measured"] for p in pts], "o", ms=4, label="measured")
        ax.plot(xs, [p["simulated"] for p in pts], "-", label="model, fitted")
        ax.plot(xs, [geometry.ir_curve(p["x"]) for p in pts], ":", color="grey", label="default model")
        ax.set_title(f"IR{s}: gain {fit.params['sensors'][s]['gain']:.3g}, "
                     f"offset {fit.params['sensors'][s]['offset']:.3g}", fontsize=9)
    axes[0][0].legend(fontsize=8)
    for ax in axes[1]:
        ax.set_xlabel("sensor to wall, mm")
    for ax in axes[:, 0]:
        ax.set_ylabel("proximity, counts")
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.1, top=0.93, wspace=0.1, hspace=0.3)
    _save(fig, path)


def _plot_camera(fit, path):
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for ax, label, key, unit in ((axes[0], "ahead, mm", "range", 1000.0), (axes[1], "to the side, deg", "fov", 0.0)):
        pts = sorted((p for p in fit.points if p["label"] == label), key=lambda p: p["x"])
        ax.plot([p["x"] for p in pts], [p["measured"] for p in pts], "o", label="seen (measured)")
        edge = fit.params[key] * unit if unit else None
        if edge is not None:
            ax.axvline(edge, color="C1", label=f"fitted reach {edge:.0f} mm")
        else:
            edges = [p["x"] for p in pts if p["simulated"] > 0]
            if edges:
                ax.axvline(max(edges), color="C1", label=f"fitted fov {fit.params['fov']:.1f} deg")
        ax.set_xlabel(f"the card {label}")
        ax.set_yticks([0, 1], ["no", "yes"])
        ax.legend(fontsize=8)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.16, top=0.95, wspace=0.2)
    _save(fig, path)


def _plot_colours(fit, path):
    """Each card's limits (the largest threshold that keeps it in its
    class) and the grey card's (the least that rejects it), and the fitted
    threshold between them."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    lim = fit.params["limits"]
    for ax, key, param, unit in ((axes[0], "margin", "min_margin", "lead, counts"),
                                 (axes[1], "saturation_q8", "min_saturation_q8", "lead, /256 of the top channel")):
        ax.plot(range(len(lim["cards"])), [c[key] for c in lim["cards"]], "o", label="cards: admitted below")
        ax.plot([len(lim["cards"]) + k for k in range(len(lim["grey"]))], [g[key] for g in lim["grey"]], "s",
                color="grey", label="grey card: rejected above")
        ax.axhline(fit.params[param], color="C1", label=f"fitted {param} {fit.params[param]}")
        ax.set_xticks(range(len(lim["cards"]) + len(lim["grey"])),
                      [p["label"].split()[0] + f" {p['x']:g}" for p in fit.points] + ["grey"] * len(lim["grey"]),
                      fontsize=7, rotation=30)
        ax.set_ylabel(unit)
        ax.legend(fontsize=7)
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.2, top=0.95, wspace=0.25)
    _save(fig, path)


def _plot_generic(fit, path, xlabel):
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    m = [p["measured"] for p in fit.points]
    s = [p["simulated"] for p in fit.points]
    a.plot(s, m, "o", ms=4)
    lo, hi = min(m + s), max(m + s)
    a.plot([lo, hi], [lo, hi], "k--", lw=0.8)
    a.set_xlabel("model, fitted")
    a.set_ylabel("measured")
    a.set_title(f"{fit.procedure}: measured against the fitted model")
    b.plot(range(len(m)), [x - y for x, y in zip(m, s, strict=True)], "o", ms=4)
    b.axhline(0, color="k", lw=0.8)
    b.set_xlabel(xlabel)
    b.set_ylabel(f"residual, {fit.unit}")
    b.set_title(f"residuals (rms {fit.rms:.3g} {fit.unit})")
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.13, top=0.9, wspace=0.3)
    _save(fig, path)


def write(fits_by_robot: dict, out: Path, fragment_name: str) -> Path:
    """Plots and report.md into `out`; the report's path."""
    out.mkdir(parents=True, exist_ok=True)
    lines = ["# Calibration fidelity report", "",
             f"Fragment: `{fragment_name}`. \"Model\" is the simulator's model with the fitted parameters "
             "(the same equations: the kit's recovery test checks that they agree).", ""]
    measured = set()
    for rid in sorted(fits_by_robot):
        lines += [f"## Robot {rid}", ""]
        for proc, fit in fits_by_robot[rid].items():
            measured.add(proc)
            png = f"robot{rid}_{proc}.png"
            if proc == "ir":
                _plot_ir(fit, out / png)
            elif proc == "camera":
                _plot_camera(fit, out / png)
            elif proc == "colours":
                _plot_colours(fit, out / png)
            else:
                _plot_generic(fit, out / png, {"ambient": "measurement", "sound": "placement"}.get(proc, "run, quantity"))
            params = {k: v for k, v in fit.params.items() if k not in ("sensors", "limits")}
            lines += [f"### {proc}", "", f"rms residual {fit.rms:.3g} {fit.unit}; parameters: "
                      + ", ".join(f"{k} = {v}" for k, v in params.items()), ""]
            if "sensors" in fit.params:
                lines += ["| sensor | gain | offset |", "|---|---|---|"]
                lines += [f"| IR{s} | {c['gain']} | {c['offset']} |" for s, c in enumerate(fit.params["sensors"])]
                lines.append("")
            if proc == "colours":
                lines += ["| card | mm | R, G, B mean | sd | its pixels the robot's detector put in its class |",
                          "|---|---|---|---|---|"]
                lines += [f"| {p['label']} | {p['x']:g} | {', '.join(f'{v:.0f}' for v in p['mean'])} | "
                          f"{', '.join(f'{v:.1f}' for v in p['sd'])} | {p['measured']:.0f} of {p['pixels']:.0f} |"
                          for p in fit.points]
                lines.append("")
            lines += [f"![{proc}]({png})", ""]
    lines += ["## Not measured", ""]
    for proc, text in NOT_MEASURED.items():
        if proc not in measured:
            lines.append(f"- {proc}: not measured in these recordings: the defaults stay")
        lines.append(f"- {proc}: {text}")
    report = out / "report.md"
    atomic_write(report, "\n".join(lines) + "\n")
    return report
