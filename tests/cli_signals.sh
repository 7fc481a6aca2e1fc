#!/usr/bin/env bash
# Signals a scheduler sends (issue 19): SIGTERM (Slurm, most batch systems, `kill`), SIGHUP (a
# closed terminal) and SIGINT (Ctrl-C) each let `tessera render` finish the frame in hand,
# wait for the frames being written, and exit 128 + N with a line saying how to continue;
# every frame on disk is complete and no temporary is left, in frames rendered in memory and in
# frames streamed band by band, and with a simulation writing checkpoints. A process started
# with SIGHUP ignored (nohup) keeps ignoring it.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
skin=$(cd "$(dirname "$0")/data" && pwd)/growing_skin.json

# entries DIR: how many files DIR holds, hidden ones included (no process started: the polls
# below run every 10 ms).
entries() {
    local all
    all=$(shopt -s nullglob dotglob; set -- "$1"/*; echo $#)
    echo "$all"
}

# interrupt SIGNAL CODE FILES ARGS...: starts `tessera ARGS`, sends SIGNAL once FILES files
# (frames or temporaries being written) are in the output folder, so that the frame loop is
# running, and expects exit CODE (or 0 if it finished first), complete frames only. (A signal
# before the loop, while the scene is built, ends the process at once: nothing to finish.)
interrupt() {
    local signal=$1 code=$2 files=$3 out=$dir/$1_$RANDOM
    shift 3
    mkdir -p "$out"
    "$tessera" "${@//@OUT@/$out}" 2>"$dir/stderr" &
    local pid=$!
    for _ in $(seq 1 3000); do
        [ "$(entries "$out")" -ge "$files" ] && break
        kill -0 $pid 2>/dev/null || break
        sleep 0.01
    done
    kill -s "$signal" $pid 2>/dev/null
    wait $pid
    local got=$?
    if [ $got -ne 0 ]; then
        [ $got -eq "$code" ] || fail "SIG$signal: exit $got, expected $code: $(cat "$dir/stderr")"
        grep -q 'rerun with --resume' "$dir/stderr" || fail "SIG$signal: no word on how to continue: $(cat "$dir/stderr")"
    fi
    [ -z "$(find "$out" -name '.*.tmp*')" ] || fail "SIG$signal left temporaries: $(find "$out" -name '.*.tmp*')"
    # iinfo --stats decodes every pixel of every file (one process for all: it starts slowly).
    local frames=("$out"/f_*)
    if [ -e "${frames[0]}" ] && iinfo --stats "${frames[@]}" 2>&1 | grep -qi error; then
        fail "SIG$signal: a frame is incomplete: $(iinfo --stats "${frames[@]}" 2>&1 | grep -i error)"
    fi
    echo "SIG$signal: exit $got, $(ls "$out" | wc -l) frames"
}

# SIGTERM in every kind of run: frames in memory in each format, frames streamed band by band
# (wider than one pass: the signal comes while a band is rendered), a growing skin writing
# checkpoints (its folder counts as one file). SIGHUP and SIGINT act alike.
for ext in png exr tif; do
    interrupt TERM 143 2 render --scene flag --size 320x240 --frames 1:200 --quiet --out "@OUT@/f_####.$ext"
done
interrupt TERM 143 1 render --scene flag --size 8300x64 --frames 1:50 --quiet --out "@OUT@/f_####.exr"
interrupt TERM 143 2 render --scene "$skin" --size 64x48 --frames 1:100 --checkpoint-every 2 --quiet \
    --out "@OUT@/f_####.png"
interrupt HUP 129 2 render --scene flag --size 320x240 --frames 1:200 --quiet --out "@OUT@/f_####.png"
interrupt INT 130 2 render --scene flag --size 320x240 --frames 1:200 --quiet --out "@OUT@/f_####.exr"

# Started with SIGHUP ignored (nohup), tessera keeps ignoring it and renders on.
out=$dir/nohup
(trap '' HUP && exec "$tessera" render --scene flag --size 64x48 --frames 1:30 --quiet --out "$out/f_####.png") &
pid=$!
for _ in $(seq 1 3000); do [ "$(ls "$out" 2>/dev/null | wc -l)" -ge 1 ] && break; sleep 0.01; done
kill -HUP $pid 2>/dev/null
wait $pid || fail "under nohup, SIGHUP ended the render (exit $?)"
[ "$(ls "$out" | wc -l)" -eq 30 ] || fail "under nohup: $(ls "$out" | wc -l) of 30 frames"
echo "cli_signals: ok"
