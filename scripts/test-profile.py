#!/usr/bin/env python3
"""Where the test command's time goes (issue 46).

Reads ctest's JUnit files of the same suite run twice over one PoCL cache folder, first empty
(cold: every program compiled) and then filled (warm: every program loaded from the cache), and
prints per test group its cold and warm seconds and their difference, the time spent compiling
OpenCL programs; the totals; the groups that cost most; and, given the log of scripts/test.sh,
its stages. scripts/test-profile.sh makes the two runs and calls this.

Usage: test-profile.py COLD.xml WARM.xml [--log TEST_SH_LOG] [--top N] [--programs N]
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ElementTree


def case_times(path):
    """Seconds per test case (ctest test) of a JUnit file, and its failures."""
    root = ElementTree.parse(path).getroot()
    times, failed = {}, []
    for case in root.iter("testcase"):
        name = case.get("name")
        times[name] = float(case.get("time", "0"))
        if case.get("status") not in (None, "run") or case.find("failure") is not None:
            failed.append(name)
    return times, failed


def stage_times(log_path):
    """The 'test.sh: STAGE took N s' lines of a scripts/test.sh log, in order."""
    stages = []
    with open(log_path, encoding="utf-8", errors="replace") as log:
        for line in log:
            m = re.match(r"test\.sh: (.+) took (\d+) s", line.strip())
            if m:
                stages.append((m.group(1), int(m.group(2))))
    return stages


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cold")
    parser.add_argument("warm")
    parser.add_argument("--log", help="scripts/test.sh's output, for its stages")
    parser.add_argument("--top", type=int, default=25, help="groups to list (default 25)")
    parser.add_argument("--programs", type=int, help="programs the cold run compiled (for the average)")
    parser.add_argument("--wall", nargs=2, type=float, metavar=("COLD_S", "WARM_S"), help="the runs' wall times")
    args = parser.parse_args()

    cold, cold_failed = case_times(args.cold)
    warm, warm_failed = case_times(args.warm)
    for name, failed in (("cold", cold_failed), ("warm", warm_failed)):
        if failed:
            print(f"test-profile: the {name} run had failures: {', '.join(failed)}", file=sys.stderr)
    names = sorted(cold, key=lambda n: -cold[n])
    cold_total = sum(cold.values())
    warm_total = sum(warm.get(n, 0.0) for n in cold)
    compile_total = sum(max(cold[n] - warm.get(n, 0.0), 0.0) for n in cold)

    if args.log:
        stages = stage_times(args.log)
        print("| stage | s |\n|---|---|")
        for stage, seconds in stages:
            print(f"| {stage} | {seconds} |")
        print(f"| **total** | **{sum(s for _, s in stages)}** |\n")

    print(f"{len(cold)} test groups: {cold_total:.0f} s of test time cold, {warm_total:.0f} s warm; "
          f"compiling OpenCL programs {compile_total:.0f} s ({100 * compile_total / max(cold_total, 1e-9):.0f} % of the cold time)")
    if args.programs:
        print(f"{args.programs} programs compiled: {compile_total / args.programs:.2f} s each on average")
    if args.wall:
        print(f"wall: {args.wall[0]:.0f} s cold, {args.wall[1]:.0f} s warm")
    print(f"\n| group | cold s | warm s | compiling s |\n|---|---|---|---|")
    for name in names[: args.top]:
        w = warm.get(name, 0.0)
        print(f"| {name} | {cold[name]:.1f} | {w:.1f} | {max(cold[name] - w, 0.0):.1f} |")


if __name__ == "__main__":
    main()
