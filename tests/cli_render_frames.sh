#!/usr/bin/env bash
# `tessera render`: frame naming (#### and %04d), shards that together give exactly the frames
# of one run (byte for byte), the same bytes with 1 and 2 threads for every example scene,
# and bad input: one error line, the right exit code, no files left behind.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
render() { "$tessera" render --quiet "$@"; }

# Naming: frames 3..5 as ####, %04d and %d.
render --scene flag --size 48x32 --frames 3:5 --out "$dir/hash/f_####.png" || fail "render #### exited $?"
[ "$(cd "$dir/hash" && ls)" = "$(printf 'f_0003.png\nf_0004.png\nf_0005.png')" ] || fail "#### names: $(ls "$dir/hash")"
render --scene flag --size 48x32 --frames 3:5 --out "$dir/printf/f_%04d.png" || fail "render %04d exited $?"
for f in 3 4 5; do cmp -s "$dir/hash/f_000$f.png" "$dir/printf/f_000$f.png" || fail "%04d frame $f differs"; done
render --scene flag --size 48x32 --frames 9:10 --out "$dir/plain/f%d.exr" || fail "render %d exited $?"
[ -f "$dir/plain/f9.exr" ] && [ -f "$dir/plain/f10.exr" ] || fail "%d names: $(ls "$dir/plain")"
render --scene flag --size 48x32 --frames 4 --out "$dir/tif/one.tif" || fail "single frame without placeholder"
[ -f "$dir/tif/one.tif" ] || fail "no tif"

# Shards: 0/2 + 1/2 and 0/3 + 1/3 + 2/3 give exactly the frames of one run, byte for byte.
# (The full run also prints --stats: the shards, without, must still match it byte for byte.)
render --scene toon --size 64x40 --frames 1:7 --stats --out "$dir/all/t_####.png" 2>"$dir/stats" || fail "full run exited $?"
# --stats: per frame and in the summary, the tile stage by pass: "tiles W [shade A, background
# B, ..., fog H, of tiles T thread ms]", every pass >= 0 and together at most T (each printed
# to 0.1 ms, hence the rounding allowance).
passes=$(sed -n 's/.* tiles [0-9.]* \[\(shade [^]]*thread ms\)\].*/\1/p' "$dir/stats")
[ "$(wc -l <<<"$passes")" -eq 8 ] || fail "expected 7 frame lines and a summary with tile passes: $(cat "$dir/stats")"
awk -F', ' '{
    n = split($0, item, ", "); sum = 0
    for (i = 1; i < n; i++) { split(item[i], kv, " "); if (kv[2] < 0) exit 1; sum += kv[2] }
    split(item[n], last, " "); if (last[1] != "of" || last[3] < 0 || sum > last[3] + 0.05 * n) exit 1
}' <<<"$passes" || fail "tile pass times do not parse or add up: $passes"
for n in 2 3; do
  for ((i = 0; i < n; i++)); do
    render --scene toon --size 64x40 --frames 1:7 --shard $i/$n --out "$dir/shard$n/t_####.png" || fail "shard $i/$n exited $?"
  done
  [ "$(ls "$dir/shard$n")" = "$(ls "$dir/all")" ] || fail "shards of $n: $(ls "$dir/shard$n")"
  for f in "$dir"/all/*.png; do cmp -s "$f" "$dir/shard$n/$(basename "$f")" || fail "shard frame $(basename "$f") differs"; done
done
# Each shard renders only its own frames.
render --scene toon --size 64x40 --frames 1:7 --shard 1/3 --out "$dir/only/t_####.png" || fail "shard 1/3"
[ "$(cd "$dir/only" && ls | tr '\n' ' ')" = "t_0002.png t_0005.png " ] || fail "shard 1/3 wrote $(ls "$dir/only")"

# Determinism of the shadow methods, 1 thread vs 2 (every example scene with its own settings
# is cli_determinism's).
render --scene toon --shadows rays --size 64x36 --frames 2 --threads 2 --renderer raytrace --out "$dir/det/rt_2.png" || fail "raytrace"
render --scene toon --shadows rays --size 64x36 --frames 2 --threads 1 --renderer raytrace --out "$dir/det/rt_1.png" || fail "raytrace"
cmp -s "$dir/det/rt_1.png" "$dir/det/rt_2.png" || fail "raytrace differs between 1 and 2 threads"
render --scene toon --size 64x36 --frames 2 --threads 1 --shadows map --out "$dir/det/map_1.png" || fail "map"
render --scene toon --size 64x36 --frames 2 --threads 2 --shadows map --out "$dir/det/map_2.png" || fail "map"
cmp -s "$dir/det/map_1.png" "$dir/det/map_2.png" || fail "shadow maps differ between 1 and 2 threads"

# Bad input: one error line, the exit code, nothing written.
source "$(dirname "$0")/shell/expect_error.sh"
expect_render_error() {  # $1: exit code, $2: text the message must contain, rest: arguments
  local want_code=$1 want=$2; shift 2
  expect_error "$want_code" render --quiet "$@"
  grep -qF -- "$want" <<<"$err" || fail "'$*': message should mention '$want': $err"
  [ -z "$(ls -A "$dir/bad" 2>/dev/null)" ] || fail "'$*' left files: $(ls -A "$dir/bad")"
}
mkdir -p "$dir/bad"
expect_render_error 2 "unknown scene 'snaeks' (available: bumpcube, flag, metaballs, snakes, stress, terrain, toon" --scene snaeks --out "$dir/bad/x_####.png"
expect_render_error 2 "frame" --scene flag --frames 5:2 --out "$dir/bad/x_####.png"
expect_render_error 2 "frame" --scene flag --frames abc --out "$dir/bad/x_####.png"
expect_render_error 2 "shard" --scene flag --shard 2/2 --out "$dir/bad/x_####.png"
expect_render_error 2 "would overwrite" --scene flag --frames 1:3 --out "$dir/bad/x.png"
expect_render_error 2 "no image format" --scene flag --frames 1 --out "$dir/bad/x.nope"
expect_render_error 2 "--shadows" --scene flag --frames 1 --shadows soft --size 8x8 --out "$dir/bad/x.png"
echo '{"objects": [{"type": "sphere", "material": 3}]}' > "$dir/broken.json"
expect_render_error 1 "broken.json: /objects/0/material: expected a string, got a number" --scene "$dir/broken.json" --out "$dir/bad/x.png" --frames 1
expect_render_error 1 "cannot read scene file" --scene "$dir/missing.json" --out "$dir/bad/x.png" --frames 1
touch "$dir/file"
expect_render_error 1 "cannot write frames to" --scene flag --frames 1 --size 8x8 --out "$dir/file/x_####.png"
if [ -w /dev/full ]; then  # a full disk: the frame name is a link to /dev/full
  mkdir -p "$dir/full" && ln -s /dev/full "$dir/full/x.png"
  expect_render_error 1 "No space left on device" --scene flag --frames 1 --size 8x8 --out "$dir/full/x.png"
  [ "$(ls -A "$dir/full")" = "x.png" ] || fail "a failed write left files: $(ls -A "$dir/full")"
fi
# Unknown keys warn (naming file and key) and the render still succeeds.
echo '{"materials": {"m": {"kd": [1, 0, 0]}}, "objects": [{"type": "sphere", "material": "m", "wobble": 1}]}' > "$dir/warn.json"
err=$("$tessera" render --quiet --scene "$dir/warn.json" --size 16x16 --frames 1 --out "$dir/warn.png" 2>&1) || fail "warn.json exited $?"
grep -qF "tessera: warning: $dir/warn.json: /objects/0/wobble: unknown key 'wobble'" <<<"$err" || fail "no warning: $err"
[ -f "$dir/warn.png" ] || fail "warn.json rendered nothing"
echo "cli_render_frames: ok"
