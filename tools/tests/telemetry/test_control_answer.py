"""swarmtools.control.Controller.send returns the run's answer to the
command, the first status with its seq: not a later status that carries the
same seq (the one a `step` sends once its steps are done), which the bus
may deliver before the caller looks.  The run is played here by statuses
handed to the Controller's own handler, in the order the bus may give."""
import unittest

from swarmtools import control
from swarmtools.telemetry import common


def status(seq, step, paused=True, key="k"):
    m = common.type_class("control_status_t")()
    m.version = m.VERSION
    m.key, m.run, m.seq, m.step, m.steps = key, 1, seq, step, 1000
    m.paused, m.ok, m.text, m.realtime, m.selected = paused, True, "", 10.0, -1
    return m.encode()


class Bus:
    """The Controller's LCM with publish() played by the test."""
    def __init__(self, lcm, publish):
        self.handle_timeout, self.publish = lcm.handle_timeout, publish


class Answer(unittest.TestCase):
    def setUp(self):
        self.c = control.Controller("memq://")
        self.addCleanup(self.c.close)

    def play(self, replies):
        """The run: to each command published, `replies(seq)`'s statuses,
        all of them delivered before send() wakes."""
        def publish(channel, data):
            seq = control.common.decode(data, channel).seq
            with self.c._cond:   # delivered as one burst, as the bus may
                for data in replies(seq):
                    self.c._on_status(control.STATUS_CHANNEL, data)
        self.c.lcm = Bus(self.c.lcm, publish)

    def test_a_step_answers_with_the_step_it_was_taken_at(self):
        self.c._on_status(control.STATUS_CHANNEL, status(0, 93))
        # The answer at step 93, then the status after the one step, at 94.
        self.play(lambda seq: [status(seq, 93, paused=False), status(seq, 94)])
        answer = self.c.send("step", timeout=5, steps=1)
        self.assertEqual(answer.step, 93)
        self.assertEqual(self.c.status.step, 94)

    def test_a_lost_answer_is_taken_from_the_next_status_of_its_seq(self):
        self.c._on_status(control.STATUS_CHANNEL, status(0, 10))
        self.play(lambda seq: [status(seq - 1, 10), status(seq, 11)])
        self.assertEqual(self.c.send("pause", timeout=5).step, 11)

    def test_no_answer_is_said_as_such(self):
        self.c._on_status(control.STATUS_CHANNEL, status(0, 10))
        self.play(lambda seq: [])
        with self.assertRaisesRegex(control.NoRun, r"did not answer pause within 0.2 s"):
            self.c.send("pause", timeout=0.2)


if __name__ == "__main__":
    unittest.main()
