"""A real headless browser for the live view's tests: Debian's chromium,
driven through Debian's chromium-driver by Selenium.  Both programs are
named, so Selenium Manager never runs and nothing downloads a browser
(SE_OFFLINE says so too); `tools/make/browser.sh install` installs them.
Each browser gets a fresh profile folder, removed when it quits."""
import os
import shutil
import tempfile
from pathlib import Path

CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = Path("/usr/bin/chromedriver")


def missing():
    """Why no browser can run here, or None."""
    gone = [str(p) for p in (CHROMIUM, CHROMEDRIVER) if not os.access(p, os.X_OK)]
    if gone:
        return (f"{' and '.join(gone)} missing: install Debian's chromium and chromium-driver "
                f"(bash tools/make/browser.sh install, as root)")
    return None


class Browser:
    """A headless Chromium of its own profile; quit() ends it and removes the profile."""

    def __init__(self, width=1400, height=1000):
        why = missing()
        if why:
            raise AssertionError(why)
        os.environ["SE_OFFLINE"] = "true"         # Selenium Manager, if anything asked for it, stays offline
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service

        self.profile = tempfile.mkdtemp(prefix="live_test_chromium.")
        opts = webdriver.ChromeOptions()
        opts.binary_location = str(CHROMIUM)
        for arg in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                    "--disable-component-update", "--disable-sync", "--no-first-run",
                    "--disable-dev-shm-usage", f"--window-size={width},{height}",
                    "--force-device-scale-factor=1", f"--user-data-dir={self.profile}"):
            opts.add_argument(arg)
        service = Service(executable_path=str(CHROMEDRIVER), log_output=os.path.join(self.profile, "chromedriver.log"))
        try:
            self.driver = webdriver.Chrome(service=service, options=opts)
        except Exception as e:
            log = Path(self.profile, "chromedriver.log")
            tail = log.read_text(errors="replace")[-2000:] if log.exists() else ""
            shutil.rmtree(self.profile, ignore_errors=True)
            raise AssertionError(f"headless chromium did not start: {e}\n{tail}") from None

    def quit(self):
        try:
            self.driver.quit()
        finally:
            shutil.rmtree(self.profile, ignore_errors=True)
