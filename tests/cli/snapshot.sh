#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Snapshots and archives through the command, one case per ctest
# (cli.snapshot.<case>): a run saved and resumed prints the summary of the
# run never stopped (every built-in scene); an archive of a run killed with
# SIGKILL opens up to its last complete snapshot, which this script finds by
# reading the records' headers as docs/SNAPSHOTS.md describes them; a
# corrupted or truncated snapshot exits 2 with one line.
#
#   snapshot.sh CALDER WORK_DIR CASE
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

# run_calder ARGS...: stdout in out, stderr in err, the exit status in rc.
run_calder() {
  "$calder" "$@" < /dev/null > out 2> err
  rc=$?
}

# expect_ok ARGS...: runs calder and requires exit 0.
expect_ok() {
  run_calder "$@"
  [ "$rc" = 0 ] || fail "calder $* exited $rc"
}

# expect_error CODE TEXT...: exit CODE, one line on stderr holding each TEXT.
expect_error() {
  local code=$1
  shift
  [ "$rc" = "$code" ] || fail "expected exit $code, got $rc"
  [ "$(wc -l < err)" = 1 ] || fail "expected one line on stderr"
  for text in "$@"; do
    grep -qF -- "$text" err || fail "expected stderr to hold: $text"
  done
}

# same_summary WHAT STRAIGHT RESUMED: two summaries, equal to the last byte.
same_summary() {
  cmp -s "$2" "$3" || fail "$1: the resumed run differs: $(diff "$2" "$3" | head -8)"
}

# u64 FILE OFFSET: the little-endian u64 at OFFSET.
u64() { od -A n -t u8 --endian=little -j "$2" -N 8 "$1" | tr -d ' '; }

# last_archived FILE: the frame of the archive's last complete record, read
# from the records' 24-byte headers (tag, CRC-32, i64 frame, u64 length).
last_archived() {
  local file=$1 size at=16 last=-1 length
  size=$(stat -c %s "$file")
  while [ $((size - at)) -ge 24 ] && [ "$(head -c $((at + 4)) "$file" | tail -c 4)" = SNAP ]; do
    length=$(u64 "$file" $((at + 16)))
    [ "$length" -le $((size - at - 24)) ] || break
    last=$(u64 "$file" $((at + 8)))
    at=$((at + 24 + (length + 7) / 8 * 8))
  done
  echo "$last"
}

case "$case_name" in
  every_scene)
    # N frames, save, resume to N + M: the summary of N + M straight, for
    # every built-in scene, with its own seed and with --seed 42.
    scenes=$("$calder" list | cut -d' ' -f1)
    [ -n "$scenes" ] || fail "calder list printed no scene"
    for scene in $scenes; do
      for seed in "" 42; do
        flags=()
        [ -n "$seed" ] && flags=(--seed "$seed")
        expect_ok run "$scene" --frames 70 "${flags[@]}"
        mv out straight
        expect_ok run "$scene" --frames 40 "${flags[@]}" --save "$scene.snap"
        [ -s "$scene.snap" ] || fail "$scene: no snapshot written"
        expect_ok run "$scene.snap" --frames 70
        same_summary "$scene seed ${seed:-default}" straight out
      done
    done
    ;;
  resume_twice_with_trajectory)
    # A trajectory and a snapshot from one run; resumed twice.
    expect_ok run example-2.5 --frames 80 --seed 3
    mv out straight
    expect_ok run example-2.5 --frames 20 --seed 3 --trajectory t.csv --save a.snap
    [ "$(wc -l < t.csv)" -gt 20 ] || fail "the trajectory is short"
    expect_ok run a.snap --frames 50 --save b.snap
    expect_ok run b.snap --frames 80
    same_summary "two hops" straight out
    expect_ok run b.snap
    grep -q '^frames  *50$' out || fail "without --frames, a resumed run stops at its scene's frames"
    ;;
  archive_random_access)
    expect_ok run rain --frames 45 --archive rain.archive --every 10
    mv out straight45
    expect_ok run rain --frames 23
    mv out straight23
    # Resumed from the snapshot of frame 20 (the last at or before 23).
    expect_ok run rain.archive --frames 23
    same_summary "from frame 20" straight23 out
    # Without --frames: from the last snapshot, frame 45, which is the end.
    expect_ok run rain.archive
    same_summary "the last snapshot" straight45 out
    [ "$(last_archived rain.archive)" = 45 ] || fail "the last record is not of frame 45"
    ;;
  archive_sigkill)
    # A long run killed with SIGKILL while it appends: the archive opens up to
    # its last complete snapshot, and goes on from it bit for bit.
    "$calder" run rain --frames 10000000 --archive run.archive --every 3 --no-work-limit > /dev/null 2> err \
      < /dev/null &
    pid=$!
    for _ in $(seq 300); do
      [ -f run.archive ] && [ "$(stat -c %s run.archive)" -gt 400000 ] && break
      sleep 0.05
    done
    kill -KILL "$pid"
    wait "$pid"
    [ "$?" = 137 ] || fail "calder was not killed by SIGKILL"
    last=$(last_archived run.archive)
    [ "$last" -ge 6 ] || fail "the archive holds no snapshot past frame 6 (last: $last)"
    expect_ok run rain --frames $((last + 4))
    mv out straight
    expect_ok run run.archive --frames $((last + 4))
    same_summary "from frame $last" straight out
    expect_ok run run.archive --frames "$last"
    grep -q "^frames  *$last\$" out || fail "resumed at the wrong frame"
    ;;
  corrupted)
    expect_ok run example-2.7 --frames 10 --save good.snap
    size=$(stat -c %s good.snap)
    # A flipped byte in the body columns (the last section).
    cp good.snap flipped.snap
    printf '\x55' | dd of=flipped.snap bs=1 seek=$((size - 20)) conv=notrunc status=none
    run_calder run flipped.snap
    expect_error 2 "flipped.snap" "section BODY" "checksum mismatch"
    head -c $((size - 100)) good.snap > cut.snap
    run_calder run cut.snap
    expect_error 2 "cut.snap" "truncated"
    head -c 12 good.snap > header.snap
    run_calder run header.snap
    expect_error 2 "header.snap" "truncated"
    printf 'CALDSNAP\003\000\000\000\000\000\000\000' > future.snap
    run_calder run future.snap
    expect_error 2 "future.snap" "version 3"
    printf 'CALDARCH\001\000\000\000\000\000\000\000' > empty.archive
    run_calder run empty.archive
    expect_error 2 "empty.archive" "no complete snapshot"
    ;;
  bad_flags)
    expect_ok run example-2.1 --frames 30 --save a.snap
    run_calder run a.snap --seed 3
    expect_error 2 "--seed" "a.snap" "snapshot"
    run_calder run a.snap --dt 0.5
    expect_error 2 "--dt"
    run_calder run a.snap --frames 10
    expect_error 2 "--frames 10" "frame 30"
    run_calder run example-2.1 --archive x.archive --every 0
    expect_error 2 "--every" "'0'"
    [ ! -e x.archive ] || fail "an archive was created for bad flags"
    run_calder run example-2.1 --save -
    expect_error 2 "--save"
    run_calder run example-2.1 --save no/such/folder/a.snap
    expect_error 2 "no/such/folder/a.snap"
    expect_ok run example-2.1 --frames 10 --archive a.archive --every 5
    cp a.archive kept.archive
    run_calder run a.archive --frames 20 --archive a.archive
    expect_error 2 "--archive" "a.archive"
    cmp -s a.archive kept.archive || fail "the archive resumed from was overwritten"
    ;;
  *)
    fail "unknown case"
    ;;
esac
exit 0
