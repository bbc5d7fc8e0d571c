"""The telemetry tools on simulated runs and on hand-built logs: the round
trip (a run's LCM log exported to CSV is its own time series and summary,
exactly), values named by the schemas whatever the controller (a new one
needs no tool change), the monitor, the plots, the robots' own telemetry
on prefixed channels, logs of another toolkit version refused with a clear
message, and the Java types lcm-spy loads."""
import ast
import csv
import io
import json
import re
import shutil
import struct
import subprocess
import tempfile
import unittest
from pathlib import Path

import swarmlcm

from swarmtools.telemetry import common, export_csv, monitor, plot_run

from .helpers import (
    ROOT,
    SCENARIOS,
    TempDir,
    event,
    has_matplotlib,
    monitor_of,
    read_log,
    robot_state,
    run_sim,
    schema,
    swarm_state,
    tool,
    write_log,
)
from .helpers import tool as run_tool

FORAGING = SCENARIOS / "foraging_base.yaml"
RANDOM_WALK = SCENARIOS / "random_walk.yaml"
#: The monitor's --exit-idle on a log: it prints once, at the log's end,
#: which comes long before (a short idle could end it early on a loaded machine).
LONG_IDLE = 120

#: A message of each telemetry v1 type: its fingerprint, then whatever.
V1 = {name: bytes.fromhex(fp) + bytes(range(40)) for name, fp in [
    ("robot_state_t", "3715081f471fd9b6"), ("swarm_state_t", "ef676ded075c496f"), ("event_t", "43c251253e108b1f"),
    ("run_info_t", "0bde89823a83dac9"), ("run_summary_t", "cf2793015152e50e")]}

_runs = {}


def runs():
    """The simulated runs the tests share (made once): a foraging run with
    the ARTM policy (1234 steps: the last row is not on the grid of
    timeseries_every), a random walk, and a short foraging run with the
    robots' own telemetry in the loop."""
    if not _runs:
        tmp = tempfile.TemporaryDirectory(prefix="telemetry_runs_")
        out = Path(tmp.name)
        run_sim(out / "forage", FORAGING, "--steps", 1234, "--seed", 4, "--set", "robots.0.policy=artm")
        run_sim(out / "walk", RANDOM_WALK, "--steps", 777)
        run_sim(out / "fw", FORAGING, "--steps", 300, "--set", "robot_telemetry.enabled=true")
        _runs.update(tmp=tmp, forage=out / "forage" / "run_4", walk=out / "walk" / "run_1", fw=out / "fw" / "run_1")
    return _runs


def tearDownModule():
    if _runs:
        _runs["tmp"].cleanup()


def read_csv(path_or_text):
    if isinstance(path_or_text, Path):
        path_or_text = path_or_text.read_text()
    return list(csv.DictReader(io.StringIO(path_or_text)))


def log_schemas(log):
    book = common.Schemas()
    for ch, m in read_log(log):
        if ch == "TELEMETRY_SCHEMA":
            book.add(m)
    return book


class SimulatedRuns(TempDir):
    @classmethod
    def setUpClass(cls):
        r = runs()
        cls.run_dir = r["forage"]
        cls.log = cls.run_dir / "telemetry.lcmlog"
        cls.walk_dir = r["walk"]
        cls.walk_log = cls.walk_dir / "telemetry.lcmlog"
        cls.summary = json.loads((cls.run_dir / "summary.json").read_text())


class RoundTrip(SimulatedRuns):
    def test_timeseries_exactly(self):
        for run_dir in (self.run_dir, self.walk_dir):
            out = self.tmp / "ts.csv"
            tool("export_csv", run_dir / "telemetry.lcmlog", "--timeseries", 10, "-o", out)
            self.assertEqual(out.read_bytes(), (run_dir / "timeseries.csv").read_bytes(), run_dir)
        r = tool("export_csv", self.walk_log, "--timeseries", 10)      # to stdout
        self.assertEqual(r.stdout, (self.walk_dir / "timeseries.csv").read_text())

    def test_timeseries_on_another_grid(self):
        r = tool("export_csv", self.log, "--timeseries", 7)
        ours = r.stdout.splitlines()
        theirs = (self.run_dir / "timeseries.csv").read_text().splitlines()
        self.assertEqual(ours[0], theirs[0])
        steps = [int(ln.split(",")[0]) for ln in ours[1:]]
        self.assertEqual(steps, list(range(0, 1234, 7)) + [1234])
        by_step = {int(ln.split(",")[0]): ln for ln in theirs[1:]}
        shared = [s for s in steps if s in by_step]
        self.assertEqual(shared, list(range(0, 1234, 70)) + [1234])
        for s, ln in zip(steps, ours[1:], strict=True):
            if s in by_step:
                self.assertEqual(ln, by_step[s])

    def test_summary_exactly(self):
        out = self.tmp / "summary.csv"
        tool("export_csv", self.log, "--channel", "RUN_SUMMARY", "-o", out)
        rows = read_csv(out)
        self.assertEqual(len(rows), 1)
        row = rows[0]
        text = (self.run_dir / "summary.json").read_text()
        self.assertEqual(row["state_hash"], self.summary["state_hash"])
        self.assertEqual(int(row["steps"]), self.summary["steps"])
        self.assertEqual(row["scenario"], self.summary["scenario"])
        self.assertEqual(int(row["run"]), self.summary["seed"])
        for name in self.summary["metrics"]:
            # The same text as summary.json prints for the metric.
            printed = re.search(rf'"{re.escape(name)}": ([^,\n]+)', text).group(1)
            self.assertEqual(row[name], printed, name)

    def test_log_is_simulated_time_and_version_2(self):
        lcm = common.lcm_module()
        last = -1
        channels = set()
        for ev in lcm.EventLog(str(self.log), "r"):
            m = common.decode(ev.data, ev.channel)
            self.assertEqual(m.version, 2)
            self.assertEqual(ev.timestamp, m.utime)
            self.assertGreaterEqual(ev.timestamp, last)
            self.assertEqual(ev.timestamp % 100000, 0)
            last = ev.timestamp
            channels.add(ev.channel)
        self.assertEqual(last, 1234 * 100000)
        self.assertEqual(channels, {"RUN_INFO", "TELEMETRY_SCHEMA", "SWARM_STATE", "ROBOT_STATE", "SWARM_EVENT",
                                    "RUN_SUMMARY", "SCENE", "TASK_DRAWING"})

    def test_schemas_name_every_value(self):
        book = log_schemas(self.log)
        header = (self.run_dir / "timeseries.csv").read_text().splitlines()[0].split(",")
        swarm = book.get("swarm", "swarm", 4)
        self.assertTrue(swarm.complete)
        self.assertEqual(swarm.names(), header)
        forager = book.get("controller", "forager", 4)
        self.assertTrue({"oae", "deposits", "threshold", "probability"} <= set(forager.names()))
        self.assertEqual({e.name for e in forager.entries.values() if e.counter}, {"oae", "deposits"})
        self.assertTrue(book.get("controller", "nest_beacon", 4).complete)
        for ch, m in read_log(self.log):
            if ch in ("ROBOT_STATE", "SWARM_STATE"):
                self.assertEqual(len(m.values), book.of(m).total, (ch, getattr(m, "controller", "")))

    def test_every_channel_to_a_folder(self):
        d = self.tmp / "csv"
        r = tool("export_csv", self.log, "-o", str(d) + "/")
        self.assertIn("ROBOT_STATE:", r.stderr)
        self.assertEqual(sorted(p.name for p in d.iterdir()),
                         sorted(f"{ch}.csv" for ch in ("RUN_INFO", "TELEMETRY_SCHEMA", "SWARM_STATE", "ROBOT_STATE",
                                                       "SWARM_EVENT", "RUN_SUMMARY", "SCENE", "TASK_DRAWING")))
        robots = read_csv(d / "ROBOT_STATE.csv")
        self.assertEqual(len(robots), 21 * (1234 // 10 + 2))   # every 10 steps and the last, 20 + beacon
        cols = list(robots[0])
        book = log_schemas(self.log)
        for ctrl in ("forager", "nest_beacon"):
            for name in book.get("controller", ctrl, 4).names():
                self.assertIn(f"{ctrl}.{name}", cols)
        for row in robots:
            mine, other = ("forager", "nest_beacon") if row["controller"] == "forager" else ("nest_beacon", "forager")
            self.assertTrue(all(row[c] != "" for c in cols if c.startswith(mine + ".")))
            self.assertTrue(all(row[c] == "" for c in cols if c.startswith(other + ".")))
        events = read_csv(d / "SWARM_EVENT.csv")
        kinds = {e["kind"] for e in events}
        self.assertTrue({"pickup", "deposit", "oae", "deposits", "state"} <= kinds, kinds)
        self.assertEqual(sum(e["kind"] == "deposit" for e in events), self.summary["metrics"]["food_collected"])
        # A counter's events: one per increment, the last one's value the robot's final count.
        last = {}
        for row in robots:
            if row["controller"] == "forager":
                last[row["robot_id"]] = row
        for rid, row in last.items():
            oaes = [int(e["value"]) for e in events if e["kind"] == "oae" and e["robot_id"] == rid]
            self.assertEqual(oaes, list(range(1, len(oaes) + 1)))
            self.assertEqual(float(row["forager.oae"]), len(oaes), rid)
        # SWARM_STATE: the time series' columns as swarm.<name>, states as state.<name>.
        swarm = read_csv(d / "SWARM_STATE.csv")
        ts = read_csv(self.run_dir / "timeseries.csv")
        by_step = {row["step"]: row for row in swarm}
        for row in ts:
            for name, text in row.items():
                self.assertEqual(by_step[row["step"]][f"swarm.{name}"], text)
        states = [c for c in swarm[0] if c.startswith("state.")]
        self.assertIn("state.search", states)
        for row in swarm:
            self.assertEqual(sum(int(row[c] or 0) for c in states), 21)

    def test_fields_to_stdout(self):
        r = tool("export_csv", self.log, "--channel", "ROBOT_STATE", "--log-time",
                 "--fields", "log_utime,robot_id,forager.threshold,state")
        lines = r.stdout.splitlines()
        self.assertEqual(lines[0], "log_utime,robot_id,forager.threshold,state")
        self.assertRegex(lines[1], r"^0,0,\d[\d.]*,wait$")
        r = tool("export_csv", self.log, "--channel", "SWARM_STATE", "--every", 100, "--fields", "step")
        self.assertEqual(r.stdout.split(), ["step"] + [str(s) for s in range(0, 1234, 100)] + ["1234"])

    def test_errors_on_bad_input(self):
        results = []

        def tool(*args, **kw):
            results.append(run_tool(*args, **kw))
            return results[-1]

        r = tool("export_csv", self.log, check=False)
        self.assertEqual(r.returncode, 1)
        self.assertIn("several channels", r.stderr)
        r = tool("export_csv", self.log, "--channel", "ROBOT_STATE", "--fields", "nope", check=False)
        self.assertIn("no field(s) nope", r.stderr)
        self.assertIn("forager.probability", r.stderr)    # what it has
        r = tool("export_csv", self.tmp / "missing.lcmlog", check=False)
        self.assertEqual(r.returncode, 1)
        self.assertIn("no such file", r.stderr)
        text = self.tmp / "notes.txt"
        text.write_text("not a log\n")
        for name, extra in (("export_csv", ()), ("plot_run", ()), ("monitor", ("--plain", "--speed", "0"))):
            r = tool(name, *(("--log",) if name == "monitor" else ()), text, *extra, check=False)
            self.assertEqual(r.returncode, 1, name)
            self.assertIn(f"{text}: not an LCM log", r.stderr, name)
            self.assertNotIn("Traceback", r.stderr, name)
        r = tool("export_csv", self.log, "--timeseries", 10, "--channel", "ROBOT_STATE", check=False)
        self.assertEqual(r.returncode, 2)
        r = tool("export_csv", self.log, "--timeseries", 10, "--run", 99, check=False)
        self.assertEqual(r.returncode, 1)
        self.assertIn("no SWARM_STATE messages of run 99", r.stderr)
        self.assertEqual(len(results), 8)
        for r in results:
            self.assertNotIn("Traceback", r.stderr)

    def test_monitor_replays_the_log(self):
        r = tool("monitor", "--log", self.log, "--speed", "0", "--plain", "--exit-idle", LONG_IDLE)
        out = r.stdout
        m = self.summary["metrics"]
        self.assertIn("run foraging_base seed 4: 21 robots, 100 ms steps, arena 4 x 4 m, tasks: foraging", out)
        self.assertIn("groups  foragers: 20 x forager/artm   nest_beacon: 1 x nest_beacon", out)
        self.assertIn("step 1234 of 1234 (100 %)", out)
        self.assertIn(f"food_collected {m['food_collected']:g} tokens", out)     # a swarm value, from the schema
        self.assertIn(f"robot_contacts {m['robot_contacts']:g}", out)
        self.assertIn(f"deposit {m['food_collected']:g}", out)                   # events by kind
        self.assertIn(f"run finished after 1234 steps (state {self.summary['state_hash']}):", out)
        self.assertEqual(len(re.findall(r"^ +\d+ foragers +\w+ ", out, re.M)), 20)
        self.assertEqual(len(re.findall(r"^ +20 nest_beacon ", out, re.M)), 1)
        head = next(ln for ln in out.splitlines() if ln.startswith(" id ") and "threshold" in ln)
        self.assertIn("probability", head)
        self.assertNotIn("Traceback", r.stderr)

    def test_monitor_model_renders_in_a_small_window(self):
        m = monitor_of(self.log)
        self.assertEqual(m.robot_line_count(), len(m.robot_lines(None)))
        lines = m.render("test", width=60, height=24, scroll=5)
        self.assertEqual(len(lines), 24)
        self.assertTrue(all(len(ln) <= 60 for ln in lines))
        self.assertTrue(any(re.search(r"lines 6-\d+ of 26 ", ln) for ln in lines), lines)  # 2 tables: 2 + 20, 2 + 1, 1 gap
        m.add("JUNK", b"not lcm at all")
        self.assertEqual(m.undecodable, 1)

    @unittest.skipUnless(has_matplotlib(), "matplotlib missing: make deps")
    def test_plots(self):
        out = self.tmp / "plots"
        r = tool("plot_run", self.log, "-o", out)
        names = sorted(p.name for p in out.iterdir())
        self.assertEqual(names, ["controller_forager.png", "controller_nest_beacon.png", "events.png",
                                 "robots_by_state.png", "swarm_values.png"])
        for p in out.iterdir():
            self.assertEqual(p.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            self.assertGreater(p.stat().st_size, 10000)
        self.assertEqual(sorted(Path(p).name for p in r.stdout.split()), names)


class FaultTimes(TempDir):
    def test_fault_events_and_the_summary_agree(self):
        # Before: the events came 0.1 s (one control step) after start_s and end_s.
        out = self.tmp / "faults"
        run_sim(out, SCENARIOS / "random_walk.yaml", "--steps", 60, "--set", "robots.0.count=4",
                "--set", "robots.0.faults=[{kind: stop, fraction: 0.5, at: 1, duration: 2}, "
                         "{kind: ir_fail, fraction: 0.25, at: 2.5}]")
        summary = json.loads((out / "run_1" / "summary.json").read_text())
        told = {}
        for ch, m in read_log(out / "run_1" / "telemetry.lcmlog"):
            if ch == "SWARM_EVENT" and m.kind == "fault":
                told.setdefault((m.robot_id, m.detail), []).append(m.utime / 1e6)
        listed = {(f["robot"], f["kind"]): [f["start_s"]] + ([f["end_s"]] if f["end_s"] is not None else [])
                  for f in summary["faults"]}
        self.assertEqual(len(listed), 3, summary["faults"])
        self.assertEqual(told, listed)
        self.assertEqual(sorted(v[0] for v in listed.values()), [1.1, 1.1, 2.6])   # the end of the first faulty step
        self.assertEqual(sorted(v[1] - v[0] for v in listed.values() if len(v) == 2), [2.0, 2.0])


class Formats(unittest.TestCase):
    def test_numbers_print_as_the_simulator_prints_them(self):
        nan = float("nan")
        cases = [(0.1, "0.1"), (1 / 3, "0.3333333333"), (1e-5, "1e-05"), (123456789012.0, "1.23456789e+11"),
                 (-0.0, "-0"), (float("inf"), "inf"), (-float("inf"), "-inf"), (nan, "nan"), (-nan, "-nan")]
        for v, text in cases:      # glibc's printf("%.10g")
            self.assertEqual(export_csv.fmt_double(v), text, v)
        for v in (0.1, 1 / 3, 3.3, 2.5e-7, 16777217.0):
            f32 = struct.unpack("<f", struct.pack("<f", v))[0]
            text = export_csv.fmt_float(f32)
            self.assertEqual(struct.pack("<f", float(text)), struct.pack("<f", f32))
            self.assertLessEqual(len(text), 12)
        self.assertEqual(export_csv.fmt_float(struct.unpack("<f", struct.pack("<f", 0.1))[0]), "0.1")


class NewControllers(SimulatedRuns):
    """A controller's values reach the CSV, the monitor and the plots by its
    schema alone: the random walk (one value, "oae") and the forager (ten,
    threshold, probability, ...) with the same tools."""

    def test_random_walk(self):
        r = tool("export_csv", self.walk_log, "--channel", "ROBOT_STATE")
        rows = read_csv(r.stdout)
        self.assertEqual([c for c in rows[0] if "." in c], ["random_walk.oae"])
        final = {row["robot_id"]: row for row in rows}
        summary = json.loads((self.walk_dir / "summary.json").read_text())
        self.assertEqual(sum(float(row["random_walk.oae"]) for row in final.values()),
                         summary["metrics"]["oae_total"])
        m = monitor_of(self.walk_log)
        self.assertEqual(m.robot_line_count(), len(m.robot_lines(None)))
        text = "\n".join(m.render("walk", width=None))
        self.assertIn("random_walk: 20 robots", text)
        self.assertRegex(text, r"\n id group .* seen +oae\n")

    def test_forager(self):
        book = log_schemas(self.log)
        names = book.get("controller", "forager", 4).names()
        self.assertTrue({"threshold", "probability", "stimulus"} <= set(names))
        r = tool("export_csv", self.log, "--channel", "ROBOT_STATE")
        cols = list(read_csv(r.stdout)[0])
        self.assertEqual([c for c in cols if c.startswith("forager.")], [f"forager.{n}" for n in names])

    @unittest.skipUnless(has_matplotlib(), "matplotlib missing: make deps")
    def test_plots_follow_the_schemas(self):
        figs = {Path(f.path).name: f for f in plot_run.plot(str(self.walk_log), str(self.tmp / "walk"))}
        self.assertEqual(sorted(figs), ["controller_random_walk.png", "events.png", "robots_by_state.png",
                                        "swarm_values.png"])
        self.assertEqual(figs["controller_random_walk.png"].series, ["oae"])
        header = (self.walk_dir / "timeseries.csv").read_text().split("\n")[0].split(",")
        self.assertEqual(figs["swarm_values.png"].series, [n for n in header if n not in ("step", "time_s")])
        self.assertEqual(set(figs["events.png"].series), {"oae", "state"})
        self.assertEqual(set(figs["robots_by_state.png"].series), {"forward", "avoid", "tumble"})
        figs = {Path(f.path).name: f for f in plot_run.plot(str(self.log), str(self.tmp / "forage"))}
        book = log_schemas(self.log)
        self.assertEqual(figs["controller_forager.png"].series, book.get("controller", "forager", 4).names())
        self.assertIn("threshold", figs["controller_forager.png"].series)
        self.assertEqual(figs["controller_nest_beacon.png"].series, book.get("controller", "nest_beacon", 4).names())
        self.assertTrue({"pickup", "deposit", "deposits", "oae", "state"} <= set(figs["events.png"].series))


class RobotsOwnTelemetry(TempDir):
    """robot_telemetry.enabled: the robots' own frames on FW_ channels, their
    schema in pieces; the tools show them with --prefix FW_ and keep them
    apart from the simulator's."""

    @classmethod
    def setUpClass(cls):
        cls.log = runs()["fw"] / "telemetry.lcmlog"

    def test_export_names_the_robots_values_from_their_schema_pieces(self):
        d = self.tmp / "csv"
        tool("export_csv", self.log, "-o", str(d) + "/")
        pieces = read_csv(d / "FW_TELEMETRY_SCHEMA.csv")
        self.assertTrue(pieces and all(int(p["n"]) < int(p["total"]) for p in pieces))   # pieces, not whole
        fw = read_csv(d / "FW_ROBOT_STATE.csv")
        sim = read_csv(d / "ROBOT_STATE.csv")
        self.assertEqual([c for c in fw[0] if "." in c], [c for c in sim[0] if "." in c])
        self.assertEqual({r["run"] for r in fw}, {"0"})
        self.assertEqual({r["robot_id"] for r in fw}, {str(k) for k in range(21)})

    def test_monitor_and_plots_keep_them_apart(self):
        r = tool("monitor", "--log", self.log, "--speed", "0", "--plain", "--exit-idle", LONG_IDLE)
        self.assertIn("not shown  FW_ROBOT_STATE", r.stdout)
        self.assertIn("--prefix FW_", r.stdout)
        self.assertRegex(r.stdout, r"\n +0 foragers ")
        r = tool("monitor", "--log", self.log, "--speed", "0", "--plain", "--exit-idle", LONG_IDLE, "--prefix", "FW_")
        self.assertIn("forager: 20 robots", r.stdout)
        self.assertRegex(r.stdout, r"\n +0 - +\w+ ")             # a robot has no group name
        self.assertIn("not shown  ", r.stdout)
        if has_matplotlib():
            figs = {Path(f.path).name: f for f in plot_run.plot(str(self.log), str(self.tmp / "p"), prefix="FW_")}
            self.assertEqual(sorted(figs), ["controller_forager.png", "controller_nest_beacon.png",
                                            "robots_by_state.png"])
            self.assertIn("probability", figs["controller_forager.png"].series)


class HandBuiltLog(TempDir):
    """A log as the bridge records it from robots: run 0, no RUN_INFO, an
    invented controller whose schema comes in pieces after its first
    states, another whose schema never comes, an invented task's swarm
    value and event kind."""

    def setUp(self):
        super().setUp()
        ev = []
        for s in range(4):
            t = s * 1000000
            ev.append((t, "ROBOT_STATE", robot_state(1, "carry" if s else "idle", values=[s, 0.25 * s, 1], utime=t)))
            ev.append((t, "ROBOT_STATE", robot_state(2, "idle", values=[0, 0.5, 2], utime=t)))
            ev.append((t, "ROBOT_STATE", robot_state(3, "roam", controller="scout", values=[7 + s], utime=t)))
            if s == 1:
                ev.append((t, "TELEMETRY_SCHEMA", schema("sorter", ["carried", "rate"], first=0, total=3,
                                                         units=["items", "1/s"], counters=[1, 0], utime=t)))
                ev.append((t, "SWARM_EVENT", event(1, "grab", value=3, utime=t)))
            if s == 2:
                ev.append((t, "TELEMETRY_SCHEMA", schema("sorter", ["drops"], first=2, total=3, utime=t)))
            ev.append((t, "TELEMETRY_SCHEMA", schema("swarm", ["step", "time_s", "sorted"], kind="swarm", utime=t)))
            ev.append((t, "SWARM_STATE", swarm_state(s * 10, [s * 10, s, s / 3.0], utime=t, robots=3,
                                                     states=[("idle", 2 - (s > 0)), ("carry", int(s > 0)),
                                                             ("roam", 1)])))
        ev.append((5000000, "OTHER_PROGRAM", b"\x01\x02 not ours"))
        self.log = write_log(self.tmp / "robots.lcmlog", ev)

    def test_export(self):
        r = tool("export_csv", self.log, "--channel", "ROBOT_STATE")
        rows = read_csv(r.stdout)
        self.assertEqual([c for c in rows[0] if "." in c],
                         ["sorter.carried", "sorter.rate", "sorter.drops", "scout.value0"])
        self.assertEqual([(row["robot_id"], row["sorter.carried"], row["sorter.rate"], row["scout.value0"])
                          for row in rows[-3:]], [("1", "3", "0.75", ""), ("2", "0", "0.5", ""), ("3", "", "", "10")])
        r = tool("export_csv", self.log, "--timeseries", 20)
        self.assertEqual(r.stdout, "step,time_s,sorted\n0,0,0\n20,2,0.6666666667\n30,3,1\n")
        r = tool("export_csv", self.log, "--timeseries", 5, check=False)    # the log has every 10 steps only
        self.assertEqual(r.returncode, 1)
        self.assertIn("misses steps 5, 15, 25", r.stderr)
        r = tool("export_csv", self.log, "-o", str(self.tmp / "all") + "/")
        self.assertIn("channels of unknown types skipped: OTHER_PROGRAM", r.stderr)

    def test_monitor(self):
        m = monitor_of(self.log)
        self.assertEqual(m.robot_line_count(), len(m.robot_lines(None)))
        text = "\n".join(m.render("robots", width=None))
        self.assertIn("sorter: 2 robots", text)
        self.assertRegex(text, r"seen +carried +rate +drops\n")
        self.assertIn("scout: 1 robot   (schema incomplete", text)
        self.assertIn("swarm   sorted 1", text)
        self.assertIn("events  grab 1", text)
        self.assertIn("grab 3", text)
        self.assertEqual(m.undecodable, 1)

    @unittest.skipUnless(has_matplotlib(), "matplotlib missing: make deps")
    def test_plots(self):
        figs = {Path(f.path).name: f for f in plot_run.plot(str(self.log), str(self.tmp / "p"))}
        self.assertEqual(sorted(figs), ["controller_scout.png", "controller_sorter.png", "events.png",
                                        "robots_by_state.png", "swarm_values.png"])
        self.assertEqual(figs["controller_sorter.png"].series, ["carried", "rate", "drops"])
        self.assertEqual(figs["controller_scout.png"].series, ["value0"])
        self.assertEqual(figs["swarm_values.png"].series, ["sorted"])
        self.assertEqual(figs["events.png"].series, ["grab"])
        self.assertEqual(figs["robots_by_state.png"].series, ["idle", "carry", "roam"])


class OtherVersions(TempDir):
    """Logs and messages of another telemetry version: a clear message and
    exit status 1 from every tool, never a traceback."""

    def check_refused(self, log, text, tools=("export_csv", "plot_run", "monitor")):
        for name in tools:
            args = {"export_csv": [log, "-o", str(self.tmp / "csv") + "/"],
                    "plot_run": [log, "-o", self.tmp / "plots"],
                    "monitor": ["--log", log, "--speed", "0", "--plain", "--exit-idle", LONG_IDLE]}[name]
            r = tool(name, *args, check=False)
            self.assertEqual(r.returncode, 1, (name, r.stderr))
            self.assertIn(text, r.stderr, name)
            self.assertNotIn("Traceback", r.stderr, name)
        self.assertFalse((self.tmp / "csv").exists())      # nothing half written
        self.assertFalse((self.tmp / "plots").exists())

    def test_a_v1_log(self):
        good = swarm_state(0, [0, 0])
        log = write_log(self.tmp / "v1.lcmlog", [(0, "SWARM_STATE", good), (0, "RUN_INFO", V1["run_info_t"]),
                                                 (0, "ROBOT_STATE", V1["robot_state_t"])])
        self.check_refused(log, f"{log}: written by an older version of the toolkit (telemetry v1, run_info_t); "
                                "re-run the simulation to get a v2 log")

    def test_every_v1_type_is_named(self):
        for name, data in V1.items():
            for channel in ("ROBOT_STATE", "SOMETHING_ELSE", None):
                with self.assertRaises(common.IncompatibleMessage) as cm:
                    common.decode(data, channel)
                self.assertEqual((cm.exception.type_name, cm.exception.version), (name, 1))
                self.assertIn(f"(telemetry v1, {name})", cm.exception.explain("x.lcmlog"))
        # On a live bus the advice is for the publisher.
        e = common.IncompatibleMessage("ROBOT_STATE", "robot_state_t", "old", version=1)
        self.assertEqual(e.explain("udpm://239.255.76.67:7667", log=False),
                         "udpm://239.255.76.67:7667: a message on ROBOT_STATE comes from an older version of the "
                         "toolkit (telemetry v1, robot_state_t); update its publisher (the simulator, or the robot's "
                         "firmware) to telemetry v2")
        m = monitor.Model()
        with self.assertRaises(common.IncompatibleMessage):
            m.add("ROBOT_STATE", V1["robot_state_t"])

    def test_a_wrong_version_field(self):
        for version, text in ((1, "written by an older version of the toolkit (telemetry v1, robot_state_t)"),
                              (3, "written by a newer version of the toolkit (telemetry v3, robot_state_t); "
                                  "update these tools")):
            msg = robot_state(values=[1])
            msg.version = version
            log = write_log(self.tmp / f"version{version}.lcmlog", [(0, "ROBOT_STATE", msg)])
            self.check_refused(log, text, tools=("export_csv", "monitor"))

    def test_what_does_not_decode_on_our_channels(self):
        cut = swarm_state(0, [1, 2, 3]).encode()[:30]
        log = write_log(self.tmp / "cut.lcmlog", [(0, "SWARM_STATE", cut)])
        self.check_refused(log, "a message on SWARM_STATE is not a swarm_state_t of telemetry v2")
        log = write_log(self.tmp / "junk.lcmlog", [(0, "FW_ROBOT_STATE", b"\x00" * 16)])   # prefixed: ours too
        self.check_refused(log, "a message on FW_ROBOT_STATE is not a robot_state_t of telemetry v2",
                           tools=("export_csv",))


class Packaging(unittest.TestCase):
    """One package, imported as such; no tool names a controller, task or value."""

    SOURCES = sorted((ROOT / "tools" / "swarmtools" / "telemetry").glob("*.py"))

    def test_no_sys_path_edits(self):
        files = self.SOURCES + sorted((ROOT / "tools" / "tests" / "telemetry").glob("*.py"))
        self.assertGreater(len(files), 8)
        for p in files:
            tree = ast.parse(p.read_text())
            for node in ast.walk(tree):
                if isinstance(node, ast.Attribute) and node.attr == "path" and \
                        isinstance(node.value, ast.Name) and node.value.id == "sys":
                    self.fail(f"{p}: edits sys.path (line {node.lineno})")

    def test_no_controller_task_or_value_names_in_the_code(self):
        words = re.compile(r"forag|\bnest|threshold|token|pickup|deposit|random_walk|drtm|artm|food|oae", re.I)
        for p in self.SOURCES:
            tree = ast.parse(p.read_text())
            for node in ast.walk(tree):     # docstrings may give examples
                body = getattr(node, "body", None)
                if isinstance(body, list) and body and isinstance(body[0], ast.Expr) and \
                        isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
                    body[0].value.value = ""
            found = words.findall(ast.unparse(tree))
            self.assertEqual(found, [], p.name)

    def test_every_lcm_type_is_known(self):
        """common.TYPE_NAMES lists lcm_types/ (so every type decodes by its
        fingerprint) and CHANNEL_TYPES names only types of it."""
        files = {p.stem for p in (ROOT / "lcm_types").glob("*.lcm")}
        self.assertEqual(set(common.TYPE_NAMES), files)
        self.assertLessEqual(set(common.CHANNEL_TYPES.values()), files)

    def test_console_scripts(self):
        text = (ROOT / "pyproject.toml").read_text()
        for script, module in (("swarm-bridge", "bridge"), ("swarm-monitor", "monitor"),
                               ("swarm-export", "export_csv"), ("swarm-plot", "plot_run")):
            self.assertIn(f'{script} = "swarmtools.telemetry.{module}:main"', text)
            r = tool(module, "--help")
            self.assertIn(f"usage: {script}", r.stdout)


class JavaTypes(TempDir):
    """build/lcm_types.jar: the classes lcm-spy finds decode our messages."""

    def test_java_decodes_a_python_message(self):
        jar = ROOT / "build" / "lcm_types.jar"
        java = shutil.which("java")
        if not jar.exists() or not java:
            self.skipTest("no JDK: the jar is built only when javac is present")
        lcm_jar = next((ROOT / ".venv").glob("lib/python*/site-packages/share/java/lcm.jar"))
        src = self.tmp / "Check.java"
        src.write_text("""
public class Check {
    public static void main(String[] a) throws Exception {
        byte[] data = java.util.HexFormat.of().parseHex(a[0]);
        swarmlcm.robot_state_t m = new swarmlcm.robot_state_t(data);
        System.out.println(m.version + " " + m.robot_id + " " + m.controller + " " + m.state + " " + m.n_values
                           + " " + m.values[1] + " " + swarmlcm.robot_state_t.LCM_FINGERPRINT);
    }
}
""")
        msg = robot_state(5, "return", controller="forager", values=[1, 2.5])
        r = subprocess.run([java, "-cp", f"{lcm_jar}:{jar}", str(src), msg.encode().hex()],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        fp = int.from_bytes(swarmlcm.robot_state_t._get_packed_fingerprint(), "big", signed=True)
        self.assertEqual(r.stdout.split(), ["2", "5", "forager", "return", "2", "2.5", str(fp)])


if __name__ == "__main__":
    unittest.main()
