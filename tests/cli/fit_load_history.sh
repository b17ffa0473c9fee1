#!/usr/bin/env bash
# sartor fit --load-history on a ramped test: 5 s ramp to 2452.5 N/m, 1 h
# hold, 5 s ramp down, 1 h recovery, the strain computed here from the creep
# law's ODE by classical Runge-Kutta (independent of the code under test),
# log-sampled after each load change, noise 2e-4. The fit must converge and
# put every generating parameter within 3 standard errors, RMSE within 5% of
# the noise.
#
#   fit_load_history.sh SARTOR WORKDIR
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SARTOR WORKDIR" >&2; exit 2; }
sartor=$1 work=$2
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
"$python" - "$work" <<'PY'
import math, random, sys
work = sys.argv[1]
K, E, alpha, ll, lu = 51200.0, 25600.0, 0.667, 0.0331, 0.0147  # denim warp, Table 5.1
sigma, hour, ramp = 2452.5, 3600.0, 5.0
knots = [(0.0, 0.0), (ramp, sigma), (ramp + hour, sigma), (2 * ramp + hour, 0.0)]
with open(f"{work}/history.csv", "w") as f:
    f.write("Time (min),Tension (N/mm)\n")
    for t, s in knots:
        f.write(f"{t / 60!r},{s / 1000!r}\n")

def tension(t):
    for (t0, s0), (t1, s1) in zip(knots, knots[1:]):
        if t < t1:
            return s0 + (s1 - s0) * (t - t0) / (t1 - t0) if t >= t0 else s0
    return knots[-1][1]

def rate(t, v, p):
    sat = max(tension(t), 0.0) / E
    tv, tp = (1 - alpha) * sat, alpha * sat
    return ((ll if v < tv else lu) * (tv - v), ll * (tp - p) if p < tp else 0.0)

random.seed(7)
times = []
for change, until in ((0.0, ramp + hour), (ramp + hour, 2 * hour + 2 * ramp)):
    n = 800
    for i in range(n):
        since = math.exp(math.log(1e-3) + (math.log(until - change) - math.log(1e-3)) * i / (n - 1))
        times.append(change + min(since, (until - change) * (1 - 1e-9)))
stops = sorted(set(times + [k[0] for k in knots]))
v = p = now = 0.0
strain = {}
for stop in stops:
    while now < stop:
        h = min(0.05, stop - now)
        k1 = rate(now, v, p)
        k2 = rate(now + h / 2, v + h / 2 * k1[0], p + h / 2 * k1[1])
        k3 = rate(now + h / 2, v + h / 2 * k2[0], p + h / 2 * k2[1])
        k4 = rate(now + h, v + h * k3[0], p + h * k3[1])
        v += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        p += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        now += h
    now = stop
    strain[stop] = (1 + tension(stop) / K) * (1 + v + p) - 1
with open(f"{work}/ramped.csv", "w") as f:
    f.write("# parameters: elastic_modulus_N_per_m=51200 E_N_per_m=25600 alpha=0.667 "
            "lambda_load_per_s=0.0331 lambda_unload_per_s=0.0147\n")
    f.write("time_s,strain\n")
    for t in times:
        f.write(f"{t!r},{strain[t] + random.gauss(0.0, 2e-4)!r}\n")
PY
"$sartor" fit "$work/ramped.csv" --load-history "$work/history.csv" --bootstrap 0 --no-plot \
  --output "$work/fit"
"$python" - "$work" <<'PY'
import json, sys
work = sys.argv[1]
fit = json.load(open(f"{work}/fit/fit.json"))
truth = {"elastic_modulus_N_per_m": 51200, "E_N_per_m": 25600, "alpha": 0.667,
         "lambda_load_per_s": 0.0331, "lambda_unload_per_s": 0.0147}
failures = []
if not fit["solver"]["converged"] or fit["input"]["load_history_knots"] != 4:
    failures.append(f"solver {fit['solver']}, knots {fit['input']['load_history_knots']}")
if abs(fit["goodness"]["rmse"] / 2e-4 - 1) > 0.05:
    failures.append(f"RMSE {fit['goodness']['rmse']}")
for key, want in truth.items():
    p = fit["parameters"][key]
    if abs(p["value"] - want) > 3 * p["std_error"]:
        failures.append(f"{key}: {p['value']} +- {p['std_error']}, generated with {want}")
if failures:
    sys.exit("fit_load_history: FAILED\n  " + "\n  ".join(failures))
print(f"fit_load_history: RMSE / noise {fit['goodness']['rmse'] / 2e-4:.3f}, "
      "parameters within 3 standard errors")
PY
