# Read by ctest before it runs the suite (the TEST_INCLUDE_FILES of tests/):
# Open MPI's default PML first tries UCX, which makes every process that
# initialises MPI (each gtest, each sartor run) wait 0.2 s on a machine
# without a fast network; the suite's thousand-odd such processes waited
# minutes. On one node ob1 over shared memory carries every message the
# tests send. A value set by the user wins.
if(NOT DEFINED ENV{OMPI_MCA_pml})
  set(ENV{OMPI_MCA_pml} ob1)
endif()
