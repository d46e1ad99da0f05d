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


# patch_snapshot FILE TAG OFFSET FORMAT VALUE: rewrites a value inside a
# snapshot's section TAG (OFFSET from the payload's end if negative, Python
# struct FORMAT) and its CRC-32, so that the file passes every checksum.
patch_snapshot() {
  python3 - "$@" <<'PY'
import struct, sys, zlib
path, tag, offset, fmt, value = sys.argv[1:]
data = bytearray(open(path, "rb").read())
(count,) = struct.unpack_from("<I", data, 12)
at = 16
for _ in range(count):
    length = struct.unpack_from("<Q", data, at + 8)[0]
    if data[at:at + 4] == tag.encode():
        start = at + 16
        where = start + length + int(offset) if int(offset) < 0 else start + int(offset)
        struct.pack_into(fmt, data, where, int(value))
        struct.pack_into("<I", data, at + 4, zlib.crc32(data[start:start + length]))
    at += 16 + ((length + 7) & ~7)
open(path, "wb").write(data)
PY
}

case "$case_name" in
  # --- outputs of a run: one policy for all of them ------------------------------
  save_over_scene_file)
    cp "$(dirname "$calder")/../../scenes/example-2.1.toml" mine.toml 2> /dev/null ||
      printf 'name = "mine"\nframes = 3\n[[bodies]]\nmass = 1\nposition = [1, 2]\n' > mine.toml
    cp mine.toml kept.toml
    run_calder run mine.toml --frames 3 --save mine.toml
    expect_error 2 "--save 'mine.toml'" "the scene file" "refusing to overwrite it"
    cmp -s mine.toml kept.toml || fail "the scene file was replaced"
    printf 'x,y,vx,vy,mass\n1,2,0,0,1\n' > rows.csv
    cp rows.csv kept.csv
    run_calder run example-2.1 --frames 3 --state rows.csv --archive rows.csv
    expect_error 2 "--archive 'rows.csv'" "--state"
    cmp -s rows.csv kept.csv || fail "the --state file was replaced"
    expect_no_temporaries
    ;;
  outputs_name_each_other)
    for pair in "--trajectory t.out --save t.out" "--save t.out --archive t.out" \
      "--trajectory t.out --archive t.out"; do
      # shellcheck disable=SC2086
      run_calder run example-2.1 --frames 3 $pair
      expect_error 2 "is also" "give each output its own file"
      [ ! -e t.out ] || fail "$pair: t.out was written"
    done
    ;;
  archive_policy)
    # The archive goes through the policy: never a device, never through a
    # dangling link, never over a write-protected file or a file that isn't one.
    run_calder run example-2.1 --frames 3 --archive /dev/null
    expect_error 2 "/dev/null" "regular file"
    ln -s victim.archive dangling
    run_calder run example-2.1 --frames 3 --archive dangling
    expect_error 2 "dangling" "symbolic link to a missing file"
    [ ! -e victim.archive ] || fail "a file was created through a dangling link"
    echo old > ro.archive && chmod 0444 ro.archive
    run_calder run example-2.1 --frames 3 --archive ro.archive
    expect_error 2 "ro.archive" "write-protected"
    [ "$(cat ro.archive)" = old ] || fail "the write-protected file was replaced"
    echo notes > notes.txt
    run_calder run example-2.1 --frames 3 --archive notes.txt
    expect_error 2 "notes.txt" "not a calder archive"
    [ "$(cat notes.txt)" = notes ] || fail "a file that is not an archive was overwritten"
    ;;
  archive_kept_on_refusal)
    # A run refused after its archive was named leaves the archive as it was;
    # a second run appends after the first one's snapshots.
    "$calder" run rain --frames 20 --archive a.archive --every 10 > /dev/null 2> err ||
      fail "the first run failed"
    cp a.archive kept.archive
    run_calder run rain --frames 10000000 --archive a.archive --every 1
    expect_error 2 "GB" "--no-work-limit"
    cmp -s a.archive kept.archive || fail "a refused run changed the archive"
    run_calder run rain --frames 20 --archive a.archive --device nothing
    [ "$rc" = 2 ] || fail "a bad --device: exit $rc"
    cmp -s a.archive kept.archive || fail "a run refused for its --device changed the archive"
    "$calder" run example-2.1 --frames 5 --archive a.archive > /dev/null 2> err ||
      fail "appending failed"
    [ "$(stat -c %s a.archive)" -gt "$(stat -c %s kept.archive)" ] || fail "nothing was appended"
    run_calder run a.archive --frames 5
    [ "$rc" = 0 ] || fail "the appended archive does not open (exit $rc)"
    grep -q "example-2.1" out || fail "the archive's last snapshot is not the appended run's"
    ;;
  archive_locked)
    # Two writers of one archive: the second is refused at once, the first's
    # archive stays whole.
    "$calder" run rain --frames 10 --archive a.archive > /dev/null 2> err || fail "first run"
    cp a.archive kept.archive
    flock -x a.archive sleep 3 &
    holder=$!
    sleep 0.5
    run_calder run rain --frames 10 --archive a.archive
    kill "$holder" 2> /dev/null
    wait "$holder" 2> /dev/null
    expect_error 2 "a.archive" "locked"
    cmp -s a.archive kept.archive || fail "the refused writer changed the archive"
    ;;
  save_planted_link)
    # The snapshot's temporary has an unpredictable name made with O_EXCL: a
    # link planted at the old fixed name (PATH.tmp-calder) is never followed.
    echo victim > victim
    ln -s victim out.snap.tmp-calder
    run_calder run example-2.1 --frames 3 --save out.snap
    [ "$rc" = 0 ] || fail "exit $rc"
    [ "$(cat victim)" = victim ] || fail "the snapshot was written through a planted link"
    [ -L out.snap.tmp-calder ] || fail "the planted link was moved"
    run_calder run out.snap --frames 4
    [ "$rc" = 0 ] || fail "the snapshot does not resume (exit $rc)"
    ;;
  # --- snapshots bounded as scene files are --------------------------------------
  snapshot_threads)
    "$calder" run example-2.9 --frames 3 --save s.snap > /dev/null 2> err || fail "save"
    cp s.snap threads.snap
    # WRLD ends: threads (u32), max_speed, time, steps.
    patch_snapshot threads.snap WRLD -28 '<i' 100000
    run_calder run threads.snap --frames 5
    expect_error 2 "threads.snap" "threads must be between 0 and 1024"
    cp s.snap frame.snap
    patch_snapshot frame.snap SIMU 0 '<q' 9223372036854775806
    run_calder run frame.snap
    expect_error 2 "frame.snap" "frame must be between 0 and"
    cp s.snap steps.snap
    patch_snapshot steps.snap WRLD -8 '<q' 9223372036854775807
    run_calder run steps.snap --frames 5
    expect_error 2 "steps.snap" "step_count must be between 0 and 2^53"
    ;;
  archive_huge_sparse)
    # A 10 GB sparse archive whose one record claims all of it: refused by
    # the sizes, without reading it into memory.
    python3 -c 'import struct, sys; sys.stdout.buffer.write(b"CALDARCH" + struct.pack(
        "<II4sIqQ", 1, 0, b"SNAP", 0, 0, (10 << 30) - 40))' > big.archive
    truncate -s 10G big.archive
    run_measured run big.archive
    expect_error 2 "big.archive" "no complete snapshot"
    [ "$kb" -lt 400000 ] || fail "reading the archive took $kb KiB"
    truncate -s 3G huge.snap
    printf 'CALDSNAP' | dd of=huge.snap conv=notrunc status=none
    run_measured run huge.snap
    expect_error 2 "huge.snap" "larger than"
    [ "$kb" -lt 400000 ] || fail "reading the snapshot took $kb KiB"
    ;;
  budget_bytes)
    run_calder run rain --frames 10000000 --archive out.archive --every 1
    expect_error 2 "would write about" "GB" "--no-work-limit"
    [ ! -e out.archive ] || fail "the archive was created for a refused run"
    ;;
  budget_reset)
    # A press that resets rebuilds the scene's million bodies, whatever
    # --state started with: counted before the run.
    printf 'name = "many"\nframes = 5\non_press = "reset"\n[[bodies]]\ncount = 1000000\n' > many.toml
    printf 'x = { min = 0, max = 640 }\ny = { min = 0, max = 240 }\nmass = 1\n' >> many.toml
    printf '[[fields]]\ntype = "mutual_attraction"\n' >> many.toml
    printf 'x,y,vx,vy,mass\n1,2,0,0,1\n3,4,0,0,1\n' > three.csv
    run_calder run many.toml --state three.csv --mouse-pressed 2-2
    expect_error 2 "many.toml" "1000000 bodies" "--no-work-limit"
    expect_within 20000
    ;;
  gpu_device_variable)
    # An index that wraps to another device (2^32 is not device 0), a sign or
    # a space: refused by name before anything runs.
    expected="CALDER_GPU_DEVICE must be a device index"
    run_calder devices
    if grep -q "CALDER_WITH_GPU=OFF" out err; then expected="CALDER_WITH_GPU=OFF"; fi
    for value in 4294967296 -1 ' 1' 1x; do
      CALDER_GPU_DEVICE=$value run_calder run example-2.9 --frames 3 --device gpu
      expect_error 2 "$expected"
    done
    ;;
  gpu_too_many_bodies)
    # Bodies that don't fit the device are refused before the run (exit 2),
    # never a failure at frame 1 (exit 1); where they fit, the run succeeds.
    printf 'name = "big"\nframes = 1\n[world]\narithmetic = "float64"\n[[bodies]]\n' > big.toml
    printf 'count = 4500000\nx = { min = 0, max = 640 }\ny = { min = 0, max = 240 }\n' >> big.toml
    printf 'mass = 1\n[[fields]]\ntype = "gravity"\n' >> big.toml
    run_calder run big.toml --device gpu
    if [ "$rc" != 0 ]; then expect_error 2 "--device gpu"; fi
    ;;
  # --- signals and pipes: one handler ----------------------------------------------
  trajectory_signal)
    # With --trajectory FILE the run still stops by calder's one handler:
    # "interrupted", both temporaries removed.
    signal_midway TERM './.t.csv.tmp-*' run rain --frames 40000 --trajectory t.csv \
      --save s.snap --no-work-limit
    grep -q "interrupted" err || fail "no 'interrupted' on stderr"
    [ ! -e t.csv ] && [ ! -e s.snap ] || fail "an output appeared"
    expect_no_temporaries
    ;;
  trajectory_pipe)
    # The reader going away is the end it asked for: no message, ever.
    for _ in $(seq 20); do
      "$calder" run rain --frames 200 --trajectory - 2> err < /dev/null | head -c 100 > /dev/null
      rc=${PIPESTATUS[0]}
      [ ! -s err ] || fail "a message after the reader left: $(cat err)"
      [ "$rc" = 0 ] || [ "$rc" = 141 ] || fail "exit $rc"
    done
    ;;
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
      signal_midway "$signal" './.calder-frames.frames.*/frame-*.png' render example-2.2 --frames 9000 --png frames -q
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
  # --- costs that grow with the input, and long frames (bounded, interruptible) --------
  summary_many_bodies)
    # 100,000 bodies under Barnes-Hut, no frame: the summary's potential energy
    # would sum 5 * 10^9 pairs (minutes); it samples a bounded number, and says so.
    printf 'frames = 0\n[[bodies]]\ncount = 100000\nmass = 1\nx = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n[[fields]]\ntype = "mutual_attraction"\nmethod = "barnes_hut"\n' > many.toml
    run_calder run many.toml
    [ "$rc" = 0 ] || fail "exit $rc"
    expect_within 60000  # 5 * 10^9 pairs took minutes
    grep -q '^potential energy  ~.* (estimated from 33554432 of 4999950000 pairs, sampled)$' out ||
      fail "the estimate is not labelled: $(grep potential out)"
    grep -q '^total energy      ~' out || fail "the total is not labelled as estimated"
    ;;
  work_theta_zero) # scene file
    printf 'frames = 10000\n[[bodies]]\ncount = 20000\nmass = 1\nx = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n[[fields]]\ntype = "mutual_attraction"\nmethod = "barnes_hut"\ntheta = 0\n' > t0.toml
    run_calder run t0.toml
    expect_error 2 "t0.toml: 20000 bodies for 10000 frames" "over the budget of 1e12"
    expect_within 2000
    ;;
  work_coincident) # scene file
    # 10^5 bodies at one point: one leaf the tree can't split, 10^10 pairs a frame.
    printf 'frames = 1000\n[[bodies]]\ncount = 100000\nmass = 1\nposition = [10, 10]\n[[fields]]\ntype = "mutual_attraction"\nmethod = "barnes_hut"\n' > one.toml
    run_calder run one.toml
    expect_error 2 "one.toml: 100000 bodies for 1000 frames" "share a point" "over the budget"
    expect_within 5000
    ;;
  work_mouse_ranges) # scene file
    { printf 'frames = 10000000\n[[bodies]]\nmass = 1\nposition = [1, 1]\n[input]\nmouse_pressed = [\n'
      seq 1 2 240000 | sed 's/.*/[&, &],/'; echo ']'; } > ranges.toml
    run_calder run ranges.toml
    expect_error 2 "ranges.toml: 1 bodies for 10000000 frames" "over the budget"
    expect_within 60000
    ;;
  work_many_fields) # scene file
    { printf 'frames = 10000000\n[[bodies]]\nmass = 1\nposition = [1, 1]\n'
      for _ in $(seq 120); do printf '[[fields]]\ntype="gravity"\n%.0s' $(seq 1000); done; } > fields.toml
    run_calder run fields.toml
    expect_error 2 "fields.toml: 1 bodies for 10000000 frames" "over the budget"
    expect_within 60000
    ;;
  hud_many_bodies) # scene file
    # The HUD's energy is bounded a frame (a sampled estimate shown with ~):
    # 5 images of 8 * 10^8 pairs each took minutes.
    printf 'frames = 4\n[[bodies]]\ncount = 40000\nmass = 1\nx = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n[[fields]]\ntype = "mutual_attraction"\nmethod = "barnes_hut"\n' > hud.toml
    run_calder render hud.toml --hud --gif out.gif -q
    [ "$rc" = 0 ] || fail "exit $rc"
    expect_within 30000
    ;;
  long_frame_signal) # scene file
    # One frame of exact mutual attraction among 60,000 bodies takes many
    # seconds: SIGTERM still ends it within a second, the temporary removed.
    printf 'frames = 1\n[[bodies]]\ncount = 60000\nmass = 1\nx = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n[[fields]]\ntype = "mutual_attraction"\n' > long.toml
    for signal in TERM INT; do
      env --default-signal="$signal" "$calder" render long.toml --no-work-limit --gif out.gif -q > /dev/null 2> err < /dev/null &
      pid=$!
      for _ in $(seq 100); do
        [ -n "$(find . -name '.out.gif.tmp-*')" ] && break
        sleep 0.1
      done
      sleep 0.5
      start=$(now_ms)
      kill -s "$signal" "$pid"
      wait "$pid"
      rc=$?
      ms=$(($(now_ms) - start))
      [ "$rc" = $((128 + $(kill -l "$signal"))) ] || fail "SIG$signal: exit $rc"
      expect_within 1500
      grep -qx 'calder: interrupted' err || fail "SIG$signal: no 'calder: interrupted' line"
      [ ! -e out.gif ] || fail "out.gif exists"
      expect_no_temporaries
    done
    ;;
  threads_1024) # scene file
    # The documented maximum, under a memory limit that can't hold 1024 thread
    # stacks: capped to the processors (results do not depend on the count).
    printf 'frames = 3\n[world]\nthreads = 1024\n[[bodies]]\ncount = 3000\nmass = 1\nx = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n[[fields]]\ntype = "mutual_attraction"\nmethod = "direct"\nthreads = 1024\n' > threads.toml
    "$calder" run threads.toml --trajectory expected.csv > /dev/null 2>&1 || fail "unlimited run failed"
    limit=4000000
    # A sanitizer's shadow memory needs more address space than any limit here.
    (ulimit -v "$limit" && exec "$calder" --version) > /dev/null 2>&1 || limit=unlimited
    (ulimit -v "$limit" && exec "$calder" run threads.toml --trajectory out.csv) > out 2> err < /dev/null
    rc=$?
    [ "$rc" = 0 ] || fail "exit $rc under ulimit -v $limit: $(head -c 300 err)"
    cmp -s expected.csv out.csv || fail "the capped run differs"
    expect_no_temporaries
    ;;
  threads_refused) # scene file
    # Thread stacks of 2 GB (ulimit -s) under 1.5 GB of address space: the
    # second thread can't start. Refused up front with one line, nothing
    # written, rather than OpenMP's abort with the temporary left behind.
    printf 'frames = 3\n[world]\nthreads = 2\n[[bodies]]\ncount = 500\nmass = 1\nx = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n[[fields]]\ntype = "mutual_attraction"\nmethod = "direct"\nthreads = 2\n' > threads.toml
    limits='ulimit -s 2000000 && ulimit -v 1500000'
    if (eval "$limits" && exec "$calder" --version) > /dev/null 2>&1; then
      (eval "$limits" && exec "$calder" run threads.toml --trajectory out.csv) > out 2> err < /dev/null
      rc=$?
      expect_error 2 "threads.toml: cannot start 2 threads"
      [ ! -e out.csv ] || fail "out.csv was written"
    else
      # A sanitizer's shadow memory needs more address space: the cap alone.
      run_calder run threads.toml --trajectory out.csv
      [ "$rc" = 0 ] || fail "exit $rc"
    fi
    expect_no_temporaries
    ;;
  # --- outputs that the policy refuses, replaces, never appends to ---------------------------
  shm_replaced)
    "$calder" run example-2.1 --frames 20 --trajectory expected.json || fail "plain run failed"
    for dir in /dev/shm "/proc/self/cwd/sub"; do
      mkdir -p sub
      target="$dir/calder-hostile-$$.json"
      for _ in 1 2; do
        run_calder run example-2.1 --frames 20 --trajectory "$target"
        [ "$rc" = 0 ] || fail "$target: exit $rc"
      done
      real=$target
      [ "$dir" = /dev/shm ] || real="sub/calder-hostile-$$.json"
      cmp -s expected.json "$real" || { rm -f "$real"; fail "$target: appended to, not replaced"; }
      rm -f "$real"
    done
    ;;
  write_protected)
    echo old > ro.csv && chmod 444 ro.csv
    run_calder run example-2.1 --frames 5 --trajectory ro.csv
    expect_error 2 "ro.csv" "write-protected"
    [ "$(cat ro.csv)" = old ] || fail "the write-protected file was replaced"
    run_calder render example-2.1 --frames 1 --gif ro.csv
    expect_error 2 "ro.csv"
    [ "$(cat ro.csv)" = old ] || fail "the write-protected file was replaced by render"
    expect_no_temporaries
    ;;
  sticky_foreign)
    # Another user's link or file in a sticky folder (/tmp): refused, as the
    # kernel's fs.protected_symlinks and protected_regular would (needs root to
    # give files away; as another user the same files are refused by the kernel).
    mkdir shared && chmod 1777 shared
    echo target > victim.csv
    ln -s "$work/victim.csv" shared/link.csv
    echo theirs > shared/theirs.csv
    if [ "$(id -u)" = 0 ]; then
      chown -h nobody shared/link.csv && chown nobody shared/theirs.csv
      run_calder run example-2.1 --frames 5 --trajectory shared/link.csv
      expect_error 2 "shared/link.csv" "another user's, in a shared (sticky) folder"
      [ "$(cat victim.csv)" = target ] || fail "the link's target was replaced"
      run_calder run example-2.1 --frames 5 --trajectory shared/theirs.csv
      expect_error 2 "shared/theirs.csv" "another user's"
      [ "$(cat shared/theirs.csv)" = theirs ] || fail "another user's file was replaced"
      [ "$(stat -c %U shared/theirs.csv)" = nobody ] || fail "the file changed owner"
    fi
    # Our own link there is followed: its target replaced, the link kept.
    ln -s "$work/victim.csv" shared/mine.csv
    run_calder run example-2.1 --frames 5 --trajectory shared/mine.csv
    [ "$rc" = 0 ] || fail "our own link: exit $rc"
    [ -L shared/mine.csv ] || fail "the link was replaced"
    [ "$(wc -l < victim.csv)" = 7 ] || fail "the link's target was not written"
    # A link to nothing is refused (nothing created through it).
    ln -s "$work/nothing.csv" dangling.csv
    run_calder run example-2.1 --frames 5 --trajectory dangling.csv
    expect_error 2 "dangling.csv" "a symbolic link to a missing file"
    [ ! -e nothing.csv ] || fail "a file was created through the link"
    expect_no_temporaries shared
    ;;
  output_is_input) # scene file
    printf 'name = "mine"\nframes = 3\n[[bodies]]\nmass = 1\nposition = [1, 1]\n' > mine.toml
    cp mine.toml kept.toml
    printf '%s\n1,2,0,0,1\n' "$rows_csv" > st.csv
    cp st.csv kept.csv
    mkdir sub
    run_calder run mine.toml --trajectory mine.toml
    expect_error 2 "--trajectory 'mine.toml': is the scene file 'mine.toml'"
    run_calder run mine.toml --trajectory ./sub/../mine.toml
    expect_error 2 "the scene file 'mine.toml'"
    run_calder render mine.toml --gif mine.toml
    expect_error 2 "--gif 'mine.toml'" "the scene file"
    run_calder run example-2.8 --state st.csv --trajectory st.csv
    expect_error 2 "--trajectory 'st.csv': is --state 'st.csv'"
    ln -s mine.toml alias.toml
    run_calder run mine.toml --trajectory alias.toml
    expect_error 2 "the scene file 'mine.toml'"
    cmp -s mine.toml kept.toml || fail "the scene file was changed"
    cmp -s st.csv kept.csv || fail "the state file was changed"
    mkdir dir
    run_calder render example-2.1 --frames 1 --png dir --gif dir/frame-000000.png
    expect_error 2 "--gif 'dir/frame-000000.png': is inside --png 'dir'"
    [ -z "$(ls -A dir)" ] || fail "dir was written"
    expect_no_temporaries
    ;;
  png_all_or_none)
    "$calder" render example-2.1 --frames 4 --png frames -q || fail "first render failed"
    echo keep > frames/notes.txt
    mkdir frames/sub && echo deep > frames/sub/file.txt
    before=$(md5sum frames/frame-* | md5sum)
    # A folder where a frame goes: refused before anything is drawn.
    rm frames/frame-000002.png && mkdir frames/frame-000002.png
    run_calder render example-2.1 --frames 3 --png frames -q
    expect_error 2 "frame-000002.png' is not a PNG file"
    rmdir frames/frame-000002.png
    # A re-render: the frames swapped as a whole, the other entries kept.
    run_calder render example-2.1 --frames 1 --png frames -q
    [ "$rc" = 0 ] || fail "re-render: exit $rc"
    [ "$(cd frames && ls | tr '\n' ' ')" = "frame-000000.png frame-000001.png notes.txt sub " ] ||
      fail "frames holds: $(ls frames | tr '\n' ' ')"
    [ "$(cat frames/notes.txt frames/sub/file.txt)" = "$(printf 'keep\ndeep')" ] || fail "other files changed"
    expect_no_temporaries frames
    [ -n "$before" ] || fail "no frames at first"
    ;;
  png_one_sync)
    # The frames are flushed to disk once a render, not once a frame.
    command -v strace > /dev/null || fail "strace is needed (Debian package strace, scripts/setup)"
    syncs=$(strace -f -c -e trace=fsync,fdatasync,syncfs "$calder" render example-2.1 --frames 60 --png frames -q 2>&1 >/dev/null |
      awk '$NF ~ /^(fsync|fdatasync|syncfs)$/ { n += $4 } END { print n + 0 }')
    [ "$(ls frames | wc -l)" = 61 ] || fail "not 61 frames"
    [ "$syncs" -ge 1 ] || fail "strace counted no flush at all"
    [ "$syncs" -le 3 ] || fail "$syncs calls to fsync/fdatasync/syncfs for 61 frames"
    ;;
  escape_in_output_path)
    dir=$'f\e]0;title\a\ncalder: forged'
    run_calder render example-2.1 --frames 1 --png "$dir" --gif "$dir.gif"
    [ "$rc" = 0 ] || fail "exit $rc"
    if LC_ALL=C grep -q $'\x1b\|\x07' out; then fail "an escape sequence in the report"; fi
    [ "$(wc -l < out)" = 2 ] || fail "expected 2 lines, got $(wc -l < out)"
    grep -q '^calder:' out && fail "a forged calder: line"
    grep -qF 'f\x1b]0;title\x07\ncalder: forged' out || fail "the path is not shown escaped: $(cat -v out)"
    ;;
  summary_overflow) # scene file
    printf 'frames = 1\n[[bodies]]\nmass = 1e10\nposition = [0, 1e300]\nvelocity = [1e300, 0]\n[[fields]]\ntype = "gravity"\ng = [0, 0.1]\nscale_by_mass = true\n' > over.toml
    run_calder run over.toml
    expect_error 1 "over.toml: frame 1:" "overflows"
    [ ! -s out ] || fail "a summary was printed: $(head -3 out)"
    ;;
  # --- work without a bound -----------------------------------------------------------
  exact_ten_million)
    printf 'frames = 10000000\n[[bodies]]\ncount = 10000000\nmass = 1\nposition = [0, 0]\n[[fields]]\ntype = "mutual_attraction"\n' > big.toml
    run_calder run big.toml
    expect_error 2 "big.toml: 10000000 bodies for 10000000 frames" "over the budget of 1e12" "--no-work-limit"
    expect_within 2000
    ;;
  # --- friendlier command errors: suggestions -----------------------------------------
  unknown_command)
    run_calder runn example-2.1
    expect_error 2 "unknown command 'runn' (did you mean 'run'?)" \
      "the commands are list, run, render, window, devices and sweep"
    run_calder nosuch --help
    expect_error 2 "unknown command 'nosuch'; the commands are list, run, render, window, devices and sweep"
    run_calder
    expect_error 2 "a command is required: list, run, render, window, devices or sweep"
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
