"""Run Sartor from Python and get its results as numpy arrays.

A thin layer over the `sartor` executable: `run` and `drape` build its
command line from keyword arguments, run it, and read what it wrote
(summary.json, result.h5, series.h5) into a `Result`. Nothing is computed
here; the executable does the work and the files are the interface
(docs/formats.md). Documentation and examples: docs/python.md.

Needs numpy and h5py (Debian python3-numpy, python3-h5py); use
/usr/bin/python3.
"""

import json
import os
import shutil
import subprocess
import tempfile

import h5py
import numpy as np

__all__ = ["run", "drape", "Result", "Series", "SartorError", "executable", "command_line"]


class SartorError(RuntimeError):
    """`sartor` failed: the message is its own, with the command line and log."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result  # what it wrote, when anything (a drape that did not converge)


def executable():
    """The `sartor` executable: $SARTOR_EXE, else the build of this checkout, else PATH."""
    if os.environ.get("SARTOR_EXE"):
        return os.environ["SARTOR_EXE"]
    here = os.path.dirname(os.path.abspath(__file__))
    built = os.path.join(here, "..", "..", "build", "solvers", "sartor")
    if os.access(built, os.X_OK):
        return os.path.normpath(built)
    found = shutil.which("sartor")
    if found:
        return found
    raise SartorError("no sartor executable: build it (./dev build) or set SARTOR_EXE")


def _option_words(options, petsc):
    """--name value words of keyword options (underscores become dashes).

    True gives a flag (--kinetic-damping), False and None leave it out; a list
    or tuple is joined with commas (gravity=(0, 0, -9.81)); petsc maps PETSc
    options without their dash to values (None: a flag).
    """
    words = []
    for name, value in options.items():
        if value is None or value is False:
            continue
        words.append("--" + name.replace("_", "-"))
        if value is not True:
            words.append(",".join(map(str, value)) if isinstance(value, (list, tuple)) else str(value))
    for name, value in (petsc or {}).items():
        words.append("-" + name)
        if value is not None:
            words.append(str(value))
    return words


def command_line(command, argument, output, plot=False, petsc=None, **options):
    """The words `run` and `drape` execute (for logs and scripts)."""
    words = [executable(), command, str(argument), "--output", str(output)]
    if not plot:
        words.append("--no-plot")
    return words + _option_words(options, petsc)


def _execute(command, argument, output, plot, petsc, check, options):
    if output is None:
        output = tempfile.mkdtemp(prefix="sartor_%s_" % command)
    words = command_line(command, argument, output, plot, petsc, **options)
    done = subprocess.run(words, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    written = os.path.isfile(os.path.join(output, "summary.json"))
    result = Result(output, done.stdout) if written else None
    if done.returncode != 0 and check:
        raise SartorError("`%s` failed (exit %d):\n%s" % (" ".join(words), done.returncode,
                                                         done.stdout.strip()), result)
    if result is None:
        raise SartorError("`%s` wrote no summary.json:\n%s" % (" ".join(words), done.stdout.strip()))
    return result


def run(case, output=None, plot=False, petsc=None, check=True, **options):
    """`sartor run CASE` with options; returns its Result.

    case: a case file (YAML). output: the folder (default: a new temporary
    one). plot: also draw result.png. petsc: PETSc options, e.g.
    {"snes_rtol": 1e-8}. check: raise SartorError when sartor fails (else
    return what it wrote). options: any option of `sartor run --help`, with
    underscores for dashes: mesh_nx=8, fabric="silk", analysis="dynamic".
    """
    return _execute("run", case, output, plot, petsc, check, options)


def drape(pattern, output=None, plot=False, petsc=None, check=True, **options):
    """`sartor drape PATTERN` with options (see `sartor drape --help`); returns its Result.

    A case file of cases/garments goes in as petsc={"options_file_yaml": FILE}.
    """
    return _execute("drape", pattern, output, plot, petsc, check, options)


def _names(dataset):
    names = dataset.attrs.get("names")
    if names is None:
        return []
    return [n.decode() if isinstance(n, bytes) else str(n) for n in np.atleast_1d(names)]


class Series:
    """The states of series.h5: times (s) and, per state, positions and cell fields."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            steps = sorted(f["/steps"].keys()) if "/steps" in f else []
            self.times = np.array([f["/steps/%s/time" % k][0] for k in steps])
            self.positions = np.array([f["/steps/%s/fields/position" % k][:] for k in steps])
            names = list(f["/steps/%s/cell_fields" % steps[0]]) if steps else []
            self.cell_fields = {n: np.array([f["/steps/%s/cell_fields/%s" % (k, n)][:] for k in steps])
                                for n in names}

    def __len__(self):
        return len(self.times)


class Result:
    """What a run or drape wrote in `directory`, as numpy arrays.

    summary      summary.json as a dict
    log          what sartor printed
    positions    (vertices, 3) final positions, m
    initial_positions, displacement   (vertices, 3), m
    triangles    (triangles, 3) vertex indices
    material_uv  (triangles, 3, 2) material (u, v) of each corner, m
    cell_fields  dict name -> (triangles,) array: strain_warp, strain_weft,
                 strain_shear (1), tension_warp, tension_weft (N/m)
    units        dict dataset name -> unit, as result.h5 records them
    fabric_ids, fabric_names, panel_ids, panel_names (empty without panels)
    series()     the time series (dynamic and creep runs, drapes), a Series
    """

    def __init__(self, directory, log=""):
        self.directory = directory
        self.log = log
        with open(os.path.join(directory, "summary.json"), encoding="utf-8") as stream:
            self.summary = json.load(stream)
        path = os.path.join(directory, "result.h5")
        if not os.path.isfile(path):
            raise SartorError("%s: no result.h5 (the run stopped before its result)" % directory)
        with h5py.File(path, "r") as f:
            self.positions = f["/fields/position"][:]
            self.displacement = f["/fields/displacement"][:]
            self.initial_positions = f["/mesh/initial_position"][:]
            self.triangles = f["/mesh/triangles"][:]
            self.material_uv = f["/mesh/material_uv"][:].reshape(-1, 3, 2)
            self.cell_fields = {n: f["/cell_fields/" + n][:] for n in f["/cell_fields"]}
            self.fabric_ids = f["/mesh/fabric_id"][:]
            self.fabric_names = _names(f["/mesh/fabric_id"])
            has_panels = "/mesh/panel_id" in f
            self.panel_ids = f["/mesh/panel_id"][:] if has_panels else np.zeros(0, dtype=int)
            self.panel_names = _names(f["/mesh/panel_id"]) if has_panels else []
            self.units = {}
            f.visititems(lambda name, item: self.units.__setitem__(name, _text(item.attrs.get("units", "")))
                         if isinstance(item, h5py.Dataset) else None)

    def series(self):
        path = os.path.join(self.directory, "series.h5")
        if not os.path.isfile(path):
            raise SartorError("%s: no series.h5 (static runs have none)" % self.directory)
        return Series(path)

    def __repr__(self):
        return "<sartor.Result %s: %d vertices, %d triangles>" % (
            self.directory, len(self.positions), len(self.triangles))


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)
