"""`clmarch preview` and its page in headless Chromium (Selenium), for the PreviewBrowser test and
scripts/preview-bench.py --browser: starts the server on a free port, opens the page, waits for its
frames and reads the pixels the page shows back through a canvas."""

import base64
import os
import pathlib
import re
import shutil
import subprocess
import time

import numpy as np
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

CLMARCH = os.environ.get("CLMARCH_EXECUTABLE", str(pathlib.Path(__file__).parents[2] / "build" / "clmarch"))
CHROMIUM = os.environ.get("CLMARCH_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
CHROMEDRIVER = os.environ.get("CLMARCH_CHROMEDRIVER") or shutil.which("chromedriver") or "/usr/bin/chromedriver"


class PreviewServer:
    """`clmarch preview SCENE --port 0`, stopped with Ctrl-C (SIGINT) on close()."""

    def __init__(self, scene, clmarch=CLMARCH, extra=()):
        self.process = subprocess.Popen([clmarch, "preview", str(scene), "--port", "0", *extra],
                                        stderr=subprocess.PIPE, text=True)
        line = self.process.stderr.readline()
        found = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        if not found:
            self.process.kill()
            raise RuntimeError(f"clmarch preview did not start: {line}{self.process.stderr.read()}")
        self.port = int(found.group(1))
        self.url = f"http://127.0.0.1:{self.port}/"

    def close(self):
        if self.process.poll() is None:
            self.process.send_signal(2)
            self.process.wait(timeout=30)
        return self.process.returncode


def chromium(width=900, height=600):
    """Headless Chromium. --no-sandbox: the tests run as root, where Chromium's sandbox refuses to
    start; the page only ever talks to the local preview."""
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--disable-extensions", "--no-first-run", "--force-device-scale-factor=1",
                 f"--window-size={width},{height}"):
        options.add_argument(flag)
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)


# The frame the page shows, once its picture has loaded: size, whether coarse, the figures' text.
SHOWN = """
const img = document.getElementById("frame"), stats = document.getElementById("stats").textContent;
return {complete: img.complete && img.naturalWidth > 0, width: img.naturalWidth, height: img.naturalHeight,
        src: img.src, stats: stats, error: document.getElementById("error").textContent,
        camera: typeof cam === "undefined" ? null : cam, seq: seq};
"""

# The pixels of the shown picture as the browser decoded them, RGBA rows from the top.
PIXELS = """
const img = document.getElementById("frame");
const canvas = document.createElement("canvas");
canvas.width = img.naturalWidth; canvas.height = img.naturalHeight;
const g = canvas.getContext("2d", {willReadFrequently: true});
g.drawImage(img, 0, 0);
const data = g.getImageData(0, 0, canvas.width, canvas.height).data;
let text = "";
for (let i = 0; i < data.length; i += 8192) text += String.fromCharCode.apply(null, data.subarray(i, i + 8192));
return btoa(text);
"""


class Page:
    """The preview's page in a browser."""

    def __init__(self, driver, url):
        self.driver = driver
        driver.get(url)

    def shown(self):
        return self.driver.execute_script(SHOWN)

    def wait(self, condition, timeout, what):
        """Polls the shown frame until condition(shown) holds; returns it and the seconds taken."""
        start = time.perf_counter()
        while True:
            shown = self.shown()
            if condition(shown):
                return shown, time.perf_counter() - start
            if time.perf_counter() - start > timeout:
                raise AssertionError(f"{what}: not within {timeout} s; the page shows {shown}")
            time.sleep(0.01)

    def wait_full(self, size, timeout, what, unlike=None):
        """Waits for a full frame of size (w, h) whose picture has loaded (and whose src differs
        from unlike's, when given)."""
        w, h = size
        return self.wait(lambda s: s["complete"] and (s["width"], s["height"]) == (w, h)
                         and s["stats"].startswith(f"{w}x{h} ") and "(coarse)" not in s["stats"]
                         and (unlike is None or s["src"] != unlike["src"]), timeout, what)

    def pixels(self):
        """The shown picture's pixels, rows × columns × RGB (the canvas's alpha dropped)."""
        shown = self.shown()
        rgba = np.frombuffer(base64.b64decode(self.driver.execute_script(PIXELS)), dtype=np.uint8)
        return rgba.reshape(shown["height"], shown["width"], 4)[:, :, :3]
