#!/usr/bin/env bash
# The sample cases of cases/fe that no other test runs, as a user would run
# them: each must end with exit status 0 and a certified equilibrium. They
# were written for the SNES path and stopped at its iteration budget once
# the static minimiser became run's default, unseen.
#   run_sample_cases.sh SARTOR OUT CASE.yaml...
set -euo pipefail
sartor=$1 out=$2
shift 2
failed=()
for case in "$@"; do
  name=$(basename "$case" .yaml)
  if "$sartor" run "$case" --no-plot --output "$out/$name" > "$out/$name.log" 2>&1 &&
    grep -q "certificate: certified" "$out/$name.log"; then
    echo "$name: $(tail -1 "$out/$name.log")"
  else
    cat "$out/$name.log" >&2
    failed+=("$name")
  fi
done
[ ${#failed[@]} -eq 0 ] || { echo "failed: ${failed[*]}" >&2; exit 1; }
