#!/usr/bin/env python3
"""Measures `clmarch preview` against issue 43's targets (docs/performance.md, Preview):
  - a camera move to its first coarse frame (target ≤ 150 ms): over HTTP as the page asks for it,
    and with --browser in headless Chromium, from a synthetic drag to the new picture's load event;
  - 300 camera moves in 15 s: the server's resident memory before and after (target flat, ± 10 %),
    every request answered (200, or 409 for one a newer request overtook), and the last picture
    equal to `clmarch render` of the last camera.
A baseline from the same run gives the numbers their scale on a shared machine: `clmarch bench`'s
kernel time of the same full and coarse frames.

Usage: scripts/preview-bench.py SCENE [--clmarch build/clmarch] [--moves 300] [--seconds 15]
                                [--browser] [--screenshots DIR]
Prints one JSON line. Run it with Debian's /usr/bin/python3 (python3-selenium, python3-openimageio;
scripts/setup.sh). --screenshots writes the page (shaded, then the steps view) into DIR."""

import argparse
import json
import math
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

import numpy as np
import OpenImageIO as oiio

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "preview_browser"))
from preview_browser import Page, PreviewServer, chromium  # noqa: E402


def resident_kib(pid):
    with open(f"/proc/{pid}/status") as status:
        return int(re.search(r"VmRSS:\s+(\d+)", status.read()).group(1))


def fetch(url):
    try:
        with urllib.request.urlopen(url, timeout=120) as response:
            return response.status, response.read(), response.headers
    except urllib.error.HTTPError as error:
        return error.code, error.read(), error.headers


def decode_png(data, path):
    path.write_bytes(data)
    return read_png(path)


def read_png(path):
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    pixels = np.asarray(image.read_image(0, 0, 0, 3, oiio.UINT8), dtype=np.uint8).reshape(spec.height, spec.width, 3)
    image.close()
    return pixels


def camera_sets(camera):
    vec = lambda v: "[" + ",".join(repr(float(x)) for x in v) + "]"  # noqa: E731
    return ["--set", f"camera.position={vec(camera['position'])}", "--set", f"camera.look_at={vec(camera['look_at'])}",
            "--set", f"camera.up={vec(camera['up'])}", "--set", f"camera.fov={float(camera['fov'])!r}"]


def render(args, out, camera):
    """`clmarch render` of the scene at a camera: its pixels."""
    subprocess.run([args.clmarch, "render", args.scene, "-o", str(out), *camera_sets(camera)],
                   capture_output=True, text=True, check=True)
    return read_png(out)


def orbit_camera(camera, angle):
    look, pos = camera["look_at"], camera["position"]
    radius = math.hypot(pos[0] - look[0], pos[2] - look[2])
    start = math.atan2(pos[0] - look[0], pos[2] - look[2])
    return {"position": [look[0] + radius * math.sin(start + angle), pos[1], look[2] + radius * math.cos(start + angle)],
            "look_at": look, "up": camera["up"], "fov": camera["fov"]}


def camera_query(c):
    j = lambda v: ",".join(repr(float(x)) for x in v)  # noqa: E731
    return f"&pos={j(c['position'])}&look={j(c['look_at'])}&up={j(c['up'])}&fov={float(c['fov'])!r}"


def http_bench(args, server, home, work):
    """The page's requests over HTTP from this script."""
    base = server.url.rstrip("/")
    seq = 0
    start = time.perf_counter()
    seq += 1
    fetch(f"{base}/frame?seq={seq}&coarse=0" + camera_query(home))
    first_full_s = time.perf_counter() - start
    seq += 1
    fetch(f"{base}/frame?seq={seq}&coarse=1" + camera_query(home))
    latencies, kernel_ms = [], []
    for k in range(30):
        seq += 1
        t0 = time.perf_counter()
        status, _, headers = fetch(f"{base}/frame?seq={seq}&coarse=1" + camera_query(orbit_camera(home, 0.05 * (k + 1))))
        latencies.append(1000 * (time.perf_counter() - t0))
        kernel_ms.append(json.loads(headers["X-Clmarch-Stats"])["kernel_ms"])
    # 300 moves in 15 s at a steady pace, each its own request from one of four threads as a page's
    # overlapping requests would be; the last move asks for the full frame.
    rss_before = resident_kib(server.process.pid)
    statuses, lock = [], threading.Lock()
    last = {}

    def move(k, number):
        camera = orbit_camera(home, 0.01 * k)
        coarse = 0 if k == args.moves - 1 else 1
        status, body, _ = fetch(f"{base}/frame?seq={number}&coarse={coarse}" + camera_query(camera))
        with lock:
            statuses.append(status)
            if k == args.moves - 1:
                last.update(status=status, body=body, camera=camera)

    threads = []
    t0 = time.perf_counter()
    interval = args.seconds / args.moves
    for k in range(args.moves):
        seq += 1
        thread = threading.Thread(target=move, args=(k, seq))
        thread.start()
        threads.append(thread)
        time.sleep(max(0.0, t0 + (k + 1) * interval - time.perf_counter()))
    for thread in threads:
        thread.join()
    moves_s = time.perf_counter() - t0
    rss_after = resident_kib(server.process.pid)
    reference = render(args, work / "last_ref.png", last["camera"])
    shown = decode_png(last["body"], work / "last.png") if last["status"] == 200 else None
    return {
        "first_full_frame_s": round(first_full_s, 3),
        "coarse_move_ms_median": round(statistics.median(latencies), 1),
        "coarse_move_ms_max": round(max(latencies), 1),
        "coarse_kernel_ms_median": round(statistics.median(kernel_ms), 1),
        "moves": args.moves, "moves_s": round(moves_s, 2),
        "answered": sum(s in (200, 409) for s in statuses), "rendered": statuses.count(200),
        "superseded": statuses.count(409),
        "rss_kib_before": rss_before, "rss_kib_after": rss_after, "rss_change": round(rss_after / rss_before - 1, 3),
        "last_is_last_camera": shown is not None and bool(np.array_equal(shown, reference)),
    }


# A synthetic drag on the picture; resolves with the milliseconds from the move to the load event
# of the next coarse picture and to the paint after it.
DRAG = """
const done = arguments[arguments.length - 1], dx = arguments[0];
const img = document.getElementById("frame"), stats = document.getElementById("stats");
const r = img.getBoundingClientRect(), x = r.left + r.width / 2, y = r.top + r.height / 2;
img.dispatchEvent(new MouseEvent("mousedown", {clientX: x, clientY: y, button: 0, bubbles: true}));
const onload = () => {
  if (!stats.textContent.includes("(coarse)")) return;
  const loaded = performance.now();
  img.removeEventListener("load", onload);
  requestAnimationFrame(() => requestAnimationFrame(() => done({load: loaded - t0, paint: performance.now() - t0})));
};
img.addEventListener("load", onload);
const t0 = performance.now();
window.dispatchEvent(new MouseEvent("mousemove", {clientX: x + dx, clientY: y, bubbles: true}));
window.dispatchEvent(new MouseEvent("mouseup", {clientX: x + dx, clientY: y, bubbles: true}));
"""

# Moves at a steady pace from the page itself, counting its requests and their answers.
MOVES = """
const done = arguments[arguments.length - 1], moves = arguments[0], interval = arguments[1];
const counts = {asked: 0, answered: 0, statuses: {}};
const realFetch = window.fetch;
window.fetch = async url => {
  if (!String(url).startsWith("/frame")) return realFetch(url);
  counts.asked++;
  const response = await realFetch(url);
  counts.answered++; counts.statuses[response.status] = (counts.statuses[response.status] || 0) + 1;
  return response;
};
const img = document.getElementById("frame");
const r = img.getBoundingClientRect(), x = r.left + r.width / 2, y = r.top + r.height / 2;
img.dispatchEvent(new MouseEvent("mousedown", {clientX: x, clientY: y, button: 0, bubbles: true}));
let k = 0;
const start = performance.now();
const step = () => {
  k++;
  window.dispatchEvent(new MouseEvent("mousemove", {clientX: x + (k % 2 ? 3 : 0), clientY: y + k % 3, bubbles: true}));
  if (k < moves) return setTimeout(step, Math.max(0, start + (k + 1) * interval - performance.now()));
  window.dispatchEvent(new MouseEvent("mouseup", {clientX: x, clientY: y, bubbles: true}));
  counts.seconds = (performance.now() - start) / 1000;
  const settle = () => (counts.answered === counts.asked ? done(counts) : setTimeout(settle, 20));
  setTimeout(settle, 400);
};
setTimeout(step, interval);
"""


def browser_bench(args, server, state, work):
    size = (state["width"], state["height"])
    driver = chromium(980, 540)
    try:
        page = Page(driver, server.url)
        page.wait_full(size, 120, "the first full frame")
        if args.screenshots:
            folder = pathlib.Path(args.screenshots)
            name = pathlib.Path(args.scene).stem
            driver.save_screenshot(str(folder / f"preview_{name}.png"))
        loads, paints = [], []
        for k in range(30):
            before = page.shown()
            result = driver.execute_async_script(DRAG, 4 if k % 2 else -4)
            loads.append(result["load"])
            paints.append(result["paint"])
            page.wait_full(size, 60, "the full frame after a drag", unlike=before)
        rss_before = resident_kib(server.process.pid)
        driver.set_script_timeout(args.seconds * 4 + 60)
        counts = driver.execute_async_script(MOVES, args.moves, 1000 * args.seconds / args.moves)
        shown, _ = page.wait_full(size, 60, "the full frame after the moves")
        time.sleep(0.5)
        shown, _ = page.wait_full(size, 60, "the full frame after the moves")
        rss_after = resident_kib(server.process.pid)
        reference = render(args, work / "browser_last_ref.png", shown["camera"])
        last_ok = bool(np.array_equal(page.pixels(), reference))
        if args.screenshots:
            from selenium.webdriver.common.by import By
            from selenium.webdriver.support.ui import Select

            before = page.shown()
            Select(driver.find_element(By.ID, "views")).select_by_visible_text("steps")
            page.wait_full(size, 60, "the steps view", unlike=before)
            driver.save_screenshot(str(pathlib.Path(args.screenshots) / f"preview_{pathlib.Path(args.scene).stem}_steps.png"))
        return {
            "browser_drag_to_coarse_load_ms_median": round(statistics.median(loads), 1),
            "browser_drag_to_coarse_load_ms_max": round(max(loads), 1),
            "browser_drag_to_paint_ms_median": round(statistics.median(paints), 1),
            "browser_moves": args.moves, "browser_moves_s": round(counts["seconds"], 2),
            "browser_requests": counts["asked"], "browser_answered": counts["answered"],
            "browser_statuses": counts["statuses"],
            "browser_rss_kib_before": rss_before, "browser_rss_kib_after": rss_after,
            "browser_rss_change": round(rss_after / rss_before - 1, 3),
            "browser_last_is_last_camera": last_ok,
        }
    finally:
        driver.quit()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene")
    parser.add_argument("--clmarch", default="build/clmarch")
    parser.add_argument("--moves", type=int, default=300)
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--browser", action="store_true", help="also measure in headless Chromium")
    parser.add_argument("--screenshots", help="folder for screenshots of the page (with --browser)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        work = pathlib.Path(folder)
        server = PreviewServer(args.scene, args.clmarch)
        try:
            state = json.loads(fetch(server.url + "state")[1])
            home = state["camera"]
            result = {"scene": args.scene, "size": [state["width"], state["height"]]}
            result.update(http_bench(args, server, home, work))
            if args.browser:
                result.update(browser_bench(args, server, state, work))
            last = json.loads(fetch(server.url + "state")[1])["stats"]
            result.update(programs_built=last.get("programs_built"), device=last.get("device"))
        finally:
            server.close()
        # The baseline, in the same run: the kernel of the same frames, full and coarse, as
        # `clmarch bench` times it (median of 9 runs after a warm-up; the scene's own camera).
        w, h = state["width"], state["height"]
        for name, extra in (("full", []), ("coarse", ["--size", f"{max(1, w // 4)}x{max(1, h // 4)}", "--samples", "1"])):
            bench = subprocess.run([args.clmarch, "bench", args.scene, "--no-reference", "--repeat", "9", "--json", *extra],
                                   capture_output=True, text=True, check=True)
            result[f"bench_{name}_kernel_ms"] = round(json.loads(bench.stdout)["kernel_ms"], 2)
    print(json.dumps(result))


if __name__ == "__main__":
    sys.exit(main())
