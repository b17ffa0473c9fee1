#!/usr/bin/python3
"""Compare two output directories of the same `sartor run` case, run under
different round-off (another CPU's BLAS kernels, OPENBLAS_CORETYPE), and fail
when they differ by more than the stated tolerances (docs/reliability.md):

  positions       1e-6 m at every state of series.h5 and in result.h5
  tensions        1e-6 of the largest tension of the run (N/m)
  time grid       the same accepted steps: equal count, times within 1e-12
                  of the end time
  energies        (dynamics.csv) 1e-6 of the largest energy of the run
  history values  (creep.csv and the like) 1e-6 of each column's largest value

usage: compare_runs.py DIR_A DIR_B
"""
import csv
import json
import os
import sys

import h5py
import numpy as np

POSITION_TOL = 1e-6  # m
RELATIVE_TOL = 1e-6
TIME_TOL = 1e-12  # of the largest time

failures = []
largest = {}
tension_scale = 1.0  # N/m, the largest tension of the first run
time_scale = 1.0  # s, the largest time of the first run


def note(what, value):
    largest[what] = max(largest.get(what, 0.0), value)


def check(condition, message):
    if not condition:
        failures.append(message)


def largest_tension(dir_a):
    """The largest |tension| of any state the run wrote (N/m)."""
    scale = 0.0

    def visit(group):
        nonlocal scale
        for name in ("tension_warp", "tension_weft"):
            key = "cell_fields/" + name
            if key in group and group[key].size:
                scale = max(scale, float(np.max(np.abs(np.asarray(group[key])))))

    for name in ("result.h5", "series.h5"):
        path = os.path.join(dir_a, name)
        if os.path.exists(path):
            with h5py.File(path, "r") as f:
                visit(f)
                for s in f.get("steps", {}):
                    visit(f["steps"][s])
    return max(scale, 1e-300)


def compare_fields(a, b, where):
    pa, pb = np.asarray(a["fields/position"]), np.asarray(b["fields/position"])
    check(pa.shape == pb.shape, f"{where}: position shapes {pa.shape} and {pb.shape}")
    if pa.shape != pb.shape:
        return
    d = float(np.max(np.abs(pa - pb))) if pa.size else 0.0
    note("position_m", d)
    check(d <= POSITION_TOL, f"{where}: positions differ by {d:.3g} m (> {POSITION_TOL:g} m)")
    for name in ("tension_warp", "tension_weft"):
        key = "cell_fields/" + name
        if key not in a or key not in b:
            continue
        ta, tb = np.asarray(a[key]), np.asarray(b[key])
        d = float(np.max(np.abs(ta - tb))) / tension_scale if ta.size else 0.0
        note("tension_relative", d)
        check(d <= RELATIVE_TOL, f"{where}: {name} differs by {d:.3g} of its largest value")


def compare_h5(dir_a, dir_b):
    for name in ("result.h5", "series.h5"):
        fa, fb = os.path.join(dir_a, name), os.path.join(dir_b, name)
        if not os.path.exists(fa):
            continue
        with h5py.File(fa, "r") as a, h5py.File(fb, "r") as b:
            if "steps" not in a:
                compare_fields(a, b, name)
                continue
            sa, sb = sorted(a["steps"]), sorted(b["steps"])
            check(len(sa) == len(sb), f"{name}: {len(sa)} and {len(sb)} states")
            for s in sa[: min(len(sa), len(sb))]:
                ga, gb = a["steps"][s], b["steps"][s]
                ta, tb = float(ga["time"][0]), float(gb["time"][0])
                check(abs(ta - tb) <= TIME_TOL * time_scale, f"{name} state {s}: times {ta} and {tb}")
                compare_fields(ga, gb, f"{name} state {s} (t = {ta:g} s)")


def largest_time(dir_a):
    path = os.path.join(dir_a, "series.h5")
    if not os.path.exists(path):
        return 0.0
    with h5py.File(path, "r") as f:
        return max([float(f["steps"][s]["time"][0]) for s in f.get("steps", {})] or [0.0])


def read_csv(path):
    """The header and the columns: numbers as float arrays, text (a
    certificate's verdict) as lists of strings."""
    with open(path) as f:
        rows = list(csv.reader(f))
    columns = []
    for j in range(len(rows[0])):
        values = [r[j] for r in rows[1:]]
        try:
            columns.append(np.array([float(v) for v in values]))
        except ValueError:
            columns.append(values)
    return rows[0], columns


def compare_csv(dir_a, dir_b):
    for name in sorted(os.listdir(dir_a)):
        if not name.endswith(".csv"):
            continue
        head_a, a = read_csv(os.path.join(dir_a, name))
        head_b, b = read_csv(os.path.join(dir_b, name))
        check(head_a == head_b, f"{name}: other columns")
        rows_a, rows_b = len(a[0]) if a else 0, len(b[0]) if b else 0
        check(rows_a == rows_b, f"{name}: {rows_a} and {rows_b} rows (another time grid)")
        if head_a != head_b or rows_a != rows_b or rows_a == 0:
            continue
        for column, ca, cb in zip(head_a, a, b):
            if isinstance(ca, list) or isinstance(cb, list):
                check(ca == cb, f"{name}: {column} differs ({ca} and {cb})")
            elif column.startswith("time"):
                d = float(np.max(np.abs(ca - cb)))
                note("time_s", d)
                check(d <= TIME_TOL * time_scale, f"{name}: {column} differs by {d:.3g} s")
            elif column.endswith("_m"):
                d = float(np.max(np.abs(ca - cb)))
                note("position_m", d)
                check(d <= POSITION_TOL, f"{name}: {column} differs by {d:.3g} m")
            elif "iterations" in column or column in ("rejected", "step"):
                continue  # counts may differ where a residual ends near a tolerance
            else:
                scale = max(float(np.max(np.abs(ca))), 1e-300)
                d = float(np.max(np.abs(ca - cb))) / scale
                note("csv_relative", d)
                check(d <= RELATIVE_TOL, f"{name}: {column} differs by {d:.3g} of its largest value")


def compare_summary(dir_a, dir_b):
    fa, fb = os.path.join(dir_a, "summary.json"), os.path.join(dir_b, "summary.json")
    if not os.path.exists(fa):
        return
    with open(fa) as f:
        a = json.load(f)
    with open(fb) as f:
        b = json.load(f)
    for key in ("converged", "completed"):
        if key in a:
            check(a.get(key) == b.get(key), f"summary.json: {key} {a.get(key)} and {b.get(key)}")


def main():
    if len(sys.argv) != 3 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(sys.argv) == 2 else 2
    dir_a, dir_b = sys.argv[1], sys.argv[2]
    global tension_scale, time_scale
    tension_scale = largest_tension(dir_a)
    time_scale = max(1.0, largest_time(dir_a))
    compare_h5(dir_a, dir_b)
    compare_csv(dir_a, dir_b)
    compare_summary(dir_a, dir_b)
    print("largest differences: " + ", ".join(f"{k} {v:.3g}" for k, v in sorted(largest.items())))
    for message in failures[:20]:
        print("DIFFERENT: " + message)
    if len(failures) > 20:
        print(f"... and {len(failures) - 20} more")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
