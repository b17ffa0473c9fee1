#!/usr/bin/python3
"""The solver benchmark: drapes and static solves at growing sizes.

Runs every row of the runs file (tests/bench/solver_runs.csv: the six sample
garments at 8, 4, 2, 1 cm target edges, the sphere drape at 32^2 to 256^2
cells, the Hencky disk at 32, 64, 100 rings) with `sartor` on each rank
count, one process tree per run under a wall-clock limit, and records per
run: wall time, CPU time (user + sys of the whole process tree, the number
to compare on a shared machine), peak resident memory (of the largest
process) and per vertex, Newton and linear iterations, convergence and the
certificate's verdict (from the run's summary.json). Once a run of a series
exceeds the limit, the finer runs of that series (at that rank count) are
skipped and recorded as skipped.

Writes into OUTPUT: solver_bench.csv (one row per run), solver_bench.json
({"host", "runs": [...]}, each run with its summary's key figures),
solver_bench.png (postproc/plot_solver_bench.py) and runs/NAME/ (each run's
output folder and log). It measures; it never fails on time. Exit status 0
unless the benchmark itself could not run (bad options, no sartor).
"""

import argparse
import csv
import json
import os
import platform
import re
import shlex
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
COLUMNS = (
    "series", "size", "size_unit", "ranks", "status", "exit_status", "wall_s", "cpu_s",
    "peak_rss_mb", "vertices", "triangles", "bytes_per_vertex", "newton_iterations",
    "linear_iterations", "settle_newton_iterations", "level_newton_iterations", "converged",
    "certificate",
    "drape_coefficient", "drape_nodes",
)


def parse_arguments():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Example: ./dev bench solver --only 'hencky|sphere_drape,32' --timeout 120")
    parser.add_argument("--runs", default=os.path.join(ROOT, "tests/bench/solver_runs.csv"),
                        help="the runs file (default: %(default)s)")
    parser.add_argument("--output", default=os.path.join(ROOT, "out/bench/solver"),
                        help="output folder (default: %(default)s)")
    parser.add_argument("--ranks", default="1,2", help="MPI rank counts (default: %(default)s)")
    parser.add_argument("--timeout", type=float, default=600.0,
                        help="wall-clock limit of one run, s (default: %(default)s)")
    parser.add_argument("--only", default="",
                        help="run only rows whose 'series,size' matches this regular expression")
    parser.add_argument("--sartor", default=os.path.join(
        os.environ.get("SARTOR_BUILD_DIR", os.path.join(ROOT, "build")), "bin", "sartor"),
                        help="the sartor executable (default: %(default)s)")
    parser.add_argument("--mpiexec", default="mpiexec", help="MPI launcher (default: %(default)s)")
    parser.add_argument("--list", action="store_true", help="print the runs and exit")
    parser.add_argument("--no-plot", action="store_true", help="do not draw solver_bench.png")
    return parser.parse_args()


def read_runs(path, only):
    """The rows of the runs file (comments start with #), checked."""
    try:
        with open(path, encoding="utf-8") as stream:
            lines = [line for line in stream if not line.lstrip().startswith("#")]
    except OSError as error:
        sys.exit(f"run_solver_bench.py: {path}: cannot read: {error.strerror}")
    rows = []
    for number, row in enumerate(csv.DictReader(lines), start=2):
        missing = [key for key in ("series", "size", "size_unit", "command", "input", "options")
                   if row.get(key) is None]
        if missing:
            sys.exit(f"run_solver_bench.py: {path}: row {number}: missing {', '.join(missing)}")
        try:
            float(row["size"])
        except ValueError:
            sys.exit(f"run_solver_bench.py: {path}: row {number}: size '{row['size']}' "
                     "is not a number")
        if re.search(only, f"{row['series']},{row['size']}"):
            rows.append(row)
    return rows


def launcher(ranks, mpiexec):
    if ranks == 1:
        return []
    flags = ["--oversubscribe"]
    if os.geteuid() == 0:
        flags.append("--allow-run-as-root")
    return [mpiexec, "-n", str(ranks)] + flags


def run_measured(command, log_path, timeout):
    """Runs `command` in its own process group; returns (status, exit, wall, rusage)."""
    with open(log_path, "w", encoding="utf-8") as log:
        started = time.monotonic()
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT,
                                   start_new_session=True)
        timed_out = False
        while True:
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)
            if pid != 0:
                break
            if time.monotonic() - started > timeout:
                os.killpg(process.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(process.pid, 0)
                timed_out = True
                break
            time.sleep(0.2)
        wall = time.monotonic() - started
    if timed_out:
        return "timeout", None, wall, usage
    exit_status = os.waitstatus_to_exitcode(status)
    return ("ok" if exit_status == 0 else "failed"), exit_status, wall, usage


def summary_figures(path):
    """Key figures of a run's summary.json (empty when it has none)."""
    try:
        with open(path, encoding="utf-8") as stream:
            summary = json.load(stream)
    except (OSError, json.JSONDecodeError):
        return {}
    solve = summary.get("dynamics") or summary.get("solver") or {}
    settle = (summary.get("dynamics") or {}).get("settle") or {}
    certificate = summary.get("certificate") or {}
    figures = {
        "vertices": summary.get("mesh", {}).get("vertices"),
        "triangles": summary.get("mesh", {}).get("triangles"),
        "newton_iterations": solve.get("newton_iterations"),
        "linear_iterations": solve.get("linear_iterations"),
        "settle_newton_iterations": settle.get("newton_iterations"),
        "converged": summary.get("drape", {}).get("converged", summary.get("converged")),
        "certificate": certificate.get("verdict"),
        # The Cusick runs' result, for their mesh convergence (else empty).
        "drape_coefficient": (summary.get("contact") or {}).get("drape", {}).get("coefficient"),
        "drape_nodes": (summary.get("contact") or {}).get("drape", {}).get("nodes"),
        "timing_s": summary.get("timing_s"),
    }
    # Per level of a coarse-to-fine solve, when the run reports levels.
    if isinstance(summary.get("levels"), list):
        figures["levels"] = summary["levels"]
        figures["level_newton_iterations"] = "/".join(
            str(level.get("newton_iterations")) for level in summary["levels"])
    return figures


def run_one(row, ranks, arguments, runs_folder):
    name = f"{row['series']}-{row['size']}-{ranks}r"
    folder = os.path.join(runs_folder, name)
    os.makedirs(folder, exist_ok=True)
    summary = os.path.join(folder, "summary.json")
    if os.path.exists(summary):
        os.remove(summary)
    command = (launcher(ranks, arguments.mpiexec) + [arguments.sartor, row["command"],
               os.path.join(ROOT, row["input"])] + shlex.split(row["options"]) +
               ["--output", folder, "--no-plot"])
    status, exit_status, wall, usage = run_measured(command, folder + ".log", arguments.timeout)
    record = {key: row[key] for key in ("series", "size", "size_unit")}
    record.update({
        "ranks": ranks, "status": status, "exit_status": exit_status, "wall_s": wall,
        "cpu_s": usage.ru_utime + usage.ru_stime, "peak_rss_mb": usage.ru_maxrss / 1024.0,
        "command": " ".join(shlex.quote(word) for word in command),
    })
    if status == "timeout":
        # The killed ranks were never waited for: their CPU time is unknown.
        record.update({"cpu_s": None, "peak_rss_mb": None})
    else:
        record.update(summary_figures(summary))
    if record.get("vertices"):
        record["bytes_per_vertex"] = usage.ru_maxrss * 1024.0 * ranks / record["vertices"]
    cpu = "unknown" if record["cpu_s"] is None else f"{record['cpu_s']:.1f} s"
    print(f"{name}: {status}, wall {wall:.1f} s, CPU {cpu}, "
          f"{record.get('vertices')} vertices, Newton {record.get('newton_iterations')}, "
          f"certificate: {record.get('certificate')}", flush=True)
    return record


def main():
    arguments = parse_arguments()
    rows = read_runs(arguments.runs, arguments.only)
    try:
        rank_counts = [int(r) for r in arguments.ranks.split(",")]
    except ValueError:
        sys.exit(f"run_solver_bench.py: --ranks: '{arguments.ranks}' is not a list of integers")
    if arguments.list:
        for row in rows:
            print(f"{row['series']},{row['size']} ({row['size_unit']}): sartor {row['command']} "
                  f"{row['input']} {row['options']}")
        return
    if not os.access(arguments.sartor, os.X_OK):
        sys.exit(f"run_solver_bench.py: {arguments.sartor}: no sartor executable (./dev build)")
    runs_folder = os.path.join(arguments.output, "runs")
    os.makedirs(runs_folder, exist_ok=True)
    records = []
    for ranks in rank_counts:
        exceeded = {}
        for row in rows:
            if row["series"] in exceeded:
                record = {key: row[key] for key in ("series", "size", "size_unit")}
                record.update({"ranks": ranks, "status": "skipped",
                               "reason": f"size {exceeded[row['series']]} exceeded "
                                         f"{arguments.timeout:g} s"})
                records.append(record)
                print(f"{row['series']}-{row['size']}-{ranks}r: skipped", flush=True)
                continue
            record = run_one(row, ranks, arguments, runs_folder)
            records.append(record)
            if record["status"] == "timeout":
                exceeded[row["series"]] = row["size"]
    with open(os.path.join(arguments.output, "solver_bench.csv"), "w", newline="",
              encoding="utf-8") as stream:
        writer = csv.DictWriter(stream, fieldnames=COLUMNS, extrasaction="ignore")
        writer.writeheader()
        for record in records:
            writer.writerow(record)
    host = {"machine": platform.node(), "processor": platform.processor(),
            "cpus": os.cpu_count(), "time_limit_s": arguments.timeout,
            "load_average": os.getloadavg()}
    with open(os.path.join(arguments.output, "solver_bench.json"), "w",
              encoding="utf-8") as stream:
        json.dump({"host": host, "runs": records}, stream, indent=1)
    if not arguments.no_plot:
        plot = os.path.join(ROOT, "postproc", "plot_solver_bench.py")
        if subprocess.call(["/usr/bin/python3", plot, arguments.output]) != 0:
            print("run_solver_bench.py: plotting failed; the CSV and JSON are complete",
                  file=sys.stderr)
    print(f"wrote {arguments.output}/solver_bench.csv, .json"
          f"{'' if arguments.no_plot else ', .png'}")


if __name__ == "__main__":
    main()
