"""Run Sartor from Python and get its results as numpy arrays.

`run` and `drape` run `sartor run` and `sartor drape` and return a `Result`.
Where the extension module `sartor._sartor` is built (pybind11; ./dev
build), they run in this process, with the commands' own code, and the
results come back as arrays without files being read; otherwise they run
the `sartor` executable and read what it wrote (summary.json, result.h5).
Both give the same Result. Documentation and examples: docs/python.md.

Needs numpy and h5py (Debian python3-numpy, python3-h5py); use
/usr/bin/python3.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import warnings

import h5py
import numpy as np

__all__ = ["run", "drape", "Result", "Series", "SartorError", "InputError", "SolveFailure",
           "set_petsc_options", "backend", "executable", "command_line"]

_here = os.path.dirname(os.path.abspath(__file__))


def _build_dir():
    """$SARTOR_BUILD_DIR, else the build/ folder of this checkout."""
    return os.environ.get("SARTOR_BUILD_DIR") or os.path.join(_here, "..", "..", "build")


# The extension module lands in BUILD/python/sartor (python/CMakeLists.txt);
# SARTOR_BACKEND=executable leaves it out.
__path__.append(os.path.normpath(os.path.join(_build_dir(), "python", "sartor")))
_extension = None
if os.environ.get("SARTOR_BACKEND", "extension") != "executable":
    try:
        from . import _sartor as _extension
    except ModuleNotFoundError:
        _extension = None  # not built: the executable
    except ImportError as error:  # built but unloadable: say so, use the executable
        warnings.warn("sartor: the extension module does not load (%s); running the "
                      "executable instead" % error)
        _extension = None

if _extension is not None:
    SartorError = _extension.Error
    InputError = _extension.InputError
    SolveFailure = _extension.SolveFailure
else:
    class SartorError(RuntimeError):
        """`sartor` failed: the message is its own, with the command line and log."""

        def __init__(self, message, result=None):
            super().__init__(message)
            self.result = result  # what it wrote, when anything (a drape that did not converge)

    class InputError(SartorError, ValueError):
        """A bad option or input (the executable's exit status 2)."""

    class SolveFailure(SartorError):
        """The solve did not converge (exit status 1); .result holds what it reached."""


def backend():
    """"extension" (in this process) or "executable" (the sartor program)."""
    return "extension" if _extension is not None else "executable"


_petsc_defaults = {}


def set_petsc_options(petsc):
    """PETSc options (without their dash; None: a flag) for every later run and drape."""
    global _petsc_defaults
    _petsc_defaults = dict(petsc)
    if _extension is not None:
        _extension.set_petsc_options(_petsc_defaults)


def executable():
    """The `sartor` executable: $SARTOR_EXE, else the build of this checkout, else PATH."""
    if os.environ.get("SARTOR_EXE"):
        return os.environ["SARTOR_EXE"]
    built = os.path.join(_build_dir(), "bin", "sartor")
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


def _execute(command, argument, output, plot, petsc, check, quiet, options):
    if output is None:
        output = tempfile.mkdtemp(prefix="sartor_%s_" % command)
    if _extension is not None:
        return _in_process(command, argument, output, plot, petsc, check, quiet, options)
    words = command_line(command, argument, output, plot, {**_petsc_defaults, **(petsc or {})},
                         **options)
    done = subprocess.run(words, stdout=subprocess.PIPE if quiet else None,
                          stderr=subprocess.STDOUT if quiet else None, text=True)
    log = done.stdout or ""
    written = os.path.isfile(os.path.join(output, "summary.json"))
    result = Result(output, log) if written else None
    if done.returncode != 0 and check:
        error = InputError if done.returncode == 2 else SolveFailure
        raise error("`%s` failed (exit %d):\n%s" % (" ".join(words), done.returncode,
                                                    log.strip()), result)
    if result is None:
        raise SartorError("`%s` wrote no summary.json:\n%s" % (" ".join(words), log.strip()))
    return result


class _CapturedOutput:
    """What the process writes to its standard output and error (file
    descriptors 1 and 2, where sartor prints) while in the block, as `text`."""

    def __enter__(self):
        sys.stdout.flush()
        sys.stderr.flush()
        self._file = tempfile.TemporaryFile(mode="w+b")
        self._saved = [os.dup(1), os.dup(2)]
        os.dup2(self._file.fileno(), 1)
        os.dup2(self._file.fileno(), 2)
        return self

    def __exit__(self, *exception):
        for fd, saved in zip((1, 2), self._saved):
            os.dup2(saved, fd)
            os.close(saved)
        self._file.seek(0)
        self.text = self._file.read().decode(errors="replace")
        self._file.close()
        return False


def _in_process(command, argument, output, plot, petsc, check, quiet, options):
    call = _extension.run if command == "run" else _extension.drape
    petsc = dict(petsc or {})
    failure = None
    capture = _CapturedOutput() if quiet else None
    try:
        if capture:
            with capture:
                arrays = call(argument, str(output), plot, petsc, options)
        else:
            arrays = call(argument, str(output), plot, petsc, options)
    except SartorError as error:
        failure = error
        arrays = error.result
    log = capture.text if capture else ""
    result = Result(output, log, arrays) if arrays is not None else None
    if result is not None and result.unused_options:
        warnings.warn("sartor %s: option(s) not used (typos?): %s"
                      % (command, ", ".join(result.unused_options)), stacklevel=3)
    if failure is not None:
        failure.result = result
        if check or result is None:
            if log.strip():
                failure.args = ("%s\n%s" % (failure.args[0], log.strip()),)
            raise failure
    return result


def run(case, output=None, plot=False, petsc=None, check=True, quiet=True, **options):
    """`sartor run CASE` with options; returns its Result.

    case: a case file (YAML), or (in process) a dict of a case's options.
    output: the folder (default: a new temporary one). plot: also draw
    result.png. petsc: PETSc options, e.g. {"snes_rtol": 1e-8}. check: raise
    SartorError when sartor fails (else return what it reached). quiet: keep
    what sartor prints in Result.log (False: print it as it goes). options:
    any option of `sartor run --help`, with underscores for dashes: mesh_nx=8,
    fabric="silk", analysis="dynamic".
    """
    if isinstance(case, dict) and _extension is None:
        raise InputError("a case given as a dict needs the extension module (./dev build)")
    return _execute("run", case, output, plot, petsc, check, quiet, options)


def drape(pattern, output=None, plot=False, petsc=None, check=True, quiet=True, **options):
    """`sartor drape PATTERN` with options (see `sartor drape --help`); returns its Result.

    A case file of cases/garments goes in as petsc={"options_file_yaml": FILE}.
    """
    return _execute("drape", pattern, output, plot, petsc, check, quiet, options)


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
    vertex_fields  dict name -> (vertices,) array: contact pressure, friction,
                 seam forces where the case has them (units: `units`)
    units        dict dataset name -> unit, as result.h5 records them
    fabric_ids, fabric_names, panel_ids, panel_names (empty without panels)
    unused_options  options that had no effect (typos?), "-name value"
    series()     the time series (dynamic and creep runs, drapes), a Series
    """

    def __init__(self, directory, log="", arrays=None):
        self.directory = directory
        self.log = log
        self.unused_options = []
        if arrays is not None:
            for name, value in arrays.items():
                setattr(self, name, value)
            return
        with open(os.path.join(directory, "summary.json"), encoding="utf-8") as stream:
            self.summary = json.load(stream)
        path = os.path.join(directory, "result.h5")
        if not os.path.isfile(path):
            raise SartorError("%s: no result.h5 (the run stopped before its result)" % directory)
        with h5py.File(path, "r") as f:
            self.positions = f["/fields/position"][:]
            self.displacement = f["/fields/displacement"][:]
            self.vertex_fields = {n: f["/fields/" + n][:] for n in f["/fields"]
                                  if n not in ("position", "displacement")}
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
