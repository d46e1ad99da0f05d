#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A same-run A/B of one Barnes-Hut step (the tree's build and the walk)
# between two revisions: builds bench_nbody at each in its own worktree, then
# runs them in turn, round after round, and prints a markdown table of the
# median step, build and walk times with the machine it ran on. A change to
# the tree's build lands with this table.
#
#   bench/barnes_hut_ab.sh BEFORE [AFTER] [--rounds N] [--work DIR]
#
#   BEFORE, AFTER   git revisions (AFTER: HEAD)
#   --rounds N      rounds, each one run of either side (6)
#   --work DIR      where the worktrees and builds go (build/barnes-hut-ab)
#
# The systems are bench_nbody's disk at 10^5 and 10^6 bodies, float64,
# theta 0.7, leaf 32, on 1 and 2 threads. Exit 0; 2 for a bad argument; 1,
# with one line, when a revision can't be checked out or built.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
me=barnes_hut_ab
die() {
  echo "$me: $*" >&2
  exit 1
}
usage_error() {
  echo "$me: $*" >&2
  exit 2
}

revisions=()
rounds=6
work="$root/build/barnes-hut-ab"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rounds | --work)
      [[ $# -ge 2 ]] || usage_error "$1 needs a value"
      [[ $1 == --rounds ]] && rounds=$2 || work=$2
      shift
      ;;
    -h | --help)
      sed -n '3,17s/^# \{0,1\}//p' "$0"
      exit 0
      ;;
    -*) usage_error "unknown option '$1' (see --help)" ;;
    *) revisions+=("$1") ;;
  esac
  shift
done
[[ ${#revisions[@]} -ge 1 && ${#revisions[@]} -le 2 ]] || usage_error "give BEFORE and optionally AFTER (see --help)"
[[ $rounds =~ ^[1-9][0-9]?$ ]] || usage_error "--rounds: expected 1 to 99, got '$rounds'"
[[ ${#revisions[@]} -eq 2 ]] || revisions+=(HEAD)

binaries=()
labels=()
for side in 0 1; do
  commit=$(git -C "$root" rev-parse --verify --quiet "${revisions[$side]}^{commit}") ||
    die "'${revisions[$side]}' is not a revision of $root"
  tree="$work/$commit"
  if [[ ! -d $tree ]]; then
    mkdir -p "$work"
    git -C "$root" worktree add --quiet --detach "$tree" "$commit" || die "cannot check out $commit in $tree"
  fi
  echo "$me: building bench_nbody at ${revisions[$side]} ($commit)" >&2
  { cmake -S "$tree" -B "$tree/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCALDER_BUILD_TESTS=OFF \
    -DCALDER_BUILD_EXAMPLES=OFF -DCALDER_BUILD_APPS=ON -DCALDER_BUILD_BENCHMARKS=ON \
    -DCALDER_WITH_WINDOW=OFF -DCALDER_WITH_GPU=OFF -DCALDER_BUILD_PYTHON=OFF &&
    cmake --build "$tree/build" --target bench_nbody; } >"$work/$commit.log" 2>&1 ||
    die "building ${revisions[$side]} failed (its output: $work/$commit.log)"
  binaries+=("$tree/build/bench/bench_nbody")
  labels+=("${revisions[$side]} (${commit:0:7})")
done

filter='^BarnesHut/N:(100000|1000000)/precision:64/threads:(1|2)/theta100:70/leaf:32/block:-1/real_time$'
results="$work/results.csv"
: >"$results"
load_start=$(cut -d' ' -f1 /proc/loadavg)
start=$(date -u '+%Y-%m-%d %H:%M UTC')
for ((round = 1; round <= rounds; round++)); do
  for side in 0 1; do
    echo "$me: round $round of $rounds, ${revisions[$side]}" >&2
    "${binaries[$side]}" --benchmark_filter="$filter" --benchmark_min_time=2 \
      --benchmark_format=csv 2>/dev/null | sed -n "s/^\"BarnesHut/$side,&/p" >>"$results" ||
      die "bench_nbody at ${revisions[$side]} failed"
  done
done

echo "## Machine"
echo
echo "- CPU: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1), $(nproc) logical cores"
echo "- compiler: $(c++ --version | head -n 1), CMake's Release flags"
echo "- date: $start; load average $load_start at the start, $(cut -d' ' -f1 /proc/loadavg) at the end"
echo
echo "## One Barnes-Hut step: before ${labels[0]}, after ${labels[1]}"
echo
python3 - "$results" <<'EOF'
import collections, csv, statistics, sys

runs = collections.defaultdict(list)
for row in csv.reader(open(sys.argv[1])):
    side, name = int(row[0]), row[1]
    parts = name.split("/")
    key = (int(parts[1].split(":")[1]), int(parts[3].split(":")[1]))
    # real_time, then the counters build_ms and walk_ms (Google Benchmark's CSV order)
    runs[key, side].append((float(row[3]), float(row[12]), float(row[17])))
print("| bodies | threads | rounds | step before (ms) | step after (ms) | after / before "
      "| build before / after (ms) | walk before / after (ms) |")
print("|--:|--:|--:|--:|--:|--:|--:|--:|")
for key in sorted({k for k, _ in runs}):
    a, b = runs[key, 0], runs[key, 1]
    med = lambda rows, i: statistics.median(r[i] for r in rows)
    print(f"| {key[0]:,} | {key[1]} | {len(a)} | {med(a, 0):.1f} | {med(b, 0):.1f} "
          f"| {med(b, 0) / med(a, 0):.3f} | {med(a, 1):.2f} / {med(b, 1):.2f} "
          f"| {med(a, 2):.1f} / {med(b, 2):.1f} |")
print()
print("Medians over the rounds; each round runs either side once, in turn, for at least 2 s a "
      "row (bench_nbody's BarnesHut: a disk of bodies, float64, theta 0.7, leaf 32).")
EOF
