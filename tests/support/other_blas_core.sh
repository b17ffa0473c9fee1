# Sourced by the tests that run a job twice with different BLAS round-off.
# other_blas_core SARTOR: prints an OPENBLAS_CORETYPE whose kernels differ
# from the ones SARTOR runs here (OPENBLAS_CORETYPE where it is set, else
# what OpenBLAS detects: Prescott's on processors it does not know, such as
# a virtual "Intel Xeon Processor"): Haswell's (AVX2) where the CPU has AVX2
# and runs other kernels, else Prescott's (SSE3). Forcing the native kernels
# instead would compare a run with itself. Names both on standard error.
other_blas_core() {
  local native other=Prescott
  native=$(OPENBLAS_VERBOSE=2 "$1" --version 2>&1 | sed -n 's/^Core: //p' | head -n 1)
  if [ "$native" != Haswell ] && grep -qw avx2 /proc/cpuinfo; then
    other=Haswell
  fi
  echo "BLAS kernels: ${native:-unknown} natively, $other for the second run" >&2
  echo "$other"
}
