#!/usr/bin/env python3
"""Line coverage of host/ from a coverage build's per-group counts (issue 46).

scripts/coverage.sh runs the suite in build-coverage/, where each test group (a process) writes its
gcov counts into a folder of its own (build-coverage/coverage-groups/GROUP, through GCOV_PREFIX).
This reads each group's counts with gcov, then prints the whole suite's line coverage per file of
host/, the total and the files under 70 %; with --sanitized, how much of what the whole suite runs
the sanitizer stage's suites run (scripts/test.sh's sanitized_suites), and for each group the lines
no group of that set (but itself) runs, with its time, to choose the stage by.

Usage: coverage-report.py [--build build-coverage] [--sanitized "SuiteA SuiteB ..."]
                          [--costs JUNIT.xml] [--threshold 70]
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def group_lines(group_dir):
    """{source: (executable lines, covered lines)} of host/ for one group's counts."""
    cached = os.path.join(group_dir, "host-lines.json")
    if not os.path.exists(cached):
        counts = [gcda for gcda in glob.glob(os.path.join(group_dir, "**", "clmarch_core.dir", "**", "*.gcda"),
                                             recursive=True)]
        # gcov wants each object's notes file (.gcno) beside its counts (.gcda): link them in.
        for gcda in counts:
            target = gcda[: -len(".gcda")] + ".gcno"
            notes = os.path.join("/", os.path.relpath(target, group_dir))
            if os.path.exists(notes) and not os.path.exists(target):
                os.link(notes, target)
        # One gcov for all of a group's objects: a gcov (or gcovr) per object took ten times longer.
        output = subprocess.run(["gcov", "--json-format", "--stdout", *counts], cwd=group_dir, check=True,
                                capture_output=True, text=True).stdout
        host = os.path.join(ROOT, "host") + "/"
        lines = {}
        for record in output.splitlines():
            for entry in json.loads(record)["files"]:
                if not entry["file"].startswith(host):
                    continue
                source = os.path.relpath(entry["file"], ROOT)
                executable, covered = lines.setdefault(source, [[], []])
                for line in entry["lines"]:
                    executable.append(line["line_number"])
                    if line["count"] > 0:
                        covered.append(line["line_number"])
        with open(cached, "w", encoding="utf-8") as f:
            json.dump(lines, f)
    with open(cached, encoding="utf-8") as f:
        return {source: (set(ex), set(cov)) for source, (ex, cov) in json.load(f).items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build-coverage"))
    parser.add_argument("--sanitized", help="the sanitizer stage's suites, space-separated (scripts/test.sh)")
    parser.add_argument("--costs", help="a JUnit file of ctest (the groups' seconds, e.g. of the sanitizer stage)")
    parser.add_argument("--threshold", type=float, default=70.0)
    args = parser.parse_args()

    groups_root = os.path.abspath(os.path.join(args.build, "coverage-groups"))
    folders = sorted(d for d in os.listdir(groups_root) if os.path.isdir(os.path.join(groups_root, d)))
    if not folders:
        sys.exit(f"coverage-report: no group counts under {groups_root}: run scripts/coverage.sh")
    per_group = {f: group_lines(os.path.join(groups_root, f)) for f in folders}

    executable, covered = {}, {}
    for lines in per_group.values():
        for source, (ex, cov) in lines.items():
            executable.setdefault(source, set()).update(ex)
            covered.setdefault(source, set()).update(cov)
    total_ex = sum(len(v) for v in executable.values())
    total_cov = sum(len(v) for v in covered.values())
    print(f"| file | lines | covered |\n|---|---|---|")
    for source in sorted(s for s in executable if executable[s]):
        ex, cov = len(executable[source]), len(covered[source])
        print(f"| {source} | {ex} | {100 * cov / max(ex, 1):.0f} % |")
    print(f"\nhost/: {total_cov} of {total_ex} lines run by the suite ({100 * total_cov / max(total_ex, 1):.1f} %), "
          f"{len(per_group)} test groups")
    low = [(100 * len(covered[s]) / len(executable[s]), s) for s in executable if executable[s]]
    low = sorted(x for x in low if x[0] < args.threshold)
    print(f"files under {args.threshold:.0f} %: " + (", ".join(f"{s} ({p:.0f} %)" for p, s in low) or "none"))

    if args.sanitized:
        chosen = {re.sub(r"[^A-Za-z0-9_]", "_", suite) for suite in args.sanitized.split()}
        costs = {}
        if args.costs:
            for case in ElementTree.parse(args.costs).getroot().iter("testcase"):
                costs[re.sub(r"[^A-Za-z0-9_]", "_", case.get("name"))] = float(case.get("time", "0"))
        in_set = {g: per_group[g] for g in per_group if g in chosen or re.sub(r"_\d+$", "", g) in chosen}
        set_cov = {}
        for lines in in_set.values():
            for source, (_, cov) in lines.items():
                set_cov.setdefault(source, set()).update(cov)
        kept = sum(len(covered[s] & set_cov.get(s, set())) for s in covered)
        print(f"\nthe sanitized suites' {len(in_set)} groups run {kept} of the {total_cov} host lines the "
              f"whole suite runs ({100 * kept / max(total_cov, 1):.1f} %)")
        missing = sorted(((len(covered[s] - set_cov.get(s, set())), s) for s in covered), reverse=True)
        print("lines only the other groups run, by file: " + ", ".join(f"{s} {n}" for n, s in missing[:12] if n))
        print("\n| group | lines no other group of the set runs | s |\n|---|---|---|")
        others_of = {}
        for g in per_group:
            candidates = set(in_set) - {g}
            union = {}
            for h in candidates:
                for source, (_, cov) in per_group[h].items():
                    union.setdefault(source, set()).update(cov)
            others_of[g] = union
        rows = []
        for g, lines in per_group.items():
            unique = sum(len(cov - others_of[g].get(source, set())) for source, (_, cov) in lines.items())
            rows.append((g in in_set, costs.get(g, 0.0), unique, g))
        for member, cost, unique, g in sorted(rows, key=lambda r: (not r[0], -r[1])):
            print(f"| {g}{'' if member else ' (not in the set)'} | {unique} | {cost:.1f} |")


if __name__ == "__main__":
    main()
