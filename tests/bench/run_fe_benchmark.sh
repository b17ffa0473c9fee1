#!/usr/bin/env bash
# Runs the finite-element benchmark (sartor-bench-fe: static solve of a hanging
# sheet) on 1 and 2 MPI ranks, one process per mesh size and rank count, and
# collects the results under OUTDIR:
#
#   OUTDIR/fe_benchmark.csv   one row per (size, ranks), columns as sartor-bench-fe --csv
#   OUTDIR/fe_benchmark.json  {"runs": [...]}: every run's --json document
#   OUTDIR/fe_benchmark.png   time against triangles (postproc/plot_fe_benchmark.py)
#   OUTDIR/runs/              each run's CSV, JSON and log
#
# It measures; it never fails on time. A run that fails or exceeds --timeout is
# logged and the larger sizes of that rank count are skipped.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${SARTOR_BUILD_DIR:-$root/build}"
sizes="71,141,224,447,708"
ranks_list="1,2"
timeout_s=1800
plot=1
bench=""

usage() {
  cat <<EOF
usage: tests/bench/run_fe_benchmark.sh OUTDIR [--sizes N,N,...] [--ranks R,R,...]
                                       [--timeout S] [--bench PATH] [--no-plot]
                                       [-- sartor-bench-fe/PETSc options]

  --sizes N,...  cells per side of the sheet (default $sizes; 2 N^2 triangles:
                 71, 224, 708 give about 1e4, 1e5, 1e6)
  --ranks R,...  MPI rank counts (default $ranks_list)
  --timeout S    wall-clock limit of one run in seconds (default $timeout_s)
  --bench PATH   the sartor-bench-fe executable
                 (default \$SARTOR_BUILD_DIR/tests/bench/sartor-bench-fe, build/ by default)
  --no-plot      do not run postproc/plot_fe_benchmark.py
  -- ...         passed on to every run, e.g. -- --solver mumps, -- -ksp_type gmres
EOF
}

outdir=""
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --sizes) sizes="${2:?--sizes needs a value}"; shift 2 ;;
    --ranks) ranks_list="${2:?--ranks needs a value}"; shift 2 ;;
    --timeout) timeout_s="${2:?--timeout needs a value}"; shift 2 ;;
    --bench) bench="${2:?--bench needs a value}"; shift 2 ;;
    --no-plot) plot=0; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    -*) echo "run_fe_benchmark.sh: unknown option $1" >&2; usage >&2; exit 2 ;;
    *)
      [[ -z "$outdir" ]] || { echo "run_fe_benchmark.sh: one OUTDIR only" >&2; exit 2; }
      outdir="$1"; shift ;;
  esac
done
[[ -n "$outdir" ]] || { usage >&2; exit 2; }
bench="${bench:-$build_dir/tests/bench/sartor-bench-fe}"
if [[ ! -x "$bench" ]]; then
  echo "run_fe_benchmark.sh: $bench: not built (cmake --build $build_dir --target sartor-bench-fe)" >&2
  exit 2
fi

# More ranks than cores is allowed (timings then mean little); Open MPI refuses root unless told.
mpi_flags=(--oversubscribe)
[[ "$(id -u)" == 0 ]] && mpi_flags+=(--allow-run-as-root)
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

mkdir -p "$outdir/runs"
IFS=, read -r -a size_array <<<"$sizes"
IFS=, read -r -a rank_array <<<"$ranks_list"
declare -A stopped=()
results=()
echo "run_fe_benchmark.sh: sizes ${sizes}, ranks ${ranks_list}, $(getconf _NPROCESSORS_ONLN) cores, output in $outdir"
for n in "${size_array[@]}"; do
  for ranks in "${rank_array[@]}"; do
    name="fe_r${ranks}_n${n}"
    if [[ -n "${stopped[$ranks]:-}" ]]; then
      echo "== $name: skipped (${stopped[$ranks]})"
      continue
    fi
    echo "== $name"
    rm -f "$outdir/runs/$name.csv" "$outdir/runs/$name.json"
    set +e
    timeout --signal=TERM --kill-after=30 "$timeout_s" \
      mpiexec -n "$ranks" "${mpi_flags[@]}" "$bench" --sizes "$n" \
      --csv "$outdir/runs/$name.csv" --json "$outdir/runs/$name.json" "${extra[@]}" \
      2>&1 | tee "$outdir/runs/$name.log"
    rc=${PIPESTATUS[0]}
    set -e
    if [[ $rc -eq 0 && -s "$outdir/runs/$name.json" ]]; then
      results+=("$name")
    else
      reason="n = $n failed with status $rc"
      [[ $rc -eq 124 || $rc -eq 137 ]] && reason="n = $n exceeded ${timeout_s} s"
      echo "== $name: $reason; see $outdir/runs/$name.log"
      stopped[$ranks]="$reason"
    fi
  done
done

if [[ ${#results[@]} -eq 0 ]]; then
  echo "run_fe_benchmark.sh: no run finished" >&2
  exit 1
fi
{
  head -n 1 "$outdir/runs/${results[0]}.csv"
  for name in "${results[@]}"; do tail -n +2 "$outdir/runs/$name.csv"; done
} >"$outdir/fe_benchmark.csv"
{
  echo '{"runs": ['
  separator=""
  for name in "${results[@]}"; do
    printf '%s' "$separator"
    cat "$outdir/runs/$name.json"
    separator=","
  done
  echo ']}'
} >"$outdir/fe_benchmark.json"
echo "run_fe_benchmark.sh: wrote $outdir/fe_benchmark.csv and $outdir/fe_benchmark.json"

if [[ $plot -eq 1 ]]; then
  if [[ -x /usr/bin/python3 ]]; then
    /usr/bin/python3 "$root/postproc/plot_fe_benchmark.py" "$outdir" ||
      echo "run_fe_benchmark.sh: plotting failed (the data files are written)" >&2
  else
    echo "run_fe_benchmark.sh: /usr/bin/python3 not found; no plot" >&2
  fi
fi
