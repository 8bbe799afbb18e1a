#!/usr/bin/env bash
# Fresh Debian 12 machine, as root: installs, builds and runs every test (on lavapipe).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest -j "$(nproc)" --output-on-failure --timeout 1500
