#!/usr/bin/env bash
# The cabbage study's body-plate calibrations (Zheng et al., Tables 4-6), redone for Repose's own
# cabbage template from the lab's numbers, on the four plates (Q235 steel, PVC, EVA, wood), the
# study's way: sweep one parameter, fit a cubic, invert it at the lab's value, verify there.
#   e    from the drop from 500 mm (rebound height, Table 4; friction 0, as the study set it)
#   mu_s from the four-cabbage slide (tilt at which the group slides, Table 5; e calibrated)
#   mu_r from the roll (beta 10 deg, S 260 mm, distance on the floor, Table 6; e and mu_s calibrated;
#        each seed rolls the body at another orientation, so 10 seeds per level are replicates)
# Each step writes its plan to OUT/plans, runs `repose calibrate` on it (resumable: a second call
# runs only what is missing) and takes the calibrated value into the next step. OUT/table.md
# gathers the results as the study's tables do; a roll whose verification is not confirmed is
# swept once more about its first value. About 15 CPU minutes in all (one thread per run).
# With --adaptive, each test is calibrated by the Gaussian process in the loop instead, with at
# most a third of the sweep's simulations (a pilot of 4 for the noisy drop and roll; the slide,
# which does not scatter, needs 3 runs for a start), verified as the sweep is; the table then
# gives the simulations each took and its credible interval's width.
#   scripts/calibrate-cabbage-plates.sh [--adaptive] [OUT] [PLATE ...]
#   (default OUT out/calibrate/cabbage_plates, or cabbage_plates_adaptive; all four plates)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
REPOSE=${REPOSE:-$ROOT/build/repose}
ADAPTIVE=0
if [ "${1:-}" = --adaptive ]; then ADAPTIVE=1; shift; fi
DEFAULT_OUT=out/calibrate/cabbage_plates
[ $ADAPTIVE = 0 ] || DEFAULT_OUT=out/calibrate/cabbage_plates_adaptive
OUT=$(mkdir -p "${1:-$DEFAULT_OUT}" && cd "${1:-$DEFAULT_OUT}" && pwd)
shift || true
PLATES=("$@")
[ ${#PLATES[@]} -gt 0 ] || PLATES=(q235_steel pvc eva wood)
JOBS=${JOBS:-$(nproc)}

# The lab's values (Tables 4, 5, 6): rebound height (m), slide angle (deg), rolling distance (m).
declare -A DROP=([q235_steel]=0.09380 [pvc]=0.10010 [eva]=0.13482 [wood]=0.08221)
declare -A SLIDE=([q235_steel]=35.31 [pvc]=20.24 [eva]=37.17 [wood]=33.82)
declare -A ROLL=([q235_steel]=0.6826 [pvc]=0.6738 [eva]=0.6538 [wood]=0.5869)
mkdir -p "$OUT/plans"

# plan NAME EXPERIMENT CASE RESPONSE MEASURED TOLERANCE FACTOR_KEY LOW HIGH LEVELS REPLICATES VERIFY SETS...
plan() {
  local name=$1 experiment=$2 case=$3 response=$4 measured=$5 tolerance=$6 key=$7 low=$8 high=$9
  local levels=${10} replicates=${11} verify=${12} plate=${13}
  shift 13
  {
    printf '# Written by scripts/calibrate-cabbage-plates.sh: the cabbage study'"'"'s body-plate test on %s.\n' "$plate"
    printf '[campaign]\nname = "%s"\nexperiment = "%s"\ncase = "%s"\n' "$name" "$experiment" "$ROOT/cases/$case"
    [ -z "${BASE_SEED:-}" ] || printf 'base_seed = %s\n' "$BASE_SEED"
    [ $ADAPTIVE = 0 ] || printf 'mode = "adaptive"\n'
    printf '\n'
    printf '[response]\nname = "%s"\nmeasured = %s\ntolerance = %s\n\n' "$response" "$measured" "$tolerance"
    printf '[set]\n"material.1.preset" = "%s"\n"wall.plate.material" = "%s"\n' "$plate" "$plate"
    printf '"interaction.0.materials" = ["cabbage", "%s"]\n' "$plate"
    for s in "$@"; do printf '%s\n' "$s"; done
    printf '\n[[factor]]\nname = "%s"\nkey = "%s"\nlow = %s\nhigh = %s\n\n' "${key##*.}" "$key" "$low" "$high"
    method "$levels" "$replicates"
    printf '[verification]\nruns = %s\n' "$verify"
  } > "$OUT/plans/$name.toml"
  nice -n 10 "$REPOSE" calibrate "$OUT/plans/$name.toml" --jobs "$JOBS" --quiet --out "$OUT/$name" > "$OUT/$name.log" 2>&1 ||
    [ $? -eq 3 ]  # exit 3: the verification did not confirm; the table says so
}

# method LEVELS REPLICATES: the study's sweep and cubic, or (--adaptive) the loop with at most a
# third of the sweep's simulations: replicated tests scatter, so a pilot measures their noise and
# each run packs its own seed; the slide sits as placed (one run a level), so no pilot.
method() {
  local levels=$1 replicates=$2
  if [ $ADAPTIVE = 0 ]; then
    printf '[design]\ntype = "sweep"\nlevels = %s\nreplicates = %s\ndegree = 3\n\n' "$levels" "$replicates"
  elif [ "$replicates" -gt 1 ]; then
    local runs=$((levels * replicates / ${THIRD:-3}))
    printf '[adaptive]\npilot = 4\nbudget = %s\nseeds = "per_run"\n\n' $((runs - 4))
  else
    printf '[adaptive]\nbudget = 3\n\n'
  fi
}

# value NAME KEY: a field of the campaign's summary.json (the calibrated factor, the verification);
# NAME may also name another JSON file of the output (roll_pvc/first_budget.json)
value() {
  local file=$OUT/$1/summary.json
  [[ $1 != *.json ]] || file=$OUT/$1
  python3 -c "import json,sys; d=json.load(open('$file')); print(eval(sys.argv[1]))" "$2"
}

# row NAME: value, 90 % credible interval (and its width), simulated mean +- se against the lab,
# agreement, and the simulations that calibrated it (the verification's apart)
row() {
  local f
  f=$(value "$1" "list(d['parameters'])[0]")
  value "$1" "'%.4g | %.4g .. %.4g | %.2g | %.4g +- %.2g | %.4g | %+.1f %% | %s | %d' % (d['parameters']['$f']['value'], \
d['parameters']['$f']['credible_low'], d['parameters']['$f']['credible_high'], \
d['parameters']['$f']['credible_high'] - d['parameters']['$f']['credible_low'], d['verification']['mean'], \
d['verification']['se'], d['measured'], 100 * d['verification']['relative_error'], d['verification']['agreement'], \
d['simulations'] - sum(len(v['runs']) for v in d['verifications']))"
}

# roll_plan NAME LOW HIGH REPLICATES: the roll of plate $p over mu_r LOW..HIGH at 7 levels, its
# e and mu_s calibrated ($e, $mu_s), each seed another orientation, 60 verification rolls.
roll_plan() {
  plan "$1" roll experiments/roll_cabbage.toml rolling_distance "${ROLL[$p]}" 0.02 \
    interaction.0.rolling_friction "$2" "$3" 7 "$4" 60 "$p" "\"interaction.0.preset\" = [\"cabbage\", \"$p\"]" \
    "\"experiment.random_orientation\" = true" \
    "\"interaction.0.restitution\" = $e" "\"interaction.0.static_friction\" = $mu_s"
}

for p in "${PLATES[@]}"; do
  echo "== $p" >&2
  plan "drop_$p" drop drop_cabbage.toml rebound_height "${DROP[$p]}" 0.05 interaction.0.restitution 0.6 0.95 8 30 30 "$p"
  e=$(value "drop_$p" "d['parameters']['restitution']['value']")
  plan "slide_$p" slide experiments/slide_cabbage_group.toml onset_angle_deg "${SLIDE[$p]}" 0.02 \
    interaction.0.static_friction 0.2 0.9 8 1 3 "$p" "\"interaction.0.restitution\" = $e"
  mu_s=$(value "slide_$p" "d['parameters']['static_friction']['value']")
  # A roll not confirmed is swept again, the study's method once more: +-15 % about the first
  # value, 20 new orientations a level (seeds from 101), 60 new verification rolls.
  # Adaptively, the same campaign resumes with its budget raised to the first sweep's 70 rolls
  # (first_budget.json keeps what the first budget said): the last verification's rolls join the
  # surrogate's data, and a new verification follows.
  if [ $ADAPTIVE = 1 ] && [ -f "$OUT/roll_$p/first_budget.json" ]; then
    THIRD=1 roll_plan "roll_$p" 0.02 0.05 10
    continue
  fi
  roll_plan "roll_$p" 0.02 0.05 10
  [ "$(value "roll_$p" "d['verification']['agreement']")" != confirmed ] || continue
  if [ $ADAPTIVE = 1 ]; then
    cp "$OUT/roll_$p/summary.json" "$OUT/roll_$p/first_budget.json"
    THIRD=1 roll_plan "roll_$p" 0.02 0.05 10
  else
    mu_r=$(value "roll_$p" "d['parameters']['rolling_friction']['value']")
    BASE_SEED=101 roll_plan "roll_fine_$p" "$(python3 -c "print(round($mu_r * 0.85, 6))")" \
      "$(python3 -c "print(round($mu_r * 1.15, 6))")" 20
  fi
done

{
  echo "| plate | test | calibrated | 90 % credible | width | simulated at it (mean +- se) | lab | error | verification | simulations |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for p in "${PLATES[@]}"; do
    for t in drop slide; do echo "| $p | $t | $(row "${t}_$p") |"; done
    if [ -f "$OUT/roll_$p/first_budget.json" ]; then
      echo "| $p | roll, first budget | $(row "roll_$p/first_budget.json") |"
      echo "| $p | roll, budget raised | $(row "roll_$p") |"
    else
      echo "| $p | roll | $(row "roll_$p") |"
    fi
    [ ! -f "$OUT/roll_fine_$p/summary.json" ] || echo "| $p | roll, swept again | $(row "roll_fine_$p") |"
  done
} > "$OUT/table.md"
cat "$OUT/table.md"
