"""The fits: each model's parameters from a procedure's steps, by least
squares (scipy.optimize.least_squares), with what is left over (residuals)
for the report.  A fit that cannot be made (too few usable points, every
reading saturated), or that lands on a bound of a parameter or leaves
residuals larger than the model allows (MAX_RMS: readings the model does
not describe, such as wheel runs answered 0 0 0), raises FitError naming
the procedure and what to redo.

  ir       per sensor: reading = gain * curve(d) + offset, the curve the
           simulator's table (ir_curve); per robot: the noise, variance =
           (noise_rel * reading)^2 + noise_abs^2 + 1/12 (rounding)
  ambient  per robot: reading = dark * half / (half + E), E each sensor's
           irradiance from the lamp (procedures.irradiance); noise_rel
  wheels   per robot: each wheel's gain (actual over commanded speed),
           from where the robot ended after each run, integrated as the
           simulator does (one straight segment per control period)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from . import geometry
from .procedures import CARD_DIAMETER_MM, COLOUR_CARDS, Setup, Step, ir_distance_m, irradiance, seen

#: A mean at or above this is saturated (the ADC's 4095, less the noise).
SATURATED = 4000.0
#: A mean below this is clipped at 0 by its noise: no use for the noise fit.
FLOOR = 20.0
#: Least usable distances per IR sensor (two parameters and a check).
MIN_IR_POINTS = 3


#: The largest rms residual of a fit, in its report's units, above which the
#: readings are not what the model describes (swarm-calibrate --max-rms
#: PROCEDURE=VALUE).  Each is well above what a working robot leaves (the
#: fake lab's robots, tools/tests/calibrate/: IR under 10 counts, ambient
#: under 16, wheels under 0.6 mm / deg, sound under 0.013) and well below
#: what readings unrelated to the placements give (ambient readings that do
#: not change with distance: 1.8e3 counts; wheel runs answered 0 0 0: 99):
#: IR and ambient 100 counts (2.5 % of the ADC's range), wheels 5 mm / deg
#: (five times the ruler's and the protractor's 1 mm and 1 deg), sound 0.1
#: (10 % of each level).
MAX_RMS = {"ir": 100.0, "ambient": 100.0, "wheels": 5.0, "sound": 0.1}


class FitError(ValueError):
    def __init__(self, procedure: str, what: str, redo: str, robot_id: int | None = None):
        who = f"robot {robot_id}: " if robot_id is not None else ""
        super().__init__(f"{who}{procedure}: {what}; redo: {redo}")
        self.procedure, self.what, self.redo, self.robot_id = procedure, what, redo, robot_id

    def of_robot(self, robot_id: int) -> FitError:
        """The same error naming the robot."""
        return FitError(self.procedure, self.what, self.redo, robot_id)


def _check_bounds(procedure: str, res, names: list, lo: list, hi: list, redo: str, reachable=()):
    """A least-squares fit whose parameter ended on its bound did not find
    the model's minimum there (the bounds are far outside any robot's
    values): the readings do not follow the model.  `reachable`: (name,
    -1 lower / +1 upper) bounds that are physical limits a robot's value
    may sit at (no noise term, the ADC's full scale), not failures."""
    for k, active in enumerate(res.active_mask):
        if active and (names[k], int(active)) not in reachable:
            raise FitError(procedure, f"{names[k]} came out {res.x[k]:.4g}, the bound of its fit "
                           f"({lo[k]:g} to {hi[k]:g}): the readings do not follow the model", redo)


def _checked_rms(procedure: str, residuals, unit: str, max_rms: float | None, redo: str) -> float:
    """The rms of a fit's residuals, once it is within the procedure's
    tolerance (`max_rms`, else MAX_RMS's)."""
    rms = float(np.sqrt(np.mean(np.asarray(residuals) ** 2)))
    tol = MAX_RMS[procedure] if max_rms is None else max_rms
    if not rms <= tol:
        raise FitError(procedure, f"the fit's rms residual is {rms:.3g} {unit}, above the tolerance {tol:g} "
                       f"{unit} (--max-rms {procedure}=...): the readings do not follow the model", redo)
    return rms


@dataclass
class Fit:
    """One model's parameters, and the points behind them for the report."""
    procedure: str
    params: dict
    points: list = field(default_factory=list)   # dicts: x, measured, simulated, label
    rms: float = 0.0
    unit: str = ""


def _pooled(windows):
    """Mean and within-window variance of each channel over windows of
    equal length."""
    m = np.array([w[0] for w in windows], float)
    v = np.array([w[1] for w in windows], float)
    return m.mean(axis=0), v.mean(axis=0) + (m.var(axis=0) if len(windows) > 1 else 0.0)


def fit_ir(steps: list[Step], max_rms: float | None = None) -> Fit:
    if not steps:
        raise FitError("ir", "no steps recorded", "the whole ir procedure")
    offsets_seen = np.zeros(8)
    per_sensor = {s: [] for s in range(8)}
    noise_pts = []
    for st in steps:
        mean, var = _pooled(st.windows)
        p = st.placement
        if p.gap_mm is None:
            offsets_seen = mean
            for s in range(8):
                per_sensor[s].append((math.inf, mean[s], var[s], "open"))
            continue
        per_sensor[p.sensor].append((ir_distance_m(p), mean[p.sensor], var[p.sensor], f"{p.gap_mm:g} mm"))
    sensors, points = [], []
    for s in range(8):
        rows = [r for r in per_sensor[s] if r[1] < SATURATED]
        near = [r for r in rows if math.isfinite(r[0])]
        if len(near) < MIN_IR_POINTS:
            sat = [r[3] for r in per_sensor[s] if r[1] >= SATURATED]
            raise FitError("ir", f"IR{s} has {len(near)} usable distances (at least {MIN_IR_POINTS}"
                           + (f"; saturated at {', '.join(sat)}" if sat else "") + ")",
                           f"the ir steps of IR{s}, the body further from the wall")
        c = np.array([geometry.ir_curve(d) if math.isfinite(d) else 0.0 for d, *_ in rows])
        y = np.array([r[1] for r in rows])
        sd = np.sqrt(np.array([r[2] for r in rows]) + 1.0)
        res = least_squares(lambda q, c=c, y=y, sd=sd: (q[0] * c + q[1] - y) / sd, x0=[1.0, float(offsets_seen[s])])
        g, o = float(res.x[0]), float(res.x[1])
        if not (0.05 < g < 20):
            raise FitError("ir", f"IR{s}'s gain came out {g:.3g}: its readings do not follow the curve",
                           f"the ir steps of IR{s} (a white wall, square on, the gaps measured)")
        sensors.append({"gain": round(g, 4), "offset": round(o, 2)})
        for (d, m, v, label), ci in zip(rows, c, strict=True):
            points.append({"sensor": s, "x": d, "label": label, "measured": m, "simulated": g * ci + o,
                           "var": v})
            if m >= FLOOR:
                noise_pts.append((g * ci + o, v))
    if len(noise_pts) < 3:
        raise FitError("ir", "too few readings above the floor for the noise", "the ir procedure")
    mu = np.array([p[0] for p in noise_pts])
    var = np.array([p[1] for p in noise_pts])

    def noise_res(q):
        model = np.sqrt((q[0] * mu) ** 2 + q[1] ** 2 + 1.0 / 12.0)
        return (model - np.sqrt(var)) / np.sqrt(model)

    lo, hi = [0.0, 0.0], [1.0, 4095.0]
    nr = least_squares(noise_res, x0=[0.01, 5.0], bounds=(lo, hi))
    redo = "the ir procedure (a white wall, square on, the gaps measured)"
    # A noise term of 0 is a sensor without it, not a failed fit.
    _check_bounds("ir", nr, ["noise_rel", "noise_abs"], lo, hi, redo, {("noise_rel", -1), ("noise_abs", -1)})
    rms = _checked_rms("ir", [p["measured"] - p["simulated"] for p in points], "counts", max_rms, redo)
    return Fit("ir", {"sensors": sensors, "noise_rel": round(float(nr.x[0]), 5),
                      "noise_abs": round(float(nr.x[1]), 3)}, points, rms, "counts")


def fit_ambient(steps: list[Step], setup: Setup, max_rms: float | None = None) -> Fit:
    if not steps:
        raise FitError("ambient", "no steps recorded", "the whole ambient procedure")
    e, y, sd = [], [], []
    labels = []
    for st in steps:
        mean, var = _pooled(st.windows)
        for s, irr in enumerate(irradiance(st.placement, setup)):
            e.append(irr)
            y.append(mean[s])
            sd.append(math.sqrt(var[s] + 1.0))
            labels.append((s, st.placement.distance_mm))
    e, y, sd = np.array(e), np.array(y), np.array(sd)
    lit = e > 0
    if lit.sum() < 3 or (~lit).sum() < 1:
        raise FitError("ambient", "too few lit (or no dark) readings", "the ambient procedure")
    if np.all(y[lit] < FLOOR):
        raise FitError("ambient", "every lit reading is near 0 (saturated by light)",
                       "the ambient procedure with a dimmer lamp or further from it")
    lo, hi = [0.0, 1e-6], [4095.0, 1e6]
    res = least_squares(lambda q: (q[0] * q[1] / (q[1] + e) - y) / sd, x0=[float(y.max()), 1.0],
                        bounds=(lo, hi), x_scale=[1000.0, 1.0])
    redo = "the ambient procedure (one lamp in a dark room, the distances from its foot measured)"
    # A dark reading at the ADC's full scale is a sensor that reads so in the dark.
    _check_bounds("ambient", res, ["dark", "half"], lo, hi, redo, {("dark", 1)})
    dark, half = float(res.x[0]), float(res.x[1])
    model = dark * half / (half + e)
    var = np.array([st_var for st in steps for st_var in _pooled(st.windows)[1]])
    usable = model >= FLOOR
    rel = float(np.sqrt(max(0.0, np.mean(np.maximum(var[usable] - 1.0 / 12.0, 0.0) / model[usable] ** 2))))
    points = [{"sensor": s, "x": float(ei), "label": f"{dist:g} mm", "measured": float(yi), "simulated": float(mi)}
              for (s, dist), ei, yi, mi in zip(labels, e, y, model, strict=True)]
    rms = _checked_rms("ambient", y - model, "counts", max_rms, redo)
    return Fit("ambient", {"dark": round(dark, 2), "half": round(half, 5), "noise_rel": round(rel, 5)}, points,
               rms, "counts")


def wheel_end(gl: float, gr: float, left: int, right: int, periods: int, period_s: float) -> tuple:
    """(forward m, left m, turned rad) after `periods` control periods, as the
    simulator moves a robot: each period a straight segment along the
    heading at its start, then the turn."""
    step, axle = geometry.step_m(), geometry.axle_m()
    vl, vr = gl * left * step, gr * right * step
    v, w = 0.5 * (vl + vr), (vr - vl) / axle
    k = np.arange(periods)
    th = w * period_s * k
    return float(np.sum(v * period_s * np.cos(th))), float(np.sum(v * period_s * np.sin(th))), w * period_s * periods


#: What a ruler and a protractor give: mm and degrees.
RULER_MM, PROTRACTOR_DEG = 1.0, 1.0


def fit_wheels(steps: list[Step], setup: Setup, max_rms: float | None = None) -> Fit:
    runs = [st for st in steps if st.moved is not None]
    if len(runs) < 2 or not any(st.placement.left == st.placement.right for st in runs):
        raise FitError("wheels", f"{len(runs)} runs measured, none straight" if runs else "no runs measured",
                       "the wheels procedure (every run, its end measured)")
    period = setup.period_ms / 1000.0

    def res(q):
        out = []
        for st in runs:
            p = st.placement
            fx, fy, ft = wheel_end(q[0], q[1], p.left, p.right, p.periods, period)
            mx, my, mt = st.moved
            out += [(fx * 1000 - mx) / RULER_MM, (fy * 1000 - my) / RULER_MM,
                    (math.degrees(ft) - mt) / PROTRACTOR_DEG]
        return np.array(out)

    lo, hi = [0.1, 0.1], [10.0, 10.0]
    fit = least_squares(res, x0=[1.0, 1.0], bounds=(lo, hi))
    redo = "the wheels procedure (every run, its end measured from the start mark)"
    _check_bounds("wheels", fit, ["gain_left", "gain_right"], lo, hi, redo)
    gl, gr = float(fit.x[0]), float(fit.x[1])
    points = []
    for st in runs:
        p = st.placement
        fx, fy, ft = wheel_end(gl, gr, p.left, p.right, p.periods, period)
        label = f"{p.left},{p.right} x{p.periods}"
        for what, m, s in (("forward mm", st.moved[0], fx * 1000), ("left mm", st.moved[1], fy * 1000),
                           ("turned deg", st.moved[2], math.degrees(ft))):
            points.append({"label": f"{label} {what}", "x": what, "measured": m, "simulated": s})
        want = p.left * p.periods * period, p.right * p.periods * period
        if st.steps is not None and max(abs(st.steps[0] - want[0]), abs(st.steps[1] - want[1])) > 2:
            raise FitError("wheels", f"run {label} counted {st.steps[0]:g}, {st.steps[1]:g} steps where "
                           f"{want[0]:g}, {want[1]:g} were commanded (motors clipped? period not "
                           f"{setup.period_ms} ms?)", f"the wheels run {label}")
    rms = _checked_rms("wheels", res(fit.x), "mm / deg", max_rms, redo)
    return Fit("wheels", {"gain_left": round(gl, 5), "gain_right": round(gr, 5)}, points, rms, "mm / deg")


def _threshold(rows, what, redo):
    """The midpoint between the farthest value seen and the nearest not seen
    beyond it, from (value, seen) pairs."""
    yes = [v for v, s in rows if s]
    if not yes:
        raise FitError("camera", f"the card was never seen {what}", redo)
    no = [v for v, s in rows if not s and v > max(yes)]
    if not no:
        raise FitError("camera", f"the card was seen at every {what} tried: no edge found", redo)
    return 0.5 * (max(yes) + min(no)), min(no) - max(yes)


def fit_camera(steps: list[Step]) -> Fit:
    """The geometric camera's reach (camera.range: lens to the card's near
    side) and field of view (camera.fov), from where the card stopped being
    seen.  At the fov's edge the model shows a blob while at least one
    pixel column of it is in view: the card's centre at bearing b* with
    half-width w is seen up to b* = half (1 - 2 / width_px) + w."""
    r_card = CARD_DIAMETER_MM / 2000.0
    ahead = [(st.placement.distance_mm, seen(st)) for st in steps if not st.placement.bearing_deg]
    side = [(st.placement.bearing_deg, seen(st), st.placement.distance_mm) for st in steps if st.placement.bearing_deg]
    if not ahead or not side:
        raise FitError("camera", "steps missing (ahead and to the side)", "the whole camera procedure")
    reach_mm, reach_gap = _threshold(ahead, "ahead", "the camera procedure (the card straight ahead)")
    b_star, b_gap = _threshold([(b, s) for b, s, _ in side], "to the side", "the camera procedure (the card to the side)")
    dc = side[0][2] / 1000.0 + r_card
    w = math.degrees(math.asin(r_card / dc))
    half = (b_star - w) / (1.0 - 2.0 / geometry.camera_width_px())
    col_at_reach = math.degrees(2 * math.asin(r_card / (reach_mm / 1000.0 + r_card))) / (2 * half / geometry.camera_width_px())
    if col_at_reach < 1.5:
        raise FitError("camera", f"at its reach ({reach_mm:g} mm) the card is {col_at_reach:.2g} pixel columns wide: "
                       "the width, not the reach, ended the view", "the camera procedure with a wider card")
    points = [{"x": v, "label": "ahead, mm", "measured": float(s), "simulated": float(v <= reach_mm)}
              for v, s in ahead]
    points += [{"x": b, "label": "to the side, deg", "measured": float(s), "simulated": float(b <= b_star)}
               for b, s, _ in side]
    return Fit("camera", {"range": round(reach_mm / 1000.0, 4), "fov": round(2 * half, 3),
                          "range_step_mm": round(reach_gap, 2), "fov_step_deg": round(b_gap, 3)},
               points, 0.0, "seen (0/1)")


def fit_sound(steps: list[Step], setup: Setup, max_rms: float | None = None) -> Fit:
    """Seed 002's eq 1 heard through this robot's microphones: level (counts)
    = 1000 gain_b (a0 e^(-alpha d) + ae) while the emitter plays band b at
    d (centre to centre), 1000 gain_b ae while it is silent; alpha shared by
    the bands.  a0 and the gains are one product: the gains are against
    the scenario's a0 (Setup.sound_a0).  The noise: eq 4's relative sd,
    from the spread within the windows."""
    by_band = {}
    for st in steps:
        mean, var = _pooled(st.windows)
        level = float(np.mean(mean[:3]))
        by_band.setdefault(st.placement.band, []).append((st.placement, level, float(np.mean(var[:3]))))
    bands = sorted(by_band)
    if not bands:
        raise FitError("sound", "no steps recorded", "the whole sound procedure")
    for b in bands:
        rows = by_band[b]
        if sum(1 for p, *_ in rows if p.tone) < 3 or not any(not p.tone for p, *_ in rows):
            raise FitError("sound", f"band {b} has too few distances (3 with the tone and one silent)",
                           f"the sound steps of band {b}")
        if all(level <= 0 for _, level, _ in rows):
            raise FitError("sound", f"band {b} was never heard", f"the sound steps of band {b} (is the emitter on?)")

    def model(q):
        alpha, rest = q[0], q[1:]
        out = []
        for k, b in enumerate(bands):
            a, e = rest[2 * k], rest[2 * k + 1]
            out += [1000.0 * (a * math.exp(-alpha * p.distance_mm / 1000.0) + e) if p.tone else 1000.0 * e
                    for p, _, _ in by_band[b]]
        return np.array(out)

    y = np.array([level for b in bands for _, level, _ in by_band[b]])
    x0 = [0.7] + [v for b in bands for v in (max(y) / 1000.0, min(y) / 1000.0)]
    lo, hi = [0.0] + [0.0] * 2 * len(bands), [1000.0] + [1e7] * 2 * len(bands)
    res = least_squares(lambda q: (model(q) - y) / np.maximum(y, 1.0), x0=x0, bounds=(lo, hi))
    redo = "the sound procedure (the distances from the emitter measured, the emitter playing)"
    # A silent level of 0 is a quiet room, not a failed fit.
    _check_bounds("sound", res, ["alpha"] + [f"band {b}'s {w}" for b in bands for w in ("a0", "ae")], lo, hi, redo,
                  {(f"band {b}'s ae", -1) for b in bands})
    alpha = float(res.x[0])
    gains = {b: float(res.x[1 + 2 * k]) / setup.sound_a0 for k, b in enumerate(bands)}
    ae = float(np.mean([res.x[2 + 2 * k] / gains[b] for k, b in enumerate(bands)]))
    tone = [(level, var) for b in bands for p, level, var in by_band[b] if p.tone and level > 0]
    noise = float(np.sqrt(np.mean([max(v - 1.0 / 12.0, 0.0) / m ** 2 for m, v in tone])))
    sim = model(res.x)
    points = [{"band": b, "x": p.distance_mm if p.tone else 0.0, "label": f"band {b}" + ("" if p.tone else " silent"),
               "measured": level, "simulated": float(s)}
              for (b, (p, level, _)), s in zip(((b, r) for b in bands for r in by_band[b]), sim, strict=True)]
    rms = _checked_rms("sound", (sim - y) / np.maximum(y, 1.0), "relative", max_rms, redo)
    return Fit("sound", {"alpha": round(alpha, 5), "ae": round(ae, 4), "noise": round(noise, 5),
                         **{f"gain{b}": round(g, 5) for b, g in gains.items()}}, points, rms, "relative")


#: A card's channel mean at or above this is clipped (the sensor's 255).
COLOUR_SATURATED = 250.0
#: The pixel spreads (sd) a threshold keeps from a card's and the grey card's
#: distributions: 2 sd on each side (about 98 % of a normal channel's pixels).
COLOUR_K = 2.0
#: Least distances per card (a distribution and a check).
MIN_COLOUR_DISTANCES = 2


def _card_stats(steps):
    """{(card, stats): [(distance, pixels, mean[3], sd[3])]}: each channel's
    mean over the windows and its spread (within frames and between them)."""
    out = {}
    for st in steps:
        p = st.placement
        m = np.array([w[0] for w in st.windows], float)
        mean = m[:, 1:4].mean(axis=0)
        spread = np.sqrt((m[:, 4:7] ** 2).mean(axis=0) + (m[:, 1:4].var(axis=0) if len(m) > 1 else 0.0))
        out.setdefault((p.colour, p.stats), []).append((p.distance_mm, float(m[:, 0].mean()), mean, spread))
    return out


def colour_limits(mean, sd, cls: int) -> dict:
    """The largest thresholds (hal/blob_detect.h's rules) that still admit a
    card's pixel COLOUR_K sd below its mean in its own channel and above it
    in the others: the dominant value m, its lead m - s and the lead in
    /256 of m."""
    c = cls - 1
    m = float(mean[c] - COLOUR_K * sd[c])
    s = max(float(mean[j] + COLOUR_K * sd[j]) for j in range(3) if j != c)
    lead = m - s
    return {"value": m, "margin": lead, "saturation_q8": 256.0 * lead / m if m > 0 else 0.0}


def grey_limits(mean, sd) -> dict:
    """The largest lead (absolute, and in /256 of the top channel) of any
    channel over the others in the grey card's pixels, COLOUR_K sd out:
    thresholds above these reject it."""
    lead, sat = 0.0, 0.0
    for a in range(3):
        top = float(mean[a] + COLOUR_K * sd[a])
        second = max(float(mean[b] - COLOUR_K * sd[b]) for b in range(3) if b != a)
        lead = max(lead, top - second)
        sat = max(sat, 256.0 * (top - second) / top if top > 0 else 0.0)
    return {"margin": lead, "saturation_q8": sat}


def thresholds(cards: list[dict], greys: list[dict]) -> dict:
    """The detector's shared thresholds between the cards' limits (every
    card of every robot admitted) and the grey's (every grey rejected): the
    midpoint of the gap, which keeps the most room on both sides (the
    largest least margin).  Both the lead and the saturation are set so; a
    grey is rejected when either one is above its own, so one gap is
    enough: where the other has none it is put at half the cards' least
    (no grey rejected by it, no card either).  min_value: half the dimmest
    card's dominant channel (it only rejects black).  None: no gap."""
    out = {}
    for key in ("margin", "saturation_q8"):
        lo, hi = max(g[key] for g in greys), min(c[key] for c in cards)
        out[key] = (0.5 * (lo + hi), hi - lo) if hi > lo else (0.5 * hi, None)
    if out["margin"][1] is None and out["saturation_q8"][1] is None:
        return None
    return {"min_value": int(max(1, min(255, math.floor(0.5 * min(c["value"] for c in cards))))),
            "min_margin": int(min(255, max(1, round(out["margin"][0])))),
            "min_saturation_q8": int(min(255, max(1, round(out["saturation_q8"][0]))))}


def fit_colours(steps: list[Step]) -> Fit:
    """The camera's colour response (camera.gain_r, gain_b against green:
    the grey card's channels over the simulator's grey, the exposure
    setting the level) and the blob detector's thresholds that keep every
    card in its class and the grey card out (thresholds())."""
    stats = _card_stats(steps)
    redo = "the colours steps of the {} card"
    for c, name in COLOUR_CARDS.items():
        rows = stats.get((c, 0), [])
        if len(rows) < MIN_COLOUR_DISTANCES:
            raise FitError("colours", f"the {name} card was recorded at {len(rows)} distances (at least "
                           f"{MIN_COLOUR_DISTANCES})", redo.format(name))
        for d, _, mean, _ in rows:
            if max(mean) >= COLOUR_SATURATED:
                ch = "RGB"[int(np.argmax(mean))]
                raise FitError("colours", f"the {name} card at {d:g} mm is saturated ({ch} {max(mean):.0f} of 255)",
                               redo.format(name) + " with less light on it (a matt card, no lamp behind you)")
            if c and int(np.argmax(mean)) != c - 1:
                raise FitError("colours", f"the {name} card at {d:g} mm reads R, G, B {mean[0]:.0f}, {mean[1]:.0f}, "
                               f"{mean[2]:.0f}: never {name} (another channel leads)",
                               redo.format(name) + " (the right card? coloured light on it?)")
    grey = geometry.obstacle_grey()
    rg, bg, cards, greys, points = [], [], [], [], []
    for d, _, mean, sd in stats[(0, 0)]:
        if mean[1] <= 0:
            raise FitError("colours", f"the grey card at {d:g} mm reads black", redo.format("grey") + " with light on it")
        rg.append(mean[0] / mean[1] * grey[1] / grey[0])
        bg.append(mean[2] / mean[1] * grey[1] / grey[2])
        greys.append(grey_limits(mean, sd))
    for c in (1, 2, 3):
        seen = {d: n for d, n, *_ in stats.get((c, c), [])}
        for d, n, mean, sd in stats[(c, 0)]:
            lim = colour_limits(mean, sd, c)
            if lim["margin"] <= 0:
                raise FitError("colours", f"the {COLOUR_CARDS[c]} card at {d:g} mm: its pixels' channels overlap "
                               f"(R, G, B {mean[0]:.0f}, {mean[1]:.0f}, {mean[2]:.0f} +- {sd[0]:.0f}, {sd[1]:.0f}, "
                               f"{sd[2]:.0f}): no threshold keeps it {COLOUR_CARDS[c]}",
                               redo.format(COLOUR_CARDS[c]) + " with a deeper-coloured card")
            cards.append(lim)
            points.append({"x": d, "label": f"{COLOUR_CARDS[c]} card", "card": c, "mean": [float(v) for v in mean],
                           "sd": [float(v) for v in sd], "limits": lim, "measured": float(seen.get(d, math.nan)),
                           "pixels": n})
    th = thresholds(cards, greys)
    if th is None:
        raise FitError("colours", "the grey card's pixels lead by as much as the coloured cards' (no threshold "
                       "separates them)", "the colours procedure with a neutral grey card and deeper colours")
    params = {**th, "gain_r": round(float(np.mean(rg)), 4), "gain_g": 1.0, "gain_b": round(float(np.mean(bg)), 4),
              "limits": {"cards": [{k: round(v, 2) for k, v in lim.items()} for lim in cards],
                         "grey": [{k: round(v, 2) for k, v in g.items()} for g in greys]}}
    for p in points:
        p["simulated"] = p["pixels"]     # the frame's pixels: every one of the card is in its class
    return Fit("colours", params, points, 0.0, "pixels")
