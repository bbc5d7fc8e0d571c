"""Live view of a swarm in the browser: a small local web server (aiohttp)
that follows LCM telemetry, or replays an LCM log, and pushes it to a page
over a WebSocket.

    swarm-live                                              # LCM's default udpm bus
    swarm-live --lcm 'udpm://239.255.76.67:7667?ttl=0'
    swarm-live --log out/run/run_1/telemetry.lcmlog --speed 10
    (or .venv/bin/python -m swarmtools.live ...; then open the address it prints)

The page draws the arena (SCENE), every robot with its id, heading, state
(a colour per controller state) and LEDs (ROBOT_STATE), what the tasks draw
(TASK_DRAWING), the clock (simulated time) and small charts of the swarm's
time series (SWARM_STATE, named by TELEMETRY_SCHEMA).  A log plays at any
speed, with pause and seek in the page.  Real robots behind swarm-bridge
show as tiles of their states and values, with the bridge's counters, and
on the arena only if their pose is known (robot_state_t.pose_known).
Everything the page needs is served from this package: no CDN, no build.

Only this server's own pages are answered (hosts.py: the Host must be one
of its names, a WebSocket's Origin its own), a page's commands are checked
before they act (commands.py), and what one message may carry is bounded
(limits.py; the page says what was cut).  Telemetry is taken in and frames
are made on worker threads, so the event loop that answers every page
stays free, and a signal stops the server at once.
"""
import argparse
import asyncio
import concurrent.futures
import json
import logging
import math
import signal
import socket
import sys
import threading
from pathlib import Path

try:
    from aiohttp import WSMsgType, web
except ImportError as e:          # a .venv from before the live view
    raise SystemExit(f"swarm-live: the `aiohttp` Python module is missing ({e}): run `make deps`") from None

from swarmtools.live import commands
from swarmtools.live.bus import Bus
from swarmtools.live.hosts import AllowedHosts
from swarmtools.live.replay import Log, Player
from swarmtools.telemetry import common

PROG = "swarm-live"
STATIC = Path(__file__).resolve().parent / "static"
#: Seconds between two frames pushed to a page (20 a second at most).
FRAME_S = 0.05
#: Replay speeds the command line and the page accept.
SPEED_MIN, SPEED_MAX = 0.01, 10000.0

#: A replay's default speed plays the log in about this many seconds (a
#: 20-minute run at 20x), at one of these speeds (the page's), at least 1.
WATCH_S = 60.0
DEFAULT_SPEEDS = (1, 2, 5, 10, 20, 50, 100, 1000)


def default_speed(end_s):
    """The speed that replays a log of end_s seconds in about WATCH_S."""
    return max([s for s in DEFAULT_SPEEDS if s <= end_s / WATCH_S] or [1])


#: Seconds a closing WebSocket waits for the page's answer when the server stops.
CLOSE_S = 2.0

FEED = web.AppKey("feed", object)
OPTIONS = web.AppKey("options", argparse.Namespace)
SOCKETS = web.AppKey("sockets", set)
HOSTS = web.AppKey("hosts", AllowedHosts)
WORKERS = web.AppKey("workers", concurrent.futures.ThreadPoolExecutor)
FILES = web.AppKey("files", dict)


def speed(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not (math.isfinite(v) and SPEED_MIN <= v <= SPEED_MAX):
        raise argparse.ArgumentTypeError(f"{text}: the speed is a factor of real time in [{SPEED_MIN:g}, {SPEED_MAX:g}]")
    return v


def port(text):
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 0 <= v <= 65535:
        raise argparse.ArgumentTypeError(f"{text}: a port is 0..65535 (0: any free one)")
    return v


class Session:
    """One page: its playback (a log: its own Player) or the shared live
    view, and what it has of it.  Its methods run on worker threads, one at
    a time (its lock; a live view's is the bus's, which applies messages
    under it)."""

    def __init__(self, feed, options):
        if isinstance(feed, Log):
            self.player = Player(feed, speed=options.speed, playing=not options.paused, prefix=options.prefix)
            self.view = self.player.view
            self.lock = threading.Lock()
        else:
            self.player = None
            self.view = feed.view
            self.lock = feed.lock
        self.feed = feed
        self.frozen = False         # live: paused, the page keeps what it shows
        self.sync = {}
        self.last_status = None
        self.shown = (0.0, None)    # the time and clock of the last frame sent

    def status(self):
        s = self.player.status() if self.player else self.feed.status()
        ctl = None if self.player else self.view.control
        s["controlled"] = ctl is not None
        if ctl is not None:      # a run under control: its own pause and speed
            s["playing"], s["speed"] = not ctl.paused, ctl.realtime
        elif not self.player:
            s["playing"] = not self.frozen
        return s

    def handle(self, text):
        """One WebSocket text message of the page: an error text or None."""
        try:
            what, fields = commands.parse(text)
        except commands.BadCommand as e:
            return str(e)
        with self.lock:
            return self.apply(what, fields)

    def command(self, cmd):
        """Applies one decoded command (any JSON value); an error text or None."""
        try:
            what, fields = commands.check(cmd)
        except commands.BadCommand as e:
            return str(e)
        with self.lock:
            return self.apply(what, fields)

    def apply(self, what, fields):
        """A checked command (commands.COMMANDS): an error text or None."""
        value = fields.get("value")
        if not self.player and (self.view.control is not None or what in ("step", "move", "select", "set")):
            return self.control(what, fields)
        if what == "step":
            return self.player.step(int(value))
        if what in ("move", "select", "set"):
            return f"{what}: a replayed log cannot be changed (only a run under swarmsim --control can)"
        if what in ("play", "pause"):
            if self.player and what == "play":
                self.player.play()
            elif self.player:
                self.player.pause()
            else:
                self.frozen = what == "pause"
        elif what in ("speed", "seek"):
            if not self.player:
                return f"{what}: only a log can be replayed at another speed or sought (this is a live bus)"
            if what == "seek":
                self.player.seek(float(value))
            elif not SPEED_MIN <= value <= SPEED_MAX:
                return f"speed: {value:g} is outside [{SPEED_MIN:g}, {SPEED_MAX:g}]"
            else:
                self.player.speed = float(value)
        return None

    def control(self, what, fields):
        """A page's command for the run under control: sent on the control
        bus (its answer comes back in the run's status), or an error text."""
        value = fields.get("value")
        if what == "play":
            return self.feed.send_control("resume")
        if what == "pause":
            return self.feed.send_control("pause")
        if what == "step":
            return self.feed.send_control("step", steps=value)
        if what == "speed":
            return self.feed.send_control("realtime", value=value)
        if what == "select":
            return self.feed.send_control("select", robot_id=fields["robot"])
        if what == "move":
            return self.feed.send_control("move", robot_id=fields["robot"], x=fields["x"], y=fields["y"],
                                          theta=fields["theta"])
        if what == "set":
            group = ""
            if fields["group"]:
                group = self.view.group_of(fields["robot"])
                if group is None:
                    return f"set: no robot {fields['robot']} in this run's groups (RUN_INFO)"
            return self.feed.send_control("set", robot_id=fields["robot"], group=group, param=fields["key"],
                                          param_value=fields["value"])
        return f"{what}: a live run is not sought (only a replayed log is)"

    def frame_text(self, wall_s):
        """The next frame as the JSON text to send, or None."""
        with self.lock:
            frame = self.frame(wall_s)
            # allow_nan=False: a NaN that slipped past convert.num is a bug
            # to see, not invalid JSON for the page.
            return None if frame is None else json.dumps(frame, separators=(",", ":"), allow_nan=False)

    def frame(self, wall_s):
        """The next frame for the page, or None when it has nothing new."""
        if self.player:
            self.player.advance(wall_s)
        status = self.status()
        if self.frozen:       # the page keeps what it has; it only learns that it is frozen
            out = {"reset": False, "time": self.shown[0], "clock": self.shown[1]}
        else:
            out = self.view.frame(self.sync)
        key = (out["time"], status["playing"], status["speed"], status["ended"])
        if len(out) == 3 and not out["reset"] and key == self.last_status:
            return None       # only reset, time, clock: and none moved
        self.last_status = key
        self.shown = (out["time"], out["clock"])
        out.update(type="frame", **status)
        return out


async def send(ws, obj):
    await ws.send_str(json.dumps(obj, separators=(",", ":"), allow_nan=False))


@web.middleware
async def only_our_host(request, handler):
    """Every request names this server in its Host (hosts.py: DNS rebinding)."""
    why = request.app[HOSTS].why_not(request.headers.get("Host"))
    if why:
        raise web.HTTPForbidden(text=f"{PROG}: {why}\n")
    return await handler(request)


async def websocket(request):
    app = request.app
    # Only this server's own page: a web site open in the same browser must
    # not read the telemetry or drive the replay (browsers send Origin).
    origin = request.headers.get("Origin")
    if origin is not None and origin.split("://", 1)[-1].lower() != request.host.lower():
        raise web.HTTPForbidden(text=f"{PROG}: WebSocket from another origin ({origin}) refused\n")
    # A text over max_msg_size closes the socket (1009); up to it, a command
    # too long is answered (commands.MAX_TEXT).
    ws = web.WebSocketResponse(heartbeat=30, timeout=CLOSE_S, max_msg_size=1 << 20)
    await ws.prepare(request)
    app[SOCKETS].add(ws)
    loop = asyncio.get_running_loop()
    work = app[WORKERS]
    feed = app[FEED]
    session = await loop.run_in_executor(work, Session, feed, app[OPTIONS])
    await send(ws, {"type": "hello", "mode": "log" if session.player else "live",
                    "source": feed.path if session.player else feed.url, **session.status()})

    async def push():
        last = loop.time()
        while not ws.closed:
            await asyncio.sleep(FRAME_S)
            now = loop.time()
            text = await loop.run_in_executor(work, session.frame_text, now - last)
            last = now
            if text is not None and not ws.closed:
                await ws.send_str(text)

    pusher = asyncio.create_task(push())
    try:
        async for msg in ws:
            if msg.type != WSMsgType.TEXT:
                continue
            error = await loop.run_in_executor(work, session.handle, msg.data)
            if error:
                await send(ws, {"type": "error", "text": error})
    finally:
        pusher.cancel()
        app[SOCKETS].discard(ws)
    return ws


async def index(request):
    return web.FileResponse(STATIC / "index.html")


async def static(request):
    """The page's own files, by name: nothing else (no path, no folder)."""
    path = request.app[FILES].get(request.match_info["name"])
    if path is None:
        raise web.HTTPNotFound(text=f"{PROG}: no such file\n")
    return web.FileResponse(path)


async def no_cache(request, response):
    # The page and its scripts change with the toolkit: never a stale copy.
    response.headers["Cache-Control"] = "no-cache"


async def close_sockets(app):
    # All at once, each waiting CLOSE_S at most for its page's answer.
    closing = [asyncio.ensure_future(ws.close(code=1001, message=b"server stopped")) for ws in list(app[SOCKETS])]
    if closing:
        await asyncio.wait(closing)


def make_app(feed, options, hosts, workers):
    app = web.Application(middlewares=[only_our_host])
    app[FEED] = feed
    app[OPTIONS] = options
    app[SOCKETS] = set()
    app[HOSTS] = hosts
    app[WORKERS] = workers
    app[FILES] = {p.name: p for p in STATIC.iterdir() if p.is_file()}
    app.router.add_get("/", index)
    app.router.add_get("/ws", websocket)
    app.router.add_get("/static/{name}", static)
    app.on_response_prepare.append(no_cache)
    app.on_shutdown.append(close_sockets)
    return app


class OneLine(logging.Formatter):
    """aiohttp's own server log as one line, without its traceback: a
    request it cannot parse (a path over 8,190 bytes, a bad header) is
    answered 400 by aiohttp and is the client's mistake, not ours."""

    def format(self, record):
        exc = record.exc_info[1] if record.exc_info else None
        text = record.getMessage() + (f": {' '.join(str(exc).split())[:200]}" if exc else "")
        return f"{PROG}: {text}"


def one_line_server_log():
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(OneLine())
    log = logging.getLogger("aiohttp.server")
    log.addHandler(handler)
    log.propagate = False


def listen(host, number):
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    try:
        return socket.create_server((host, number), family=family)
    except OSError as e:
        raise SystemExit(f"{PROG}: cannot listen on {host}:{number}: {e.strerror or e}") from None


async def serve(feed, sock, options, hosts):
    loop = asyncio.get_running_loop()
    one_line_server_log()
    workers = concurrent.futures.ThreadPoolExecutor(max_workers=4, thread_name_prefix="swarm-live")
    runner = web.AppRunner(make_app(feed, options, hosts, workers), handle_signals=False, access_log=None,
                           shutdown_timeout=CLOSE_S)
    await runner.setup()
    await web.SockSite(runner, sock, shutdown_timeout=CLOSE_S).start()
    if isinstance(feed, Bus):
        feed.start()
    stop = asyncio.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):     # before the address is out: a signal then stops it cleanly
        loop.add_signal_handler(sig, stop.set)
    host, number = sock.getsockname()[:2]
    shown = f"[{host}]" if ":" in host else host
    what = f"{options.log} at {options.speed:g}x" if options.log else options.lcm
    print(f"{PROG}: http://{shown}:{number}/  ({what}; Ctrl-C stops)", flush=True)
    await stop.wait()
    if isinstance(feed, Bus):
        feed.stop()
    await runner.cleanup()
    workers.shutdown(wait=False, cancel_futures=True)    # a frame being made ends on its own
    print(f"{PROG}: stopped", file=sys.stderr, flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--lcm", default=common.DEFAULT_URL, help="LCM URL to follow (default %(default)s)")
    src.add_argument("--log", help="replay an LCM log file instead (pause, seek and speed in the page)")
    ap.add_argument("--control-lcm", default=common.DEFAULT_URL, metavar="URL",
                    help="the bus of a run under swarmsim --control, which the page's buttons steer (default "
                         "%(default)s, loopback-only, as swarmsim's)")
    ap.add_argument("--speed", type=speed, default=None,
                    help=f"with --log: replay speed, a factor of the recorded time (default: the log in about "
                         f"{WATCH_S:g} s of watching, at least 1: a 20-minute run at 20x)")
    ap.add_argument("--paused", action="store_true", help="with --log: start paused at the beginning")
    ap.add_argument("--host", default="127.0.0.1", help="address to serve on (default %(default)s: this machine only)")
    ap.add_argument("--port", type=port, default=8080, help="port (default %(default)s; 0: any free one, printed)")
    ap.add_argument("--allow-host", action="append", default=[], metavar="NAME[:PORT]",
                    help="another name the page may be opened by (a DNS name, an ssh tunnel's localhost:PORT); "
                         "by default only the server's own address and names")
    ap.add_argument("--prefix", default="",
                    help="show the channels with this prefix (FW_: the robots' own telemetry in a simulation)")
    options = ap.parse_args(argv)
    if not (STATIC / "index.html").is_file():
        raise SystemExit(f"{PROG}: the page is missing from the package ({STATIC}): reinstall it (make deps)")
    try:
        feed = Log(options.log, PROG) if options.log else Bus(options.lcm, PROG, options.prefix, options.control_lcm)
    except KeyboardInterrupt:     # Ctrl-C while a long log is read
        print(f"{PROG}: stopped", file=sys.stderr, flush=True)
        return 130
    if options.speed is None:
        options.speed = default_speed(feed.end) if options.log else 1.0
    sock = listen(options.host, options.port)
    try:
        hosts = AllowedHosts(options.host, sock.getsockname()[1], options.allow_host)
    except ValueError as e:
        ap.error(str(e))
    try:
        asyncio.run(serve(feed, sock, options, hosts))
    except KeyboardInterrupt:     # a second Ctrl-C while it was stopping
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
