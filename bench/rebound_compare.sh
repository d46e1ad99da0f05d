#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# calder's ias15 beside REBOUND's IAS15 on the classic problems (the
# Pythagorean three-body problem to t = 70, the figure-eight for ten periods,
# a Kepler orbit of e = 0.9 for 1,000 orbits), in one run: steps, force
# evaluations, wall time (best of N) and relative energy error, as a
# markdown table with calder / REBOUND ratios and the machine it ran on.
#
#   bench/rebound_compare.sh [--repetitions N] [--output FILE] [--work DIR]
#
#   --repetitions N  whole runs per problem, calder and REBOUND in turn; the
#                    best wall time counts (5)
#   --output FILE    also write the table to FILE (bench/results/rebound-ias15.md)
#   --work DIR       where REBOUND is fetched and built (BUILD/rebound-compare)
#
# REBOUND is GPL-3: this script fetches and builds it in the work folder for
# the benchmark alone; nothing calder builds or installs links it. Its side
# is bench/peers/rebound_classic.c (calder's, MIT), linked against it here.
# Exit 0; 2 for a bad argument; 1, with one line, when REBOUND can't be had
# or built, or a run fails. Environment:
#   REBOUND_SRC    a REBOUND source tree (with src/rebound.h) or a git
#                  directory holding REBOUND_REF; unset: git clone REBOUND_URL
#   REBOUND_REF    the tag to fetch (5.0.0)
#   REBOUND_URL    https://github.com/hannorein/rebound
#   CALDER_BUILD   calder's configured build folder with benchmarks on (build)
#   CC             the C compiler for REBOUND and the driver (cc)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
me=rebound_compare

die() {
  echo "$me: $*" >&2
  exit 1
}
usage_error() {
  echo "$me: $*" >&2
  exit 2
}

repetitions=5
output=""
work=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --repetitions | --output | --work)
      [[ $# -ge 2 ]] || usage_error "$1 needs a value"
      case "$1" in
        --repetitions) repetitions=$2 ;;
        --output) output=$2 ;;
        --work) work=$2 ;;
      esac
      shift
      ;;
    -h | --help)
      sed -n '3,26s/^# \{0,1\}//p' "$0"
      exit 0
      ;;
    *) usage_error "unknown argument '$1' (see --help)" ;;
  esac
  shift
done
[[ $repetitions =~ ^[1-9][0-9]{0,3}$ ]] ||
  usage_error "--repetitions must be an integer from 1 to 9999, got '$repetitions'"
if [[ -n $output && ! -d $(dirname "$output") ]]; then
  usage_error "--output $output: no folder $(dirname "$output")"
fi

ref=${REBOUND_REF:-5.0.0}
url=${REBOUND_URL:-https://github.com/hannorein/rebound}
calder_build=${CALDER_BUILD:-$root/build}
[[ $calder_build == /* ]] || calder_build=$PWD/$calder_build
work=${work:-$calder_build/rebound-compare}
cc=${CC:-cc}
# REBOUND's own optimised build (its setup.py): -O3, no fused multiply-adds.
cflags=(-O3 -std=c99 -D_GNU_SOURCE -fPIC -ffp-contract=off)
mkdir -p "$work" || die "cannot make the work folder $work"

# --- REBOUND's source ---------------------------------------------------------
if [[ -n ${REBOUND_SRC:-} ]]; then
  if [[ -f $REBOUND_SRC/src/rebound.h ]]; then
    src=$(cd "$REBOUND_SRC" && pwd)
    where="the source tree $src"
  elif git --git-dir="$REBOUND_SRC" rev-parse --verify -q "$ref^{commit}" >/dev/null 2>&1 ||
    git -C "$REBOUND_SRC" rev-parse --verify -q "$ref^{commit}" >/dev/null 2>&1; then
    gitdir=$(git --git-dir="$REBOUND_SRC" rev-parse --absolute-git-dir 2>/dev/null ||
      git -C "$REBOUND_SRC" rev-parse --absolute-git-dir)
    src=$work/rebound-$ref
    rm -rf "$src" && mkdir -p "$src"
    git --git-dir="$gitdir" archive "$ref" src | tar -x -C "$src" ||
      die "cannot export $ref from the git directory $REBOUND_SRC"
    where="tag $ref of the git directory $REBOUND_SRC"
  else
    die "REBOUND_SRC=$REBOUND_SRC is neither a REBOUND source tree (src/rebound.h) nor a git directory holding $ref"
  fi
else
  src=$work/rebound-$ref
  if [[ ! -f $src/src/rebound.h ]]; then
    rm -rf "$src"
    if ! GIT_TERMINAL_PROMPT=0 timeout 300 git clone -q --depth 1 --branch "$ref" "$url" "$src" \
      >"$work/clone.log" 2>&1; then
      rm -rf "$src"
      die "cannot fetch REBOUND $ref from $url (no network? see $work/clone.log); set REBOUND_SRC to a REBOUND source tree or git directory"
    fi
  fi
  where="tag $ref cloned from $url"
fi
version=$(sed -n 's/.*reb_version_str = "\([^"]*\)".*/\1/p' "$src/src/rebound.c" | head -n 1)
[[ -n $version ]] || die "$src/src/rebound.c: no reb_version_str: not a REBOUND source tree?"

# --- librebound.a and the driver, in the work folder ----------------------------
lib=$work/lib-$version
stamp="$src ${cc} ${cflags[*]}"
if [[ ! -f $lib/librebound.a || $(cat "$lib/stamp" 2>/dev/null) != "$stamp" ]]; then
  echo "$me: building REBOUND $version in $lib ..." >&2
  rm -rf "$lib" && mkdir -p "$lib"
  for file in "$src"/src/*.c; do
    "$cc" -c "${cflags[@]}" -w -o "$lib/$(basename "$file" .c).o" "$file" ||
      die "cannot compile REBOUND's $(basename "$file") with $cc"
  done
  ar rcs "$lib/librebound.a" "$lib"/*.o || die "cannot archive librebound.a"
  echo "$stamp" >"$lib/stamp"
fi
driver=$work/rebound_classic
"$cc" "${cflags[@]}" -Wall -Wextra -Werror -isystem "$src/src" -o "$driver" \
  "$root/bench/peers/rebound_classic.c" "$lib/librebound.a" -lm -lpthread ||
  die "cannot build bench/peers/rebound_classic.c against REBOUND $version"

# --- calder's side ----------------------------------------------------------------
[[ -f $calder_build/CMakeCache.txt ]] ||
  die "$calder_build is not a configured calder build folder (configure with -DCALDER_BUILD_BENCHMARKS=ON, or set CALDER_BUILD)"
cmake --build "$calder_build" --target bench_classic >"$work/calder-build.log" 2>&1 ||
  die "cannot build bench_classic in $calder_build (benchmarks on? see $work/calder-build.log)"
calder_exe=$calder_build/bench/bench_classic

# --- the run --------------------------------------------------------------------
cpu_busy() { # busy and total jiffies of the whole machine
  awk '/^cpu / { print $2 + $3 + $4 + $7 + $8 + $9, $2 + $3 + $4 + $5 + $6 + $7 + $8 + $9 }' /proc/stat
}
load_start=$(cut -d' ' -f1 /proc/loadavg)
read -r busy0 total0 < <(cpu_busy)
start=$(date -u '+%Y-%m-%d %H:%M UTC')
echo "$me: timing calder and REBOUND, best of $repetitions ..." >&2
results=$work/results.tsv
# Turn about, one whole run each per round, so that the load of the machine
# weighs on both sides alike; the table keeps each row's best.
for ((round = 1; round <= repetitions; ++round)); do
  "$calder_exe" 1 || die "bench_classic failed"
  "$driver" 1 || die "rebound_classic failed"
done >"$results"
read -r busy1 total1 < <(cpu_busy)
cores=$(nproc)
# What the machine did besides one core of ours: (busy - one core) / all cores.
others=$(awk -v b="$((busy1 - busy0))" -v t="$((total1 - total0))" -v n="$cores" \
  'BEGIN { o = t > 0 ? 100 * (b - t / n) / t : 0; if (o < 0) o = 0; printf "%.0f%%", o }')

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$calder_build/CMakeCache.txt")
build_type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$calder_build/CMakeCache.txt")
cxx_version=$("${cxx:-c++}" --version 2>/dev/null | head -n 1)
cc_version=$("$cc" --version 2>/dev/null | head -n 1)

table=$work/rebound-ias15.md
awk -F'\t' -v reps="$repetitions" '
  function thousands(n,   s, out) {
    s = sprintf("%d", n)
    out = ""
    while (length(s) > 3) {
      out = "," substr(s, length(s) - 2) out
      s = substr(s, 1, length(s) - 3)
    }
    return s out
  }
  function ratio(a, b) { return b > 0 ? sprintf("%.2f", a / b) : "-" }
  /^#/ { next }
  {
    key = $1 SUBSEP $2 SUBSEP $3
    if ((key in steps) && steps[key] != $4) {
      print "the runs of " $1 " " $2 " took " steps[key] " and " $4 " steps" > "/dev/stderr"
      exit 1
    }
    if (!(key in wall) || $6 < wall[key]) wall[key] = $6
    steps[key] = $4; evals[key] = $5; err[key] = $7
    if ($1 == "calder") { iters[$2] = $8; rejected[$2] = $9 }
  }
  END {
    split("pythagorean figure-eight kepler", problems, " ")
    title["pythagorean"] = "Pythagorean, t = 70"
    title["figure-eight"] = "figure-eight, 10 periods"
    title["kepler"] = "Kepler e = 0.9, 1,000 orbits"
    label["calder" SUBSEP "frames"] = "calder ias15"
    label["rebound" SUBSEP "frames"] = "REBOUND IAS15, to each frame end"
    label["rebound" SUBSEP "whole"] = "REBOUND IAS15, to the end at once"
    print "| problem | run | steps | force evaluations | per step | wall (s) | µs per step | energy error | calder / this: steps | calder / this: wall |"
    print "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|"
    for (p = 1; p <= 3; ++p) {
      name = problems[p]
      c = "calder" SUBSEP name SUBSEP "frames"
      n = split("calder,frames rebound,frames rebound,whole", runs, " ")
      for (r = 1; r <= n; ++r) {
        split(runs[r], part, ",")
        key = part[1] SUBSEP name SUBSEP part[2]
        if (!(key in steps)) continue
        mine = part[1] == "calder"
        printf "| %s | %s | %s | %s | %.1f | %.3g | %.2f | %s | %s | %s |\n", \
          r == 1 ? title[name] : "", label[part[1] SUBSEP part[2]], thousands(steps[key]), \
          thousands(evals[key]), evals[key] / steps[key], wall[key], 1e6 * wall[key] / steps[key], \
          err[key], \
          mine ? "" : ratio(steps[c], steps[key]), mine ? "" : ratio(wall[c], wall[key])
      }
    }
    printf "\ncalder predictor-corrector iterations per step:"
    for (p = 1; p <= 3; ++p) {
      name = problems[p]
      c = "calder" SUBSEP name SUBSEP "frames"
      printf " %s %.2f (%d rejected)%s", name, iters[name] / steps[c], rejected[name], p < 3 ? "," : ".\n"
    }
  }' "$results" >"$work/table.md" || die "cannot make the table from $results"

{
  echo "## Machine"
  echo
  echo "- CPU: ${cpu:-unknown CPU}, $cores logical cores"
  echo "- calder: ${calder_exe#"$root"/}, ${cxx_version:-$cxx}, build type ${build_type:-unknown}"
  echo "- REBOUND: $version ($where), built by this script with $cc_version, ${cflags[*]}"
  echo "- date: $start; load average $load_start at the start"
  echo "- timing: best of $repetitions whole runs per row (making the simulation, integrating, one thread), calder's and REBOUND's in turn; wall clock"
  echo "- others: other processes took $others of the CPUs during the run (0% for clean figures)"
  echo
  echo "## ias15 beside REBOUND's IAS15 (epsilon 1e-9)"
  echo
  cat "$work/table.md"
  echo
  echo "- Same initial conditions, G and frames as calder's built-in scenes (there in pixels, here in the literature's units). calder's tolerance 1e-9 is REBOUND's epsilon; both use the step criterion of Pham, Rein & Spiegel (2024), REBOUND's default (adaptive_mode PRS23), and start from REBOUND's default first step (0.001) or, in calder, the frame's dt if the criterion accepts it."
  echo "- calder ends every frame exactly (World::step advances dt): 700 frames of 0.1, 1,200 of a 120th of the period, 1,000 of one orbit. REBOUND to each frame end does the same with exact_finish_time; to the end at once is REBOUND's one call to t_end."
  echo "- Force evaluations: calder counts them (AdaptiveStats); REBOUND's through a no-op additional_forces callback, in an untimed run. One per step's start plus seven per predictor-corrector iteration."
  echo "- Energy error: |E - E0| / |E0| at the end, kinetic plus pair potential energy (Kepler: of the orbiting unit mass around the fixed one)."
  echo "- Per step, REBOUND integrates three coordinates a body (x, y, z; here z stays 0), calder two: the problems are planar."
  echo "- Command: bench/rebound_compare.sh --repetitions $repetitions${output:+ --output $output}"
} >"$table"

cat "$table"
if [[ -n $output ]]; then
  tmp=$(mktemp "$(dirname "$output")/.$(basename "$output").tmp-XXXXXX") || die "cannot write $output"
  if ! { cp "$table" "$tmp" && mv "$tmp" "$output"; }; then
    rm -f "$tmp"
    die "cannot write $output"
  fi
fi
