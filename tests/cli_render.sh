#!/usr/bin/env bash
# `tessera render`: example scenes render to files of the requested size and format; bad
# input is one clear error line (exit 2 for usage, 1 for runtime) and leaves no file behind.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

for scene in flag toon bumpcube snakes; do
    "$tessera" render --scene $scene --size 96x64 --threads 2 --out "$dir/$scene.png" || fail "$scene exited $?"
    [ -s "$dir/$scene.png" ] || fail "$scene wrote no image"
done
oiiotool --info "$dir/flag.png" | grep -q "96 x  *64" || fail "flag.png has the wrong size: $(oiiotool --info "$dir/flag.png")"

"$tessera" render --scene toon --size 32x32 --frames 3 --fps 10 --out "$dir/toon_###.exr" || fail "frames exited $?"
for i in 000 001 002; do [ -s "$dir/toon_$i.exr" ] || fail "missing frame toon_$i.exr"; done
"$tessera" render --scene flag --size 32x32 --out "$dir/flag.tif" || fail "tif exited $?"

for face in px nx py ny pz nz; do
    oiiotool --pattern constant:color=0.2,0.4,0.8 8x8 3 -d uint8 -o "$dir/sky_$face.png" || fail "oiiotool"
done
"$tessera" render --scene toon --size 32x32 --cube-map "$dir/sky_{face}.png" --out "$dir/cube.png" || fail "cube map exited $?"
err=$("$tessera" render --scene toon --size 32x32 --cube-map "$dir/none_{face}.png" --out "$dir/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 1 ] || fail "missing cube face exited $code, expected 1"
grep -q "none_px.png" <<<"$err" || fail "missing face not named: $err"

"$tessera" testmesh --kind sphere --count 500 --out "$dir/s.obj" >/dev/null || fail "testmesh exited $?"
"$tessera" render --obj "$dir/s.obj" --model toon --size 48x32 --out "$dir/obj.png" || fail "--obj exited $?"
err=$("$tessera" render --obj "$dir/nothing.obj" --size 32x32 --out "$dir/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 1 ] || fail "missing OBJ exited $code, expected 1"
err=$("$tessera" render --obj "$dir/s.obj" --scene flag --out "$dir/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "--obj with --scene exited $code, expected 2"

err=$("$tessera" render --scene nosuch --size 32x32 --out "$dir/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "unknown scene exited $code, expected 2"
grep -q "unknown scene 'nosuch'; valid scenes: flag, toon, bumpcube, snakes" <<<"$err" || fail "message: $err"

err=$("$tessera" render --scene flag --frames 2 --out "$dir/same.png" 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "--frames without a pattern exited $code"
grep -q "exactly one frame number" <<<"$err" || fail "message: $err"

err=$("$tessera" render --scene flag --size 0x10 --out "$dir/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 2 ] || fail "--size 0x10 exited $code"

err=$("$tessera" render --scene flag --size 32x32 --out "$dir/missing/x.png" 2>&1 >/dev/null); code=$?
[ $code -eq 1 ] || fail "unwritable output exited $code, expected 1"
[ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "expected one error line: $err"
[ ! -e "$dir/x.png" ] || fail "a failed run left a file"
echo "cli_render: ok"
