"""Input and output shared by the postproc/ plotting scripts (run them with
/usr/bin/python3: they need Debian's python3-numpy and python3-matplotlib)."""

import csv
import json
import os
import sys

# Every plotting script imports this module before numpy and matplotlib, so
# that a missing package is reported here, once, in the user's terms.
try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
except ImportError as missing:  # pragma: no cover - depends on the interpreter
    sys.exit(
        "%s: error: %s. This script needs numpy and matplotlib; run it with /usr/bin/python3 "
        "(Debian packages python3-numpy, python3-matplotlib)."
        % (os.path.basename(sys.argv[0]), missing)
    )


class PlotError(Exception):
    """An error the user can act on; printed without a traceback."""


def read_json(path):
    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    try:
        with open(path, encoding="utf-8") as stream:
            return json.load(stream)
    except json.JSONDecodeError as error:
        raise PlotError("%s:%d: not valid JSON: %s" % (path, error.lineno, error.msg))
    except OSError as error:
        raise PlotError("%s: cannot read: %s" % (path, error.strerror or error))


def read_csv_columns(path, required):
    """Columns of a numeric CSV file with a header line, as float arrays."""
    if not os.path.isfile(path):
        raise PlotError("%s: no such file" % path)
    try:
        with open(path, newline="", encoding="utf-8") as stream:
            reader = csv.reader(stream)
            header = next(reader, None)
            if header is None:
                raise PlotError("%s: empty file (expected a header line)" % path)
            header = [name.strip() for name in header]
            lowered = [name.lower() for name in header]  # units spelled N or n alike
            missing = [name for name in required if name.lower() not in lowered]
            if missing:
                raise PlotError(
                    "%s:1: missing column(s) %s (header is: %s)"
                    % (path, ", ".join(missing), ",".join(header))
                )
            index = [lowered.index(name.lower()) for name in required]
            rows = []
            for line, record in enumerate(reader, start=2):
                if not record or all(not field.strip() for field in record):
                    continue
                try:
                    rows.append([float(record[i]) for i in index])
                except (ValueError, IndexError):
                    raise PlotError(
                        "%s:%d: expected %d numeric fields, got: %s"
                        % (path, line, len(header), ",".join(record))
                    )
    except OSError as error:
        raise PlotError("%s: cannot read: %s" % (path, error.strerror or error))
    if not rows:
        raise PlotError("%s: no data rows" % path)
    data = np.array(rows, dtype=float)
    return {name: data[:, k] for k, name in enumerate(required)}


def time_unit(span):
    if span > 3 * 3600:
        return 3600.0, "h"
    if span > 3 * 60:
        return 60.0, "min"
    return 1.0, "s"


def save_figure(fig, output, dpi):
    """Write `fig` to `output`; a PlotError names what went wrong."""
    folder = os.path.dirname(os.path.abspath(output))
    if not os.path.isdir(folder):
        raise PlotError("%s: folder of the output file does not exist" % folder)
    try:
        fig.savefig(output, dpi=dpi)
    except OSError as error:
        raise PlotError("%s: cannot write: %s" % (output, error.strerror or error))
