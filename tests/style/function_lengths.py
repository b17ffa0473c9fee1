#!/usr/bin/env python3
"""Fails when a function in the given C++ trees is longer than the limit.

    function_lengths.py LIMIT DIR_OR_FILE...

Counts the definitions at namespace scope (free functions and members
defined outside their class), from the first line of the signature to the
closing brace, in clang-formatted sources: a signature starts at column 0,
its last line ends with '{', and the body ends at the first line that starts
with '}' at column 0. Functions defined inside a class body are left out.
Prints every function over the limit with its file and line. Standard
library only, so any python3 runs it.
"""
import pathlib
import sys

NOT_SIGNATURES = ("//", "#", "}", "namespace", "class ", "struct ", "enum ", "using ", "template")


def definitions(path):
    """(first line, number of lines, signature) of each definition in path."""
    lines = path.read_text(encoding="utf-8").splitlines()
    code = [line.split("//")[0].rstrip() for line in lines]  # no trailing comments
    i = 0
    while i < len(lines):
        line = code[i]
        if line and not line[0].isspace() and "(" in line and not line.startswith(NOT_SIGNATURES):
            end = i
            while end < len(lines) and end - i < 10 and not code[end].endswith(("{", ";")):
                end += 1
            if end < len(lines) and code[end].endswith("{"):
                close = end + 1
                while close < len(lines) and not lines[close].startswith("}"):
                    close += 1
                yield i + 1, close - i + 1, line.strip()
                i = close
        i += 1


def sources(arguments):
    for argument in arguments:
        path = pathlib.Path(argument)
        if path.is_file():
            yield path
        else:
            yield from sorted(p for p in path.rglob("*") if p.suffix in (".cpp", ".hpp"))


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    limit = int(sys.argv[1])
    too_long = [(path, first, count, signature)
                for path in sources(sys.argv[2:])
                for first, count, signature in definitions(path) if count > limit]
    for path, first, count, signature in too_long:
        print(f"{path}:{first}: {count} lines (limit {limit}): {signature}")
    if too_long:
        print(f"{len(too_long)} function(s) longer than {limit} lines: split them", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
