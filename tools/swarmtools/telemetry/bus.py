"""Listening to a live LCM bus without dropping the simulator's bursts.

LCM keeps, per subscription, at most 30 received messages that the program
has not handled yet (lcm_subscription_set_queue_capacity) and drops the
next ones.  The simulator publishes every robot's state, the swarm state
and the events of a step in the same instant (about 30 messages at once
for 20 robots, when RUN_INFO and the schemas are due too), faster than a
Python handler takes them, so with LCM's default a listener loses robot
states and, in the last burst of a run, the summary (measured with
tools/bench/udp_loss.py; docs/reference/telemetry.md gives the figures).  The tools
therefore subscribe with a long queue, and ask the kernel for a larger
receive buffer on udpm:// sockets (LCM's `recv_buf_size`; the kernel caps
it at net.core.rmem_max, which is the machine's setting, not ours).
"""
import urllib.parse

from swarmtools.telemetry import common

#: Messages a subscription may hold before LCM drops new ones (LCM: 30):
#: the states of a 2,000-robot swarm in one burst, several times over.
QUEUE_CAPACITY = 10_000
#: SO_RCVBUF asked for on udpm:// sockets (Linux's default rmem_default is 208 KiB).
RECV_BUF_BYTES = 4 << 20


def listen_url(url):
    """`url` with recv_buf_size=RECV_BUF_BYTES added when it is a udpm://
    URL that does not set it (the user's own setting wins)."""
    parts = urllib.parse.urlsplit(url)
    if parts.scheme != "udpm":
        return url
    options = urllib.parse.parse_qsl(parts.query, keep_blank_values=True)
    if any(k == "recv_buf_size" for k, _ in options):
        return url
    query = parts.query + ("&" if parts.query else "") + f"recv_buf_size={RECV_BUF_BYTES}"
    return urllib.parse.urlunsplit(parts._replace(query=query))


def subscribe(bus, pattern, handler):
    """bus.subscribe with a queue long enough for the simulator's bursts."""
    sub = bus.subscribe(pattern, handler)
    sub.set_queue_capacity(QUEUE_CAPACITY)
    return sub


def open_listener(url, prog):
    """(lcm.LCM on listen_url(url), that URL); a URL LCM refuses stops the
    tool with one line."""
    lcm = common.lcm_module()
    url = listen_url(url)
    try:
        return lcm.LCM(url), url
    except Exception as e:
        raise SystemExit(f"{prog}: cannot open LCM URL {url!r}: {e}") from None
