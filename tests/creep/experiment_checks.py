"""Checks shared by the thesis-experiment tests (tests/creep/experiment_*.sh;
run with /usr/bin/python3): runs that did not finish, and a measure that
must grow from run to run."""


def unfinished(runs, prefix=""):
    """A failure line for each run that did not converge or complete."""
    return [f"{prefix}{r['label']}: converged {r['converged']}, completed {r['completed']}"
            for r in runs if not (r["converged"] and r["completed"])]


def rising(runs, key, unit=""):
    """Failure lines unless `key` is positive in the first run and more than
    20 % above the previous run's in each next one."""
    values = [r[key] for r in runs]
    failures = []
    if not values[0] > 0.0:
        failures.append(f"{key} of {runs[0]['label']} is not positive: {values[0]}")
    for a, b, la, lb in zip(values, values[1:], runs, runs[1:]):
        if not b > 1.2 * a:
            failures.append(f"{key}: {lb['label']} {b:.4g}{unit} is not 20 % above "
                            f"{la['label']} {a:.4g}{unit}")
    return failures
