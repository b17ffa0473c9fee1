#!/usr/bin/env bash
# Checks a creep CSV written by `sartor creep` for a constant-force
# creep-and-recovery test of a fabric with a LINEAR immediate-elastic modulus:
#
#   check_creep_csv.sh CSV SIGMA K E ALPHA LAMBDA_LOAD LAMBDA_UNLOAD T_LOAD T_END
#
# SIGMA in N/m, K and E in N/m, rates in 1/s, times in s. Checks
#  * the header, the first row (all zero) and that time never decreases;
#  * on every row: total = elastic + viscoelastic + permanent, the elastic
#    part equals (tension/K)(1 + eps_v + eps_p), the tension is SIGMA while
#    loading and 0 after, the permanent strain never decreases;
#  * at the end of loading (the loaded row at t = T_LOAD), to 1e-9 relative:
#      total = (1 + s/K)(1 + s/E (1 - exp(-lambda_l T))) - 1,  s = SIGMA,
#      eps_v = (1-alpha) s/E (1 - exp(-lambda_l T)), eps_p = alpha s/E (...);
#  * at T_END: eps_v = eps_v(T) exp(-lambda_u (T_END - T)), eps_p unchanged.
# Exit 0 when everything holds; otherwise prints what failed and exits 1.
set -u
if [ $# -ne 9 ]; then
  echo "usage: $0 CSV SIGMA K E ALPHA LAMBDA_LOAD LAMBDA_UNLOAD T_LOAD T_END" >&2
  exit 2
fi
csv=$1
[ -s "$csv" ] || { echo "check_creep_csv: $csv is missing or empty" >&2; exit 1; }

awk -F, -v sigma="$2" -v K="$3" -v E="$4" -v alpha="$5" -v ll="$6" -v lu="$7" \
    -v T="$8" -v tend="$9" -v file="$csv" '
function abs(x) { return x < 0 ? -x : x }
function fail(msg) { printf "check_creep_csv: %s:%d: %s\n", file, NR, msg > "/dev/stderr"; bad = 1 }
function close_to(got, want, rel) { return abs(got - want) <= rel * abs(want) + 1e-300 }
NR == 1 {
  if ($0 != "time_s,tension_N_per_m,strain_total,strain_elastic,strain_viscoelastic,strain_permanent")
    fail("unexpected header: " $0)
  next
}
{
  if (NF != 6) { fail("expected 6 fields, got " NF); next }
  t = $1 + 0; s = $2 + 0; tot = $3 + 0; el = $4 + 0; v = $5 + 0; p = $6 + 0
  rows++
  if (rows == 1 && (t != 0 || s != 0 || tot != 0 || el != 0 || v != 0 || p != 0))
    fail("the first row must be the unloaded start at t = 0, got " $0)
  if (rows > 1 && t < last_t) fail("time decreases: " t " after " last_t)
  if (rows > 1 && p < last_p) fail("permanent strain decreases: " p " after " last_p)
  # The parts add up (the program sums them in this order: exact).
  if (!close_to(el + (v + p), tot, 1e-14))
    fail(sprintf("total %.17g != elastic + viscoelastic + permanent %.17g", tot, el + v + p))
  # Tension: the test load while loading, zero in recovery (both rows at T).
  if (t > 0 && t < T && s != sigma) fail("tension " s " while loading, expected " sigma)
  if (t > T && s != 0) fail("tension " s " in recovery, expected 0")
  # Structural kinematics: elastic elongation over the rest length.
  want_el = s / K * (1 + v + p)
  if (!close_to(el, want_el, 1e-12))
    fail(sprintf("elastic strain %.17g, expected (tension/K)(1+eps_v+eps_p) = %.17g", el, want_el))
  if (t == T && s == sigma) { found_T = 1; tot_T = tot; v_T = v; p_T = p }
  last_t = t; last_p = p; last_row_t = t; last_v = v; last_tot = tot
}
END {
  if (rows < 10) { printf "check_creep_csv: %s: only %d rows\n", file, rows > "/dev/stderr"; exit 1 }
  creep = sigma / E * (1 - exp(-ll * T))
  want_tot = (1 + sigma / K) * (1 + creep) - 1
  if (!found_T) {
    printf "check_creep_csv: %s: no loaded row at t = %s\n", file, T > "/dev/stderr"; bad = 1
  } else {
    if (!close_to(tot_T, want_tot, 1e-9)) {
      printf "check_creep_csv: %s: end-of-loading total %.17g, expected %.17g\n", file, tot_T, want_tot > "/dev/stderr"; bad = 1
    }
    if (!close_to(v_T, (1 - alpha) * creep, 1e-9) || !close_to(p_T, alpha * creep, 1e-9)) {
      printf "check_creep_csv: %s: end-of-loading eps_v %.17g eps_p %.17g, expected %.17g %.17g\n", file, v_T, p_T, (1 - alpha) * creep, alpha * creep > "/dev/stderr"; bad = 1
    }
  }
  if (last_row_t != tend) {
    printf "check_creep_csv: %s: last row at t = %.17g, expected %s\n", file, last_row_t, tend > "/dev/stderr"; bad = 1
  } else {
    want_v = (1 - alpha) * creep * exp(-lu * (tend - T))
    if (!close_to(last_v, want_v, 1e-9) || !close_to(last_p, alpha * creep, 1e-9)) {
      printf "check_creep_csv: %s: final eps_v %.17g eps_p %.17g, expected %.17g %.17g\n", file, last_v, last_p, want_v, alpha * creep > "/dev/stderr"; bad = 1
    }
  }
  if (bad) exit 1
  printf "check_creep_csv: %s: %d rows OK; end-of-loading total strain %.12g (expected %.12g)\n", file, rows, tot_T, want_tot
}' "$csv"
