#!/usr/bin/python3
"""The residual scalars of the thesis' creep experiments (§5.4), per variant.

    creep_experiments.py EXPERIMENT RUN_DIR... [--labels A,B,...]
                         [--json FILE] [--plot FILE.png]

EXPERIMENT is push (Fig. 5.6), expansion (Fig. 5.7), pinch (Fig. 5.8) or
twist (Fig. 5.10);
each RUN_DIR is the output folder of one `sartor run cases/creep/...` variant.
From a run's files (never its terminal output) the script reads:

* summary.json: whether the run converged and reached its end time;
* result.h5: the final positions and displacements, and the initial placement;
* series.h5: the per-triangle creep state of the last state written
  (viscoelastic_warp, permanent_warp, viscoelastic_weft, permanent_weft).

and computes (docs/creep-experiments.md):

* push:      residual_bulge_m = the largest downward displacement of the sheet
             (normal to its initial plane z = const) at the end;
* expansion: excess_circumference = the mean over triangles of the warp
             (hoop) non-elastic strain eps_v + eps_p at the end, i.e. the
             relative growth of the tube's unloaded circumference, and
             sag_gap_m = the largest distance of the tube from its initial
             radius about the drum's axis (y);
* pinch:     residual_sag_m = the largest out-of-plane displacement of the
             sheet (along z, its initial normal) at the end, and
             residual_nonelastic_strain (as for twist);
* twist:     residual_nonelastic_strain = the mean over triangles of
             (eps_v + eps_p)_warp + (eps_v + eps_p)_weft at the end, and
             bulge_m = the largest radial displacement about the tube's axis (z).

It prints one line per run, writes the numbers as JSON with --json, and draws
the experiment's scalar per variant as a bar chart with --plot (matplotlib,
Agg backend, 150 dpi). Run it with /usr/bin/python3 (numpy, h5py, matplotlib).
"""

import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sartor_plotio import PlotError, read_json  # noqa: E402

# The scalar each experiment orders its variants by, with its axis label.
MAIN_SCALAR = {
    "push": ("residual_bulge_m", "residual bulge (m)"),
    "expansion": ("excess_circumference", "excess circumference (eps_v + eps_p, warp)"),
    "pinch": ("residual_sag_m", "residual sag (m)"),
    "twist": ("residual_nonelastic_strain", "mean eps_v + eps_p (warp + weft)"),
}


def read_h5(path):
    import h5py  # only needed here; numpy-only users get a clear message

    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    try:
        return h5py.File(path, "r")
    except OSError as error:
        raise PlotError("%s: cannot read as HDF5: %s" % (path, error))


def final_creep_state(run_dir):
    """The cell fields of the last state in series.h5, as arrays."""
    path = os.path.join(run_dir, "series.h5")
    with read_h5(path) as series:
        if "steps" not in series or not len(series["steps"]):
            raise PlotError("%s: no states written (group 'steps' is empty)" % path)
        last = series["steps"][sorted(series["steps"])[-1]]
        fields = {}
        for name in ("viscoelastic_warp", "permanent_warp", "viscoelastic_weft", "permanent_weft"):
            key = "cell_fields/" + name
            if key not in last:
                raise PlotError("%s: the last state has no %s (not a creep run?)" % (path, key))
            fields[name] = np.asarray(last[key][()], dtype=float)
    return fields


def final_geometry(run_dir):
    """(initial positions, final positions) of every vertex, from result.h5."""
    path = os.path.join(run_dir, "result.h5")
    with read_h5(path) as result:
        for key in ("mesh/initial_position", "fields/position"):
            if key not in result:
                raise PlotError("%s: missing dataset %s" % (path, key))
        initial = np.asarray(result["mesh/initial_position"][()], dtype=float).reshape(-1, 3)
        final = np.asarray(result["fields/position"][()], dtype=float).reshape(-1, 3)
    return initial, final


def scalars(experiment, run_dir):
    summary = read_json(os.path.join(run_dir, "summary.json"))
    creep = summary.get("creep", {})
    row = {
        "run": run_dir,
        "converged": bool(summary.get("converged", False)),
        "completed": bool(creep.get("completed", False)),
        "final_time_s": creep.get("final_time_s"),
        "steps": creep.get("steps"),
        "newton_iterations": creep.get("newton_iterations"),
    }
    state = final_creep_state(run_dir)
    warp = state["viscoelastic_warp"] + state["permanent_warp"]
    weft = state["viscoelastic_weft"] + state["permanent_weft"]
    row["mean_nonelastic_warp"] = float(warp.mean())
    row["mean_nonelastic_weft"] = float(weft.mean())
    row["max_nonelastic"] = float(max(warp.max(), weft.max()))
    initial, final = final_geometry(run_dir)
    if experiment == "push":
        row["residual_bulge_m"] = float(np.max(initial[:, 2] - final[:, 2]))
    elif experiment == "expansion":
        radius0 = np.hypot(initial[:, 0], initial[:, 2])
        radius = np.hypot(final[:, 0], final[:, 2])
        row["excess_circumference"] = float(warp.mean())
        row["sag_gap_m"] = float(np.max(radius - radius0))
    elif experiment == "pinch":
        row["residual_sag_m"] = float(np.max(np.abs(final[:, 2] - initial[:, 2])))
        row["residual_nonelastic_strain"] = float((warp + weft).mean())
    else:
        radius0 = np.hypot(initial[:, 0], initial[:, 1])
        radius = np.hypot(final[:, 0], final[:, 1])
        row["residual_nonelastic_strain"] = float((warp + weft).mean())
        row["bulge_m"] = float(np.max(np.abs(radius - radius0)))
    return row


def plot(experiment, rows, labels, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    key, axis_label = MAIN_SCALAR[experiment]
    values = [row[key] for row in rows]
    figure, axes = plt.subplots(figsize=(6.0, 3.8))
    bars = axes.bar(range(len(values)), values, color="tab:blue")
    for bar, value in zip(bars, values):
        axes.annotate("%.3g" % value, (bar.get_x() + bar.get_width() / 2, value),
                      ha="center", va="bottom", fontsize=8)
    axes.set_xticks(range(len(values)))
    axes.set_xticklabels(labels, rotation=0)
    axes.set_ylabel(axis_label)
    titles = {"push": "Push test (thesis Fig. 5.6)",
              "expansion": "Cylinder expansion (thesis Fig. 5.7)",
              "pinch": "Pinch and release (thesis Fig. 5.8)",
              "twist": "Twist test (thesis Fig. 5.10)"}
    axes.set_title(titles[experiment])
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("experiment", choices=sorted(MAIN_SCALAR))
    parser.add_argument("runs", nargs="+", metavar="RUN_DIR")
    parser.add_argument("--labels", help="comma-separated variant names (default: folder names)")
    parser.add_argument("--json", metavar="FILE", help="write the numbers here")
    parser.add_argument("--plot", metavar="FILE.png", help="draw the scalar per variant here")
    args = parser.parse_args()
    labels = args.labels.split(",") if args.labels else [os.path.basename(os.path.normpath(r))
                                                          for r in args.runs]
    if len(labels) != len(args.runs):
        raise PlotError("--labels: %d labels for %d runs" % (len(labels), len(args.runs)))
    rows = []
    key = MAIN_SCALAR[args.experiment][0]
    for label, run_dir in zip(labels, args.runs):
        row = scalars(args.experiment, run_dir)
        row["label"] = label
        rows.append(row)
        print("%-14s %s = %.6g  converged %s, completed %s, %s steps"
              % (label, key, row[key], row["converged"], row["completed"], row["steps"]))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as stream:
            json.dump({"experiment": args.experiment, "scalar": key, "runs": rows}, stream, indent=2)
    if args.plot:
        plot(args.experiment, rows, labels, args.plot)
        print("wrote %s" % args.plot)


if __name__ == "__main__":
    try:
        main()
    except PlotError as error:
        print("creep_experiments.py: error: %s" % error, file=sys.stderr)
        sys.exit(1)
