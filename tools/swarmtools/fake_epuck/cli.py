"""swarm-fake-epuck - e-puck1s without a robot: pseudo-terminals that behave
like the robots' Bluetooth serial ports, for the flasher, the bridge, the
monitor, the live view and the host link.

    swarm-fake-epuck hex forager -o out/fake/forager.hex      # a stand-in image to flash
    swarm-fake-epuck run --robots 2 --dir out/fake --background
    epuck-flash out/fake/forager.hex out/fake/rfcomm0 --robot-id 7
    swarm-bridge out/fake/rfcomm0 out/fake/rfcomm1 ...
    swarm-fake-epuck stop --dir out/fake

Each robot's port is a link DIR/rfcomm<k> (as udev names rfcomm ports).
Behind it the robot resets into its bootloader (the flasher's protocol,
answers and errors as the real Tiny Bootloader's), then runs the image its
program memory holds: the image's declaration
(platforms/epuck1/images.list) as the host build (or, --platform, its ELF
on an emulated MCU), in a simulated world of its own, sending the image's own telemetry frames and taking the host
link's poses and messages.  The flasher's handshake presses the robot's
reset button.  --image preloads a robot as if it had been flashed before.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
import time
from pathlib import Path

PROG = "swarm-fake-epuck"
PID_FILE = "fake-epuck.pid"
LOG_FILE = "fake-epuck.log"


def _run(args) -> int:
    from .bootloader import Faults
    from .images import ImageError, declaration
    from .server import FakeEpucks, log_to_stderr
    try:
        for name in args.image or []:
            if name != "none":
                declaration(name)
        faults = Faults.parse(args.boot_fault)
    except (ImageError, ValueError) as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    if args.world and not os.path.isfile(args.world):
        print(f"{PROG}: --world {args.world}: no such file", file=sys.stderr)
        return 2
    images = [None if n == "none" else n for n in (args.image or [])]
    ids = args.id if args.id else list(range(args.robots))
    if len(images) > args.robots or len(ids) != args.robots:
        print(f"{PROG}: {args.robots} robots: give at most {args.robots} --image and none or {args.robots} --id",
              file=sys.stderr)
        return 2
    if any(not 0 <= i <= 0xFFFE for i in ids):
        print(f"{PROG}: --id: robot ids are 0..65534", file=sys.stderr)
        return 2
    # Every image runs in the simulator's library: without it a robot would
    # only say so in its log once flashed (with --background, after this
    # command had reported success), so refuse here, before any port exists.
    from ..sim._lib import LibraryMissing, lib
    try:
        lib()
    except (LibraryMissing, OSError) as e:
        print(f"{PROG}: the fake robots could run no image: {e}", file=sys.stderr)
        return 1
    log = None if args.quiet else log_to_stderr(PROG)
    fakes = FakeEpucks(args.robots, args.dir, images=images, ids=ids, faults=[faults] * args.robots,
                       world=args.world, speed=args.speed, log=log, platform=args.platform,
                       shared_world=args.shared_world)
    fakes.power_on()
    for r, name, rid in zip(fakes.robots, images + [None] * args.robots, ids, strict=False):
        what = f"image {name}, robot {rid}" if name else "nothing flashed yet"
        print(f"{r.link} -> {os.ttyname(r.port.slave)} ({what})", flush=True)
    pid_path = Path(args.dir) / PID_FILE
    if args.background:
        pid = os.fork()
        if pid:
            pid_path.write_text(f"{pid}\n")
            print(f"{PROG}: running in the background (pid {pid}; its messages in {Path(args.dir) / LOG_FILE}; "
                  f"stop it with: {PROG} stop --dir {args.dir})", flush=True)
            os._exit(0)
        os.setsid()
        out = os.open(Path(args.dir) / LOG_FILE, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        os.dup2(out, 1)
        os.dup2(out, 2)
        os.close(out)
        os.close(null)
    stop = threading.Event()
    why = []

    def on_signal(signum, _frame):
        why.append(signal.Signals(signum).name)
        stop.set()
    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)
    try:
        fakes.serve(args.duration, stop)
    finally:
        for r in fakes.robots:
            s = r.status()
            dev = "; ".join(s["deviations"]) or "none"
            print(f"{PROG}: {r.name}: {s['state']}, image {s['image']}, robot {s['robot_id']}, {s['steps']} steps, "
                  f"{s['bytes_out']} bytes sent, {s['bytes_lost']} lost; host link {s['host_link']}; "
                  f"flasher deviations: {dev}", file=sys.stderr, flush=True)
        for r in fakes.robots:
            r.power_off()
        if args.background and pid_path.is_file() and pid_path.read_text().strip() == str(os.getpid()):
            pid_path.unlink()
    print(f"{PROG}: stopped" + (f" by {why[0]}" if why else f" after --duration {args.duration:g} s"),
          file=sys.stderr, flush=True)
    return 0


def _hex(args) -> int:
    from .images import ImageError, declaration, stand_in_hex
    try:
        decl = declaration(args.image)
    except ImageError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    text = stand_in_hex(decl)
    if args.out == "-":
        sys.stdout.write(text)
        return 0
    out = Path(args.out or f"{args.image}.hex")
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(out.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, out)
    print(f"{PROG}: {out}: the stand-in image of {decl.describe()}", file=sys.stderr)
    return 0


def _images(args) -> int:
    from .images import ImageError, declarations
    try:
        for decl in declarations().values():
            print(decl.describe())
    except ImageError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    return 0


def _stop(args) -> int:
    pid_path = Path(args.dir) / PID_FILE
    try:
        pid = int(pid_path.read_text())
    except (OSError, ValueError):
        print(f"{PROG}: no fake robots run from {args.dir} (no {pid_path})", file=sys.stderr)
        return 1
    try:
        os.kill(pid, signal.SIGTERM)
    except ProcessLookupError:
        pid_path.unlink(missing_ok=True)
        print(f"{PROG}: process {pid} of {pid_path} is gone already", file=sys.stderr)
        return 0
    end = time.monotonic() + args.timeout
    while time.monotonic() < end:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            print(f"{PROG}: stopped the fake robots of {args.dir} (pid {pid})", file=sys.stderr)
            return 0
        time.sleep(0.05)
    print(f"{PROG}: process {pid} did not stop within {args.timeout:g} s", file=sys.stderr)
    return 1


def main(argv=None) -> int:
    from .runtime import PLATFORMS
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    sub = ap.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="start fake robots (until stopped, or --duration)")
    run.add_argument("--robots", type=int, default=1, help="how many (default %(default)s)")
    run.add_argument("--dir", default="out/fake-epuck", help="where their ports' links go (default %(default)s)")
    run.add_argument("--image", action="append", metavar="NAME",
                     help="robot k's program (k-th --image; 'none': nothing), as if flashed before")
    run.add_argument("--id", action="append", type=int, metavar="N",
                     help="robot k's id for its --image (k-th --id; default 0, 1, ...)")
    run.add_argument("--world", metavar="SCENARIO",
                     help="a scenario whose arena, objects and lights the robots run in (default: a 2 m square "
                          "with a lamp at its centre)")
    run.add_argument("--platform", choices=PLATFORMS, default="host",
                     help="what runs the image: its host build (default), or its ELF on an emulated "
                          "ATmega2560 (pil_avr) or Cortex-M4F (pil_m4): make pil-avr / pil-m4 builds them")
    run.add_argument("--shared-world", action="store_true",
                     help="robots 1.. are robots of robot 0's world (they see and hear each other), each on "
                          "its own port (default: each robot in a world of its own)")
    run.add_argument("--speed", type=float, default=1.0, help="simulated seconds per second (default 1: real time)")
    run.add_argument("--duration", type=float, default=0.0, help="stop after this many seconds (0: when stopped)")
    run.add_argument("--background", action="store_true",
                     help="once the ports exist, go on in the background (stop it with the stop command)")
    run.add_argument("--boot-fault", action="append", metavar="KEY=VALUE",
                     help="make the bootloaders misbehave: answer_after=N, silent, nak=P:N, stop_after=N, "
                          "noise=HEX, flood (repeatable)")
    run.add_argument("--quiet", action="store_true", help="no messages but errors and the last report")
    hx = sub.add_parser("hex", help="write an image's stand-in .hex (what `make firmware` builds with XC16)")
    hx.add_argument("image", help="an image of platforms/epuck1/images.list")
    hx.add_argument("-o", "--out", help="the file (default IMAGE.hex; '-': stdout)")
    sub.add_parser("images", help="list the images a fake robot runs")
    st = sub.add_parser("stop", help="stop fake robots started with --background")
    st.add_argument("--dir", default="out/fake-epuck", help="their --dir (default %(default)s)")
    st.add_argument("--timeout", type=float, default=10.0, help="seconds to wait for them to stop")
    args = ap.parse_args(argv)
    if args.command == "run":
        if args.robots < 1 or args.robots > 64:
            ap.error("--robots: 1 to 64")
        if args.speed <= 0 or args.duration < 0:
            ap.error("--speed must be > 0 and --duration >= 0")
        return _run(args)
    return {"hex": _hex, "images": _images, "stop": _stop}[args.command](args)


if __name__ == "__main__":
    sys.exit(main())
