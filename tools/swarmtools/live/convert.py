"""Our LCM messages as the page's JSON: plain dicts and lists of numbers
and strings, field names as in lcm_types/ where they are not shortened.
Floats that are not finite become None (JSON has no NaN)."""
import math


def num(v):
    """A number JSON can carry: float32 values as Python floats, NaN and
    infinities as None."""
    v = float(v)
    return v if math.isfinite(v) else None


def info(m):
    return {
        "run": m.run, "scenario": m.scenario, "scenario_file": m.scenario_file, "steps": m.steps,
        "period_ms": m.control_period_ms, "arena": [num(m.arena_width), num(m.arena_height)],
        "robots": m.robots, "tasks": list(m.tasks),
        "groups": [{"name": n, "controller": c, "policy": p, "count": k}
                   for n, c, p, k in zip(m.group_names, m.group_controllers, m.group_policies, m.group_counts,
                                         strict=True)],
        "robot_hz": num(m.robot_state_hz), "swarm_hz": num(m.swarm_state_hz),
    }


def scene(m):
    return {
        "arena": [num(m.arena_width), num(m.arena_height)], "wall": num(m.wall_thickness),
        "robot_radius": num(m.robot_radius),
        "obstacles": [{"shape": o.shape, "x": num(o.x), "y": num(o.y), "radius": num(o.radius),
                       "width": num(o.width), "depth": num(o.depth), "angle": num(o.angle), "rgb": o.rgb}
                      for o in m.obstacles],
        "lights": [{"x": num(li.x), "y": num(li.y)} for li in m.lights],
        # The run's legend, the PNG frames' (sim_host/core/legend.h): the
        # page colours robots and lists the keys from it.
        "robot_rgb": m.robot_rgb,
        "legend": [{"kind": k, "rgb": rgb, "label": label}
                   for k, rgb, label in zip(m.key_kind, m.key_rgb, m.key_label, strict=True)],
    }


def drawing(m):
    return {
        "shapes": [{"kind": s.kind, "layer": s.layer, "rgb": s.rgb, "x": num(s.x), "y": num(s.y),
                    "radius": num(s.radius), "w": num(s.w), "h": num(s.h), "x2": num(s.x2), "y2": num(s.y2),
                    "line": num(s.line), "text": s.text} for s in m.shapes],
        "items": [[num(i.x), num(i.y), num(i.radius), i.rgb] for i in m.items],
        "fills": {str(r): rgb for r, rgb in zip(m.fill_robot, m.fill_rgb, strict=True)},
    }


def swarm(m):
    return {"step": m.step, "clock": m.utime / 1e6, "robots": m.robots,
            "states": [[n, c] for n, c in zip(m.state_names, m.state_counts, strict=True)],
            "values": [num(v) for v in m.values]}


def robot(m, seen):
    """One robot's latest state; `seen` is the feed time it came at."""
    return {
        "id": m.robot_id, "group": m.group, "controller": m.controller, "state": m.state,
        "pose": bool(m.pose_known), "x": num(m.x), "y": num(m.y), "theta": num(m.theta),
        "leds": m.leds, "wheels": [m.wheel_left, m.wheel_right], "ir_max": m.ir_max,
        "ambient_min": m.ambient_min, "blobs": m.blobs, "values": [num(v) for v in m.values],
        "clock": m.utime / 1e6, "seen": seen,
    }


def summary(m):
    return {"steps": m.steps, "state_hash": m.state_hash, "clock": m.utime / 1e6,
            "metrics": [[n, num(v)] for n, v in zip(m.metric_names, m.metric_values, strict=True)]}


def bridge(m):
    return {"devices": [{"device": d.device, "robot_id": d.robot_id, "connected": bool(d.connected),
                         "frames": d.frames, "crc_errors": d.crc_errors, "framing_errors": d.framing_errors,
                         "lost": d.lost, "reconnects": d.reconnects} for d in m.devices]}


def event(m, seen):
    return {"t": seen, "clock": m.utime / 1e6, "robot": m.robot_id, "kind": m.kind, "detail": m.detail,
            "value": m.value}


def schemas(book):
    """Every schema heard (common.Schemas), by kind and name: names, units
    and which are counters."""
    out = {}
    for s in book:
        entries = [s.entry(k) for k in range(s.total)]
        out.setdefault(s.kind, {})[s.name] = {"names": [e.name for e in entries], "units": [e.unit for e in entries],
                                              "counters": [e.counter for e in entries]}
    return out


def control(m):
    """A run under control's status (control_status_t), without its key:
    the page never needs it, the server sends the commands."""
    return {"step": m.step, "steps": m.steps, "paused": bool(m.paused), "pending": m.steps_pending,
            "realtime": num(m.realtime), "selected": m.selected, "commands": m.commands, "seq": m.seq,
            "ok": bool(m.ok), "text": m.text, "clock": m.utime / 1e6}


def detail(m):
    """The selected robot's readings (robot_detail_t)."""
    return {
        "id": m.robot_id, "controller": m.controller, "state": m.state, "state_time_s": num(m.state_time_s),
        "clock": m.utime / 1e6, "x": num(m.x), "y": num(m.y), "theta": num(m.theta), "wheels": [m.wheel_left, m.wheel_right],
        "leds": m.leds, "values": [num(v) for v in m.values],
        "prox": list(m.prox) if m.prox_known else None, "ambient": list(m.ambient) if m.ambient_known else None,
        "ir_bearing_mrad": list(m.ir_bearing_mrad),
        "blobs": [{"colour": c, "bearing_mrad": b, "width_mrad": w}
                  for c, b, w in zip(m.blob_colour, m.blob_bearing_mrad, m.blob_width_mrad, strict=True)],
        "camera_fov_rad": num(m.camera_fov_rad), "camera_range_m": num(m.camera_range_m),
        "mic": [num(v) for v in m.mic],
        "heard": [{"value": v, "bearing_mrad": b, "range_mm": r}
                  for v, b, r in zip(m.heard_value, m.heard_bearing_mrad, m.heard_range_mm, strict=True)],
        "ircom_range_m": num(m.ircom_range_m),
        "group": m.group,
        "params": [{"name": n, "value": v, "range": r}
                   for n, v, r in zip(m.param_names, m.param_values, m.param_ranges, strict=True)],
    }
