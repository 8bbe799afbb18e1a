#!/usr/bin/env bash
# Fresh Debian 12 machine, as root: installs, builds and runs the default case
# (cases/settle_box.toml: 2,400 spheres settling in a steel box) on the default Vulkan device.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/repose devices
# out/settle_box is this script's own folder: each run replaces the previous one's results.
./build/repose run cases/settle_box.toml --out out/settle_box --overwrite --state-out out/settle_box/final.state "$@"
echo "summary:"; cat out/settle_box/summary.json
