#!/usr/bin/env bash
# An interrupted render leaves only complete frames, and --resume finishes the job: a run is
# killed with SIGKILL mid-way (no chance to clean up); every frame file present must then be a
# complete image, --resume must skip those, remove the dead run's temporaries and render the
# rest, and the result must equal an uninterrupted run byte for byte. Ctrl-C (SIGINT) stops
# after the frame in hand with exit code 130.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
args=(--scene flag --size 320x180 --frames 1:150)

complete_png() {  # a PNG ends with its IEND chunk
  [ "$(tail -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "49454e44ae426082" ]
}

"$tessera" render "${args[@]}" --quiet --out "$dir/run/f_####.png" &
pid=$!
for _ in $(seq 1 400); do
  [ "$(ls "$dir/run" 2>/dev/null | wc -l)" -ge 5 ] && break
  sleep 0.02
done
kill -KILL $pid 2>/dev/null
wait $pid 2>/dev/null
written=$(ls "$dir/run" | wc -l)
[ "$written" -ge 1 ] || fail "nothing was written before the kill"
[ "$written" -lt 150 ] || echo "note: the run finished before the kill; resume is checked anyway"
for f in "$dir"/run/*.png; do complete_png "$f" || fail "$(basename "$f") is incomplete after SIGKILL"; done
# Pretend the killed run was caught mid-write, as it may be.
echo partial > "$dir/run/.f_0150.png.tmp99999_0"

out=$("$tessera" render "${args[@]}" --resume --out "$dir/run/f_####.png" 2>&1) || fail "--resume exited $?: $out"
grep -q "resume: $written complete frame(s) skipped" <<<"$out" || fail "resume did not skip $written frames: $out"
[ "$(ls "$dir/run" | wc -l)" -eq 150 ] || fail "after resume: $(ls "$dir/run" | wc -l) frames"
[ -z "$(ls -A "$dir/run" | grep '^\.')" ] || fail "temporaries left: $(ls -A "$dir/run" | grep '^\.')"

"$tessera" render "${args[@]}" --quiet --out "$dir/ref/f_####.png" || fail "reference run exited $?"
for f in "$dir"/ref/*.png; do cmp -s "$f" "$dir/run/$(basename "$f")" || fail "$(basename "$f") differs after resume"; done

# A second --resume has nothing to do.
out=$("$tessera" render "${args[@]}" --resume --out "$dir/run/f_####.png" 2>&1) || fail "second resume exited $?"
grep -q "resume: 150 complete frame(s) skipped" <<<"$out" || fail "second resume: $out"

# SIGINT: stops cleanly after the frame in hand, exit 130, only complete frames.
"$tessera" render "${args[@]}" --quiet --out "$dir/int/f_####.png" &
pid=$!
for _ in $(seq 1 400); do
  [ "$(ls "$dir/int" 2>/dev/null | wc -l)" -ge 3 ] && break
  sleep 0.02
done
kill -INT $pid
wait $pid
code=$?
if [ "$(ls "$dir/int" | wc -l)" -lt 150 ]; then
  [ $code -eq 130 ] || fail "SIGINT exit code $code, expected 130"
fi
[ -z "$(ls -A "$dir/int" | grep '^\.')" ] || fail "SIGINT left temporaries"
for f in "$dir"/int/*.png; do complete_png "$f" || fail "$(basename "$f") incomplete after SIGINT"; done
echo "cli_render_resume: ok"
