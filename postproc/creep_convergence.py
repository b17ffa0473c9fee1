#!/usr/bin/python3
"""Time-step convergence of the creep coupling schemes (docs/creep-structure.md).

Runs `sartor run CASE --analysis creep` at fixed time steps (the adaptive step
control switched off: --max-time-step DT, --creep-tolerance 1) with both
coupling schemes, staggered and monolithic, and a reference run of the
monolithic scheme at a much finer step. From each run's creep.csv it takes
three quantities of the relaxation case (cases/creep/relaxation.yaml):

* the tension at the end of the hold (max_tension_N_per_m at --hold-end),
* the permanent and the viscoelastic strain at the end (at --end),

and writes to OUTDIR:

* convergence.csv: scheme, step, the quantities and their errors against the
  reference;
* convergence.json: the same, plus the observed order between consecutive
  steps, log2(error(dt) / error(dt/2)) for halved steps;
* convergence.png (unless --no-plot): the errors against the step, log-log.

Needs numpy (and matplotlib for the plot); run it with /usr/bin/python3.

Example:
    postproc/creep_convergence.py --sartor build/bin/sartor \\
        --case cases/creep/relaxation.yaml --steps 2,1,0.5,0.25,0.125 out/creep_convergence
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys

SCHEMES = ("staggered", "monolithic")
QUANTITIES = (
    ("tension_end_of_hold_N_per_m", "max_tension_N_per_m", "hold"),
    ("permanent_strain_at_end", "max_permanent_strain", "end"),
    ("viscoelastic_strain_at_end", "max_viscoelastic_strain", "end"),
)


class StudyError(Exception):
    """An error the user can act on; printed without a traceback."""


def run(sartor, case, scheme, step, folder, extra):
    command = [
        sartor, "run", case, "--analysis", "creep", "--creep-scheme", scheme,
        "--time-step", repr(step), "--max-time-step", repr(step), "--creep-tolerance", "1",
        "--output", folder,
    ] + extra
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        raise StudyError("%s failed (exit %d):\n%s" % (" ".join(command), result.returncode,
                                                       result.stdout[-2000:]))


def read_quantities(folder, times):
    path = os.path.join(folder, "creep.csv")
    try:
        with open(path, encoding="utf-8") as stream:
            rows = {float(row["time_s"]): row for row in csv.DictReader(stream)}
    except (OSError, KeyError, ValueError) as error:
        raise StudyError("%s: cannot read the creep history: %s" % (path, error))
    values = {}
    for name, column, when in QUANTITIES:
        time = times[when]
        match = [t for t in rows if abs(t - time) <= 1e-9 * max(1.0, abs(time))]
        if not match:
            raise StudyError("%s: no state at t = %g s (is it a knot or output time of the case?)"
                             % (path, time))
        values[name] = float(rows[match[0]][column])
    return values


def numbers(text, what):
    try:
        values = [float(item) for item in text.split(",")]
    except ValueError:
        raise StudyError("%s: expected comma-separated numbers, got '%s'" % (what, text))
    if not values or any(not (v > 0.0) for v in values):
        raise StudyError("%s: the steps must be positive, got '%s'" % (what, text))
    return sorted(values, reverse=True)


def plot(study, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(1, len(QUANTITIES), figsize=(4.2 * len(QUANTITIES), 3.8))
    for axis, (name, _, _) in zip(axes, QUANTITIES):
        for scheme, marker in zip(SCHEMES, ("o", "s")):
            runs = study["schemes"][scheme]
            steps = [r["step_s"] for r in runs]
            errors = [r["errors"][name] for r in runs]
            axis.loglog(steps, errors, marker=marker, label="%s (order %.2f)"
                        % (scheme, study["orders"][scheme][name][-1]))
        axis.set_xlabel("time step (s)")
        axis.set_ylabel("error")
        axis.set_title(name.replace("_", " "), fontsize=9)
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=8)
    figure.suptitle("creep coupling: time-step convergence (reference: monolithic, dt = %g s)"
                    % study["reference_step_s"], fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=150)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="folder for the runs and the study's files")
    parser.add_argument("--sartor", default="build/bin/sartor", help="the sartor binary")
    parser.add_argument("--case", default="cases/creep/relaxation.yaml", help="the case file")
    parser.add_argument("--steps", default="2,1,0.5,0.25,0.125", help="time steps, s")
    parser.add_argument("--reference-step", type=float, default=0.0078125,
                        help="the reference run's step, s (monolithic)")
    parser.add_argument("--hold-end", type=float, default=60.0,
                        help="a time near the end of the hold, s")
    parser.add_argument("--end", type=float, default=120.0, help="time of the end, s")
    parser.add_argument("--no-plot", action="store_true", help="write no PNG")
    arguments, extra = parser.parse_known_args()
    try:
        steps = numbers(arguments.steps, "--steps")
        times = {"hold": arguments.hold_end, "end": arguments.end}
        # Outputs (step landings) on a grid through both times, few enough to
        # keep the runs' HDF5 series small.
        extra = extra + ["--output-interval", repr(math.gcd(int(arguments.hold_end),
                                                            int(arguments.end)) or arguments.end)]
        os.makedirs(arguments.output, exist_ok=True)
        folder = os.path.join(arguments.output, "reference")
        run(arguments.sartor, arguments.case, "monolithic", arguments.reference_step, folder, extra)
        reference = read_quantities(folder, times)
        study = {"case": arguments.case, "reference_step_s": arguments.reference_step,
                 "reference": reference, "schemes": {}, "orders": {}}
        for scheme in SCHEMES:
            runs = []
            for step in steps:
                folder = os.path.join(arguments.output, "%s_%g" % (scheme, step))
                run(arguments.sartor, arguments.case, scheme, step, folder, extra)
                values = read_quantities(folder, times)
                errors = {name: abs(values[name] - reference[name]) for name in values}
                runs.append({"step_s": step, "values": values, "errors": errors})
                print("%-10s dt = %-9g %s" % (scheme, step, "  ".join(
                    "%s %.3e" % (name.split("_")[0], errors[name]) for name in errors)))
            study["schemes"][scheme] = runs
            study["orders"][scheme] = {
                name: [math.log(a["errors"][name] / b["errors"][name])
                       / math.log(a["step_s"] / b["step_s"])
                       if a["errors"][name] > 0.0 and b["errors"][name] > 0.0 else float("nan")
                       for a, b in zip(runs, runs[1:])]
                for name, _, _ in QUANTITIES}
            print("%-10s observed orders: %s" % (scheme, "  ".join(
                "%s %s" % (name.split("_")[0], ", ".join("%.2f" % o for o in orders))
                for name, orders in study["orders"][scheme].items())))
        with open(os.path.join(arguments.output, "convergence.json"), "w", encoding="utf-8") as out:
            json.dump(study, out, indent=1)
        with open(os.path.join(arguments.output, "convergence.csv"), "w", encoding="utf-8") as out:
            names = [name for name, _, _ in QUANTITIES]
            out.write("scheme,step_s," + ",".join(names) + "," +
                      ",".join("error_" + n for n in names) + "\n")
            for scheme in SCHEMES:
                for r in study["schemes"][scheme]:
                    out.write("%s,%r,%s,%s\n" % (
                        scheme, r["step_s"], ",".join(repr(r["values"][n]) for n in names),
                        ",".join(repr(r["errors"][n]) for n in names)))
        if not arguments.no_plot and len(steps) > 1:
            plot(study, os.path.join(arguments.output, "convergence.png"))
    except StudyError as error:
        sys.exit("creep_convergence.py: error: %s" % error)


if __name__ == "__main__":
    main()
