#!/usr/bin/env python3
"""The build's cost per translation unit (docs/performance.md, "The build").

Compiles each translation unit of the library, the program and the Python
module alone, with the build's own flags and without a compiler cache, and
the fixed yardstick (compile_yardstick.cpp beside this file, with the
build's compiler) before every eighth unit and at the end; writes each
unit's CPU time (user + system) and its multiple of the yardstick's
median, largest first, and prints the total. Tests, benchmarks and
examples are not counted.

usage: benchmarks/compile_units.py BUILD_DIR OUT.tsv
"""
import json
import os
import pathlib
import resource
import shlex
import statistics
import subprocess
import sys
import tempfile

YARDSTICK = pathlib.Path(__file__).resolve().parent / "compile_yardstick.cpp"
YARDSTICK_FLAGS = ("-DBOOST_ALL_NO_LIB -DFMT_SHARED -isystem /usr/include/eigen3 -O3 -DNDEBUG -fPIC "
                   "-Wall -Wextra -Wpedantic -Wno-missing-field-initializers -fopenmp -std=c++20")


def cpu_seconds(arguments, directory):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(arguments, cwd=directory, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def main():
    build, out = sys.argv[1], sys.argv[2]
    commands = json.load(open(os.path.join(build, "compile_commands.json")))
    units = [c for c in commands
             if not any(part in c["file"] for part in ("/tests/", "/benchmarks/", "/examples/"))]
    scratch = tempfile.mkdtemp()
    target = os.path.join(scratch, "unit.o")
    # the yardstick with the build's own compiler (CMAKE_CXX_COMPILER)
    compiler = shlex.split(units[0]["command"])[0]
    yardstick = [compiler, *YARDSTICK_FLAGS.split(), "-c", str(YARDSTICK), "-o", target]
    yards, rows = [], []
    for index, unit in enumerate(units):
        if index % 8 == 0:
            yards.append(cpu_seconds(yardstick, scratch))
        arguments = [a for a in shlex.split(unit["command"]) if not a.endswith("ccache")]
        arguments[arguments.index("-o") + 1] = target
        rows.append((unit["file"], cpu_seconds(arguments, unit["directory"])))
    yards.append(cpu_seconds(yardstick, scratch))
    median = statistics.median(yards)
    total = sum(seconds for _, seconds in rows)
    with open(out, "w") as table:
        table.write(f"# yardstick median {median:.2f} s over {len(yards)} compiles: "
                    + ", ".join(f"{y:.1f}" for y in yards) + "\n")
        for name, seconds in sorted(rows, key=lambda row: -row[1]):
            table.write(f"{seconds:.2f}\t{seconds / median:.2f}\t{name}\n")
        summary = (f"# {len(rows)} units, total {total:.1f} s = {total / median:.1f} x yardstick; "
                   f"largest {max(s for _, s in rows) / median:.2f} x")
        table.write(summary + "\n")
    print(summary)


if __name__ == "__main__":
    main()
