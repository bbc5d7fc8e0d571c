"""Writes the seed corpora of the fuzz targets (tests/fuzz/corpus/<target>/)
from real inputs: the shipped scenarios and the loader's test files, the
UART bytes the robots of a simulated foraging run send (software in the
loop: robot_telemetry.dump), and the nest-link messages their values make
(each forager's deposit and OAE totals, the beacon's F(t), N_W and M_T2,
read from those same bytes).  Deterministic: the run has a fixed seed.

Run it again when a format changes, and commit what it writes:

    .venv/bin/python tests/fuzz/seeds.py --sim build/swarmsim

Each file is in its target's input format (the comment at the top of
tests/fuzz/<target>.c).  The corpora also keep regression inputs that
fuzzing found (named regression-*); this script leaves those alone.
"""
import argparse
import shutil
import struct
import subprocess
import tempfile
from pathlib import Path

from swarmtools.telemetry import common
from swarmtools.telemetry.frames import FrameDecoder

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests" / "fuzz" / "corpus"
STEPS = 3000            # 5 simulated minutes: every forager has left and come back
FORAGER, BEACON = 0, 20  # robot ids in foraging_base.yaml: 20 foragers, then the beacon
ROBOT_STATE, SCHEMA = 1, 6


def sil_run(sim, out):
    """The UART bytes of every robot of foraging_base over STEPS steps."""
    subprocess.run([str(sim), str(ROOT / "sim_host/scenarios/foraging_base.yaml"), "--out", str(out),
                    "--steps", str(STEPS), "--set", "robot_telemetry.enabled=true",
                    "--set", "robot_telemetry.dump=true"], check=True, capture_output=True)
    uart = out / "run_1" / "uart"
    return {int(p.stem.split("_")[1]): p.read_bytes() for p in uart.glob("robot_*.bin")}


def states(stream):
    """Each robot_state_t in a robot's bytes as {value name: value}, and the frames."""
    frames = FrameDecoder().feed(stream)
    names = []
    for f in frames:
        if f.channel == SCHEMA:
            m = common.decode(f.payload)
            names[m.first:m.first + m.n] = list(m.names)
    out = []
    for f in frames:
        if f.channel == ROBOT_STATE:
            m = common.decode(f.payload)
            out.append(dict(zip(names, m.values, strict=True)))
    return out, frames


# ---------------------------------------------------------------- nest_link.h
def deposits(rid, total):
    return (1 << 14) | ((rid & 63) << 8) | (int(total) & 0xFF)


def oaes(rid, total):
    return (2 << 14) | ((rid & 63) << 8) | (int(total) & 0xFF)


def beacon(kind, value):
    return (3 << 14) | (kind << 12) | (int(value) & 0x0FFF)


def beacon_frames(s, n_robots=20):
    """The three frames a beacon broadcasts for one of its states."""
    food_q4 = max(-2048, min(2047, round(s["nest_food"] * 16)))
    mean_q8 = min(4095, int(s["oae_window"]) * 256 // n_robots)
    return [beacon(0, food_q4), beacon(1, min(4095, int(s["waiting"]))), beacon(2, mean_q8)]


# ---------------------------------------------------------------- writers
def put(target, name, data):
    d = CORPUS / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(bytes(data))


def scenario_seeds():
    sets = {
        "random_walk.yaml": ["--set duration=2", "--set robots.0.count=6"],
        "foraging_base.yaml": ["--set robots.0.policy=artm", "--set robot_telemetry.enabled=true"],
        "foraging_l3.yaml": ["--set foraging.information=global"],
        "phototaxis_gather.yaml": ["--set robots.0.placement.shape=ring"],
    }
    for p in sorted((ROOT / "sim_host/scenarios").glob("*.yaml")):
        text = p.read_bytes()
        put("scenario", p.name, text)
        if p.name in sets:
            put("scenario", p.stem + "_set.yaml", text + "".join(s + "\n" for s in sets[p.name]).encode())
    for p in sorted((ROOT / "tests/data/scenarios").glob("*.yaml")):
        put("scenario", "test_" + p.name, p.read_bytes())


def telemetry_frame_seeds(streams):
    _, fr = states(streams[FORAGER])
    state = next(f for f in fr if f.channel == ROBOT_STATE)
    schema = max((f for f in fr if f.channel == SCHEMA), key=lambda f: len(f.payload))
    put("telemetry_frame", "wire_forager", b"\x00" + streams[FORAGER][:1200])
    put("telemetry_frame", "wire_beacon", b"\x00" + streams[BEACON][:1200])
    for name, f in (("state", state), ("schema", schema)):
        put("telemetry_frame", "encode_" + name,
            struct.pack(">BBHH", 1, f.channel, f.robot_id, f.seq) + f.payload)
        put("telemetry_frame", "cobs_" + name, b"\x02" + f.payload)
        body = struct.pack(">BBHH", 1, f.channel, f.robot_id, f.seq) + f.payload
        # Mode 3 with lengths 0..300 (how = 0).
        put("telemetry_frame", "body_" + name, struct.pack(">BBBBH", 3, 0, 4, 4, len(body)) + body + b"\0\1\2\3" * 2)
    # Mode 3 near the limit with a header that passes (how = 3, 230 + b % 30
    # bytes): the longest body the format allows, and one byte longer.
    long_body = (body + bytes(range(1, 256)))[:250]
    for name, blen in (("body_at_limit", 246), ("body_over_limit", 247)):
        put("telemetry_frame", name, struct.pack(">BBBBB", 3, 3, 0, 0, blen - 230) + long_body[:blen])


def robot_link_seeds(streams):
    def ops(stream, budget, chunk=64, steps=60):
        out, at = bytearray(), 0
        for _ in range(steps):
            out += struct.pack(">BH", 0, budget)
            for _ in range(4):
                part = stream[at:at + chunk]
                at += len(part)
                out += struct.pack(">BH", 1, len(part)) + part
        return out
    put("robot_link", "forager_115200", ops(streams[FORAGER], 1152, steps=20))
    put("robot_link", "beacon_2400", ops(streams[BEACON], 24, chunk=24, steps=30))
    put("robot_link", "forager_unlimited", ops(streams[FORAGER][:4000], 0xFFFF, chunk=1000, steps=2))


def nest_link_seeds(streams):
    fs, _ = states(streams[FORAGER])
    bs, _ = states(streams[BEACON])
    last_f, last_b = fs[-1], bs[-1]
    frames = beacon_frames(last_b) + [deposits(7, last_f["deposits"]), oaes(7, last_f["oae"])]
    for k, fr in enumerate(frames):
        put("nest_link", f"frame_{k}", struct.pack(">HIHB", fr, int(last_f["oae"]), 7, 3))


def ir_controllers_seeds(streams):
    """Scripts of the messages a forager and the beacon hear in a real run."""
    bs, _ = states(streams[BEACON])
    others = {rid: states(streams[rid])[0] for rid in range(1, 20)}

    def msg(value, range_mm=200, bearing=0, sensor=0, stride=0):
        return struct.pack(">HHHBB", value, range_mm, bearing & 0xFFFF, sensor, stride)

    def segment(steps, world, msgs):
        r = steps - 1 if steps <= 128 else 127 + steps // 16
        return struct.pack(">BBB", r, len(msgs), world) + b"".join(msgs)

    # In the nest: the beacon's real frames, one state a second.
    nest = bytearray(struct.pack(">BH", 4, 3))          # DRTM, loop closed, forager 3
    for s in bs[:60:6]:
        nest += segment(10, 0, [msg(f) for f in beacon_frames(s)])
    put("ir_controllers", "nest_drtm", nest)
    # The beacon hearing the other foragers' real totals (16 a step).
    reports = bytearray(struct.pack(">BHHB", 1 | 8, 5, 400, 5))   # ARTM, T2 and timeout given
    for k in range(0, 60, 6):
        msgs = []
        for rid in range(1, 9):
            s = others[rid][min(k, len(others[rid]) - 1)]
            msgs += [msg(deposits(rid, s["deposits"]), 300, 1000), msg(oaes(rid, s["oae"]), 300, 1000)]
        reports += segment(10, 0, msgs)
    put("ir_controllers", "reports_artm", reports)
    # A trip: search (a token in view), carry it home toward the light,
    # beacon frames from inside the nest, back off and wait again.
    food = beacon_frames(bs[0])
    trip = bytearray(struct.pack(">BH", 2, 9))          # FRTM, open loop
    trip += segment(60, 0, [msg(f, 200) for f in food])
    trip += segment(40, 1 | 8, [])
    trip += segment(30, 1 | 2 | 4 | (2 << 4), [msg(food[0], 2000)])
    trip += segment(5, 1 | 2 | 4, [msg(food[1], 300)])
    trip += segment(20, 0, [msg(f, 300) for f in food])
    put("ir_controllers", "trip_frtm", trip)
    # Issue 12's defect, fixed: robot 0 alternately reporting deposit totals
    # 255 and 254 (frames 0x40FF, 0x40FE), 8 a step, for 2048 steps used to
    # overflow the beacon's ledger; kept as a regression input.
    hostile = bytearray(struct.pack(">BH", 0, 7)) + segment(2048, 0, [msg(0x40FF - k % 2, 300) for k in range(8)])
    put("ir_controllers", "regress_ledger_overflow", hostile)


def epuck_ir_seeds(streams):
    bs, _ = states(streams[BEACON])
    frames = beacon_frames(bs[-1]) + [deposits(4, 2), oaes(4, 17)]
    randb = bytearray()
    for k, fr in enumerate(frames):
        randb += bytes([3]) + b"".join(struct.pack(">Hf H".replace(" ", ""), fr, (k - 2) * 1.1 + j, 20 + 30 * j)
                                       for j in range(3))
    put("epuck_ir_randb", "turret_frames", randb)
    libircom = bytearray()
    for k, fr in enumerate(frames):
        libircom += bytes([2]) + b"".join(struct.pack(">iffbB", fr & 0xFF, 4.0 + 6 * j, -2.4 + 0.8 * k, k % 8, j % 2)
                                          for j in range(2))
    put("epuck_ir_libircom", "ircom_messages", libircom)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sim", default=str(ROOT / "build/swarmsim"), help="the swarmsim to run")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        streams = sil_run(args.sim, Path(tmp) / "run")
    for t in ("scenario", "telemetry_frame", "robot_link", "nest_link", "ir_controllers",
              "epuck_ir_randb", "epuck_ir_libircom"):
        d = CORPUS / t
        if d.is_dir():
            for p in d.iterdir():
                if not p.name.startswith("regression-"):
                    p.unlink()
    scenario_seeds()
    telemetry_frame_seeds(streams)
    robot_link_seeds(streams)
    nest_link_seeds(streams)
    ir_controllers_seeds(streams)
    epuck_ir_seeds(streams)
    shutil.rmtree(ROOT / "tests/fuzz/__pycache__", ignore_errors=True)


if __name__ == "__main__":
    main()
