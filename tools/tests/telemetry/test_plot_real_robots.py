"""swarm-plot on what a log of real robots holds: what the bridge
republishes from their frames (robot states on the robots' own clocks,
run 0, schema pieces, events; no SWARM_STATE, no RUN_INFO) and its
BRIDGE_STATUS, recorded as lcm-logger would."""
import unittest
from pathlib import Path

from swarmtools.telemetry import bridge, common, plot_run
from swarmtools.telemetry.frames import encode_frame

from .helpers import TempDir, event, has_matplotlib, robot_state, schema, tool
from .test_bridge import PtyRobot, pump


class LogWriter:
    """An LCM log written as the bridge publishes, stamped as lcm-logger
    stamps events (wall clock; here a made-up one, advanced by tick())."""

    def __init__(self, path):
        self.log = common.lcm_module().EventLog(str(path), "w", overwrite=True)
        self.utime = 1_700_000_000_000_000

    def tick(self, seconds):
        self.utime += int(seconds * 1e6)

    def __call__(self, channel, data):
        self.utime += 1000
        self.log.write_event(self.utime, channel, data)


def robots_log(path, tmp, seconds=6, status=True):
    """Two robots (pseudo-terminals) behind the bridge for `seconds`: a
    state a second each on its own clock, its controller's schema in
    pieces, an event, and from robot 7 a frame with a bad CRC; a
    BRIDGE_STATUS a second when `status`."""
    out = LogWriter(path)
    robots = {rid: PtyRobot(str(tmp / f"rfcomm{rid}")) for rid in (3, 7)}
    devs = [bridge.Device(r.link) for r in robots.values()]
    br = bridge.Bridge(devs, out)
    seq = dict.fromkeys(robots, 0)

    def send(rid, channel, msg, corrupt=False):
        frame = bytearray(encode_frame(channel, rid, seq[rid], msg.encode()))
        seq[rid] += 1
        if corrupt:
            frame[6] ^= 0x10
        robots[rid].send(bytes(frame))

    try:
        br.reopen_due()
        for s in range(seconds):
            for rid in robots:
                t = (s + rid) * 1_000_000          # each robot's clock since its own power-on
                send(rid, 1, robot_state(rid, "search" if s % 2 else "rest", values=[s, rid], utime=t))
                send(rid, 6, schema("sorter", [["carried", "speed"][s % 2]], first=s % 2, total=2, utime=t))
                if s == 2:
                    send(rid, 2, event(rid, "grab", value=1, utime=t))
                if s == 3 and rid == 7:
                    send(rid, 1, robot_state(rid, utime=t), corrupt=True)
            # Every good frame republished and the bad one counted, before
            # the status: the bad frame is robot 7's last bytes of second 3,
            # and a poll can stop between its good frames and it.
            want, bad = sum(seq.values()) - (s >= 3), int(s >= 3)
            pump(br, lambda want=want, bad=bad: sum(d.republished for d in devs) == want
                 and sum(d.counters()["crc_errors"] for d in devs) == bad)
            if status:
                out("BRIDGE_STATUS", br.status_message(out.utime).encode())
            out.tick(1.0)
    finally:
        for r in robots.values():
            r.close()
        for d in devs:
            d.close()
        out.log.close()
    return path


@unittest.skipUnless(has_matplotlib(), "matplotlib missing: make deps")
class RealRobots(TempDir):
    def test_robots_and_the_bridge(self):
        log = robots_log(self.tmp / "robots.lcmlog", self.tmp)
        figs = {Path(f.path).name: f for f in plot_run.plot(str(log), str(self.tmp / "p"))}
        # Before: no bridge.png; BRIDGE_STATUS was skipped.
        self.assertEqual(sorted(figs), ["bridge.png", "controller_sorter.png", "events.png", "robots_by_state.png"])
        self.assertEqual(figs["robots_by_state.png"].series, ["rest", "search"])
        self.assertEqual(figs["controller_sorter.png"].series, ["carried", "speed"])
        self.assertEqual(figs["bridge.png"].series[:3], ["frames", "bytes", "crc_errors"])
        self.assertIn("connected", figs["bridge.png"].series + figs.get("bridge_2.png", figs["bridge.png"]).series)
        for f in figs.values():
            self.assertGreater(Path(f.path).stat().st_size, 10_000, f.path)

    def test_bridge_counters_per_device(self):
        log = robots_log(self.tmp / "robots.lcmlog", self.tmp)
        panels = {key: lines for key, _, lines in plot_run.bridge_panels(plot_run.read_log(log).bridge)}
        self.assertEqual(sorted(panels["crc_errors"]), [f"{self.tmp}/rfcomm3 (robot 3)", f"{self.tmp}/rfcomm7 (robot 7)"])
        t, crc = panels["crc_errors"][f"{self.tmp}/rfcomm7 (robot 7)"]
        self.assertEqual(crc, [0, 0, 0, 1, 1, 1])
        self.assertEqual([round(x) for x in t], [0, 1, 2, 3, 4, 5])    # s since the log began
        robot3 = f"{self.tmp}/rfcomm3 (robot 3)"
        self.assertEqual(panels["frames"][robot3][1][-1], 13)   # 6 states, 6 schema pieces, 1 event
        self.assertEqual(panels["connected"][robot3][1], [1] * 6)
        self.assertEqual(panels["lost"][robot3][1], [0] * 6)

    def test_robots_on_the_log_clock(self):
        # Robot 7 was switched on 4 s before robot 3: on their own clocks
        # their states would be 4 s apart; the logger heard them together.
        r = plot_run.read_log(robots_log(self.tmp / "robots.lcmlog", self.tmp))
        first = {}
        for m in r.robots["sorter"]:
            first.setdefault(m.robot_id, m.utime)
        self.assertLess(abs(first[3] - first[7]), 100_000, first)
        self.assertEqual(r.time_label, plot_run.LOG_CLOCK)

    def test_a_log_of_the_bridge_alone(self):
        dev = bridge.Device("/dev/rfcomm5")
        out = LogWriter(self.tmp / "status.lcmlog")
        br = bridge.Bridge([dev], out)
        for _ in range(3):
            out("BRIDGE_STATUS", br.status_message(out.utime).encode())
        out.log.close()
        r = tool("plot_run", self.tmp / "status.lcmlog", "-o", self.tmp / "p")
        self.assertEqual(r.stdout.strip(), str(self.tmp / "p" / "bridge.png"))

    def test_command_line(self):
        log = robots_log(self.tmp / "robots.lcmlog", self.tmp, status=False)
        r = tool("plot_run", log, "-o", self.tmp / "p")
        self.assertEqual(sorted(Path(p).name for p in r.stdout.split()),
                         ["controller_sorter.png", "events.png", "robots_by_state.png"])
        self.assertEqual(r.stderr, "")
