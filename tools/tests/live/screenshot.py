"""The docs' picture of the live view, taken by the tests' headless
browser (make live-figure):

    .venv/bin/python -m tools.tests.live.screenshot LOG OUT.png [--at SECONDS]

Serves LOG with swarm-live, seeks the page to --at, and saves the window as
a PNG (palette-quantised with Pillow so it stays small)."""
import argparse
import io
import sys
import time

from PIL import Image

from .browser import Browser
from .serve import Server, wait_for


def main(argv=None):
    ap = argparse.ArgumentParser(prog="screenshot", description=__doc__.split("\n\n")[0])
    ap.add_argument("log")
    ap.add_argument("out")
    ap.add_argument("--at", type=float, default=60.0, help="the log time shown, s")
    ap.add_argument("--size", default="1400x860", help="window, WIDTHxHEIGHT pixels")
    args = ap.parse_args(argv)
    width, height = (int(v) for v in args.size.split("x"))
    server = Server("--log", args.log, "--paused")
    browser = Browser(width, height)
    try:
        d = browser.driver
        d.get(server.url)
        wait_for(lambda: d.execute_script("return window.liveState.frames") > 0, "the page")
        d.execute_script("const s = document.getElementById('seek'); s.value = arguments[0];"
                         "s.dispatchEvent(new Event('change'));", str(args.at))
        wait_for(lambda: d.execute_script("return window.liveState.time") == args.at, f"t = {args.at} s")
        time.sleep(0.5)                                     # the charts' next redraw
        png = Image.open(io.BytesIO(d.get_screenshot_as_png())).convert("RGB")
        png.quantize(colors=128, method=Image.Quantize.MEDIANCUT).save(args.out, optimize=True)
    finally:
        browser.quit()
        server.stop()
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
