"""The person at the table: told what to set up and where to put the robot,
asked what a ruler says.  TerminalOperator prompts in the terminal; the
simulated lab (fake_lab.py) has an operator that does it in a simulated
world."""

from __future__ import annotations

import sys
import time


class Aborted(RuntimeError):
    """The operator stopped a procedure (nothing of it is written)."""


class TerminalOperator:
    def __init__(self, read=input, out=sys.stdout):
        self.read = read
        self.out = out

    def _say(self, text):
        print(text, file=self.out, flush=True)

    def _ask(self, prompt):
        try:
            answer = self.read(prompt + " ")
        except EOFError as e:
            raise Aborted("no answer (end of input)") from e
        if answer.strip().lower() in ("q", "quit"):
            raise Aborted("stopped by the operator")
        return answer

    def setup(self, procedure, text):
        self._say(f"\n== {procedure} ==\n{text}")
        self._ask("Enter when ready (q to stop):")

    def place(self, placement, text):
        self._ask(f"{text} Enter when it is there:")

    def tone(self, band, text):
        self._ask(f"{text} Enter when it does:")

    def measure_move(self, placement, text):
        while True:
            answer = self._ask(f"{text} (three numbers, e.g. 120 -3 2):")
            parts = answer.replace(",", " ").split()
            try:
                values = [float(p) for p in parts]
            except ValueError:
                values = []
            if len(values) == 3:
                return tuple(values)
            self._say("  three numbers please: forward mm, left mm, turned degrees")

    def progress(self, text):
        self._say(f"  {text}")


#: The live view's events: kind "calibrate", the text in detail (SWARM_EVENT).
EVENT_KIND = "calibrate"


class LiveOperator:
    """An operator whose prompts and progress also go out as events
    (event_t, kind EVENT_KIND, on SWARM_EVENT) for the live view's events
    panel, beside the robot's own telemetry the kit republishes; the
    answers still come from `inner` (the terminal)."""

    def __init__(self, inner, publish, robot_id=lambda: -1, clock=time.time):
        self.inner = inner
        self.publish = publish
        self.robot_id = robot_id
        self.clock = clock
        self.sent = 0

    def _event(self, what, text):
        from ..telemetry import common
        m = common.type_class("event_t")()
        m.version, m.utime, m.run = m.VERSION, int(self.clock() * 1e6), 0
        rid = self.robot_id()
        m.robot_id = rid if rid is not None else -1
        m.kind, m.detail, m.value, m.pose_known, m.x, m.y = EVENT_KIND, f"{what}: {text}", self.sent, False, 0.0, 0.0
        self.publish("SWARM_EVENT", m.encode())
        self.sent += 1

    def setup(self, procedure, text):
        self._event("setup", f"{procedure}: {text}")
        return self.inner.setup(procedure, text)

    def place(self, placement, text):
        self._event("place", text)
        return self.inner.place(placement, text)

    def tone(self, band, text):
        self._event("tone", text)
        return self.inner.tone(band, text)

    def measure_move(self, placement, text):
        self._event("measure", text)
        moved = self.inner.measure_move(placement, text)
        self._event("measured", ", ".join(f"{v:g}" for v in moved))
        return moved

    def progress(self, text):
        self._event("progress", text)
        return self.inner.progress(text)
