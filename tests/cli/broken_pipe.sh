#!/usr/bin/env bash
# A closed pipe and a termination signal end sartor cleanly: no PETSc
# traceback ("Caught signal", MPI_ABORT), the signal's own exit status.
#
#   broken_pipe.sh SARTOR WORKDIR
set -uo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SARTOR WORKDIR" >&2; exit 2; }
sartor=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "broken_pipe: $*" >&2; cat "$work"/*.err >&2; exit 1; }
traceback='PETSC ERROR|Caught signal|MPI_ABORT|internal error'

# `sartor creep | head -1`: the reader goes away after one line.
"$sartor" creep --no-plot --output "$work/creep" 2> "$work/pipe.err" | head -1 > /dev/null
status=${PIPESTATUS[0]}
[ "$status" -eq 0 ] || [ "$status" -eq 141 ] || fail "exit status $status after a closed pipe"
grep -Eq "$traceback" "$work/pipe.err" && fail "a traceback after a closed pipe"

# SIGTERM during a long dynamic run.
"$sartor" run "$(dirname "$0")/../../cases/fe/hanging_sheet.yaml" --analysis dynamic \
  --time-end 1000 --mesh-nx 30 --mesh-ny 30 --output "$work/run" 2> "$work/term.err" > /dev/null &
pid=$!
sleep 3
kill -TERM "$pid"
wait "$pid"
status=$?
[ "$status" -eq 143 ] || fail "exit status $status after SIGTERM (expected 143)"
grep -Eq "$traceback" "$work/term.err" && fail "a traceback after SIGTERM"
grep -q "sartor: interrupted" "$work/term.err" || fail "no note of the interruption"
echo "broken_pipe: closed pipe and SIGTERM end cleanly"
