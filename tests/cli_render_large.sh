#!/usr/bin/env bash
# `tessera render` beyond one 8192 x 8192 pass: the frame is rendered in bands of regions and
# streamed into the file (tiled EXR/TIFF, scanline PNG). Checks: the file has the full size,
# the same bytes with 1 and 2 threads, --resume recognises a streamed frame, a full disk or a
# blocked name is one clear error with nothing left behind, absurd sizes are usage errors.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
render() { "$tessera" render --quiet "$@"; }
info() { oiiotool --info -v "$1" 2>&1; }
source "$(dirname "$0")/shell/expect_error.sh"

# Wider than a viewport: one band of two regions (8192 + 64 columns).
render --scene toon --shadows rays --size 8256x64 --frames 2 --threads 1 --out "$dir/wide1.png" || fail "wide render exited $?"
render --scene toon --shadows rays --size 8256x64 --frames 2 --threads 2 --out "$dir/wide2.png" || fail "wide render 2 threads exited $?"
info "$dir/wide1.png" | grep -q "8256 x   64" || fail "wide PNG size: $(info "$dir/wide1.png" | head -2)"
cmp -s "$dir/wide1.png" "$dir/wide2.png" || fail "streamed frame differs between 1 and 2 threads"

# Taller than a viewport: two bands (8192 + 128 rows), tiled EXR and TIFF.
render --scene flag --size 64x8320 --frames 1 --out "$dir/tall.exr" || fail "tall EXR exited $?"
info "$dir/tall.exr" | grep -q "64 x 8320" || fail "tall EXR size: $(info "$dir/tall.exr" | head -2)"
info "$dir/tall.exr" | grep -q "tile size: 64 x 64" || fail "EXR not tiled: $(info "$dir/tall.exr")"
render --scene flag --size 64x8320 --frames 1:2 --out "$dir/r_####.tif" || fail "tall TIFF exited $?"
info "$dir/r_0001.tif" | grep -q "64 x 8320" || fail "tall TIFF size"
rm "$dir/r_0002.tif"
err=$("$tessera" render --scene flag --size 64x8320 --frames 1:2 --resume --out "$dir/r_####.tif" 2>&1) ||
  fail "--resume exited $?: $err"
grep -q "resume: 1 complete frame(s) skipped" <<<"$err" || fail "--resume did not skip the streamed frame: $err"
[ -f "$dir/r_0002.tif" ] || fail "--resume did not render frame 2"

# Failures: one error line, exit 1, no file and no temporary.
if [ -w /dev/full ]; then  # a full disk: the frame name is a link to /dev/full
  for ext in png exr; do
    mkdir -p "$dir/full" && ln -sf /dev/full "$dir/full/x.$ext"
    expect_error 1 render --quiet --scene flag --size 8256x64 --frames 1 --out "$dir/full/x.$ext"
    grep -q "^tessera: error: cannot write '.*x.$ext'" <<<"$err" || fail "full disk ($ext): $err"
  done
  [ "$(ls -A "$dir/full" | tr '\n' ' ')" = "x.exr x.png " ] || fail "full disk left: $(ls -A "$dir/full")"
fi
mkdir -p "$dir/blocked/b_0001.png"
expect_error 1 render --quiet --scene flag --size 8256x64 --frames 1 --out "$dir/blocked/b_####.png"
grep -q "^tessera: error: cannot write '.*b_0001.png'" <<<"$err" || fail "error does not name the frame: $err"
[ -z "$(ls -A "$dir/blocked" | grep -v '^b_0001.png$')" ] || fail "left behind: $(ls -A "$dir/blocked")"

expect_error 2 render --quiet --scene flag --size 70000x64 --frames 1 --out "$dir/huge.png"
grep -q "at most 65536" <<<"$err" || fail "70000 wide: $err"
echo "cli_render_large: ok"
