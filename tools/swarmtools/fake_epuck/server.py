"""Several fake e-pucks in one process: one event loop over their ports and
clocks (select), in the calling thread (serve) or a thread of its own
(start / stop: the tests' way).

    with FakeEpucks(2, "out/fake", images=["forager", "phototaxis"], ids=[7, 8]) as fakes:
        ...  # out/fake/rfcomm0, out/fake/rfcomm1 behave like two e-puck1s
"""

from __future__ import annotations

import os
import select
import sys
import threading
import time
from pathlib import Path

from .bootloader import Faults
from .robot import FakeRobot


class FakeEpucks:
    """`count` fake robots with links DIR/rfcomm0 .. DIR/rfcomm<count-1>.

    images  image per robot already in its program memory (None: nothing
            flashed yet), as if flashed with ids[k] before power-on
    faults  Faults (or a list of one per robot) for their bootloaders
    world   a scenario file whose arena, objects and lights the robots run in
    speed   simulated time per wall second (1: real time)
    platform  what runs each image: "host" (its host build), "pil_avr" or
            "pil_m4" (its ELF on an emulated MCU: runtime.py)
    shared_world  robots 1.. are robots of robot 0's world (the next ones
            running their images' controllers), each on its own port: two
            e-pucks that see and hear each other (robot 0 starts first)
    """

    def __init__(self, count: int = 1, directory: str | os.PathLike = "out/fake-epuck", images=None, ids=None,
                 faults=None, world: str | None = None, speed: float = 1.0, reset_on_handshake: bool = True,
                 log=None, platform: str = "host", shared_world: bool = False):
        if count < 1:
            raise ValueError("at least one robot")
        self.dir = Path(directory)
        self.dir.mkdir(parents=True, exist_ok=True)
        images = list(images or [])
        ids = list(ids) if ids is not None else list(range(count))
        if len(images) > count or len(ids) != count:
            raise ValueError(f"{count} robots: at most {count} images and exactly {count} ids")
        faults = faults if isinstance(faults, list) else [faults or Faults() for _ in range(count)]
        self.robots = [FakeRobot(f"rfcomm{k}", str(self.dir / f"rfcomm{k}"), faults=faults[k], world=world,
                                 speed=speed, reset_on_handshake=reset_on_handshake, log=log,
                                 platform=platform)
                       for k in range(count)]
        if shared_world:
            for r in self.robots[1:]:
                r.shares = self.robots[0]
        for k, name in enumerate(images):
            if name:
                self.robots[k].load_image(name, ids[k])
        self._stop = threading.Event()
        self._thread = None
        self._lock = threading.Lock()
        self.error = None

    @property
    def links(self) -> list[str]:
        return [r.link for r in self.robots]

    def power_on(self):
        now = time.monotonic()
        for r in self.robots:
            r.power_on(now)

    def serve(self, duration: float | None = None, stop: threading.Event | None = None):
        """Runs the robots until `duration` s passed or `stop` is set."""
        stop = stop or self._stop
        end = None if not duration else time.monotonic() + duration
        while not stop.is_set():
            now = time.monotonic()
            if end is not None and now >= end:
                break
            with self._lock:
                for r in self.robots:
                    if r.state != "off":
                        r.tick(now)
                fds = {r.port.master: r for r in self.robots if r.port.master >= 0}
                deadlines = [d for r in self.robots if r.state != "off" and (d := r.deadline(now)) is not None]
            wait = 0.1 if not deadlines else max(0.0, min(deadlines) - time.monotonic())
            if end is not None:
                wait = min(wait, max(0.0, end - time.monotonic()))
            try:
                ready, _, _ = select.select(list(fds), [], [], min(wait, 0.1))
            except (OSError, ValueError):         # a port closed under us (a test's disconnect)
                continue
            now = time.monotonic()
            with self._lock:
                for fd in ready:
                    r = fds[fd]
                    if r.port.master == fd:
                        r.readable(now)

    def start(self):
        """Powers the robots on and serves them in a thread."""
        self.power_on()
        self._stop.clear()

        def loop():
            try:
                self.serve()
            except BaseException as e:            # a test sees it in stop()
                self.error = e
                raise
        self._thread = threading.Thread(target=loop, name="fake-epucks", daemon=True)
        self._thread.start()
        return self

    def stop(self):
        self._stop.set()
        if self._thread is not None:
            self._thread.join(10)
            self._thread = None
        for r in self.robots:
            r.power_off()
        if self.error is not None:
            raise RuntimeError(f"the fake robots' loop failed: {self.error!r}") from self.error

    def locked(self):
        """The lock the loop holds while it touches the robots (a test that
        reads or changes a robot between events takes it)."""
        return self._lock

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


def log_to_stderr(prog: str):
    def log(text: str):
        print(f"{prog}: {text}", file=sys.stderr, flush=True)
    return log


__all__ = ["FakeEpucks", "log_to_stderr"]
