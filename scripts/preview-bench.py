#!/usr/bin/env python3
"""Times `clmarch preview` as the page uses it (issue 43's targets): a camera move to its first
coarse frame, and 300 camera moves in 15 s with the server's resident memory before and after.

Usage: scripts/preview-bench.py SCENE [--clmarch build/clmarch] [--moves 300] [--seconds 15]
Prints one JSON line. The server runs on a free port of 127.0.0.1; nothing else is needed."""

import argparse
import json
import math
import re
import statistics
import subprocess
import sys
import time
import urllib.error
import urllib.request


def resident_kib(pid):
    with open(f"/proc/{pid}/status") as status:
        return int(re.search(r"VmRSS:\s+(\d+)", status.read()).group(1))


def fetch(url):
    with urllib.request.urlopen(url, timeout=120) as response:
        return response.status, response.read()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene")
    parser.add_argument("--clmarch", default="build/clmarch")
    parser.add_argument("--moves", type=int, default=300)
    parser.add_argument("--seconds", type=float, default=15.0)
    args = parser.parse_args()
    server = subprocess.Popen([args.clmarch, "preview", args.scene, "--port", "0"], stderr=subprocess.PIPE, text=True)
    try:
        line = server.stderr.readline()
        port = int(re.search(r"http://127\.0\.0\.1:(\d+)/", line).group(1))
        base = f"http://127.0.0.1:{port}"
        state = json.loads(fetch(base + "/state")[1])
        cam = state["camera"]
        look, pos = cam["look_at"], cam["position"]
        radius = math.dist(pos, look)

        def camera_at(angle):
            p = [look[0] + radius * math.sin(angle), pos[1], look[2] + radius * math.cos(angle)]
            return (f"&pos={p[0]},{p[1]},{p[2]}&look={look[0]},{look[1]},{look[2]}"
                    f"&up={cam['up'][0]},{cam['up'][1]},{cam['up'][2]}&fov={cam['fov']}")

        seq = 0
        start = time.perf_counter()
        seq += 1
        fetch(f"{base}/frame?seq={seq}&coarse=0" + camera_at(0.0))
        first_full_s = time.perf_counter() - start
        latencies = []
        for k in range(30):
            seq += 1
            t0 = time.perf_counter()
            fetch(f"{base}/frame?seq={seq}&coarse=1" + camera_at(0.05 * (k + 1)))
            latencies.append(1000 * (time.perf_counter() - t0))
        rss_before = resident_kib(server.pid)
        answered = 0
        t0 = time.perf_counter()
        interval = args.seconds / args.moves
        for k in range(args.moves):
            seq += 1
            status, _ = fetch(f"{base}/frame?seq={seq}&coarse={k % 2}" + camera_at(0.01 * k))
            answered += status == 200
            time.sleep(max(0.0, t0 + (k + 1) * interval - time.perf_counter()))
        moves_s = time.perf_counter() - t0
        rss_after = resident_kib(server.pid)
        last = json.loads(fetch(base + "/state")[1])["stats"]
        print(json.dumps({
            "scene": args.scene, "first_full_frame_s": round(first_full_s, 3),
            "coarse_move_ms_median": round(statistics.median(latencies), 1),
            "coarse_move_ms_max": round(max(latencies), 1),
            "moves": args.moves, "answered": answered, "moves_s": round(moves_s, 2),
            "rss_kib_before": rss_before, "rss_kib_after": rss_after,
            "rss_change": round(rss_after / rss_before - 1, 3),
            "programs_built": last.get("programs_built"), "device": last.get("device")}))
    finally:
        server.send_signal(2)
        server.wait(timeout=30)


if __name__ == "__main__":
    sys.exit(main())
