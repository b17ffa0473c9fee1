#!/usr/bin/python3
"""Runs the Python examples of docs/python.md exactly as written (every
```python block, in order, from the top folder of the checkout) and checks
their numbers against this test's own references:

1. fabric sweep: the strip's free edge moves by L T / E (L = 0.15 m,
   T = 196.133 N / 0.08 m, E = the fabrics' elastic moduli 2E of the
   thesis' Table 5.1, this file's own table), within 2 %;
2. convergence study: the error against Hencky's series falls from mesh to
   mesh and is below 0.2 % on the finest;
3. drape: both panels named, every triangle in one, the fall recorded.

  run_doc_examples.py REPO_ROOT SARTOR_EXECUTABLE
Fails (never skips) when numpy or h5py is missing.
"""
import os
import re
import sys

root, exe = sys.argv[1], sys.argv[2]
os.environ["SARTOR_EXE"] = exe
sys.path.insert(0, os.path.join(root, "python"))
os.chdir(root)
with open(os.path.join(root, "docs", "python.md"), encoding="utf-8") as stream:
    blocks = re.findall(r"```python\n(.*?)```", stream.read(), re.S)
if len(blocks) != 3:
    sys.exit(f"docs/python.md has {len(blocks)} python blocks, this test knows 3")
spaces = []
for number, block in enumerate(blocks, start=1):
    print(f"--- docs/python.md example {number}")
    namespace = {"__name__": "__main__"}
    exec(compile(block, f"docs/python.md example {number}", "exec"), namespace)
    spaces.append(namespace)

failures = []
elastic = {"cotton_twill": 65200.0, "silk": 108000.0, "polyester": 160800.0}  # warp 2E, N/m
tension = 196.133 / 0.08
for fabric, modulus in elastic.items():
    expected = 0.15 * tension / modulus
    got = spaces[0]["stretch"][fabric]
    if abs(got - expected) > 0.02 * expected:
        failures.append(f"{fabric}: stretch {got} m, expected {expected} m")
errors = spaces[1]["errors"]
if not (errors[0] > errors[1] > errors[2] and errors[2] < 2e-3):
    failures.append(f"Hencky errors do not fall: {errors}")
skirt = spaces[2]["skirt"]
if skirt.panel_names != ["skirt_front", "skirt_back"]:
    failures.append(f"panel names {skirt.panel_names}")
if sorted(set(skirt.panel_ids.tolist())) != [0, 1] or len(skirt.panel_ids) != len(skirt.triangles):
    failures.append("panel ids do not cover the triangles")
if len(spaces[2]["fall"]) < 2 or spaces[2]["moved"].max() <= 0:
    failures.append("the drape's fall was not recorded")
if failures:
    sys.exit("\n".join(failures))
print("run_doc_examples: the three examples of docs/python.md ran and agree")
