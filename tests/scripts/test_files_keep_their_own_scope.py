#!/usr/bin/env python3
"""Fails when a test file puts its own names in the anonymous namespace.

The test programs are unity builds (tests/CMakeLists.txt): several test files
compiled as one unit. There the anonymous namespaces of all of them are one
namespace, so one file's helper could be found, or overloaded, from another.
Each file's own names go in namespace IMPACTLAB_TEST_FILE_SCOPE instead,
which the unity build names anew for each file.

Usage: test_files_keep_their_own_scope.py FOLDER
Exit status 0 when no FOLDER/*/*_test.cpp (the files the test programs are
made of, tests/CMakeLists.txt) opens an anonymous namespace,
1 otherwise, with one line FILE:LINE per one that does.
"""
import pathlib
import re
import sys

ANONYMOUS = re.compile(r"^\s*namespace\s*\{")


def main():
    folder = pathlib.Path(sys.argv[1])
    found = []
    for path in sorted(folder.glob("*/*_test.cpp")):
        for number, line in enumerate(path.read_text().splitlines(), start=1):
            if ANONYMOUS.match(line):
                found.append(f"{path}:{number}: anonymous namespace: use "
                             "namespace IMPACTLAB_TEST_FILE_SCOPE (tests/CMakeLists.txt says why)")
    print("\n".join(found) if found else f"{folder}: every test file keeps its own scope")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
