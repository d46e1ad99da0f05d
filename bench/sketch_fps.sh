#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Frames per second of a sketch drawing 10,000 circles a frame (bench/sketch_circles.cpp),
# headless and in a window under Xvfb, beside `calder render` of a 10,000-body scene
# (example 2.1's forces, the bodies from a --state file), in one run:
#
#   bench/sketch_fps.sh [BUILD_DIR] [FRAMES]     (default build, 120)
set -euo pipefail
build=${1:-build}
frames=${2:-120}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sketch="$build/bench/sketch_circles"
calder="$build/apps/calder"

awk 'BEGIN { srand(1); print "x,y,vx,vy,mass,radius";
             for (i = 0; i < 10000; i++) printf "%.3f,%.3f,%.3f,%.3f,1,4\n", rand() * 640, rand() * 240, rand() * 2 - 1, rand() * 2 - 1 }' \
  >"$work/bodies.csv"

seconds() { date +%s.%N; }
rate() { awk -v f="$1" -v a="$2" -v b="$3" 'BEGIN { printf "%.1f frames/s (%d frames in %.2f s)", f / (b - a), f, b - a }'; }

echo "10,000 circles a frame, 640 x 240, scale 1, $frames frames ($(nproc) cores)"
printf '%-44s %s\n' "sketch, headless, draw only:" "$("$sketch" --headless --frames "$frames" --quiet | sed 's/.*: //')"
start=$(seconds)
"$sketch" --png "$work/sketch" --frames "$frames" --quiet >/dev/null
printf '%-44s %s\n' "sketch, headless, each frame a PNG:" "$(rate "$frames" "$start" "$(seconds)")"
start=$(seconds)
"$calder" render example-2.1 --state "$work/bodies.csv" --frames "$frames" --png "$work/render" \
  --quiet --no-work-limit
printf '%-44s %s\n' "calder render, 10,000 bodies, each a PNG:" "$(rate "$((frames + 1))" "$start" "$(seconds)")"
if command -v xvfb-run >/dev/null; then
  window=$(SDL_RENDER_DRIVER=software xvfb-run -a -s "-screen 0 1024x768x24" \
    "$sketch" --window --frames "$frames" --quiet | sed 's/.*: //')
  printf '%-44s %s\n' "sketch, window under Xvfb (software):" "$window"
else
  echo "sketch, window: no xvfb-run"
fi
