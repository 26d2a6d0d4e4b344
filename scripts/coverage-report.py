#!/usr/bin/env python3
"""Line coverage of host/ from a coverage build's per-group counts (issue 46).

scripts/coverage.sh runs the suite in build-coverage/, where each test group (a process) writes its
gcov counts into a folder of its own (build-coverage/coverage-groups/GROUP, through GCOV_PREFIX).
This reads each group's counts with gcovr, then prints the whole suite's line coverage per file of
host/, the total and the files under 70 %; with --sanitized, how much of what the whole suite runs
the sanitizer stage's test sources run (scripts/test.sh's sanitized_tests), and which groups of
those add lines no other sanitized group runs, with their time, to choose the stage by.

Usage: coverage-report.py [--build build-coverage] [--sanitized "a_test.cpp b_test.cpp"]
                          [--costs JUNIT.xml] [--threshold 70]
"""
import argparse
import concurrent.futures
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def group_lines(build, group_dir):
    """{source: (executable lines, covered lines)} of host/ for one group's counts."""
    cached = os.path.join(group_dir, "coverage.json")
    if not os.path.exists(cached):
        # gcov wants each object's notes file (.gcno) beside its counts (.gcda): link them in.
        for gcda in glob.glob(os.path.join(group_dir, "**", "*.gcda"), recursive=True):
            relative = os.path.relpath(gcda, group_dir)
            gcno = os.path.join("/", relative)[: -len(".gcda")] + ".gcno"
            target = gcda[: -len(".gcda")] + ".gcno"
            if os.path.exists(gcno) and not os.path.exists(target):
                os.link(gcno, target) if os.stat(gcno).st_dev == os.stat(group_dir).st_dev else shutil.copy(gcno, target)
        subprocess.run(["gcovr", "-r", ROOT, "--filter", os.path.join(ROOT, "host") + "/", "--json", cached, group_dir],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(cached, encoding="utf-8") as f:
        report = json.load(f)
    lines = {}
    for entry in report["files"]:
        executable = {line["line_number"] for line in entry["lines"]}
        covered = {line["line_number"] for line in entry["lines"] if line["count"] > 0}
        old = lines.get(entry["file"], (set(), set()))
        lines[entry["file"]] = (old[0] | executable, old[1] | covered)
    return lines


def suite_files():
    """{suite name: test source file name} from the TEST/TEST_F/TEST_P and INSTANTIATE lines."""
    files = {}
    for path in glob.glob(os.path.join(ROOT, "tests", "*.cpp")):
        text = open(path, encoding="utf-8").read()
        name = os.path.basename(path)
        for m in re.finditer(r"\b(?:TEST|TEST_F|TEST_P)\(\s*(\w+)\s*,", text):
            files.setdefault(m.group(1), name)
        for m in re.finditer(r"INSTANTIATE_TEST_SUITE_P\(\s*(\w+)\s*,\s*(\w+)", text):
            files[m.group(1) + "_" + m.group(2)] = name
    return files


def file_of_group(folder, files):
    base = re.sub(r"_\d+$", "", folder)
    for candidate in (folder, base):
        if candidate in files:
            return files[candidate]
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build-coverage"))
    parser.add_argument("--sanitized", help="the sanitizer stage's test sources, space-separated")
    parser.add_argument("--costs", help="a JUnit file of ctest (the groups' seconds, e.g. of the sanitizer stage)")
    parser.add_argument("--threshold", type=float, default=70.0)
    args = parser.parse_args()

    groups_root = os.path.join(args.build, "coverage-groups")
    folders = sorted(d for d in os.listdir(groups_root) if os.path.isdir(os.path.join(groups_root, d)))
    if not folders:
        sys.exit(f"coverage-report: no group counts under {groups_root}: run scripts/coverage.sh")
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        per_group = dict(zip(folders, pool.map(lambda f: group_lines(args.build, os.path.join(groups_root, f)), folders)))

    executable, covered = {}, {}
    for lines in per_group.values():
        for source, (ex, cov) in lines.items():
            executable.setdefault(source, set()).update(ex)
            covered.setdefault(source, set()).update(cov)
    total_ex = sum(len(v) for v in executable.values())
    total_cov = sum(len(v) for v in covered.values())
    print(f"| file | lines | covered |\n|---|---|---|")
    for source in sorted(executable):
        ex, cov = len(executable[source]), len(covered[source])
        print(f"| {source} | {ex} | {100 * cov / max(ex, 1):.0f} % |")
    print(f"\nhost/: {total_cov} of {total_ex} lines run by the suite ({100 * total_cov / max(total_ex, 1):.1f} %), "
          f"{len(per_group)} test groups")
    low = [(100 * len(covered[s]) / max(len(executable[s]), 1), s) for s in executable]
    low = sorted(x for x in low if x[0] < args.threshold)
    print(f"files under {args.threshold:.0f} %: " + (", ".join(f"{s} ({p:.0f} %)" for p, s in low) or "none"))

    if args.sanitized:
        chosen = set(args.sanitized.split())
        files = suite_files()
        costs = {}
        if args.costs:
            for case in ElementTree.parse(args.costs).getroot().iter("testcase"):
                costs[re.sub(r"[^A-Za-z0-9_]", "_", case.get("name"))] = float(case.get("time", "0"))
        in_set = {g: per_group[g] for g in per_group if file_of_group(g, files) in chosen}
        unknown = [g for g in per_group if file_of_group(g, files) is None]
        if unknown:
            print(f"coverage-report: groups of no known test file: {', '.join(unknown)}", file=sys.stderr)
        set_cov = {}
        for lines in in_set.values():
            for source, (_, cov) in lines.items():
                set_cov.setdefault(source, set()).update(cov)
        kept = sum(len(covered[s] & set_cov.get(s, set())) for s in covered)
        print(f"\nthe sanitized test sources' {len(in_set)} groups run {kept} of the {total_cov} host lines the "
              f"whole suite runs ({100 * kept / max(total_cov, 1):.1f} %)")
        missing = sorted(((len(covered[s] - set_cov.get(s, set())), s) for s in covered), reverse=True)
        print("lines only the other groups run, by file: " +
              ", ".join(f"{s.replace(ROOT + '/', '')} {n}" for n, s in missing[:12] if n))
        print("\n| sanitized group | lines no other sanitized group runs | s |\n|---|---|---|")
        rows = []
        for g, lines in in_set.items():
            others = {}
            for h, other in in_set.items():
                if h == g:
                    continue
                for source, (_, cov) in other.items():
                    others.setdefault(source, set()).update(cov)
            unique = sum(len(cov - others.get(source, set())) for source, (_, cov) in lines.items())
            rows.append((costs.get(g, 0.0), unique, g))
        for cost, unique, g in sorted(rows, reverse=True):
            print(f"| {g} ({file_of_group(g, files)}) | {unique} | {cost:.1f} |")


if __name__ == "__main__":
    main()
