#!/usr/bin/python3
"""Malformed and hostile inputs for every reader of `sartor`, each of which
must be answered as a user's mistake: a clean exit with status 2 (bad input),
a message naming the file, the option or the key, no signal, no hang, no
traceback (PETSc's, C++'s), no "internal error". (Valid inputs whose
solve fails end with status 1; tests/cli checks those.)

    run_corpus.py SARTOR SOURCE_DIR WORKDIR [--list]

The corpus is the hand-written files in tests/fuzz/corpus/ (one command each,
its first line `# sartor ARGS`, with {file} for the file itself) plus
variants generated here from valid seed inputs of the project (cases,
patterns, OBJ meshes, CSV files, fabric files, a checkpoint written by a
short run) by fixed mutations: values replaced by non-numbers, infinities,
overflows and huge or negative counts, keys given twice, cuts, garbage and
non-UTF-8 bytes. The mutations are chosen to make every input invalid.

Each input runs with a time limit and an address-space limit (an unbounded
allocation fails instead of exhausting the machine), four at a time (a
run mostly waits on the start of Open MPI). The script prints one line per
failure and a count per outcome, and exits 1 when any input was not
answered cleanly.
"""
import concurrent.futures
import os
import re
import resource
import subprocess
import sys

TIMEOUT_S = 20
MEMORY_LIMIT = 6 << 30  # bytes of address space
CRASH_SIGNS = ("PETSC ERROR", "internal error", "terminate called", "Segmentation fault",
               "Caught signal", "MPI_ABORT", "Assertion", "AddressSanitizer", "runtime error")


class Case:
    def __init__(self, name, argv, expect):
        self.name = name  # where the input came from and what was done to it
        self.argv = argv  # after `sartor`
        self.expect = expect  # regular expression the message must match


def write(path, data):
    with open(path, "wb") as out:
        out.write(data if isinstance(data, bytes) else data.encode())


def read(path):
    with open(path, "rb") as f:
        return f.read()


def without_comments(text):
    """The seed without its comments, so that every mutation hits data."""
    lines = []
    for line in text.split(b"\n"):
        if line.lstrip().startswith(b"#"):
            continue
        lines.append(re.sub(rb"\s+#.*$", b"", line))
    return b"\n".join(lines)


# --- mutations of text -------------------------------------------------------
NUMBER = re.compile(rb"(?<![A-Za-z_0-9.])-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?")
BAD_NUMBERS = [b"nan", b"inf", b"-inf", b"1e999", b"abc", b"12abc", b"1,5", b"--1",
               b"9" * 5000, b"\xff\xfe"]


def replace_number(text, index, bad):
    """`text` with its index-th number (modulo the count) replaced by `bad`."""
    matches = list(NUMBER.finditer(text))
    if not matches:
        return text + b"\n" + bad
    m = matches[index % len(matches)]
    return text[:m.start()] + bad + text[m.end():]


def number_variants(stem, text, count):
    """`count` variants, each with one number replaced by a bad one."""
    variants = []
    for k in range(count):
        bad = BAD_NUMBERS[k % len(BAD_NUMBERS)]
        variants.append((f"{stem}.number{k}", replace_number(text, 7 * k + 3, bad)))
    return variants


def byte_variants(stem, text):
    """Garbage, NUL and non-UTF-8 bytes, an empty file, a very long line."""
    middle = len(text) // 2
    return [
        (f"{stem}.empty", b""),
        (f"{stem}.garbage", bytes((i * 131 + 17) % 256 for i in range(4096))),
        (f"{stem}.nul", text[:middle] + b"\0\0\0" + text[middle:]),
        (f"{stem}.latin1", text[:middle] + b"\xe9\xff\xfe" + text[middle:]),
        (f"{stem}.long_line", text[:middle] + b"x" * 200000 + text[middle:]),
    ]


# --- the readers ----------------------------------------------------------------
def case_yaml_cases(src, work):
    """Case YAML (`sartor run CASE`): bad values, keys twice, bad syntax."""
    seed = without_comments(read(f"{src}/cases/fe/hanging_sheet.yaml"))
    # An empty case is valid (every option has a default).
    variants = number_variants("case", seed, 30) + byte_variants("case", seed)[1:]
    lines = seed.split(b"\n")
    keys = [i for i, line in enumerate(lines) if re.match(rb"^[a-z_]+:", line)]
    for k, i in enumerate(keys):
        variants.append((f"case.twice{k}", b"\n".join(lines + [lines[i]])))
    variants += [
        ("case.unclosed_list", seed + b"\nmesh_nx: [4\n"),
        ("case.list_value", seed + b"\ngravity: [0, 0, -9.8]\n"),
        ("case.tab_indent", seed + b"\nmesh:\n\t- a\n"),
        ("case.bad_indent", b"mesh: rectangle\n  mesh_nx: 4\n mesh_ny: 3\n"),
        ("case.unknown_analysis", seed + b"\nanalysis: quantum\n"),
        ("case.negative_count", seed.replace(b"mesh_nx: 20", b"mesh_nx: -20")),
        ("case.wrapping_count", seed.replace(b"mesh_nx: 20", b"mesh_nx: 4294967306")),
        ("case.huge_mesh", seed.replace(b"mesh_nx: 20", b"mesh_nx: 1000000")),
        ("case.refine_12", seed + b"\nmesh_refine: 12\n"),
        ("case.time_end_1e300", seed + b"\nanalysis: dynamic\ntime_end: 1e300\n"),
        ("case.zero_width", seed.replace(b"mesh_width: 1.0", b"mesh_width: 0")),
    ]
    cases = []
    for name, data in variants:
        path = f"{work}/{name}.yaml"
        write(path, data)
        cases.append(Case(name, ["run", path, "--output", f"{work}/out/{name}"],
                          re.escape(os.path.basename(path)) + "|option --|options --|unknown fabric"))
    return cases


def pattern_cases(src, work):
    """Pattern JSON (`sartor pattern`)."""
    seed = read(f"{src}/cases/patterns/skirt.json")
    variants = number_variants("pattern", seed, 30) + byte_variants("pattern", seed)
    for k in range(1, 8):
        variants.append((f"pattern.cut{k}", seed[: len(seed) * k // 8]))
    variants += [
        ("pattern.key_twice", seed.replace(b'"version": 1,', b'"version": 1, "version": 1,', 1)),
        ("pattern.overflow", seed.replace(b'"version": 1', b'"version": 1e999', 1)),
        ("pattern.huge_panel", re.sub(rb"\[(-?[0-9.]+), (-?[0-9.]+)\]",
                                      rb"[\1e300, \2e300]", seed)),
        ("pattern.not_object", b"[1, 2, 3]"),
        ("pattern.deep", b"[" * 100000 + b"]" * 100000),
        ("pattern.string_number", seed.replace(b'"version": 1', b'"version": "1"', 1)),
    ]
    cases = []
    for name, data in variants:
        path = f"{work}/{name}.json"
        write(path, data)
        cases.append(Case(name, ["pattern", path, "--output", f"{work}/out/{name}"],
                          re.escape(os.path.basename(path)) + "|option --"))
    cases.append(Case("pattern.edge_1e-5", ["pattern", f"{src}/cases/patterns/skirt.json",
                                            "--edge-length", "1e-5", "--output",
                                            f"{work}/out/edge"], "option --edge-length"))
    return cases


def seams_cases(src, work):
    """Seams JSON (`sartor run --seams-file`) on a 4 x 4 sheet."""
    seed = b'{"seams": [{"name": "s", "a": [0, 1, 2], "b": [20, 21, 22]}]}'
    variants = [(f"seams.number{k}", replace_number(seed, k, BAD_NUMBERS[k % len(BAD_NUMBERS)]))
                for k in range(12)]
    variants += byte_variants("seams", seed)
    variants += [(f"seams.cut{k}", seed[: len(seed) * k // 6]) for k in range(1, 6)]
    variants += [
        ("seams.key_twice", b'{"seams": [], "seams": []}'),
        ("seams.vertex_out", seed.replace(b"22", b"2200")),
        ("seams.negative", seed.replace(b"22", b"-22")),
        ("seams.million", b'{"seams": [' + b",".join(
            [b'{"a": [0, 1], "b": [20, 21]}'] * 1000000) + b"]}"),
        ("seams.not_array", b'{"seams": 5}'),
        ("seams.name_bytes", seed.replace(b'"s"', b'"\xff\xfe"')),
    ]
    cases = []
    for name, data in variants:
        path = f"{work}/{name}.json"
        write(path, data)
        cases.append(Case(name, ["run", f"{src}/cases/fe/hanging_sheet.yaml", "--mesh-nx", "4",
                                 "--mesh-ny", "4", "--seams-file", path, "--output",
                                 f"{work}/out/{name}"],
                          re.escape(os.path.basename(path)) + "|option --"))
    return cases


def obj_cases(src, work):
    """OBJ cloth (`sartor run --mesh obj`) and body (`sartor body --body`)."""
    # Without the statements the readers ignore (normals, lines, groups).
    ignored = re.compile(rb"^(vn|l|s|g|o|usemtl|mtllib) .*$", re.M)
    cloth = ignored.sub(b"", without_comments(read(f"{src}/tests/mesh/data/panel_cm.obj")))
    body = ignored.sub(b"", without_comments(read(f"{src}/tests/body/data/cube.obj")))
    cases = []
    for kind, seed, command in (("cloth", cloth, "run"), ("body", body, "body")):
        variants = number_variants(f"obj_{kind}", seed, 22) + byte_variants(f"obj_{kind}", seed)
        variants += [
            (f"obj_{kind}.face_zero", seed + b"\nf 0 1 2\n"),
            (f"obj_{kind}.face_far", seed + b"\nf 1 2 99999999999\n"),
            (f"obj_{kind}.face_short", seed + b"\nf 1 2\n"),
            (f"obj_{kind}.vertex_short", seed + b"\nv 1 2\n"),
            (f"obj_{kind}.faces_only", b"f 1 2 3\n"),
        ]
        for name, data in variants:
            path = f"{work}/{name}.obj"
            write(path, data)
            if command == "run":
                argv = ["run", f"{src}/cases/fe/hanging_sheet.yaml", "--mesh", "obj",
                        "--mesh-file", path, "--pin-box", "-1,1,-1,1,-1,1", "--mesh-rotate-x",
                        "0", "--output", f"{work}/out/{name}"]
            else:
                argv = ["body", "--body", path, "--no-plot", "--output", f"{work}/out/{name}"]
            cases.append(Case(name, argv, re.escape(os.path.basename(path))))
    return cases


def csv_cases(src, work):
    """CSV measurements (`sartor fit`) and tension histories (`sartor creep`)."""
    measured = without_comments(read(f"{src}/tests/cli/data/strain_only.csv"))
    history = without_comments(read(f"{src}/tests/cli/data/history_ramp_hold.csv"))
    cases = []
    for kind, seed in (("measured", measured), ("history", history)):
        variants = number_variants(f"csv_{kind}", seed, 20) + byte_variants(f"csv_{kind}", seed)
        variants += [
            (f"csv_{kind}.extra_field", seed + b"\n5,1,2,3\n"),
            (f"csv_{kind}.header_twice", seed.split(b"\n", 1)[0] + b"\n" + seed),
            (f"csv_{kind}.only_header", b"time_s,strain\n"),
        ]
        for name, data in variants:
            path = f"{work}/{name}.csv"
            write(path, data)
            if kind == "measured":
                argv = ["fit", path, "--tension", "2000", "--no-plot", "--output",
                        f"{work}/out/{name}"]
            else:
                argv = ["creep", "--fabric", "cotton_twill:warp", "--tension-history", path,
                        "--no-plot", "--output", f"{work}/out/{name}"]
            cases.append(Case(name, argv, re.escape(os.path.basename(path))))
    return cases


def fabric_cases(src, work):
    """Fabric YAML (`sartor creep --fabric FILE.yaml`)."""
    seed = without_comments(read(f"{src}/tests/cli/data/curve_fabric.yaml"))
    variants = number_variants("fabric", seed, 16) + byte_variants("fabric", seed)
    variants += [("fabric.name_twice", seed + b"\nname: again\n"),
                 ("fabric.warp_twice", seed + b"\nwarp:\n  E: 1\n")]
    cases = []
    for name, data in variants:
        path = f"{work}/{name}.yaml"
        write(path, data)
        cases.append(Case(name, ["creep", "--fabric", path, "--no-plot", "--output",
                                 f"{work}/out/{name}"], re.escape(os.path.basename(path))))
    return cases


def checkpoint_cases(src, sartor, work):
    """Checkpoint HDF5 (`sartor run --restart`): a real one, damaged."""
    strip = f"{src}/cases/creep/strip.yaml"
    short = ["--time-end", "20", "--checkpoint-interval", "10", "--output-interval", "0"]
    good = f"{work}/checkpoint_seed.h5"
    subprocess.run([sartor, "run", strip, *short, "--checkpoint", good, "--output",
                    f"{work}/out/checkpoint_seed"], stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL, timeout=120, check=True)
    seed = read(good)
    variants = [("checkpoint.empty", b""), ("checkpoint.text", b"not HDF5\n")]
    for k in range(1, 6):
        variants.append((f"checkpoint.cut{k}", seed[: len(seed) * k // 6]))
        tail = len(seed) * k // 6
        variants.append((f"checkpoint.zero_tail{k}", seed[:tail] + b"\0" * (len(seed) - tail)))
    # Bits flipped in the values the checkpoint holds (the positions' first x
    # is 0.0: the first 8-byte zero run after the header is data).
    for k in range(24):
        at = len(seed) * (k + 1) // 25
        flipped = bytearray(seed)
        flipped[at] ^= 1 << (k % 8)
        variants.append((f"checkpoint.flip{k}", bytes(flipped)))
    cases = []
    for name, data in variants:
        path = f"{work}/{name}.h5"
        write(path, data)
        cases.append(Case(name, ["run", strip, *short, "--restart", path, "--output",
                                 f"{work}/out/{name}"], re.escape(os.path.basename(path))))
    return cases


def option_cases(src, work):
    """Command-line options: bad values, limits, inapplicable options."""
    case = f"{src}/cases/fe/hanging_sheet.yaml"
    strip = f"{src}/cases/creep/strip.yaml"
    out = ["--output", f"{work}/out/options"]
    run_bad = [("mesh-nx", "4294967306"), ("mesh-nx", "-3"), ("mesh-nx", "1e3"),
               ("mesh-refine", "12"), ("mesh-width", "nan"), ("mesh-width", "-1"),
               ("mesh-width", "1e999"), ("gravity", "0,0"), ("gravity", "a,b,c"),
               ("pin-box", "1,2,3"), ("point-force", "99999,0,0,1"), ("analysis", "foo"),
               ("membrane-model", "foo"), ("bending-model", "foo"), ("mesh", "hexagon"),
               ("load-steps", "0"), ("load-steps", "99999999999"), ("density", "-1"),
               ("time-end", "3"), ("checkpoint-interval", "-1"), ("restart", "x.h5"),
               ("pin-motion", "0:0,0,0; -1:1,1,1"), ("body", "sphere radius=-1"),
               ("body", "teapot"), ("mesh-translate", "1,2"), ("fabric", "nosuch"),
               ("pin-vertices", "1,abc"), ("pin-vertices", "99999999"),
               ("probe", "1,2"), ("bending-stiffness", "-1")]
    cases = [Case(f"option.run.{name}={value}", ["run", case, f"--{name}", value, *out],
                  f"option --{name}|--{name}|{re.escape(value)}")
             for name, value in run_bad]
    cases.append(Case("option.run.pin_list_4096", ["run", case, "--pin-vertices",
                                                   ",".join(["1"] * 2100) + ",x", *out],
                      "option --pin-vertices"))
    dynamic_bad = [("time-end", "1e300"), ("time-step", "1e-300"), ("output-interval", "1e-300"),
                   ("checkpoint-interval", "1e-300")]
    cases += [Case(f"option.dynamic.{name}={value}",
                   ["run", case, "--analysis", "dynamic", f"--{name}", value, *out],
                   f"option --{name}") for name, value in dynamic_bad]
    creep_bad = [("time-end", "1e300"), ("checkpoint-interval", "1e-300"),
                 ("creep-parameters", "1,2"), ("load-history", "0:1; -5:1"),
                 ("creep-scheme", "foo")]
    cases += [Case(f"option.creep.{name}={value}", ["run", strip, f"--{name}", value, *out],
                   f"option --{name}") for name, value in creep_bad]
    creep_command_bad = [("samples-per-decade", "1000000000"), ("sample-interval", "1e-9"),
                         ("tension", "1e308"), ("load-duration", "1e300"), ("force", "abc"),
                         ("width", "0"), ("fabric", "cotton_twill:diagonal")]
    cases += [Case(f"option.creep_command.{name}={value}",
                   ["creep", f"--{name}", value, "--no-plot", *out],
                   f"option --{name}|cotton_twill|--fabric")
              for name, value in creep_command_bad]
    cases += [Case("option.synth.samples", ["synth", "--fabric", "silk:warp", "--samples",
                                            "10000000000", "--output", f"{work}/out/s.csv"],
                   "option --samples"),
              Case("option.unknown", ["run", case, "--frobnicate", "1"], "unknown option"),
              Case("option.missing_value", ["run", case, "--mesh-nx"], "needs a value"),
              Case("option.no_case", ["run"], "takes 1 argument"),
              Case("option.missing_case", ["run", f"{work}/nosuch.yaml"], "nosuch.yaml"),
              Case("option.drape_seams", ["drape", f"{src}/cases/patterns/skirt.json",
                                          "--seams-file", "x.json", *out], "x.json")]
    return cases


def corpus_file_cases(src, work):
    """The hand-written files of tests/fuzz/corpus/."""
    cases = []
    folder = f"{src}/tests/fuzz/corpus"
    for name in sorted(os.listdir(folder)):
        path = f"{folder}/{name}"
        first = read(path).split(b"\n", 1)[0].decode()
        words = first[len("# sartor "):].split()
        argv = [w.replace("{file}", path).replace("{src}", src) for w in words]
        cases.append(Case(f"corpus/{name}", argv + ["--output", f"{work}/out/{name}"],
                          re.escape(name)))
    return cases


# --- running -----------------------------------------------------------------------
def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def run(sartor, case):
    """(outcome, detail): 'ok' or what went wrong."""
    try:
        done = subprocess.run([sartor, *case.argv], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, timeout=TIMEOUT_S, preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return "hang", f"no answer in {TIMEOUT_S} s"
    text = (done.stdout + done.stderr).decode("utf-8", "replace")
    last = text.strip().splitlines()[-1] if text.strip() else "(no output)"
    if done.returncode < 0:
        return "crash", f"signal {-done.returncode}: {last}"
    for sign in CRASH_SIGNS:
        if sign in text:
            kind = "allocation" if "bad_alloc" in text or "memory" in text.lower() else "crash"
            return kind, f"'{sign}': {last}"
    if done.returncode == 0:
        return "silent", "accepted (exit status 0)"
    if done.returncode == 1:
        return "status", f"exit status 1 (a failed computation), expected 2 (bad input): {last}"
    if done.returncode != 2:
        return "crash", f"exit status {done.returncode}: {last}"
    if not re.search(case.expect, text):
        return "unnamed", f"message does not match /{case.expect}/: {last}"
    return "ok", last


def main():
    if len(sys.argv) < 4:
        sys.exit("usage: run_corpus.py SARTOR SOURCE_DIR WORKDIR [--list]")
    sartor, src, work = sys.argv[1:4]
    os.makedirs(f"{work}/out", exist_ok=True)
    cases = (case_yaml_cases(src, work) + pattern_cases(src, work) + seams_cases(src, work) +
             obj_cases(src, work) + csv_cases(src, work) + fabric_cases(src, work) +
             checkpoint_cases(src, sartor, work) + option_cases(src, work) +
             corpus_file_cases(src, work))
    if "--list" in sys.argv:
        for case in cases:
            print(case.name, " ".join(case.argv))
        return
    counts = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        results = list(pool.map(lambda c: run(sartor, c), cases))
    for case, (outcome, detail) in zip(cases, results):
        counts[outcome] = counts.get(outcome, 0) + 1
        if outcome != "ok":
            print(f"{outcome:10s} {case.name}: {detail}")
    print(f"{len(cases)} inputs: " + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())))
    sys.exit(0 if counts.get("ok", 0) == len(cases) else 1)


if __name__ == "__main__":
    main()
