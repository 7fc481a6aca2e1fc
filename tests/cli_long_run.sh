#!/usr/bin/env bash
# Long runs (issue 10): an animation killed at random moments (SIGKILL twice, SIGINT once) and
# resumed with --resume ends with every frame present exactly once and byte-identical to an
# uninterrupted render of the same frames (so each decodes fully); and the resident memory of
# a 100-frame render, as it reports it per frame, does not grow after warm-up.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# A small animated scene: a spinning, tessellated torus and sphere, so frames differ.
cat >"$dir/spin.json" <<'JSON'
{"animation": {"fps": 24, "frames": [1, 100]},
 "camera": {"eye": [0, 1.5, 4], "lookat": [0, 0, 0], "orbit": 0.5},
 "lights": [{"direction": [0.3, 1, 0.5], "La": [0.1, 0.1, 0.1], "Le": [1, 1, 1]}],
 "materials": {"m": {"kd": [0.9, 0.5, 0.2], "ks": [0.4, 0.4, 0.4], "shine": 30}},
 "objects": [
   {"type": "torus", "material": "m", "major": 1, "minor": 0.35, "tessellation": [96, 48],
    "spin": {"axis": [1, 1, 0], "speed": 40}},
   {"type": "sphere", "material": "m", "radius": 0.4, "tessellation": [64, 32]}
 ]}
JSON
frames=60
args=(render --scene "$dir/spin.json" --size 64x48 --frames 1:$frames)

# Reference: one uninterrupted run.
"$tessera" "${args[@]}" --quiet --out "$dir/reference/f_####.png" || fail "reference render exited $?"

# Interrupted runs, then a final --resume to completion. Each kill comes once a random number
# (1..12) of further frames is on disk, i.e. at a random point of the frame loop and the
# background writer.
mkdir -p "$dir/resumed"
RANDOM=$$
interrupted=0
for signal in KILL INT KILL; do
    "$tessera" "${args[@]}" --resume --out "$dir/resumed/f_####.png" 2>>"$dir/log" &
    pid=$!
    target=$(( $(ls "$dir/resumed" | wc -l) + 1 + RANDOM % 12 ))
    for _ in $(seq 1000); do [ "$(ls "$dir/resumed" | wc -l)" -ge $target ] && break; sleep 0.01; done
    kill -s $signal $pid 2>/dev/null
    wait $pid; code=$?
    # SIGKILL: 137; SIGINT: 130 (finishes the frame in hand); 0 if it finished first.
    case $signal:$code in KILL:137 | INT:130) interrupted=$((interrupted + 1)) ;; *:0) ;;
        *) fail "render killed by $signal exited $code" ;; esac
    echo "after SIG$signal (exit $code): $(ls "$dir/resumed" | wc -l) of $frames frames on disk"
done
[ $interrupted -ge 1 ] || fail "no run was interrupted (frames render too fast for this test)"
"$tessera" "${args[@]}" --resume --out "$dir/resumed/f_####.png" 2>>"$dir/log" || fail "final --resume exited $?"

# Every frame exactly once, identical to the reference, and nothing else: the temporaries a
# SIGKILL left are removed when their frames are rewritten (atomic_file.h).
for f in $(seq 1 $frames); do
    name=$(printf 'f_%04d.png' "$f")
    [ -f "$dir/resumed/$name" ] || fail "frame $f missing after resume"
    cmp -s "$dir/reference/$name" "$dir/resumed/$name" || fail "frame $f differs from the uninterrupted render"
done
present=$(ls -A "$dir/resumed" | wc -l)
[ "$present" -eq $frames ] || fail "expected $frames files, found $present: $(ls -A "$dir/resumed" | grep -v '^f_')"
grep -q 'complete frame(s) skipped' "$dir/log" || fail "--resume never skipped a frame: $(cat "$dir/log")"

# Memory of a 100-frame render, as the render itself reports it after each frame (--stats:
# "heap N MiB, rss N MiB", read in the process while it is surely alive; sampling
# /proc/PID/status from here raced with the process's exit). After 20 frames of warm-up, the
# peak over frames 21-100 may exceed the level at frame 20 by at most:
#  - heap (the bytes of live allocations, as the allocator counts them): 4 MiB, in every build.
#    Leaking one 96x72 frame's buffers (~190 KiB of float colour, ids, depth and PNG bytes)
#    per frame would add ~15 MiB; the heap varies by the frames in flight in the writer (a few
#    hundred KiB).
#  - resident set: 24 MiB, in a build without a sanitizer; it also catches what bypasses malloc
#    (mmap). Under AddressSanitizer (make sanitize) RSS counts the sanitizer's shadow memory
#    and allocator regions, which it keeps: it was seen to rise by ~48 MB over the last 15
#    frames with the quarantine off and the heap flat. There, the heap is the measure (the
#    sanitizer's allocator counts live bytes, not its quarantine) and LeakSanitizer checks
#    the exit.
"$tessera" render --scene "$dir/spin.json" --size 96x72 --frames 1:100 --threads 2 --stats \
    --out "$dir/mem/f_####.png" 2>"$dir/stats" || fail "100-frame render exited $?"
# memory NAME: the per-frame values of "NAME N MiB" in KiB, one per line.
memory() { sed -n "s/^frame [0-9]*: .* $1 \([0-9.]*\) MiB.*/\1/p" "$dir/stats" | awk '{printf "%d\n", $1 * 1024}'; }
mapfile -t heap < <(memory heap)
mapfile -t rss < <(memory rss)
[ ${#heap[@]} -eq 100 ] && [ ${#rss[@]} -eq 100 ] ||
    fail "expected 100 per-frame lines with heap and rss, got ${#heap[@]} and ${#rss[@]}: $(head -3 "$dir/stats")"
# growth NAME LIMIT_KIB VALUES...: the peak of VALUES[20..] over VALUES[19], at most LIMIT_KIB.
growth() {
    local name=$1 limit=$2
    shift 2
    local values=("$@")
    local warm=${values[19]} peak
    peak=$(printf '%s\n' "${values[@]:20}" | sort -n | tail -1)
    echo "long run: $name after 20 frames ${warm} KiB, peak over frames 21-100 ${peak} KiB, growth $((peak - warm)) KiB"
    [ "$warm" -gt 0 ] || fail "the render reported no $name: $(head -3 "$dir/stats")"
    [ $((peak - warm)) -lt "$limit" ] || fail "$name grew by $((peak - warm)) KiB over 80 frames: ${values[*]}"
}
growth heap $((4 * 1024)) "${heap[@]}"
if sanitizer=$("$tessera" info | grep '^sanitizer:'); then
    echo "long run: resident set not checked ($sanitizer)"
else
    growth rss $((24 * 1024)) "${rss[@]}"
fi
echo "cli_long_run: ok"
