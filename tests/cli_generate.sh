#!/usr/bin/env bash
# The `tessera generate` contract: rd / heightfield / normalmap write images; bad input is one
# `tessera: error:` line, exit 2, and no file; output is identical for 1 and 2 threads.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

out=$("$tessera" generate rd --list-presets) || fail "--list-presets exited $?"
for name in spots stripes mitosis coral worms; do
  grep -q "^$name " <<<"$out" || fail "--list-presets lacks $name: $out"
done

"$tessera" generate rd --preset spots --size 48x32 --steps 200 --seed 3 --threads 1 --out "$dir/rd1.png" \
  || fail "rd exited $?"
"$tessera" generate rd --preset spots --size 48x32 --steps 200 --seed 3 --threads 2 --out "$dir/rd2.png" \
  || fail "rd --threads 2 exited $?"
[ "$(head -c 8 "$dir/rd1.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "rd output is not a PNG"
cmp -s "$dir/rd1.png" "$dir/rd2.png" || fail "rd output differs between 1 and 2 threads"
# As EXR the same pattern is stored as linear light (the PNG's sRGB colours decoded).
"$tessera" generate rd --preset spots --size 48x32 --steps 200 --seed 3 --out "$dir/rd.exr" || fail "rd .exr exited $?"
oiiotool "$dir/rd.exr" --colorconvert linear sRGB -d uint8 -o "$dir/rd_exr.png" || fail "oiiotool could not convert rd.exr"
idiff -fail 0.0040 -warn 0.0040 "$dir/rd1.png" "$dir/rd_exr.png" >/dev/null || fail "rd EXR is not the linear light of the PNG"

# An animation: --frames N writes N files, the '#' run becomes the zero-padded frame number.
"$tessera" generate rd --size 16x16 --steps 30 --frames 3 --out "$dir/anim/f_#.png" 2>/dev/null \
  && fail "frames into a missing directory should fail"
mkdir -p "$dir/anim"
"$tessera" generate rd --size 16x16 --steps 30 --frames 3 --out "$dir/anim/f_#.png" || fail "--frames exited $?"
[ "$(ls "$dir/anim")" = "$(printf 'f_1.png\nf_2.png\nf_3.png')" ] || fail "frame files: $(ls "$dir/anim")"
cmp -s "$dir/anim/f_1.png" "$dir/anim/f_3.png" && fail "frames 1 and 3 are identical"
"$tessera" generate rd --size 16x16 --steps 30 --out "$dir/single.png" || fail "rd exited $?"
cmp -s "$dir/anim/f_3.png" "$dir/single.png" || fail "the last frame should equal a plain run of all the steps"

# Bad input: one error line, exit 2, nothing written.
expect_usage_error() {  # $1: what the message must mention; the rest: the command
  local want=$1; shift
  local err code
  err=$("$tessera" "$@" 2>&1 >/dev/null); code=$?
  [ $code -eq 2 ] || fail "'$*' exited $code, expected 2: $err"
  [ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "'$*': expected one error line, got: $err"
  grep -q -- "$want" <<<"$err" || fail "'$*': message should mention '$want': $err"
  [ -z "$(ls -A "$dir/bad" 2>/dev/null)" ] || fail "'$*' left files: $(ls "$dir/bad")"
}
mkdir -p "$dir/bad"
expect_usage_error "valid presets: spots" generate rd --preset nope --size 8x8 --steps 1 --out "$dir/bad/x.png"
expect_usage_error "finite" generate rd --size 8x8 --steps 1 --dt nan --out "$dir/bad/x.png"
expect_usage_error "feed" generate rd --size 8x8 --steps 1 --feed nan --out "$dir/bad/x.png"
expect_usage_error "WIDTHxHEIGHT" generate rd --size 0x8 --steps 1 --out "$dir/bad/x.png"
expect_usage_error "out of range" generate rd --size 70000x8 --steps 1 --out "$dir/bad/x.png"
expect_usage_error "GiB" generate rd --size 65536x65536 --steps 1 --out "$dir/bad/x.png"
expect_usage_error "--out" generate rd --size 8x8 --steps 1
expect_usage_error "placeholder" generate rd --size 8x8 --steps 2 --frames 2 --out "$dir/bad/x.png"
expect_usage_error "no image format" generate heightfield --size 8x8 --out "$dir/bad/x.nope"
expect_usage_error "--in" generate normalmap --out "$dir/bad/x.png"

# An unstable dt is clamped to the limit with a warning, and the run succeeds.
err=$("$tessera" generate rd --size 16x16 --steps 5 --dt 5 --out "$dir/clamped.png" 2>&1 >/dev/null) \
  || fail "unstable dt should be clamped, exited $?"
grep -q "warning: --dt 5 is unstable.*using dt=1.25" <<<"$err" || fail "no clamp warning: $err"

# A run that cannot write its output fails with exit 1 and leaves nothing behind.
err=$("$tessera" generate rd --size 8x8 --steps 1 --out "$dir/missing/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 1 ] || fail "unwritable output exited $code, expected 1: $err"
[ ! -e "$dir/missing" ] || fail "unwritable output left a directory"

# Heightfields: 16-bit PNG (IHDR bit depth at byte 24), float EXR; deterministic over threads.
"$tessera" generate heightfield --size 64x48 --seed 2 --octaves 5 --threads 1 --out "$dir/h1.png" || fail "heightfield exited $?"
"$tessera" generate heightfield --size 64x48 --seed 2 --octaves 5 --threads 2 --out "$dir/h2.png" || fail "heightfield exited $?"
cmp -s "$dir/h1.png" "$dir/h2.png" || fail "heightfield differs between 1 and 2 threads"
[ "$(od -An -tu1 -j24 -N1 "$dir/h1.png" | tr -d ' ')" = 16 ] || fail "heightfield PNG is not 16-bit"
"$tessera" generate heightfield --size 32x32 --relief dunes --out "$dir/d.exr" || fail "dunes EXR exited $?"
[ -s "$dir/d.exr" ] || fail "no EXR written"
"$tessera" generate heightfield --size 48x48 --erode 10 --out "$dir/eroded.tif" || fail "eroded heightfield exited $?"
"$tessera" generate heightfield --size 48x48 --out "$dir/plain.tif" || fail "plain heightfield exited $?"
cmp -s "$dir/plain.tif" "$dir/eroded.tif" && fail "--erode changed nothing"

# Normal maps from a height map; a flat one is the flat blue (128,128,255).
"$tessera" generate normalmap --in "$dir/h1.png" --out "$dir/n.png" || fail "normalmap exited $?"
[ -s "$dir/n.png" ] || fail "no normal map written"
"$tessera" generate heightfield --size 16x16 --out "$dir/flat_src.png" >/dev/null || fail "heightfield"
if command -v oiiotool >/dev/null; then
  oiiotool --pattern constant:color=0.5 16x16 1 -d uint16 -o "$dir/flat.png" || fail "oiiotool"
  "$tessera" generate normalmap --in "$dir/flat.png" --out "$dir/flat_n.png" || fail "normalmap of flat exited $?"
  stats=$(oiiotool --stats "$dir/flat_n.png")
  grep -q "Min: 128 128 255" <<<"$stats" && grep -q "Max: 128 128 255" <<<"$stats" \
    || fail "flat height map should give (128,128,255): $stats"
  # A tileable dune map wraps: the step from its last column to its first is no larger than the
  # steps between neighbouring columns inside (an untiled map jumps about 3x further there).
  "$tessera" generate heightfield --size 128x128 --relief dunes --out "$dir/dunes.exr" >/dev/null \
    || fail "dune heightfield exited $?"
  read -r inner wrap < <(oiiotool --dumpdata "$dir/dunes.exr" | awk '
    $1 == "Pixel" { x = $2; y = $3; gsub(/[^0-9]/, "", x); gsub(/[^0-9]/, "", y); v[x, y] = $4
                    if (x + 0 > w) w = x + 0; if (y + 0 > h) h = y + 0 }
    END { for (y = 0; y <= h; ++y) {
            for (x = 0; x < w; ++x) { d = v[x + 1, y] - v[x, y]; if (d < 0) d = -d; if (d > inner) inner = d }
            d = v[0, y] - v[w, y]; if (d < 0) d = -d; if (d > wrap) wrap = d }
          print inner, wrap }')
  awk -v i="$inner" -v w="$wrap" 'BEGIN { exit !(i > 0 && w <= 1.2 * i) }' \
    || fail "dune heightfield does not tile: step $wrap across the wrap, at most $inner inside"
fi
echo "cli_generate: ok"
