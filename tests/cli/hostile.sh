#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Hostile input and hostile outputs for `calder`, one case per ctest
# (cli.hostile.<case>): what an attacker or an unlucky user would try. Each
# case states what must hold; a failure prints why and exits 1.
#
#   hostile.sh CALDER WORK_DIR CASE
set -u
calder=$1
work=$2
case_name=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

fail() {
  echo "FAIL ($case_name): $*" >&2
  [ -f err ] && { echo "--- stderr:" >&2; head -c 2000 err >&2; echo >&2; }
  exit 1
}

now_ms() { date +%s%3N; }

# run_calder ARGS...: runs calder (stdin from /dev/null) with stdout in out,
# stderr in err; sets rc and ms (wall time).
run_calder() {
  local start
  start=$(now_ms)
  "$calder" "$@" < /dev/null > out 2> err
  rc=$?
  ms=$(($(now_ms) - start))
}

# expect_error CODE [TEXT...]: exit CODE, one line on stderr starting
# "calder: ", holding each TEXT, no control character but the newline.
expect_error() {
  local code=$1
  shift
  [ "$rc" = "$code" ] || fail "expected exit $code, got $rc"
  [ "$(wc -l < err)" = 1 ] || fail "expected one line on stderr"
  head -c 8 err | grep -q '^calder: ' || fail "expected 'calder: ' first"
  [ "$(grep -o 'calder: ' err | wc -l)" = 1 ] || fail "the 'calder: ' prefix repeats"
  if LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n' < err); then fail "control characters on stderr"; fi
  for text in "$@"; do
    grep -qF -- "$text" err || fail "expected stderr to hold: $text"
  done
}

expect_within() {  # expect_within MS: the last run took less than MS milliseconds
  [ "$ms" -lt "$1" ] || fail "took ${ms} ms, expected under $1 ms"
}

expect_no_temporaries() {  # in the current folder and those given
  local left
  left=$(find . "$@" -name '.*.tmp-*' -o -name '.calder-frames.*' -o -name '.calder.tmp-*' | head -5)
  [ -z "$left" ] || fail "temporaries left behind: $left"
}

# run_measured ARGS...: run_calder, with calder's peak memory in KiB (GNU
# time) in kb.
run_measured() {
  /usr/bin/time -f '%M' -o rss "$calder" "$@" < /dev/null > out 2> err
  rc=$?
  kb=$(tail -1 rss)
}

rows_csv='x,y,vx,vy,mass'

# signal_midway SIGNAL PATTERN ARGS...: starts calder ARGS with SIGNAL's
# default action (a background job of a script ignores SIGINT and SIGQUIT),
# waits until a file matching PATTERN (a find -path pattern) exists, sends
# SIGNAL and sets rc to calder's exit status.
signal_midway() {
  local signal=$1 pattern=$2 pid
  shift 2
  env --default-signal="$signal" "$calder" "$@" > /dev/null 2> err < /dev/null &
  pid=$!
  for _ in $(seq 100); do
    [ -n "$(find . -path "$pattern")" ] && break
    sleep 0.1
  done
  kill -s "$signal" "$pid"
  wait "$pid"
  rc=$?
  [ "$rc" = $((128 + $(kill -l "$signal"))) ] || fail "SIG$signal: exit $rc"
}

case "$case_name" in
  # --- a crash on a small file ---------------------------------------------------
  deep_dotted_key) # scene file
    { echo 'name = "deep"'; printf 'a%.0s.' $(seq 50000); echo 'a = 1'; } > deep.toml
    run_calder run deep.toml
    expect_error 2 "deep.toml:2:" "nested more than 32 deep"
    ;;
  deep_table_header) # scene file
    { printf '['; printf 'a%.0s.' $(seq 50000); echo 'a]'; } > deep.toml
    run_calder run deep.toml
    expect_error 2 "deep.toml:1:" "nested more than 32 deep"
    ;;
  deep_inline_tables) # scene file
    { printf 'x = '; printf '{ a = %.0s' $(seq 20000); echo; } > deep.toml
    run_calder run deep.toml
    expect_error 2 "deep.toml:1:" "nested more than 32 deep"
    ;;
  # --- unbounded time and memory ------------------------------------------------
  huge_unknown_key) # scene file
    { echo 'name = "x"'; head -c 3000000 /dev/zero | tr '\0' q; echo ' = 1'; } > key.toml
    run_calder run key.toml
    expect_error 2 "key.toml:2:1:"
    expect_within 1000
    [ "$(wc -c < err)" -lt 200 ] || fail "message of $(wc -c < err) characters"
    # Within the line limit but beyond the key limit, and a long unknown key
    # inside the limit: short messages, no distance table of a huge word.
    { echo 'name = "x"'; head -c 250 /dev/zero | tr '\0' q; echo ' = 1'; } > key.toml
    run_calder run key.toml
    expect_error 2 "unknown key 'qqqq" "...'"
    [ "$(wc -c < err)" -lt 400 ] || fail "message of $(wc -c < err) characters"
    ;;
  scene_dev_zero) # scene file
    run_calder run /dev/zero
    expect_error 2 "/dev/zero: not a regular file"
    expect_within 2000
    mkfifo scene.toml
    run_calder run scene.toml
    expect_error 2 "scene.toml: not a regular file"
    expect_within 2000
    ;;
  scene_too_big) # scene file
    { echo 'name = "x"'; for _ in $(seq 5); do head -c 1048576 /dev/zero | tr '\0' ' '; done; } > big.toml
    run_calder run big.toml
    expect_error 2 "big.toml: larger than 4 MiB"
    ;;
  state_dev_zero)
    run_calder run example-2.8 --state /dev/zero
    expect_error 2 "/dev/zero: not a regular file"
    expect_within 2000
    mkfifo state.csv
    run_calder run example-2.8 --state state.csv
    expect_error 2 "state.csv: not a regular file"
    expect_within 2000
    ;;
  state_too_many_rows)
    # 10^7 + 1 rows: refused before any is stored (a stored row takes 56 bytes:
    # 560 MB for 10^7).
    { echo "$rows_csv"; yes 0,0,0,0,1 | head -n 10000001; } > state.csv
    run_measured run example-2.8 --state state.csv
    expect_error 2 "state.csv: 10000001 rows, more than 10000000"
    [ "$kb" -lt 200000 ] || fail "peak memory ${kb} KiB"
    ;;
  state_long_line)
    { echo "$rows_csv"; head -c 100000 /dev/zero | tr '\0' 1; echo ',0,0,0,1'; } > state.csv
    run_calder run example-2.8 --state state.csv
    expect_error 2 "state.csv:2: a line longer than 4096 bytes"
    ;;
  # --- outputs that must not be replaced ------------------------------------------
  trajectory_fifo)
    "$calder" run example-2.1 --frames 50 --trajectory expected.csv || fail "plain run failed"
    mkfifo pipe.csv
    cat pipe.csv > got.csv &
    reader=$!
    run_calder run example-2.1 --frames 50 --trajectory pipe.csv
    wait "$reader"
    [ "$rc" = 0 ] || fail "exit $rc"
    cmp -s expected.csv got.csv || fail "the FIFO's reader did not receive the rows"
    [ -p pipe.csv ] || fail "the FIFO was replaced"
    expect_no_temporaries
    ;;
  trajectory_symlink)
    "$calder" run example-2.1 --frames 50 --trajectory expected.csv || fail "plain run failed"
    mkdir real && echo old > real/target.csv && chmod 600 real/target.csv
    ln -s real/target.csv link.csv
    run_calder run example-2.1 --frames 50 --trajectory link.csv
    [ "$rc" = 0 ] || fail "exit $rc"
    [ -L link.csv ] || fail "the link was replaced"
    cmp -s expected.csv real/target.csv || fail "the link's target did not receive the rows"
    [ "$(stat -c %a real/target.csv)" = 600 ] || fail "mode $(stat -c %a real/target.csv), not 600"
    expect_no_temporaries real
    ;;
  trajectory_keeps_mode)
    echo old > out.csv && chmod 640 out.csv
    run_calder run example-2.1 --frames 5 --trajectory out.csv
    [ "$rc" = 0 ] || fail "exit $rc"
    [ "$(stat -c %a out.csv)" = 640 ] || fail "mode $(stat -c %a out.csv), not 640"
    ;;
  trajectory_long_name)
    name=$(printf 'n%.0s' $(seq 251)).csv  # 255 bytes: the longest legal name
    run_calder run example-2.1 --frames 5 --trajectory "$name"
    [ "$rc" = 0 ] || fail "exit $rc"
    [ "$(wc -l < "$name")" = 7 ] || fail "the file was not written"
    expect_no_temporaries
    ;;
  trajectory_dev_full)
    run_calder run example-2.1 --trajectory /dev/full
    expect_error 1 "cannot write '/dev/full': No space left on device"
    [ -c /dev/full ] || fail "/dev/full is no longer a device"
    "$calder" run example-2.1 --trajectory - > /dev/full 2> err < /dev/null
    rc=$?
    expect_error 1 "standard output: write failed"
    "$calder" --help > /dev/full 2> err
    rc=$?
    expect_error 1 "standard output: write failed"
    ;;
  trajectory_full_disk)
    # A full file system: the first failed write stops the run (rain's 50000
    # frames of 1000 bodies would format 5 * 10^7 rows first), with the
    # system's message; the temporary is removed, an existing file untouched.
    mkdir disk
    if mount -t tmpfs -o size=256k tmpfs disk 2> /dev/null; then
      trap 'umount "$work/disk"' EXIT
      echo old > disk/out.csv
      run_calder run rain --frames 49999 --trajectory disk/out.csv
      expect_error 1 "cannot write 'disk/out.csv': No space left on device"
      expect_within 3000
      [ "$(cat disk/out.csv)" = old ] || fail "the existing file was changed"
      expect_no_temporaries disk
    else
      # No mount here (not root, or a container without CAP_SYS_ADMIN): the
      # file-size limit gives the same moment, SIGXFSZ at the first write past
      # it; calder removes the temporary and ends by that signal.
      echo old > out.csv
      (ulimit -f 256 && exec "$calder" run rain --frames 49999 --trajectory out.csv) > out 2> err < /dev/null
      rc=$?
      [ "$rc" = $((128 + $(kill -l XFSZ))) ] || fail "exit $rc, expected 128 + SIGXFSZ"
      [ "$(cat out.csv)" = old ] || fail "the existing file was changed"
      expect_no_temporaries
    fi
    ;;
  signals_run)
    for signal in HUP QUIT PIPE XFSZ ALRM USR1 USR2 INT TERM; do
      rm -f out.csv
      signal_midway "$signal" './.out.csv.tmp-*' run exercise-2.16 --frames 400000 --trajectory out.csv
      [ ! -e out.csv ] || fail "SIG$signal: out.csv exists"
      expect_no_temporaries
    done
    ;;
  signals_render)
    "$calder" render example-2.1 --frames 3 --png frames -q || fail "first render failed"
    before=$(md5sum frames/* | md5sum)
    for signal in HUP QUIT PIPE TERM; do
      signal_midway "$signal" './frames/.calder-frames.*/frame-*.png' render example-2.2 --frames 9000 --png frames -q
      [ "$(md5sum frames/* | md5sum)" = "$before" ] || fail "SIG$signal: the earlier frames changed"
      expect_no_temporaries frames
    done
    ;;
  signals_window)
    # Under SDL's dummy driver, which needs no display: each signal ends the
    # window with 128 + N (SDL would have turned SIGINT into a normal quit).
    export SDL_VIDEODRIVER=dummy
    for signal in HUP INT TERM USR1; do
      env --default-signal="$signal" "$calder" window example-2.1 -q > /dev/null 2> err < /dev/null &
      pid=$!
      sleep 1
      kill -s "$signal" "$pid"
      wait "$pid"
      rc=$?
      [ "$rc" = $((128 + $(kill -l "$signal"))) ] || fail "SIG$signal: exit $rc"
    done
    ;;
  rerender_failed)
    "$calder" render example-2.1 --frames 3 --png frames -q || fail "first render failed"
    before=$(md5sum frames/* | md5sum)
    # Positions overflow in the first step: frame 0 is drawn, then the run fails.
    printf '%s\n1e308,0,1.7e308,0,1\n' "$rows_csv" > state.csv
    run_calder render example-2.8 --state state.csv --png frames -q
    expect_error 1 "frame 1:"
    [ "$(md5sum frames/* | md5sum)" = "$before" ] || fail "the earlier frames changed"
    expect_no_temporaries frames
    ;;
  # --- drawing hangs on huge shapes ---------------------------------------------------
  huge_radius_render)
    for radius in 1e300 1e25; do
      printf '%s,radius\n320,180,0,0,1,%s\n0,0,0,0,1,%s\n' "$rows_csv" "$radius" "$radius" > state.csv
      run_calder render example-2.8 --state state.csv --frames 2 --png "frames$radius" -q
      [ "$rc" = 0 ] || fail "radius $radius: exit $rc"
      expect_within 2000
    done
    ;;
  huge_radius_window)
    printf '%s,radius\n320,180,0,0,1,1e300\n' "$rows_csv" > state.csv
    export SDL_VIDEODRIVER=dummy
    run_calder window example-2.8 --state state.csv --frames 3 -q
    [ "$rc" = 0 ] || fail "exit $rc"
    expect_within 5000
    ;;
  # --- a stale display, raw control characters, undefined behaviour -------------------
  stale_display)
    display=:97
    [ -e /tmp/.X11-unix/X97 ] && fail "an X server runs on $display: pick another number"
    unset SDL_VIDEODRIVER WAYLAND_DISPLAY
    DISPLAY=$display run_calder window example-2.1 --frames 3 -q
    expect_error 2 "no display"
    expect_within 5000
    ;;
  escape_in_key) # scene file
    printf 'name = "x"\n"a\\u001b]0;title\\u0007b" = 1\n' > esc.toml
    run_calder run esc.toml
    expect_error 2 "unknown key 'a\\x1b]0;title\\x07b'"
    printf 'name = "x"\n"a\x1b[2Jb" = 1\n' > raw.toml
    run_calder run raw.toml
    expect_error 2 "raw.toml:2:3: control character U+001B"
    printf 'name = "\\u001b[2J"\n' > name.toml
    "$calder" run name.toml > out 2> err < /dev/null || fail "exit $?"
    if LC_ALL=C grep -q $'\x1b' out; then fail "an escape sequence in the summary"; fi
    grep -qF 'scene             \x1b[2J' out || fail "the name is not shown escaped"
    ;;
  nul_in_state)
    printf '%s\n1,2\0zz,3,4,5\n' "$rows_csv" > state.csv
    run_calder run example-2.8 --state state.csv
    expect_error 2 "state.csv:2: y: '2\\x00zz' is not a number"
    ;;
  unreachable_code_points) # scene file
    # toml++ 3.3.0 reaches __builtin_unreachable when it tests these for
    # whitespace: refused before it sees them; inside strings they are text.
    for text in 'x = \uFC00' '\uFEFE = 1' 'x = 1 \u3001'; do
      printf "name = \"x\"\n$text\n" > cp.toml
      run_calder run cp.toml
      expect_error 2 "cp.toml:2:" "outside a string or comment"
    done
    printf 'name = "\uFC00\uFEFE"\n# \uFC00\n' > ok.toml
    run_calder run ok.toml
    [ "$rc" = 0 ] || fail "non-ASCII text in a string or comment refused"
    printf 'name = "x"\nx = """a\\\n  \uFC00"""\n' > escape.toml
    run_calder run escape.toml
    expect_error 2 "escape.toml:3:3: non-ASCII text right after a line-ending backslash"
    printf 'name = "\xff"\n' > bad.toml
    run_calder run bad.toml
    expect_error 2 "bad.toml:1:9: the file is not valid UTF-8"
    ;;
  # --- work without a bound -----------------------------------------------------------
  exact_ten_million)
    printf 'frames = 10000000\n[[bodies]]\ncount = 10000000\nmass = 1\nposition = [0, 0]\n[[fields]]\ntype = "mutual_attraction"\n' > big.toml
    run_calder run big.toml
    expect_error 2 "big.toml: 10000000 bodies for 10000000 frames" "over the budget of 1e12" "--no-work-limit"
    expect_within 2000
    ;;
  # --- friendlier command errors (issue 13) -------------------------------------------
  unknown_command)
    run_calder runn example-2.1
    expect_error 2 "unknown command 'runn' (did you mean 'run'?)"
    ;;
  near_scene_names)
    run_calder run example2.7
    expect_error 2 "unknown scene 'example2.7' (did you mean 'example-2.7'?)"
    echo 'name = "three"' > three.toml
    run_calder run three
    expect_error 2 "unknown scene 'three' (did you mean 'three.toml'?)"
    ;;
  key_after_table) # scene file
    printf '[[bodies]]\nmass = 1\nposition = [1, 2]\nframes = 10\n' > after.toml
    run_calder run after.toml
    expect_error 2 "after.toml:4:1: unknown key 'frames' in [[bodies]]" \
      "keys after a table header belong to that table"
    ;;
  *)
    echo "hostile.sh: unknown case '$case_name'" >&2
    exit 2
    ;;
esac
exit 0
