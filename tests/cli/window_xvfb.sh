#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Drives `calder window` with xdotool, inside an X display made by xvfb-run
# (window.cmake runs: xvfb-run -a -s "-screen 0 1024x768x24" bash window_xvfb.sh ...).
#
#   window_xvfb.sh CALDER drag SCALE   drags example-2.7's attractor from (320, 120) to
#                                      (200, 80) (canvas pixels); the window writes
#                                      out.png and prints its state to state.txt
#   window_xvfb.sh CALDER keys         presses s, g, f, space, ., ., k, g, +, q on example-2.1
#
# Runs in the current folder; calder's stdout goes to state.txt, its stderr to
# stderr.txt; every step is logged to log.txt.
set -euo pipefail

calder=$1
scenario=$2
scale=${3:-1}

log() { printf '%s %s\n' "$(date +%T.%N | cut -c1-12)" "$*" >>log.txt; }

# The window pixel of canvas pixel $1.
px() { awk -v s="$scale" -v v="$1" 'BEGIN { printf "%d", v * s + 0.5 }'; }

# Waits (30 s at most) for a visible window whose name starts with $1.
find_window() {
  local wid
  wid=$(timeout 30 xdotool search --sync --onlyvisible --name "^$1" | head -n 1) || true
  if [[ -z "$wid" ]]; then
    log "no window named '$1' appeared"
    return 1
  fi
  log "window $wid: $(xdotool getwindowname "$wid")"
  printf '%s\n' "$wid"
}

# Waits (60 s at most) for calder to exit; its status goes to status.txt.
finish() {
  local pid=$1 status=0
  for _ in $(seq 600); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    log "calder did not exit; killing it"
    kill "$pid" 2>/dev/null || true
  fi
  wait "$pid" || status=$?
  log "calder exited with $status"
  printf '%s\n' "$status" >status.txt
}

: >log.txt
log "DISPLAY=$DISPLAY"
# Software rendering: nothing to set up in Xvfb, and no driver to leak.
export SDL_RENDER_DRIVER=software

case "$scenario" in
  drag)
    "$calder" window example-2.7 --seed 1 --scale "$scale" --frames 600 \
      --exit-after-seconds 60 --screenshot out.png --print-state --quiet \
      >state.txt 2>stderr.txt &
    pid=$!
    if ! wid=$(find_window "calder: example-2.7"); then
      finish "$pid"
      exit 1
    fi
    sleep 0.3
    # Onto the attractor, press, drag in small moves, release.
    xdotool mousemove --window "$wid" "$(px 320)" "$(px 120)"
    log "mouse at $(xdotool getmouselocation)"
    sleep 0.3
    xdotool mousedown 1
    log "pressed"
    sleep 0.3
    for point in "290 110" "260 100" "230 90" "200 80"; do
      read -r x y <<<"$point"
      xdotool mousemove --window "$wid" "$(px "$x")" "$(px "$y")"
      sleep 0.1
    done
    log "dragged to $(xdotool getmouselocation)"
    sleep 0.3
    xdotool mouseup 1
    log "released"
    # Away from the canvas, so nothing else is pressed or followed.
    xdotool mousemove 1000 700
    finish "$pid"
    ;;
  keys)
    "$calder" window example-2.1 --exit-after-seconds 60 --screenshot out.png --print-state --quiet \
      >state.txt 2>stderr.txt &
    pid=$!
    if ! wid=$(find_window "calder: example-2.1"); then
      finish "$pid"
      exit 1
    fi
    sleep 0.3
    xdotool windowfocus --sync "$wid" || xdotool windowfocus "$wid" || true
    sleep 0.2
    # Each key, then (once calder has had time to take it) the window's title.
    for key in s g f space period period k g plus q; do
      xdotool key --clearmodifiers "$key"
      sleep 0.5
      log "key $key; title: $(xdotool getwindowname "$wid" 2>/dev/null || echo gone)"
    done
    finish "$pid"
    ;;
  *)
    echo "window_xvfb.sh: unknown scenario '$scenario'" >&2
    exit 2
    ;;
esac
