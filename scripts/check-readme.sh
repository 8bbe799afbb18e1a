#!/usr/bin/env bash
# The README's numbers against what its quick commands print: each check names a phrase the README
# says, the number in it, and the command (a few seconds on one cpu thread) whose output must give
# that number rounded to the README's digits. Fails when the README no longer says the phrase or the
# command prints another number. ctest runs it as "readme: numbers of its quick commands".
#   bash scripts/check-readme.sh build/repose [SOURCE_DIR]
set -uo pipefail
repose=${1:?usage: check-readme.sh REPOSE_BINARY [SOURCE_DIR]}
src=${2:-$(cd "$(dirname "$0")/.." && pwd)}
readme="$src/README.md"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0

# The output of `repose ARGS...` (run once per distinct command, from the source folder; an
# experiment on the cpu backend, one thread, into its own scratch folder).
output_of() {
  local key
  key=$(printf '%s ' "$@" | md5sum | cut -c1-16)
  if [[ ! -f "$scratch/$key.out" ]]; then
    local extra=()
    [[ $1 == experiment ]] && extra=(--quiet --backend cpu --threads 1 --out "$scratch/$key")
    (cd "$src" && "$repose" "$@" "${extra[@]}" > "$scratch/$key.out" 2>&1)
  fi
  cat "$scratch/$key.out"
}

# check PHRASE NUMBER SCALE PATTERN -- ARGS...: the README says PHRASE, which holds NUMBER; the
# command's output holds PATTERN (an extended regex) followed by a value that, times SCALE (1000:
# metres printed, millimetres in the README) and rounded to NUMBER's decimals, is NUMBER.
check() {
  local phrase=$1 number=$2 scale=$3 pattern=$4
  shift 5
  if ! grep -qF -- "$phrase" "$readme"; then
    echo "FAIL: the README no longer says '$phrase'"
    failures=$((failures + 1))
    return
  fi
  local text value decimals shown
  text=$(output_of "$@")
  value=$(grep -oE -- "${pattern}[-+0-9.eE]+" <<< "$text" | head -1 | sed -E "s|^${pattern}||")
  decimals=$(awk -v n="$number" 'BEGIN { i = index(n, "."); print i ? length(n) - i : 0 }')
  shown=$(awk -v v="$value" -v s="$scale" -v d="$decimals" 'BEGIN { if (v == "") exit 1; printf "%.*f", d, v * s }') || shown="(none)"
  if [[ $shown == "$number" ]]; then
    echo "ok: '$phrase' (repose $*: $value)"
  else
    echo "FAIL: the README says '$phrase'; repose $* gives $shown (printed: '${value}')"
    echo "$text" | sed 's/^/    /'
    failures=$((failures + 1))
  fi
}

check "L = 0.652 m, the" 0.652 1 "rolling distance L = " -- experiment roll cases/experiments/roll_sphere.toml
check "formula gives 0.0497" 0.0497 1 "\(S cos\(beta\) \+ L\) = " -- experiment roll cases/experiments/roll_sphere.toml
check "slides at 19.05 deg" 19.05 1 "alpha = " -- experiment slide cases/experiments/slide_four_spheres.toml
check "gives sqrt(h/H) = 0.4145, 0.4159" 0.4145 1 "sqrt\(h/H\) = " -- experiment drop cases/drop_sphere.toml --height 0.3
check "0.4181, 0.4189 at H = 0.3 ... 0.5 m" 0.4189 1 "sqrt\(h/H\) = " -- experiment drop cases/drop_sphere.toml --height 0.5
check "h = 80.6 mm, sqrt(h/H) = 0.4016" 80.6 1000 "rebound h = " -- experiment drop cases/experiments/drop_on_cabbages.toml
check "h = 80.6 mm, sqrt(h/H) = 0.4016" 0.4016 1 "sqrt\(h/H\) = " -- experiment drop cases/experiments/drop_on_cabbages.toml
check "gives h = 126.06 mm, e = 0.5021 (seed 1)" 126.06 1000 "\(seed 1\): h = " -- experiment drop cases/drop_cabbage.toml --replicates 3
check "gives h = 126.06 mm, e = 0.5021 (seed 1)" 0.5021 1 "\(seed 1\): h = [0-9.e-]+ m, e = " -- experiment drop cases/drop_cabbage.toml --replicates 3
check "h = 97.10 mm, e = 0.4407" 97.10 1000 "\(seed 3\): h = " -- experiment drop cases/drop_cabbage.toml --replicates 3
check "h = 97.10 mm, e = 0.4407" 0.4407 1 "\(seed 3\): h = [0-9.e-]+ m, e = " -- experiment drop cases/drop_cabbage.toml --replicates 3
check "mean 94.75 mm" 94.75 1000 "h mean " -- experiment drop cases/drop_cabbage.toml --replicates 3
check "L = 0.794 m (mu_r formula 0.0430)" 0.794 1 "rolling distance L = " -- experiment roll cases/experiments/roll_cabbage.toml
check "L = 0.794 m (mu_r formula 0.0430)" 0.0430 1 "\(S cos\(beta\) \+ L\) = " -- experiment roll cases/experiments/roll_cabbage.toml
check "mean L (0.702 m, sd 0.0945 m" 0.702 1 "replicates: mean " -- experiment roll cases/experiments/roll_cabbage.toml --replicates 5
check "mean L (0.702 m, sd 0.0945 m" 0.0945 1 "replicates: mean [0-9.e-]+ m, sd " -- experiment roll cases/experiments/roll_cabbage.toml --replicates 5
check "slides, at 35.30 deg" 35.30 1 "slide at alpha = " -- experiment slide cases/experiments/slide_cabbage_group.toml
check "1.86 kg; the pair restitution" 1.86 1 "mass +" -- clump cases/templates/cabbage.csv --density 850

if ((failures)); then
  echo "$failures README number(s) do not match"
  exit 1
fi
echo "every README number checked matches"
