#!/usr/bin/env bash
# Everything we want to know the first time Repose meets a hardware GPU, in one report:
# the devices and their limits, the bit-exact twin tests run on the GPU (every kernel against the
# CPU twin, whole runs byte-compared with the cpu backend), the particle order (the order and
# lazy download tests on the GPU, a run in the case's order against the cpu backend's cell
# order, and `repose bench` in both orders), `repose bench` at 1e5, 1e6 and 1e7 spheres on the
# GPU beside the cpu backend on every core, and the scan's block passes against one workgroup.
# the large heap (cases/large_heap: a million grains poured and their angle measured) on the GPU.
# Usage: bash scripts/gpu-check.sh [--bundle DIR] [--out DIR] [--sizes "100000 1000000"] [--only REGEX] [--heap N]
#                                  [--budget SECONDS] [--quick] [--pack DIR]
#   --bundle: a folder made by scripts/gpu-bundle.sh (a machine without this project's packages);
#             default: build/ of this checkout.
#   --out:    where report.md and the raw logs go (default out/gpu-check).
#   --only:   run only the steps whose title matches REGEX (grep -E, any case), e.g. --only 'heap|1000000 spheres'
#             where a session's device time is short; the report lists the steps left out.
#   --heap:   grains in the large heap (default its case's million; 100000, a tenth, ends in ~99,000
#             steps, and its result files can be compared with the cpu backend's for the same count).
#   --budget: stop within SECONDS: each step gets at most the time left, and the steps that find
#             less than 15 s left are listed as left out. The whole check takes ~15 minutes on an
#             H200 (the million-grain heap ~6 of them), more than one call of a 15-minute lease
#             may run (10 minutes): e.g. --budget 540 --sizes 1000000 --heap 100000, then
#             --only heap --budget 560 for the million.
#   --pack:   at the end, copy report.md and the logs (one logs.tar.gz, no states nor caches) into DIR:
#             two files, for a machine that sends back only a few (its --out then holds the rest).
#   --quick:  a check of this script itself on any Vulkan device (lavapipe through VK_DRIVER_FILES):
#             the twin tests left out, 2,000-sphere beds, short runs and benches.
# Each step has a time limit, and a failed step is reported, not fatal: the report is what counts.
set -u
cd "$(dirname "$0")/.."
bundle="" out="out/gpu-check" sizes="100000 1000000 10000000" quick=0 only="" heap=1000000 budget=0 pack=""
while [ $# -gt 0 ]; do
  case "$1" in
    --bundle) bundle=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --heap) heap=$2; shift 2 ;;
    --budget) budget=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --pack) pack=$2; shift 2 ;;
    *) echo "gpu-check: unknown option $1" >&2; exit 2 ;;
  esac
done
# Steps of the whole-run comparisons, spheres and steps of the order benches.
run_steps=2000 order_n=1000000 order_steps=300 scan_sizes="20000 1000000" scan_steps=100
[ $quick = 1 ] && { sizes=2000 run_steps=200 order_n=2000 order_steps=20 scan_sizes=2000 scan_steps=20; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
report="$out/report.md"
if [ -n "$bundle" ]; then
  bundle=$(cd "$bundle" && pwd)
  bin="$bundle/bin"
  # The bundle's libraries, then the driver's own folder where the image keeps it out of the loader's path.
  export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
    [ -d "$d" ] && LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$d"
  done
  src=$(cat "$bundle/source_dir")
  # The tests read cases from the source folder compiled into them: point it here.
  if [ "$src" != "$PWD" ] && [ ! -e "$src" ]; then mkdir -p "$(dirname "$src")" && ln -s "$PWD" "$src"; fi
  exe=$(cat "$bundle/binary_path")
  if [ ! -e "$exe" ]; then mkdir -p "$(dirname "$exe")" && ln -s "$bin/repose" "$exe"; fi
else
  bin="build"
fi
# The GPU's Vulkan driver, unless the caller chose one (never lavapipe here).
if [ -z "${VK_DRIVER_FILES:-}" ]; then
  for f in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
           /etc/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/radeon_icd.x86_64.json \
           /usr/share/vulkan/icd.d/intel_icd.x86_64.json; do
    if [ -f "$f" ]; then export VK_DRIVER_FILES=$f; break; fi
  done
fi

deadline=$(( $(date +%s) + budget ))
say() { printf '%s\n' "$*" | tee -a "$report"; }
# step TITLE SECONDS COMMAND...: runs it with a limit, keeps its log, puts its tail in the report;
# SECONDS "always": 60 s, and never left out by --only.
step() {
  local title=$1 limit=$2; shift 2
  # The devices are always listed; --only picks among the rest.
  if [ -n "$only" ] && [ "$limit" != always ] && ! printf '%s' "$title" | grep -qiE -- "$only"; then
    say "- left out (--only): $title"
    return 0
  fi
  [ "$limit" = always ] && limit=60
  if [ "$budget" != 0 ]; then
    local left=$(( deadline - $(date +%s) ))
    if [ $left -lt 15 ]; then say "- left out (--budget, $left s left): $title"; return 0; fi
    [ $left -lt $limit ] && limit=$left
  fi
  local log="$out/$(echo "$title" | tr -c 'A-Za-z0-9_\n' '_' | tr -s _).log"
  local t0=$(date +%s)
  timeout --signal=TERM --kill-after=10 "$limit" "$@" >"$log" 2>&1
  local rc=$? t1=$(date +%s)
  say ""
  say "## $title"
  say "\`$*\` -> exit $rc in $((t1 - t0)) s$([ $rc = 124 ] && echo " (stopped at the $limit s limit)")"
  say '```'
  tail -n "${TAIL:-40}" "$log" | tee -a "$report" >/dev/null
  say '```'
  return $rc
}

: >"$report"
say "# Repose on a hardware GPU: $(date -u '+%Y-%m-%d %H:%M UTC')"
say ""
say "- version: $(git describe --always --dirty 2>/dev/null || echo unknown); binaries: $bin"
say "- host: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(free -g | awk '/Mem:/{print $2}') GiB"
say "- VK_DRIVER_FILES=${VK_DRIVER_FILES:-unset}$([ "$budget" != 0 ] && echo "; budget $budget s")"
step "nvidia-smi" always nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
[ -x "$bin/vulkaninfo" ] && step "vulkaninfo --summary" always "$bin/vulkaninfo" --summary
step "repose devices" always "$bin/repose" devices
if [ $quick = 0 ]; then
  # Each kernel alone from the twin's buffers first: the table of kernels whose own arithmetic differs.
  TAIL=80 step "each kernel alone on the GPU" 300 "$bin/test_engine" "each kernel alone*" -d yes
  # Every twin test: the GPU against the CPU twin after each dispatch, whole runs, split dispatches.
  TAIL=60 step "bit-exact tests on the GPU" 300 "$bin/test_engine" "[bitexact]" -d yes
  TAIL=30 step "clump and fixed-particle twin tests on the GPU" 200 "$bin/test_engine" "*lavapipe*" "~repose devices lists lavapipe" -d yes
fi
# The particle order: scrambled, rescrambled and cell orders against the case's order on the GPU;
# runs whose state is read after every batch, by positions alone or at the end, the same bytes.
TAIL=30 step "particle order and lazy download tests on the GPU" 300 "$bin/test_engine" "[order],[lazy]" -d yes
cmp_runs() {  # a case on the GPU (in the variant $3, else its default) and on the cpu backend: the same state bytes?
  local name=$1 steps=$2 variant=${3:-}
  "$bin/repose" run "cases/$name.toml" --backend vulkan --steps "$steps" --quiet --overwrite \
      ${variant:+--variant "$variant"} --out "$out/$name-gpu" --state-out "$out/$name-gpu.state" &&
    "$bin/repose" run "cases/$name.toml" --backend cpu --steps "$steps" --quiet --overwrite \
      --out "$out/$name-cpu" --state-out "$out/$name-cpu.state" &&
    cmp "$out/$name-gpu.state" "$out/$name-cpu.state" && echo "$name${variant:+ ($variant on the GPU)}: identical state after $steps steps"
}
export -f cmp_runs
export bin out run_steps
step "settle_box: GPU and cpu backend byte for byte" 200 bash -c 'cmp_runs settle_box $run_steps'
step "settle_box: GPU in the case's order, cpu backend in cell order, byte for byte" 200 \
    bash -c 'cmp_runs settle_box $run_steps lean,reorder=0'
step "cabbage_settle: GPU and cpu backend byte for byte" 300 bash -c 'cmp_runs cabbage_settle $run_steps'
for n in $sizes; do
  steps=$([ "$n" -ge 10000000 ] && echo 100 || echo 300)
  [ $quick = 1 ] && steps=20
  TAIL=30 step "bench, $n spheres" 600 "$bin/repose" bench --n "$n" --backend vulkan cpu --steps "$steps" \
      --cache "$out/bench-cache"
done
# The scans of a rebuild in their block passes over the whole GPU (REPOSE_SCAN_BLOCKS_FROM=1) and in
# one workgroup, a rebuild every step so that they run in every timed step: where the block passes
# start to pay (kScanBlocksFrom in host/engine/step_program.h). The same bytes either way.
for n in $scan_sizes; do
  for from in 1 4294967295; do
    TAIL=4 step "bench, $n spheres, a rebuild every step, scans in blocks from $from blocks" 600 \
        env REPOSE_SCAN_BLOCKS_FROM=$from "$bin/repose" bench --n "$n" --backend vulkan --variant lean,rebuild=1 \
        --steps "$scan_steps" --cache "$out/bench-cache"
  done
done
# The case's order against cell order on the GPU: the lattice bed (its case order is already
# spatial) and a random fill settled (cases/bench_bed.toml, 50k spheres, stored as the fill placed them).
TAIL=40 step "bench, $order_n spheres, the case's order and cell order" 600 "$bin/repose" bench --n "$order_n" \
    --backend vulkan --variant lean,reorder=0 --variant lean,reorder=20 --steps "$order_steps" --cache "$out/bench-cache"
TAIL=40 step "bench, a random fill of 50k spheres, the case's order and cell order" 600 "$bin/repose" bench \
    --case cases/bench_bed.toml --backend vulkan --variant lean,reorder=0 --variant lean,reorder=20 \
    --steps "$order_steps" --cache "$out/bench-cache"
# The large heap on the GPU: the README gives the cpu backend's angle, time and steps for the same
# case, and a GPU that keeps the cpu backend's bytes gives the same angle to the last digit.
# --quick: a 2,000-grain pour's first steps, which checks the case and the step only.
if [ $quick = 1 ]; then
  step "the large heap (cases/large_heap), 2000 grains, 100 steps" 300 "$bin/repose" run \
      cases/large_heap/large_heap.toml --set fill.0.count=2000 --backend vulkan --steps 100 --quiet \
      --overwrite --out "$out/large_heap"
else
  TAIL=60 step "the large heap (cases/large_heap), $heap grains poured and measured" 540 "$bin/repose" \
      experiment repose cases/large_heap/large_heap.toml --set fill.0.count=$heap --backend vulkan --profile \
      --overwrite --out "$out/large_heap"
fi
# The heap's files by hash, to compare with the cpu backend's run of the same case and count
# (`repose experiment repose cases/large_heap/large_heap.toml --set fill.0.count=N --backend cpu`):
# the same bytes give the same hashes (repose.json differs: it names the device and its times).
if [ -d "$out/large_heap" ]; then
  say ""
  say "sha256 of the large heap's files:"
  say '```'
  (cd "$out/large_heap" && sha256sum -- * 2>/dev/null) | tee -a "$report" >/dev/null
  say '```'
fi
say ""
say "Logs: $out"
if [ -n "$pack" ]; then
  mkdir -p "$pack"
  cp "$report" "$pack/report.md"
  (cd "$out" && find . -type f \( -name '*.log' -o -name '*.csv' -o -name '*.json' \) -size -4M | grep -v bench-cache |
     tar -czf "$(cd "$pack" && pwd)/logs.tar.gz" -T -)
  echo "packed: $pack/report.md, $pack/logs.tar.gz"
fi
