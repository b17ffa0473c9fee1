#!/usr/bin/python3
"""The extension module sartor._sartor called directly, in one process:

1. a strip held along one short edge and pulled on the other by a line
   tension T, given as a dict case with a linear warp modulus K and no
   Poisson coupling: the tension is uniform, so the free edge moves by
   L T / K and every triangle's warp tension is T (this test's closed form),
   within 1 %; the arrays agree with the summary and with each other, and
   are the numbers the run wrote to result.h5 and summary.json;
2. the same process runs it again, with another modulus in between, and gets
   the same numbers (no state carried from call to call);
3. a bad option value, an unknown option, a PETSc type PETSc does not know
   and a missing PETSc options file raise sartor InputError (a ValueError)
   with the option named, and the process runs on;
4. PETSc options set once (set_petsc_options) reach every later run: an
   option nothing reads comes back in unused_options until cleared;
5. a run that fails raises SolveFailure with what it reached in .result.

  test_extension.py REPO_ROOT BUILD_DIR
"""
import os
import sys
import tempfile

root, build = sys.argv[1], sys.argv[2]
os.environ["SARTOR_BUILD_DIR"] = build
sys.path.insert(0, os.path.join(root, "python"))
os.chdir(root)
import numpy as np  # noqa: E402
import sartor  # noqa: E402
from sartor import _sartor  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    print(("ok    " if condition else "FAIL  ") + message)


def output():
    return tempfile.mkdtemp(prefix="sartor_extension_")


length, width, force = 0.15, 0.08, 20.0  # m, m, N
tension = force / width  # N/m
strip = {"mesh": "rectangle", "mesh_width": length, "mesh_height": width, "mesh_nx": 6,
         "mesh_ny": 4, "membrane_model": "baraff_witkin", "warp_modulus": 5000.0,
         "weft_modulus": 5000.0, "shear_modulus": 500.0, "bending_stiffness": 1e-6,
         "gravity": (0, 0, 0), "pin_box": (-0.001, 0.001, -1, 1, -1, 1),
         "edge_force": (force, 0, 0), "edge_force_box": (length - 0.001, length + 0.001, -1, 1, -1, 1),
         "probe": (length, width / 2, 0)}


def stretch(modulus):
    folder = output()
    result = _sartor.run(strip, folder, options={"warp_modulus": modulus})
    result["directory"] = folder
    return result, result["summary"]["probe"]["displacement_m"][0]


check(sartor.backend() == "extension", "sartor uses the extension module")
result, moved = stretch(5000.0)
expected = length * tension / 5000.0
check(abs(moved - expected) < 0.01 * expected,
      f"strip: free edge moved {moved:.6e} m, closed form L T / K = {expected:.6e} m")
warp = result["cell_fields"]["tension_warp"]
check(np.all(np.abs(warp - tension) < 0.01 * tension),
      f"strip: warp tension {warp.min():.2f} to {warp.max():.2f} N/m, T = {tension:.2f} N/m")
vertices, triangles = result["summary"]["mesh"]["vertices"], result["summary"]["mesh"]["triangles"]
check(result["positions"].shape == (vertices, 3) and result["triangles"].shape == (triangles, 3)
      and result["material_uv"].shape == (triangles, 3, 2) and warp.shape == (triangles,),
      f"arrays: {vertices} vertices, {triangles} triangles as the summary says")
check(np.allclose(result["positions"] - result["initial_positions"], result["displacement"],
                  rtol=0, atol=1e-12 * length),
      "displacement = positions - initial_positions")
check(result["units"]["fields/position"] == "m" and
      result["units"]["cell_fields/tension_warp"] == "N/m", "units as result.h5 names them")

written = sartor.Result(result["directory"])  # what the same run wrote, read back
check(all(np.array_equal(result[name], getattr(written, name))
          for name in ["positions", "initial_positions", "triangles", "material_uv", "fabric_ids"])
      and all(np.array_equal(result["cell_fields"][name], written.cell_fields[name])
              for name in written.cell_fields)
      and result["units"] == written.units and result["summary"] == written.summary,
      "the arrays in memory are those result.h5 and summary.json hold")

stretch(8000.0)
_, again = stretch(5000.0)
check(abs(again - moved) < 1e-6 * expected, f"the same run again in the process: {again:.9e} m")

for options, named in [({"mesh_nx": "six"}, "mesh-nx"), ({"mesh_nq": 6}, "mesh-nq")]:
    try:
        _sartor.run(strip, output(), options=options)
        check(False, f"{options} raised nothing")
    except sartor.InputError as error:
        check(isinstance(error, ValueError) and named in str(error),
              f"{options}: InputError: {error}")
try:
    _sartor.run(strip, output(), petsc={"pc_type": "no_such_preconditioner"})
    check(False, "an unknown PETSc preconditioner raised nothing")
except sartor.InputError as error:
    check("no_such_preconditioner" in str(error), f"unknown PETSc type: InputError: {error}")
try:
    _sartor.run(strip, output(), petsc={"options_file_yaml": "no/such/file.yaml"})
    check(False, "a missing options file raised nothing")
except sartor.InputError as error:
    check("no/such/file.yaml" in str(error), f"missing options file: InputError: {error}")

_sartor.set_petsc_options({"not_read_by_anything": 3})
unused = _sartor.run(strip, output())["unused_options"]
check(unused == ["-not_read_by_anything 3"], f"a set PETSc option reaches the run: {unused}")
_sartor.set_petsc_options({})
unused = _sartor.run(strip, output())["unused_options"]
check(unused == [], f"and is gone once cleared: {unused}")

try:
    _sartor.run(strip, output(), options={"load_steps": 1}, petsc={"snes_max_it": 1})
    check(False, "a solve stopped after one iteration raised nothing")
except sartor.SolveFailure as error:
    reached = error.result
    check(reached is not None and reached["positions"].shape == (vertices, 3)
          and not reached["summary"]["converged"],
          f"SolveFailure with what it reached: {str(error).splitlines()[0]}")

if failures:
    sys.exit("test_extension: %d failure(s):\n%s" % (len(failures), "\n".join(failures)))
print("test_extension: the extension module runs, agrees with L T / K and reports errors")
