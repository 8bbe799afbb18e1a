#!/usr/bin/env bash
# Installs the Debian packages (when missing) and builds build/repose and the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "$(id -u)" = 0 ]; then
  bash scripts/install-deps.sh
else
  echo "not root: skipping the package check (run scripts/install-deps.sh as root once)" >&2
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
