"""A plan as the robots receive it: each robot's route as a host message
(firmware/waypoint/route_msg.h, the bytes the e-puck gets over Bluetooth
and the simulator from `host.messages`), and the scenario that runs the
plan: the world's own, its robots replaced by waypoint followers with a
tracker, their routes sent at 0 s.

Robot i gets route i: every route starts at the nest centre and the robots
start in a 0.48 m grid around it, so which robot takes which route moves a
finishing time by at most the grid's half-diagonal at 0.1 m/s (3.4 s)."""

from __future__ import annotations

import math
import struct
from collections.abc import Sequence

KIND = 0x52                 # 'R'
MAX_TARGETS = 6             # ROUTE_MAX_TARGETS
COORD_MAX_MM = 1_000_000    # ROUTE_COORD_MAX_MM
#: Where a robot stops for a target by a wall: this far from the wall (m),
#: the body's radius (35 mm, hal/units.h) plus the ~25 mm at which its IR
#: reads above avoid_enter and it turns away, plus 10 mm for noise.  The
#: targets task reaches 55 mm centre to centre (35 + target 10 + reach 10),
#: so a stop moved up to WALL_SHIFT_MAX_M (with arrive_mm 10) still picks.
WALL_CLEARANCE_M = 0.070
WALL_SHIFT_MAX_M = 0.045


def _mm(v: float) -> int:
    mm = int(round(v * 1000.0))
    if abs(mm) > COORD_MAX_MM:
        raise ValueError(f"{v} m is beyond the route message's +-{COORD_MAX_MM} mm")
    return mm


def route_message(targets_m: Sequence[tuple[float, float]], drop_m: tuple[float, float]) -> bytes:
    """The route message: 'R', n, the n targets and the drop-off point as
    big-endian int32 millimetres."""
    if not 1 <= len(targets_m) <= MAX_TARGETS:
        raise ValueError(f"a route holds 1 to {MAX_TARGETS} targets, not {len(targets_m)}")
    out = struct.pack(">BB", KIND, len(targets_m))
    for x, y in [*targets_m, drop_m]:
        out += struct.pack(">ii", _mm(x), _mm(y))
    return out


def stop_point(target: tuple[float, float], arena: tuple[float, float]) -> tuple[float, float]:
    """Where the robot stops for `target` in an arena of (width, height) m
    centred on the origin: the target itself, or, by a wall, the nearest
    point WALL_CLEARANCE_M from it (the robot would turn away before
    reaching the target's own spot)."""
    (x, y), (w, h) = target, arena
    sx = min(max(x, -w / 2 + WALL_CLEARANCE_M), w / 2 - WALL_CLEARANCE_M)
    sy = min(max(y, -h / 2 + WALL_CLEARANCE_M), h / 2 - WALL_CLEARANCE_M)
    if math.hypot(sx - x, sy - y) > WALL_SHIFT_MAX_M:
        raise ValueError(f"the target at ({x:.3f}, {y:.3f}) m is too near a wall to be picked up: "
                         f"its stop would be {math.hypot(sx - x, sy - y) * 1000:.0f} mm away")
    return sx, sy


def run_scenario(world_doc: dict, routes_m: Sequence[Sequence[tuple[float, float]]], drop_m: tuple[float, float],
                 name: str) -> dict:
    """The world's effective scenario (a dict, as the simulator wrote it)
    with its robots following `routes_m`: the first group kept for its
    count, placement and spacing, its controller now `waypoint` (speed and
    avoidance run as the RepAtt robots'), an exact tracker, no sound (no
    robot listens), and each robot's route message at 0 s, with each
    target's stop point (stop_point: moved off a wall)."""
    doc = {k: v for k, v in world_doc.items() if k not in ("robots", "host", "sound")}
    groups = world_doc.get("robots") or []
    if len(groups) != 1:
        raise ValueError(f"the world has {len(groups)} robot groups; a plan is for one")
    g = groups[0]
    if int(g.get("count", 0)) != len(routes_m):
        raise ValueError(f"the world has {g.get('count')} robots but the plan {len(routes_m)} routes")
    params = g.get("params") or {}
    keep = {k: params[k] for k in ("speed_steps_s", "oa_run_max_mm") if k in params}
    # The targets task picks up the target nearest the waiting robot within
    # reach (55 mm centre to centre); a cluster's targets lie about 0.1 m
    # apart, so the robot stops within 10 mm of its own.
    keep["arrive_mm"] = 10
    nest = (world_doc.get("targets") or {}).get("nest") or {}
    if "radius" in nest:   # delivered once its body is inside the nest
        keep["home_radius_mm"] = max(1, int(round(1000.0 * float(nest["radius"]))) - 37)
    robot = {"name": "alns", "count": len(routes_m), "controller": "waypoint", "params": keep}
    for k in ("placement", "min_spacing", "heading"):
        if k in g:
            robot[k] = g[k]
    doc["name"] = name
    doc["robots"] = [robot]
    doc["tracker"] = {"enabled": True, "noise_mm": 0, "noise_deg": 0, "dropout": 0}
    arena = world_doc.get("arena") or {}
    if "width" not in arena or "height" not in arena:
        raise ValueError("the world's scenario does not give arena.width and arena.height (its stops by the walls "
                         "need them)")
    size = (float(arena["width"]), float(arena["height"]))
    doc["host"] = {"messages": [{"robot": i, "at": 0,
                                 "hex": route_message([stop_point(t, size) for t in r], drop_m).hex()}
                                for i, r in enumerate(routes_m)]}
    return doc
