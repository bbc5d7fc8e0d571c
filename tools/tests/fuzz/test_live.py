"""Properties of what the live view (swarmtools.live) takes from outside:
the page's commands and the telemetry's messages.

- any text a page sends, and any JSON value, is applied or answered with
  one line of text (commands.BadCommand), never anything else; whatever
  the sequence, the replay stays within its log and its speed range;
- any bytes after one of our types' fingerprints, on its channel, decode
  (cut to the limits) or are refused as IncompatibleMessage; a message
  that decodes keeps no array or text past its limit, and the view it is
  applied to makes a frame that is JSON without NaN.
"""
import json
import struct
import tempfile
import unittest
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

from swarmtools.live import commands, limits, server
from swarmtools.live.replay import Log
from swarmtools.live.view import View
from swarmtools.telemetry import common

from ..telemetry.helpers import robot_state, swarm_state, write_log

json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=20),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
    max_leaves=12)
command_like = st.fixed_dictionaries(
    {"cmd": st.sampled_from([*commands.COMMANDS, "jump", ""])},
    optional={"value": json_values, "extra": json_values})
texts = st.one_of(
    st.text(max_size=60), json_values.map(json.dumps), command_like.map(json.dumps),
    st.integers(1, 3000).map(lambda n: "[" * n + "]" * n),
    st.integers(1, 5000).map(lambda n: '{"cmd": "seek", "value": 1' + "0" * n + "}"))


class Commands(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="fuzz_live.")
        events = [(k * 100_000, "SWARM_STATE", swarm_state(k, [k], run=1)) for k in range(30)]
        cls.log = Log(write_log(Path(cls._tmp.name) / "l.lcmlog", events), "test")

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def session(self):
        opts = server.argparse.Namespace(speed=1.0, paused=True, prefix="")
        return server.Session(self.log, opts)

    def check(self, s, answer):
        self.assertTrue(answer is None or (isinstance(answer, str) and answer and "\n" not in answer), answer)
        p = s.player
        self.assertTrue(0.0 <= p.time <= self.log.end and server.SPEED_MIN <= p.speed <= server.SPEED_MAX)
        text = s.frame_text(0.1)
        self.assertTrue(text is None or isinstance(json.loads(text), dict))

    @given(st.lists(texts, max_size=6))
    def test_any_text_is_applied_or_answered(self, sent):
        s = self.session()
        for text in sent:
            self.check(s, s.handle(text))

    @given(st.lists(st.one_of(json_values, command_like), max_size=6))
    def test_any_json_value_is_applied_or_answered(self, sent):
        s = self.session()
        for cmd in sent:
            self.check(s, s.command(cmd))


TYPES = sorted(common.CHANNEL_TYPES.items())


class Messages(unittest.TestCase):
    @given(st.sampled_from(TYPES), st.binary(max_size=600), st.booleans())
    def test_any_bytes_of_our_types_decode_bounded_or_are_refused(self, channel_type, body, real_start):
        channel, name = channel_type
        cls = common.type_class(name)
        data = cls._get_packed_fingerprint() + body
        if real_start and name != "bridge_status_t":      # the right version, so that more of it decodes
            data = cls._get_packed_fingerprint() + struct.pack(">h", common.VERSION) + body
        try:
            msg, cut = limits.decode(data, channel)
        except common.IncompatibleMessage:
            return
        self.assert_bounded(msg)
        v = View()
        v.note(cut)
        v.apply(1.0, channel, msg)
        json.dumps(v.frame({}), allow_nan=False)

    @given(st.integers(0, 3000), st.integers(0, 300), st.text(max_size=3000))
    def test_big_states_are_cut_to_the_limits(self, n_values, n_states, text):
        n_values = min(n_values, 32767)
        long_text = len(text) > limits.MAX_TEXT
        for m, want in ((swarm_state(1, [0.5] * n_values, states=[(text, 1)] * n_states, run=1),
                         n_values > 256 or n_states > 256 or (n_states > 0 and long_text)),
                        (robot_state(1, text, values=[1.0] * min(n_values, 127), run=1), long_text)):
            cut = limits.bound(m)
            self.assert_bounded(m)
            self.assertEqual(bool(cut), want, cut)

    def assert_bounded(self, msg):
        for slot, typename, dims in zip(msg.__slots__, msg.__typenames__, msg.__dimensions__, strict=True):
            v = getattr(msg, slot)
            if dims:
                self.assertLessEqual(len(v), limits.MAX_BY_LENGTH.get(dims[0], limits.MAX_ITEMS), slot)
                self.assertEqual(len(v), getattr(msg, dims[0]), slot)
                items = v
            else:
                items = [v]
            for x in items:
                if typename == "string":
                    self.assertLessEqual(len(x), limits.MAX_TEXT, slot)
                elif hasattr(x, "__slots__"):
                    self.assert_bounded(x)
