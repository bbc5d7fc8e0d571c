"""How the telemetry tools end when told to: Ctrl-C or SIGTERM, and a
reader that closed their output (`swarm-export ... | head`).

A signal is recorded, not raised as KeyboardInterrupt: LCM's
handle_timeout, waiting in select(), returns an error (OSError) when a
signal interrupts it, and a tool reading a log must not take that for the
end of the log; a KeyboardInterrupt raised inside an LCM message handler
would be lost in LCM's C code; and the dashboard must leave curses (and so
restore the terminal) before it says anything.  Loops check the flag and
end; the tool then prints one line and exits with 128 + the signal (130
for SIGINT, 143 for SIGTERM), as a shell reports a process it interrupted.
"""
import os
import signal
import sys

HANDLED = (signal.SIGINT, signal.SIGTERM)


class Signals:
    """While active (a `with` block), SIGINT and SIGTERM set `signum`
    instead of stopping the program.  A signal the caller's shell ignores
    (a background job's SIGINT) stays ignored."""

    def __init__(self):
        self.signum = None
        self._old = {}

    def __enter__(self):
        for s in HANDLED:
            if signal.getsignal(s) is not signal.SIG_IGN:
                self._old[s] = signal.signal(s, self._record)
        return self

    def __exit__(self, *exc):
        for s, handler in self._old.items():
            signal.signal(s, handler)
        self._old.clear()
        return False

    def _record(self, signum, _frame):
        self.signum = signum

    def __bool__(self):
        return self.signum is not None

    @property
    def name(self):
        return signal.Signals(self.signum).name

    def exit_status(self, prog, what="stopped"):
        """Says `prog: <what> by SIG...` on stderr; returns 128 + signal."""
        print(f"{prog}: {what} by {self.name}", file=sys.stderr, flush=True)
        return 128 + self.signum


def interrupted(prog):
    """For a KeyboardInterrupt that came before or after a Signals block
    (while starting or ending): one line, status 130."""
    print(f"{prog}: interrupted by SIGINT", file=sys.stderr, flush=True)
    return 128 + signal.SIGINT


def stdout_closed():
    """After a BrokenPipeError on stdout (`tool | head`): the reader has
    what it wanted.  Points stdout at /dev/null so that the interpreter's
    flush at exit does not fail a second time (with a traceback)."""
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except OSError:
        pass
    return 0
