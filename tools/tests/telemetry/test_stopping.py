"""How the tools end when told to: Ctrl-C in the monitor's dashboard (on a
pseudo-terminal, as a user's terminal) and in its line mode, reading a log
and listening to a bus, restores the terminal and exits 130 with one line;
SIGTERM 143; a reader that closes the output early (`| head`) ends the
monitor and the export without a traceback."""
import fcntl
import os
import select
import signal
import struct
import subprocess
import termios
import time

from .helpers import LONG, PYTHON, ROOT, TempDir, default_sigint, robot_state, schema, swarm_state, write_log


def long_log(path, seconds=600):
    """A log that a replay at speed 1 takes `seconds` to play."""
    events = [(0, "TELEMETRY_SCHEMA", schema("swarm", ["step", "time_s", "x"], kind="swarm"))]
    for step in range(0, seconds * 10, 10):
        events.append((step * 100000, "SWARM_STATE", swarm_state(step, [step, step / 10, 1.0], robots=1)))
        events.append((step * 100000, "ROBOT_STATE", robot_state(utime=step * 100000)))
    return write_log(path, events)


def monitor_argv(*args):
    return [PYTHON, "-m", "swarmtools.telemetry.monitor", *map(str, args)]


class Dashboard:
    """The monitor's curses dashboard on a pseudo-terminal that is its
    controlling terminal: ^C typed on it is a SIGINT from the terminal."""

    def __init__(self, argv):
        self.master, self.slave = os.openpty()
        fcntl.ioctl(self.slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 120, 0, 0))
        self.before = termios.tcgetattr(self.slave)
        slave = self.slave

        def child():
            os.setsid()
            fcntl.ioctl(slave, termios.TIOCSCTTY, 0)
            default_sigint()

        self.proc = subprocess.Popen(argv, stdin=slave, stdout=slave, stderr=slave, cwd=ROOT, preexec_fn=child,
                                     env={**os.environ, "TERM": "xterm"})
        self.output = b""

    def read_until(self, text, timeout=LONG):
        end = time.monotonic() + timeout
        while text not in self.output:
            left = end - time.monotonic()
            if left <= 0:
                raise AssertionError(f"no {text!r} on the terminal: {self.output[-500:]!r}")
            if select.select([self.master], [], [], left)[0]:
                self.output += os.read(self.master, 65536)

    def finish(self):
        """Exit status and the terminal's modes after the monitor ended."""
        rc = self.proc.wait(timeout=LONG)
        while select.select([self.master], [], [], 0.2)[0]:
            try:
                data = os.read(self.master, 65536)
            except OSError:
                break
            if not data:
                break
            self.output += data
        after = termios.tcgetattr(self.slave)
        os.close(self.master)
        os.close(self.slave)
        return rc, after


class MonitorInterrupted(TempDir):
    def setUp(self):
        super().setUp()
        self.log = long_log(self.tmp / "long.lcmlog")

    def check_dashboard(self, *args):
        d = Dashboard(monitor_argv(*args))
        d.read_until(b"swarm monitor")            # drawn: in its loop, the terminal in curses' modes
        os.write(d.master, b"\x03")              # Ctrl-C typed on the terminal
        rc, after = d.finish()
        text = d.output.decode(errors="replace")
        self.assertEqual(rc, 130, text[-800:])
        self.assertEqual(after, d.before, "the terminal's modes were not restored")
        self.assertNotIn("Traceback", text)
        self.assertTrue(text.rstrip().endswith("swarm-monitor: stopped by SIGINT"), text[-300:])

    def test_dashboard_reading_a_log(self):
        self.check_dashboard("--log", self.log, "--speed", 1)

    def test_dashboard_listening(self):
        self.check_dashboard("--lcm", "memq://")

    def check_plain(self, *args, sig=signal.SIGINT, status=130):
        p = subprocess.Popen(monitor_argv("--plain", "--interval", 0.2, *args), cwd=ROOT, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, preexec_fn=default_sigint)
        try:
            first = p.stdout.readline()           # its first report: in its loop, the signals its own
            self.assertIsNone(p.poll(), "the monitor ended before it was interrupted")
            p.send_signal(sig)
            out, err = p.communicate(timeout=LONG)
        finally:
            p.kill()
        self.assertEqual(p.returncode, status, err)
        self.assertEqual(err, f"swarm-monitor: stopped by {sig.name}\n")
        self.assertIn("swarm monitor", first + out)

    def test_plain_reading_a_log(self):
        # LCM reports Ctrl-C during its wait as it reports the end of a log:
        # the monitor used to take it for the end and exit 0.
        self.check_plain("--log", self.log, "--speed", 1)

    def test_plain_listening(self):
        self.check_plain("--lcm", "memq://")

    def test_sigterm(self):
        self.check_plain("--lcm", "memq://", sig=signal.SIGTERM, status=143)


class ClosedPipe(TempDir):
    """`tool ... | head`: the reader goes away before the tool has written."""

    def check(self, module, *args):
        r, w = os.pipe()
        p = subprocess.Popen([PYTHON, "-m", f"swarmtools.telemetry.{module}", *map(str, args)], cwd=ROOT,
                             stdout=w, stderr=subprocess.PIPE, text=True)
        os.close(w)
        os.close(r)                              # nobody reads: the first write fails
        _, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 0, err)
        self.assertEqual(err, "")

    def test_monitor(self):
        self.check("monitor", "--log", long_log(self.tmp / "a.lcmlog", 30), "--plain", "--speed", 0)

    def test_export(self):
        self.check("export_csv", long_log(self.tmp / "a.lcmlog", 30), "--channel", "ROBOT_STATE")

    def test_export_timeseries(self):
        self.check("export_csv", long_log(self.tmp / "a.lcmlog", 30), "--timeseries", 1)
