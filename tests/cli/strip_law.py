"""The creep strip's FE elongation against `sartor creep` (the material law),
shared by the CLI tests of the creep analysis (run with /usr/bin/python3)."""

import csv

STRIP_LENGTH = 0.15  # m, cases/creep/strip.yaml along the load


def law_strains(law_csv):
    """Time (s) -> total strain of `sartor creep`; after a jump its right side."""
    return {float(r["time_s"]): float(r["strain_total"]) for r in csv.DictReader(open(law_csv))}


def compare(law, run_csv):
    """Output times of the run that the law has, and the worst relative
    difference of the probe's elongation / length from the law there."""
    compared, worst = 0, 0.0
    for row in csv.DictReader(open(run_csv)):
        t = float(row["time_s"])
        if t in law:
            fe = float(row["probe_dx_m"]) / STRIP_LENGTH
            worst = max(worst, abs(fe - law[t]) / abs(law[t]))
            compared += 1
    return compared, worst
