#!/usr/bin/env python3
"""Fails when an #include runs upwards through impactlab's layers.

Layers, bottom to top (docs/architecture.md); a file may include headers of
its own layer and of the layers below it:

  1 engine      src/core, src/integrate, src/contact, src/rigidbody, src/platform
  2 io          src/io
  3 physics     oscillators/
  4 analysis    analysis/
  5 scene API   src/api/
  6 front ends  src/cli, python/, examples/

Usage: check_layers.py [ROOT]   (ROOT defaults to the repository root)
Exit status 0 when every include points down or sideways, 1 otherwise, with
one line per offending include: FILE:LINE: layer of FILE < layer of HEADER.
"""
import pathlib
import re
import sys

# (path prefix relative to ROOT, layer number, layer name); longest prefix wins
FOLDER_LAYERS = [
    ("src/core/", 1, "engine"),
    ("src/integrate/", 1, "engine"),
    ("src/contact/", 1, "engine"),
    ("src/rigidbody/", 1, "engine"),
    ("src/platform/", 1, "engine"),
    ("src/io/", 2, "io"),
    ("oscillators/", 3, "physics"),
    ("analysis/", 4, "analysis"),
    ("src/api/", 5, "scene API"),
    ("src/cli/", 6, "front end"),
    ("python/", 6, "front end"),
    ("examples/", 6, "front end"),
]
# how a quoted include names each folder (include roots are src/ and the repository root)
INCLUDE_PREFIXES = [
    ("core/", "src/core/"),
    ("integrate/", "src/integrate/"),
    ("contact/", "src/contact/"),
    ("rigidbody/", "src/rigidbody/"),
    ("platform/", "src/platform/"),
    ("io/", "src/io/"),
    ("oscillators/", "oscillators/"),
    ("analysis/", "analysis/"),
    ("api/", "src/api/"),
    ("cli/", "src/cli/"),
]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
SOURCE_SUFFIXES = {".hpp", ".cpp", ".h", ".cc"}


def layer_of_path(relative: str):
    for prefix, number, name in sorted(FOLDER_LAYERS, key=lambda f: -len(f[0])):
        if relative.startswith(prefix):
            return number, name
    return None


def layer_of_include(header: str):
    for include_prefix, folder in INCLUDE_PREFIXES:
        if header.startswith(include_prefix):
            return layer_of_path(folder)
    return None


def violations(root: pathlib.Path):
    found = []
    for path in sorted(root.rglob("*")):
        if path.suffix not in SOURCE_SUFFIXES or not path.is_file():
            continue
        relative = path.relative_to(root).as_posix()
        if relative.startswith(("build", ".git")):
            continue
        own = layer_of_path(relative)
        if own is None:
            continue  # tests/, benchmarks/: above every layer
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), start=1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = layer_of_include(match.group(1))
            if target and target[0] > own[0]:
                found.append(f"{relative}:{number}: {own[1]} (layer {own[0]}) includes "
                             f"{match.group(1)} of {target[1]} (layer {target[0]})")
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    found = violations(root.resolve())
    for line in found:
        print(line)
    print(f"layers: {len(found)} upward include(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
