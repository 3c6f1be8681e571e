#!/usr/bin/env bash
# From a fresh clone: installs missing Debian packages, builds, runs every test with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 300
