#!/usr/bin/python3
"""Runs the gtest tests of a build, one process per test program instead of
one per test: `./dev sanitize` uses it (docs/reliability.md#asan-and-ubsan).

    run_gtest_programs.py BUILD_DIR [--exclude REGEX] [--jobs N]

The tests are those ctest lists in BUILD_DIR whose names start with a
capital letter (the discovered gtest tests; cli_*, mpi.* and the scripts
are left out), less the disabled ones and those matching --exclude. Each
program runs once, in its tests' working directory, with a --gtest_filter
naming exactly its selected tests, N programs at a time (default: the
number of cores). Under the sanitizers a process per test costs the start
of PETSc and Open MPI and the default mannequin each time; with a process
per program the ASan+UBSan run of `./dev sanitize --quick` took 400 s
instead of 908 s on 2 cores (2026-12-07).
Prints one line per program (tests, seconds, verdict) and the output of
every program that failed, or that ran fewer tests than it was named;
exits 1 when any failed. Each program's time is kept in
BUILD_DIR/gtest_program_times.json, and the next run starts the longest
first.
"""
import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import time


def property_of(test, name, default=None):
    for entry in test.get("properties", []):
        if entry["name"] == name:
            return entry["value"]
    return default


def programs(build_dir, exclude):
    """{(program, working directory): [gtest names]} of the selected tests."""
    listing = subprocess.run(["ctest", "--show-only=json-v1"], cwd=build_dir, check=True,
                             capture_output=True, text=True).stdout
    selected = {}
    for test in json.loads(listing)["tests"]:
        name = test["name"]
        if not re.match(r"[A-Z]", name) or property_of(test, "DISABLED", False):
            continue
        if exclude and re.search(exclude, name):
            continue
        # The test's own filter: a parameterised test's ctest name carries
        # its parameter ("Suite.Test/Name  # GetParam() = ...").
        command = test.get("command", [])
        filters = [a[len("--gtest_filter="):] for a in command if a.startswith("--gtest_filter=")]
        if not filters:
            continue
        key = (command[0], property_of(test, "WORKING_DIRECTORY", build_dir))
        selected.setdefault(key, []).append(filters[0])
    return selected


def run(program, directory, names):
    """(verdict, seconds, output); verdict None when every named test ran and passed."""
    start = time.monotonic()
    done = subprocess.run([program, "--gtest_filter=" + ":".join(names)], cwd=directory,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          errors="replace")
    seconds = time.monotonic() - start
    if done.returncode != 0:
        return f"FAILED (exit status {done.returncode})", seconds, done.stdout
    # A name the filter does not match would leave its test out unnoticed.
    ran = re.search(r"^\[==========\] (\d+) tests? from .* ran\.", done.stdout, re.MULTILINE)
    if not ran or int(ran.group(1)) != len(names):
        count = ran.group(1) if ran else "no"
        return f"FAILED ({count} of its {len(names)} tests ran)", seconds, done.stdout
    return None, seconds, done.stdout


def load_times(path):
    """Each program's seconds in the last run, to start the longest first."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("--exclude", default="", help="regular expression of test names left out")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    args = parser.parse_args()
    selected = programs(args.build_dir, args.exclude)
    if not selected:
        sys.exit(f"run_gtest_programs.py: no gtest tests in {args.build_dir}")
    times_path = os.path.join(args.build_dir, "gtest_program_times.json")
    times = load_times(times_path)
    order = sorted(selected.items(), key=lambda item: -times.get(item[0][0], 0.0))
    start = time.monotonic()
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(run, program, directory, names): (program, names)
                   for (program, directory), names in order}
        for future in concurrent.futures.as_completed(futures):
            program, names = futures[future]
            verdict, seconds, output = future.result()
            times[program] = seconds
            print(f"{os.path.basename(program)}: {len(names)} tests, {seconds:.1f} s, "
                  f"{verdict or 'passed'}", flush=True)
            if verdict:
                failed.append(program)
                print(output, flush=True)
    with open(times_path, "w") as f:
        json.dump(times, f, indent=1)
    tests = sum(len(names) for names in selected.values())
    print(f"{tests} tests in {len(selected)} programs, {time.monotonic() - start:.0f} s; "
          + (f"{len(failed)} programs failed: " + ", ".join(map(os.path.basename, failed))
             if failed else "all passed"))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
