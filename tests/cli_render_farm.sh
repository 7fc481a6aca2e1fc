#!/usr/bin/env bash
# `tessera render` on a farm: two processes sharing one output folder with --claim render
# every frame exactly once (none half-written, no claim left); stale claims are respected
# without --resume and taken over with it (dead pid on this host, or --claim-timeout); a
# growing skin (state that depends on every earlier frame) gives the same bytes whether the
# frames come from one run, from shards, or from a run starting at frame k with or without
# checkpoints, and a damaged checkpoint is refused.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scene=$(dirname "$0")/data/growing_skin.json

# --- Two processes, one folder ---------------------------------------------------------------
args=(--scene flag --size 128x96 --frames 1:60 --threads 1)
"$tessera" render "${args[@]}" --quiet --out "$dir/ref/f_####.png" || fail "reference run exited $?"
"$tessera" render "${args[@]}" --claim --out "$dir/farm/f_####.png" 2>"$dir/a.log" & a=$!
"$tessera" render "${args[@]}" --claim --out "$dir/farm/f_####.png" 2>"$dir/b.log" & b=$!
wait $a || fail "process A exited $?: $(tail -2 "$dir/a.log")"
wait $b || fail "process B exited $?: $(tail -2 "$dir/b.log")"
rendered=$(cat "$dir/a.log" "$dir/b.log" | sed -n 's/^frame \([0-9]*\) .*/\1/p' | sort -n)
[ "$rendered" = "$(seq 1 60)" ] || fail "frames rendered (each must appear once): $(echo $rendered)"
na=$(grep -c '^frame ' "$dir/a.log"); nb=$(grep -c '^frame ' "$dir/b.log")
echo "process A rendered $na frames, B $nb"
[ "$(ls -A "$dir/farm" | grep -c '^\.')" -eq 0 ] || fail "claims or temporaries left: $(ls -A "$dir/farm" | grep '^\.')"
for f in "$dir"/ref/*.png; do cmp -s "$f" "$dir/farm/$(basename "$f")" || fail "$(basename "$f") differs"; done

# --- Stale claims ----------------------------------------------------------------------------
mkdir -p "$dir/stale"
dead=$(sh -c 'echo $$')  # a pid that has exited
host=$(hostname)
echo "$host $dead $(date +%s)" > "$dir/stale/.s_0002.png.claim"
echo "stale" > "$dir/stale/.s_0002.png.tmp${dead}_0"
echo "$host $$ $(date +%s)" > "$dir/stale/.s_0003.png.claim"               # alive: this shell
echo "otherhost 12345 $(( $(date +%s) - 1000 ))" > "$dir/stale/.s_0004.png.claim"  # old, elsewhere
sargs=(--scene flag --size 48x32 --frames 1:4 --claim --quiet --out "$dir/stale/s_####.png")
"$tessera" render "${sargs[@]}" || fail "claim run exited $?"
[ "$(cd "$dir/stale" && ls)" = "s_0001.png" ] || fail "without --resume every claim is respected: $(ls "$dir/stale")"
"$tessera" render "${sargs[@]}" --resume || fail "resume exited $?"
[ "$(cd "$dir/stale" && ls | tr '\n' ' ')" = "s_0001.png s_0002.png " ] || fail "--resume takes over only the dead claim: $(ls "$dir/stale")"
[ ! -e "$dir/stale/.s_0002.png.tmp${dead}_0" ] || fail "the dead owner's temporary is still there"
"$tessera" render "${sargs[@]}" --resume --claim-timeout 600 || fail "timeout resume exited $?"
[ -f "$dir/stale/s_0004.png" ] && [ ! -f "$dir/stale/s_0003.png" ] || fail "--claim-timeout 600: $(ls "$dir/stale")"
[ "$(ls -A "$dir/stale" | tr '\n' ' ')" = ".s_0003.png.claim s_0001.png s_0002.png s_0004.png " ] ||
  fail "left: $(ls -A "$dir/stale")"

# A claimer killed mid-run (SIGKILL: its claim and maybe a temporary stay behind): a run with
# --claim respects the dead claim, --resume --claim takes it over and completes the set.
"$tessera" render "${args[@]}" --claim --quiet --out "$dir/kill/f_####.png" & k=$!
for _ in $(seq 1 400); do [ "$(ls "$dir/kill" 2>/dev/null | wc -l)" -ge 5 ] && break; sleep 0.02; done
kill -KILL $k; wait $k 2>/dev/null
"$tessera" render "${args[@]}" --claim --resume --quiet --out "$dir/kill/f_####.png" || fail "resume after SIGKILL exited $?"
[ "$(ls "$dir/kill" | wc -l)" -eq 60 ] || fail "after SIGKILL and --resume: $(ls "$dir/kill" | wc -l) frames"
[ "$(ls -A "$dir/kill" | grep -c '^\.')" -eq 0 ] || fail "left after resume: $(ls -A "$dir/kill" | grep '^\.')"
for f in "$dir"/ref/*.png; do cmp -s "$f" "$dir/kill/$(basename "$f")" || fail "after SIGKILL: $(basename "$f") differs"; done

# --- Growing skin: shards, a late start, checkpoints -------------------------------------------
render() { "$tessera" render --quiet --scene "$scene" "$@"; }
render --frames 0:11 --checkpoint-every 0 --out "$dir/one/g_####.png" || fail "growing run exited $?"
cmp -s "$dir/one/g_0001.png" "$dir/one/g_0008.png" && fail "the skin does not grow (frames 1 and 8 equal)"
[ ! -d "$dir/one/.tessera-sim" ] || fail "--checkpoint-every 0 wrote checkpoints"
for i in 0 1; do render --frames 0:11 --shard $i/2 --checkpoint-every 4 --out "$dir/shard/g_####.png" || fail "shard $i/2 exited $?"; done
for f in "$dir"/one/*.png; do cmp -s "$f" "$dir/shard/$(basename "$f")" || fail "shard frame $(basename "$f") differs"; done
ls "$dir/shard/.tessera-sim" | grep -q -- '-00000008\.sim$' || fail "no checkpoint of frame 8: $(ls -A "$dir/shard/.tessera-sim")"
# A run starting at frame 9 restores frame 8's checkpoint; one without checkpoints simulates from 0.
render --frames 9:11 --out "$dir/late/g_####.png" --checkpoints "$dir/shard/.tessera-sim" || fail "late start exited $?"
render --frames 9:11 --out "$dir/cold/g_####.png" --checkpoints "$dir/none" --checkpoint-every 0 || fail "cold start exited $?"
for f in 9 10 11; do
  cmp -s "$dir/one/g_00$(printf %02d $f).png" "$dir/late/g_00$(printf %02d $f).png" || fail "late start frame $f differs"
  cmp -s "$dir/one/g_00$(printf %02d $f).png" "$dir/cold/g_00$(printf %02d $f).png" || fail "cold start frame $f differs"
done
# A damaged checkpoint is refused with a warning, and the frames are still right.
ckpt=$(ls "$dir"/shard/.tessera-sim/*-00000008.sim)
printf 'XXXX' | dd of="$ckpt" bs=1 seek=100 conv=notrunc status=none
err=$("$tessera" render --quiet --scene "$scene" --frames 9 --out "$dir/bad/g_####.png" --checkpoints "$dir/shard/.tessera-sim" 2>&1) ||
  fail "damaged checkpoint run exited $?: $err"
grep -q "damaged" <<<"$err" || fail "no warning for a damaged checkpoint: $err"
cmp -s "$dir/one/g_0009.png" "$dir/bad/g_0009.png" || fail "frame 9 differs after a damaged checkpoint"
echo "cli_render_farm: ok"
