"""The person at the table: told what to set up and where to put the robot,
asked what a ruler says.  TerminalOperator prompts in the terminal; the
simulated lab (fake_lab.py) has an operator that does it in a simulated
world."""

from __future__ import annotations

import sys


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
