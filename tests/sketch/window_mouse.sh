#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# An example sketch in a real window (run inside xvfb-run), the mouse pressed
# in it by xdotool, its trajectory compared with the same sketch headless
# without the mouse:
#
#   window_mouse.sh SKETCH EXPECT
#     wind     (2.1-2.4) held for a while: wind, so some frame has vx > 0
#              (never headless, where nothing pushes sideways)
#     reset    (2.5) a click starts the movers again at the top: some frame
#              has them all at y < 1 right after one with a mover below 5
#     drag     (2.6, 2.7) the attractor dragged from (320, 120) to (200, 80):
#              another trajectory than headless
#     fan      (exercise 2.5) the mouse moved near the circles: another trajectory
#     none     (2.8, 2.9: the book's sketch has no mouse) the same trajectory,
#              bit for bit
#
# Runs in the current folder: window.csv, headless.csv and log.txt.
set -euo pipefail

sketch=$1
expect=$2
frames=240
name=$(basename "$sketch")

log() { printf '%s %s\n' "$(date +%T.%N | cut -c1-12)" "$*" >>log.txt; }
fail() {
  echo "window_mouse.sh: $name ($expect): $*" >&2
  cat log.txt >&2
  exit 1
}

: >log.txt
export SDL_RENDER_DRIVER=software
rm -f window.csv headless.csv
"$sketch" --window --frames "$frames" --trajectory window.csv --exit-after-seconds 60 --quiet \
  2>stderr.txt &
pid=$!
wid=$(timeout 30 xdotool search --sync --onlyvisible --name "^$name" | head -n 1) || true
[[ -n "$wid" ]] || { kill "$pid" 2>/dev/null || true; fail "no window named $name appeared"; }
log "window $wid: $(xdotool getwindowname "$wid")"
sleep 0.3
case "$expect" in
  wind | none)
    xdotool mousemove --window "$wid" 320 120 mousedown 1
    log "pressed"
    sleep 1
    xdotool mouseup 1
    log "released"
    ;;
  reset)
    sleep 1  # past frame 30
    xdotool mousemove --window "$wid" 320 120 click 1
    log "clicked"
    ;;
  drag)
    xdotool mousemove --window "$wid" 320 120
    sleep 0.2
    xdotool mousedown 1
    for point in "290 110" "260 100" "230 90" "200 80"; do
      read -r x y <<<"$point"
      sleep 0.1
      xdotool mousemove --window "$wid" "$x" "$y"
    done
    sleep 0.2
    xdotool mouseup 1
    log "dragged"
    ;;
  fan)
    for point in "100 200" "200 200" "300 190"; do
      read -r x y <<<"$point"
      xdotool mousemove --window "$wid" "$x" "$y"
      sleep 0.3
    done
    log "moved"
    ;;
  *) fail "unknown expectation" ;;
esac
xdotool mousemove 1000 700
status=0
wait "$pid" || status=$?
log "exited with $status"
[[ $status -eq 0 ]] || fail "the sketch exited with $status: $(cat stderr.txt)"
"$sketch" --frames "$frames" --trajectory headless.csv --quiet
[[ -s window.csv ]] || fail "no window.csv"
rows() { awk -F, 'NR > 1' "$1" | wc -l; }
[[ $(rows window.csv) -eq $(rows headless.csv) ]] || fail "window.csv has other frames than headless.csv"

case "$expect" in
  wind)
    count() { awk -F, 'NR > 1 && $5 > 0 { n++ } END { print n + 0 }' "$1"; }
    [[ $(count headless.csv) -eq 0 ]] || fail "headless has frames with vx > 0"
    [[ $(count window.csv) -gt 0 ]] || fail "no wind: no frame with vx > 0"
    ;;
  reset)
    # Frames whose bodies are all at the top (y < 1) right after a frame with
    # one lower than 5: the movers started again.
    count() {
      awk -F, 'NR > 1 { if ($1 != f) { if (f != "" && top(f)) n++; f = $1 } m[$1] = ($4 > m[$1] ? $4 : m[$1]) }
               function top(k) { return k > 1 && m[k] < 1 && m[k - 1] > 5 }
               END { if (top(f)) n++; print n + 0 }' "$1"
    }
    [[ $(count headless.csv) -eq 0 ]] || fail "headless has the movers jump back to the top"
    [[ $(count window.csv) -gt 0 ]] || fail "no reset: the movers never went back to the top"
    ;;
  drag | fan)
    ! cmp -s window.csv headless.csv || fail "the mouse changed nothing"
    ;;
  none)
    cmp -s window.csv headless.csv || fail "the mouse changed the trajectory"
    ;;
esac
log "ok"
