"""The scenario fragment: the fitted parameters as the models' own sections
(ir, ambient, wheels, sound, camera: one `robots:` entry per robot id and
the lab's average in the sections' own keys, which robots without an entry
take, sim_host/models/per_robot.h).  `apply` puts a fragment into a scenario,
per robot id or as the lab's average only."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml

from ..sweep.store import atomic_write
from . import fit as fitting

HEADER = """# Model parameters fitted to a lab's e-pucks by swarm-calibrate
# (docs/how-to/calibrate.md): per robot id in each section's `robots:`, the
# lab's average in the section's own keys (robots without an entry).
# Put it into a scenario with: swarm-calibrate apply SCENARIO THIS -o OUT
# (--average: every robot the lab's average).
"""


def _mean(values):
    return round(float(np.mean(values)), 5)


def build(fits_by_robot: dict) -> dict:
    """{robot id: {procedure: Fit}} -> the fragment's sections."""
    out = {}
    ids = sorted(fits_by_robot)
    ir = [(i, fits_by_robot[i]["ir"].params) for i in ids if "ir" in fits_by_robot[i]]
    if ir:
        out["ir"] = {
            "noise_rel": _mean([p["noise_rel"] for _, p in ir]),
            "noise_abs": _mean([p["noise_abs"] for _, p in ir]),
            "sensors": [{"gain": _mean([p["sensors"][s]["gain"] for _, p in ir]),
                         "offset": _mean([p["sensors"][s]["offset"] for _, p in ir])} for s in range(8)],
            "robots": [{"id": i, **p} for i, p in ir],
        }
    amb = [(i, fits_by_robot[i]["ambient"].params) for i in ids if "ambient" in fits_by_robot[i]]
    if amb:
        out["ambient"] = {k: _mean([p[k] for _, p in amb]) for k in ("dark", "half", "noise_rel")}
        out["ambient"]["robots"] = [{"id": i, **p} for i, p in amb]
    wh = [(i, fits_by_robot[i]["wheels"].params) for i in ids if "wheels" in fits_by_robot[i]]
    if wh:
        out["wheels"] = {k: _mean([p[k] for _, p in wh]) for k in ("gain_left", "gain_right")}
        out["wheels"]["robots"] = [{"id": i, **p} for i, p in wh]
    snd = [(i, fits_by_robot[i]["sound"].params) for i in ids if "sound" in fits_by_robot[i]]
    if snd:
        out["sound"] = {k: _mean([p[k] for _, p in snd]) for k in ("alpha", "ae", "noise")}
        out["sound"]["robots"] = [{"id": i, **{k: v for k, v in p.items() if k.startswith("gain")}} for i, p in snd]
    cam = {i: fits_by_robot[i]["camera"].params for i in ids if "camera" in fits_by_robot[i]}
    col = {i: fits_by_robot[i]["colours"].params for i in ids if "colours" in fits_by_robot[i]}
    if cam or col:
        section, entries = {}, {i: {"id": i} for i in ids if i in cam or i in col}
        if cam:
            section.update({"range": _mean([p["range"] for p in cam.values()]),
                            "fov": _mean([p["fov"] for p in cam.values()])})
            for i, p in cam.items():
                entries[i].update({"range": p["range"], "fov": p["fov"]})
        if col:
            # One image, one detector: the lab's thresholds keep every robot's cards in their classes.
            th = fitting.thresholds([c for p in col.values() for c in p["limits"]["cards"]],
                                    [g for p in col.values() for g in p["limits"]["grey"]])
            if th is None:
                raise fitting.FitError("colours", "no thresholds separate every robot's cards from its grey card "
                                       f"(robots {', '.join(map(str, col))})", "the colours procedure of the "
                                       "robot whose limits the report shows furthest off")
            section.update(th)
            section.update({k: _mean([p[k] for p in col.values()]) for k in ("gain_r", "gain_g", "gain_b")})
            for i, p in col.items():
                entries[i].update({k: p[k] for k in ("gain_r", "gain_g", "gain_b")})
        out["camera"] = {**section, "robots": [entries[i] for i in sorted(entries)]}
    return out


def dump(sections: dict) -> str:
    return HEADER + yaml.safe_dump(sections, sort_keys=False, default_flow_style=None)


def write(sections: dict, path: str | Path):
    atomic_write(Path(path), dump(sections))


SECTIONS = ("ir", "ambient", "wheels", "camera", "sound")


class FragmentError(ValueError):
    pass


def _load_mapping(path, what):
    try:
        # From the open file, so that a YAML error names it (from a string it says "<unicode string>").
        with open(path, encoding="utf-8") as f:
            data = yaml.safe_load(f)
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as e:
        raise FragmentError(f"{path}: cannot read the {what}: {e}") from e
    if not isinstance(data, dict):
        raise FragmentError(f"{path}: the {what} is not a mapping of sections")
    return data


def apply(scenario: str | Path, fragment: str | Path, average: bool = False) -> str:
    """The scenario's text with the fragment's sections merged in (the
    fragment's keys win; --average leaves out the per-robot entries)."""
    sc = _load_mapping(scenario, "scenario")
    fr = _load_mapping(fragment, "fragment")
    for name, section in fr.items():
        if name not in SECTIONS or not isinstance(section, dict):
            raise FragmentError(f"{fragment}: {name!r} is not a section a calibration fragment has "
                                f"({', '.join(SECTIONS)})")
        merged = dict(sc.get(name) or {})
        merged.update({k: v for k, v in section.items() if not (average and k == "robots")})
        if average:
            merged.pop("robots", None)
        sc[name] = merged
    how = "the lab's average" if average else "per robot id"
    return (f"# {Path(scenario).name} with the calibration {Path(fragment).name} ({how}), by swarm-calibrate apply\n"
            + yaml.safe_dump(sc, sort_keys=False, default_flow_style=None))


def apply_checked(scenario: str | Path, fragment: str | Path, output: str | Path, average: bool = False) -> None:
    """apply() into `output`, once the simulator has loaded the merged
    scenario: a fragment the simulator refuses (a sensors list of the wrong
    length, a negative gain, an id twice) is a FragmentError naming the
    fragment and the simulator's reason, and nothing is written."""
    from ..sim import ScenarioError, Sim, SimError
    from ..sim._lib import LibraryMissing
    text = apply(scenario, fragment, average)
    output = Path(output)

    def check(tmp: str) -> None:
        try:
            with Sim(tmp):
                pass
        except ScenarioError as e:
            where = f"{e.key}: " if e.key else ""
            raise FragmentError(f"{fragment}: the simulator refuses {Path(scenario).name} with it: "
                                f"{where}{e.reason}") from e
        except SimError as e:
            raise FragmentError(f"{fragment}: the simulator cannot run {Path(scenario).name} with it: "
                                f"{str(e).replace(tmp, str(output))}") from e
        except LibraryMissing as e:
            raise FragmentError(f"cannot check {output} with the simulator: {e}") from e

    # The check loads the very file that becomes the output, in the output's
    # folder (where any path in it will be read from), before it is renamed
    # into place: the output is whole and checked, or absent.
    atomic_write(output, text, check=check, suffix=".yaml")
