#!/usr/bin/env bash
# sartor validate on synthetic tests at two load levels: the fit of the full
# load (20 kgf) must predict the half load of the same fabric within the noise
# (RMSE within 10% of the fit's residual s.d., 92-98% of the samples inside the
# 95% prediction interval) and must flag another fabric's test (RMSE over 3x).
#
#   validate_two_levels.sh SARTOR WORKDIR
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SARTOR WORKDIR" >&2; exit 2; }
sartor=$1 work=$2
python=/usr/bin/python3
[ -x "$python" ] || { echo "error: $python not found (./dev deps installs it)" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
"$sartor" synth --fabric denim:warp --samples 6000 --seed 11 --output "$work/full.csv"
"$sartor" synth --fabric denim:warp --samples 6000 --seed 12 --force 98.0665 \
  --output "$work/half.csv"
"$sartor" synth --fabric nylon:weft --samples 6000 --seed 13 --force 98.0665 \
  --output "$work/other.csv"
"$sartor" validate "$work/full.csv" "$work/half.csv" --no-plot --output "$work/same"
"$sartor" validate "$work/full.csv" "$work/other.csv" --no-plot --output "$work/other"
"$python" - "$work" <<'PY'
import json, sys
work = sys.argv[1]
failures = []
same = json.load(open(f"{work}/same/validate.json"))["prediction"]
other = json.load(open(f"{work}/other/validate.json"))["prediction"]
if not 0.9 <= same["rmse_over_fit_residual_std"] <= 1.1:
    failures.append(f"same fabric: RMSE / residual s.d. {same['rmse_over_fit_residual_std']}")
if not 0.92 <= same["fraction_within_prediction_interval"] <= 0.98:
    failures.append(f"same fabric: {same['fraction_within_prediction_interval']} inside")
if not other["rmse_over_fit_residual_std"] > 3:
    failures.append(f"other fabric: RMSE / residual s.d. {other['rmse_over_fit_residual_std']}")
with open(f"{work}/same/validate.csv") as f:
    rows = f.read().splitlines()
header = "time_s,strain_measured,strain_predicted,band_low,band_high,interval_half_width,error"
if rows[0] != header or len(rows) != 6001:
    failures.append(f"validate.csv: header {rows[0]}, {len(rows) - 1} rows")
for row in rows[1:]:
    t, measured, predicted, low, high, interval, error = map(float, row.split(","))
    if not (low <= predicted <= high and high - predicted <= interval
            and abs(error - (measured - predicted)) <= 1e-15):
        failures.append(f"validate.csv row {row}")
        break
if failures:
    sys.exit("validate_two_levels: FAILED\n  " + "\n  ".join(failures))
print(f"validate_two_levels: same fabric RMSE/s {same['rmse_over_fit_residual_std']:.3f}, "
      f"{100 * same['fraction_within_prediction_interval']:.1f}% inside; other fabric "
      f"RMSE/s {other['rmse_over_fit_residual_std']:.1f}")
PY
