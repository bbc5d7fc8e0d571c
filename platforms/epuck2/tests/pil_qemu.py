#!/usr/bin/env python3
"""pil_qemu.py - e-puck2 images on QEMU's netduinoplus2 (the e-puck2's
Cortex-M4F core, an STM32F405): each image's ELF (make epuck2-pil: our
code with the e-puck2's flags over the library's stubs and the emulator's
glue, tests/qemu/epuck2_qemu_os.c) runs for 3 s of emulated time; what its
UART sends goes through the serial bridge (swarmtools.telemetry.bridge, as
a robot's rfcomm port would) and the LCM types.  Checks: QEMU stops by
itself (the image's semihosting exit), the bridge counts no garbage, CRC
error, bad payload or lost frame and takes the frame's robot id (5), the
controller's schema comes (whole for the small ones), the robot_state_t messages name the
image's controller and the robot (5), their times advance one control period
at a time; the image with the host link is sent POSE frames on its UART and
must report the pose.  A hang is caught by a generous timeout.

usage: pil_qemu.py --elf-dir build/firmware/epuck2/pil IMAGE ...
"""
import argparse
import concurrent.futures
import os
import subprocess
import sys
import threading

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'tools'))
from swarmtools.plan import routes  # noqa: E402
from swarmtools.telemetry import bridge, common, host_link  # noqa: E402

ROBOT = 5
TIMEOUT_S = 120   # only a hang reaches it: a run is 3 s of emulated time
PERIOD_MS = {'waypoint': 25}
CONTROLLER = {'phototaxis': 'phototaxis', 'forager': 'forager', 'waypoint': 'waypoint'}
HOST_LINK = {'waypoint'}
SCHEMA_WHOLE = {'phototaxis', 'waypoint'}


def run(elf, host_bytes):
    """Runs `elf` until it stops QEMU; `host_bytes` go to its UART once its
    first telemetry frame has come out (bytes sent before the image has
    enabled its USART would be dropped by the emulated USART).  Returns
    (exit code, the UART's bytes, stderr)."""
    proc = subprocess.Popen(['qemu-system-arm', '-M', 'netduinoplus2', '-nodefaults', '-display', 'none',
                             '-monitor', 'none', '-serial', 'stdio',
                             '-semihosting-config', 'enable=on,target=native', '-kernel', elf],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out = bytearray()
    up = threading.Event()

    def read():
        while True:
            chunk = proc.stdout.read1(4096)
            if not chunk:
                up.set()
                return
            out.extend(chunk)
            if out.count(0) >= 2:
                up.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        up.wait(TIMEOUT_S)
        if host_bytes and proc.poll() is None:
            proc.stdin.write(host_bytes)
            proc.stdin.flush()
        proc.wait(TIMEOUT_S)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        raise
    finally:
        try:
            proc.stdin.close()
        except BrokenPipeError:
            pass
    reader.join(TIMEOUT_S)
    return proc.returncode, bytes(out), proc.stderr.read().decode(errors='replace')


def check(image, elf, failures):
    def fail(what):
        failures.append(f'{image}: {what}')

    stdin = b''
    if image in HOST_LINK:
        route = routes.route_message([(0.5, 0.2), (1.0, -0.3)], (0.0, 0.0))
        stdin = host_link.encode_host_msg(ROBOT, 0, route)
        stdin += b''.join(host_link.encode_pose(ROBOT, 1 + k, 1000 + k, -2000, 1571) for k in range(40))
    try:
        rc, out, err = run(elf, stdin)
    except subprocess.TimeoutExpired:
        fail(f'QEMU still running after {TIMEOUT_S} s')
        return None
    if rc != 0:
        fail(f'QEMU exited {rc}: {err.strip()[:300]}')
    # Through the serial bridge, as a robot's rfcomm port would be: it
    # republishes what the telemetry tools read.
    published = []
    dev = bridge.Device(image)
    bridge.Bridge([dev], lambda channel, data: published.append((channel, common.decode(data, channel)))).feed(dev, out)
    states = [m for ch, m in published if ch == 'ROBOT_STATE']
    book = common.Schemas()
    for ch, m in published:
        if ch == 'TELEMETRY_SCHEMA':
            book.add(m)
    counts = dev.counters()
    bad = {k: v for k, v in counts.items() if k not in ('bytes', 'frames') and v}
    if bad:
        fail(f'the bridge counted {bad}')
    if dev.robot_id != ROBOT:
        fail(f'the bridge took the robot for {dev.robot_id}')
    if len(states) < 3:
        fail(f'{len(states)} robot_state_t messages in 3 s')
    # The schema comes three entries a frame between the states: whole in
    # 3 s for a controller of a few observables; the forager's needs longer,
    # and its first pieces are checked.
    schema = book.get('controller', CONTROLLER[image], 0)
    names = schema.names() if schema is not None and schema.complete else []
    if image in SCHEMA_WHOLE and not names:
        fail(f'the schema of {CONTROLLER[image]} did not come whole in 3 s')
    if not any(ch == 'TELEMETRY_SCHEMA' and m.name == CONTROLLER[image] for ch, m in published):
        fail(f'no schema piece of {CONTROLLER[image]}')
    period = PERIOD_MS.get(image, 100)
    times = [m.utime // 1000 for m in states]
    if any(t % period for t in times) or any(b <= a for a, b in zip(times, times[1:], strict=False)):
        fail(f'times not whole, rising periods of {period} ms: {times[:8]}...')
    if any(m.controller != CONTROLLER[image] or m.robot_id != ROBOT for m in states):
        fail('a robot_state_t of another controller or robot')
    index = {v: k for k, v in enumerate(names)}

    def value(m, key):
        return m.values[index[key]] if key in index and index[key] < m.n_values else None

    if image in HOST_LINK:
        last = states[-1] if states else None
        if last is None or value(last, 'routes') != 1.0 or value(last, 'route_n') != 2.0:
            fail('the route sent to its UART is not in its telemetry (routes, route_n: '
                 f'{last and value(last, "routes")}, {last and value(last, "route_n")})')
        if not any(value(m, 'pose_ok') == 1.0 for m in states):
            fail('the POSE frames sent to its UART never gave it a fresh pose (pose_ok)')
    schema_text = f'schema of {len(names)} values' if names else 'schema in part'
    host_text = (f', route taken, pose_ok in {sum(1 for m in states if value(m, "pose_ok") == 1.0)}'
                 if image in HOST_LINK else '')
    span = f'{times[0]}..{times[-1]} ms' if times else 'no times'
    return (f'{image}: {len(out)} bytes from its UART, {counts["frames"]} frames republished by the bridge, '
            f'{len(states)} robot_state_t, {schema_text} ({span}, period {period} ms){host_text}')

def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--elf-dir', required=True)
    ap.add_argument('images', nargs='+')
    args = ap.parse_args()
    failures = []
    for image in args.images:
        if image not in CONTROLLER:
            sys.exit(f'pil_qemu.py: no expectations for image {image!r} (known: {", ".join(CONTROLLER)})')
    # One QEMU per image, side by side: each run is 3 s of the host's clock
    # (the emulated core sleeps in wfi between its steps).
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(args.images)) as ex:
        lines = list(ex.map(lambda im: check(im, os.path.join(args.elf_dir, im + '.elf'), failures), args.images))
    for line in lines:
        if line:
            print(line)
    for f in failures:
        print('FAIL ' + f)
    print(f'e-puck2 on the emulated Cortex-M4F: {len(args.images) - len({f.split(":")[0] for f in failures})} '
          f'of {len(args.images)} images pass')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
