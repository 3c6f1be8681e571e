#!/usr/bin/env python3
"""Fails when an #include runs upwards through impactlab's layers, or names a
project header by any spelling but its project-prefixed path.

Layers, bottom to top (docs/architecture.md); a file may include headers of
its own layer and of the layers below it:

  1 engine      src/platform < src/core < src/integrate < src/contact
                < src/simulate < src/rigidbody   (the engine's own order)
  2 io          src/io
  3 physics     oscillators/
  4 analysis    analysis/
  5 scene API   api/
  6 front ends  cli/, python/, examples/

A project header is included as <impactlab/LAYER/...> (LAYER: core,
integrate, contact, simulate, rigidbody, platform, io, oscillators, analysis,
api). Every other spelling that reaches a project header is read too and
reported: "core/x.hpp" or <core/x.hpp>, "src/core/x.hpp", "../core/x.hpp", a
bare "x.hpp" beside the file. The front end cli/ includes its own headers by
their bare names ("command.hpp"), and so does an example: those stay inside
their folder and are allowed.

Usage: check_layers.py [ROOT]   (ROOT defaults to the repository root)
Exit status 0 when every include points down or sideways by its prefixed
path, 1 otherwise, with one line per offending include:
  FILE:LINE: LAYER (layer N) includes HEADER of LAYER (layer M)
  FILE:LINE: HEADER is a project header: include it as <impactlab/...>
"""
import pathlib
import posixpath
import re
import sys

# (folder relative to ROOT, layer number, layer name); the engine's folders
# carry their own order as the fraction
FOLDER_LAYERS = [
    ("src/platform/", 1.0, "engine/platform"),
    ("src/core/", 1.1, "engine/core"),
    ("src/integrate/", 1.2, "engine/integrate"),
    ("src/contact/", 1.3, "engine/contact"),
    ("src/simulate/", 1.4, "engine/simulate"),
    ("src/rigidbody/", 1.5, "engine/rigidbody"),
    ("src/io/", 2, "io"),
    ("oscillators/", 3, "physics"),
    ("analysis/", 4, "analysis"),
    ("api/", 5, "scene API"),
    ("cli/", 6, "front end"),
    ("python/", 6, "front end"),
    ("examples/", 6, "front end"),
]
# the folder each <impactlab/PREFIX/...> names
PREFIX_FOLDERS = {
    "platform": "src/platform/", "core": "src/core/", "integrate": "src/integrate/",
    "contact": "src/contact/", "simulate": "src/simulate/", "rigidbody": "src/rigidbody/",
    "io": "src/io/", "oscillators": "oscillators/", "analysis": "analysis/", "api": "api/",
}
# folders whose files may include their own neighbours by bare name
BARE_NAME_FOLDERS = ("cli/", "examples/")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
SOURCE_SUFFIXES = {".hpp", ".cpp", ".h", ".cc"}


def layer_of_path(relative: str):
    for prefix, number, name in sorted(FOLDER_LAYERS, key=lambda f: -len(f[0])):
        if relative.startswith(prefix):
            return number, name
    return None


def resolve(root: pathlib.Path, relative: str, header: str, bracket: str):
    """The header's path relative to ROOT and whether it was spelled with the
    project prefix; (None, _) when it is not a project header."""
    if header.startswith("impactlab/"):
        parts = header.split("/", 2)
        if len(parts) == 3 and parts[1] in PREFIX_FOLDERS:
            return PREFIX_FOLDERS[parts[1]] + parts[2], bracket == "<"
        return None, False
    candidates = []
    if bracket == '"':
        # beside the including file, then ../ and the like
        candidates.append(posixpath.normpath(posixpath.join(posixpath.dirname(relative), header)))
    candidates.append(posixpath.normpath(header))  # "src/core/x.hpp"
    first = header.split("/", 1)[0]
    if first in PREFIX_FOLDERS and "/" in header:  # "core/x.hpp", <core/x.hpp>
        candidates.append(PREFIX_FOLDERS[first] + header.split("/", 1)[1])
    for candidate in candidates:
        if not candidate.startswith("..") and layer_of_path(candidate) and (root / candidate).is_file():
            return candidate, False
    # a header not in this tree (a checked tree of excerpts): by its spelling
    if first in PREFIX_FOLDERS and "/" in header:
        return PREFIX_FOLDERS[first] + header.split("/", 1)[1], False
    plain = posixpath.normpath(header)
    if layer_of_path(plain):  # "src/core/x.hpp"
        return plain, False
    if header.startswith("../"):
        beside = posixpath.normpath(posixpath.join(posixpath.dirname(relative), header))
        if not beside.startswith("..") and layer_of_path(beside):
            return beside, False
    return None, False


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
            bracket, header = match.group(1), match.group(2)
            target_path, prefixed = resolve(root, relative, header, bracket)
            if target_path is None:
                continue
            target = layer_of_path(target_path)
            if target[0] > own[0]:
                found.append(f"{relative}:{number}: {own[1]} (layer {own[0]:g}) includes "
                             f"{header} of {target[1]} (layer {target[0]:g})")
            elif not prefixed and not (relative.startswith(BARE_NAME_FOLDERS) and
                                       target_path.startswith(BARE_NAME_FOLDERS)):
                found.append(f"{relative}:{number}: {header} is a project header: "
                             f"include it as <impactlab/...>")
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    found = violations(root.resolve())
    for line in found:
        print(line)
    print(f"layers: {len(found)} offending include(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
