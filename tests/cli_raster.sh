#!/usr/bin/env bash
# The contract of `tessera raster` (issue 3): outputs and their formats, the frame_ms line,
# one-line errors with exit 1 (runtime) or 2 (usage), never a crash or a half-written file.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

"$tessera" testmesh --kind sphere --count 2000 --out "$dir/s.obj" --camera-out "$dir/s.cam" >/dev/null ||
    fail "testmesh exited $?"

out=$("$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 96x64 --shade phong \
      --out-color "$dir/c.png" --out-id "$dir/i.id" --out-depth "$dir/d.pfm" --repeat 3 --stats) ||
    fail "raster exited $?"
grep -Eq '^frame_ms median=[0-9.]+ min=[0-9.]+ max=[0-9.]+$' <<<"$out" || fail "no frame_ms line: $out"
grep -q '^stats: vertex_ms=' <<<"$out" || fail "no stage times: $out"
grep -q 'triangles_in=' <<<"$out" || fail "no counts: $out"
[ "$(head -n 1 "$dir/i.id")" = "TSID 96 64" ] || fail "bad TSID header: $(head -c 20 "$dir/i.id" | od -c | head -2)"
[ "$(stat -c %s "$dir/i.id")" -eq $((11 + 96 * 64 * 4)) ] || fail "TSID size $(stat -c %s "$dir/i.id")"
[ "$(head -n 1 "$dir/d.pfm")" = "Pf" ] || fail "depth is not a grey PFM"
[ -s "$dir/c.png" ] || fail "no colour image"

# An EXR colour output holds linear light: converted back to sRGB 8-bit by OpenImageIO it is
# the PNG of the same render to within one level (half-float rounding). Storing the 8-bit sRGB
# values as they are would make it brighter by up to 40 levels in the mid-tones.
"$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 96x64 --shade phong \
    --out-color "$dir/c.exr" || fail "raster --out-color c.exr exited $?"
oiiotool "$dir/c.exr" --colorconvert linear sRGB -d uint8 -o "$dir/c_exr.png" || fail "oiiotool could not convert c.exr"
idiff -fail 0.0040 -warn 0.0040 "$dir/c.png" "$dir/c_exr.png" >/dev/null || fail "EXR colour is not the linear light of the PNG"

# Flags override the camera file; every shade mode and cull mode runs.
for shade in id depth normal; do
    "$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 32x32 --shade $shade \
        --eye 0,0,4 --fov 40 --cull back --threads 1 --out-color "$dir/$shade.png" || fail "--shade $shade"
done

# Usage errors: exit 2, one error line.
source "$(dirname "$0")/shell/expect_error.sh"
expect_error 2 raster --mesh "$dir/s.obj" --size 0x10
expect_error 2 raster --mesh "$dir/s.obj" --size 100000x10
expect_error 2 raster --mesh "$dir/s.obj" --shade toon
expect_error 2 raster --mesh "$dir/s.obj" --cull sideways
expect_error 2 raster --mesh "$dir/s.obj" --eye 1,2
expect_error 2 raster --mesh "$dir/s.obj" --eye 0,0,0 --lookat 0,0,0
expect_error 2 raster --mesh "$dir/s.obj" --near -1
expect_error 2 raster --camera "$dir/s.cam"

# Runtime errors: exit 1 and nothing written.
expect_error 1 raster --mesh "$dir/missing.obj" --out-id "$dir/none.id"
[ ! -e "$dir/none.id" ] || fail "an output was written for a failed run"
printf 'v 0 0 0\nv 1 0 zz\nf 1 2 3\n' >"$dir/bad.obj"
expect_error 1 raster --mesh "$dir/bad.obj"
grep -q "line 2" <<<"$err" || fail "malformed OBJ error should name the line: $err"
printf 'eye 0 0\n' >"$dir/bad.cam"
expect_error 1 raster --mesh "$dir/s.obj" --camera "$dir/bad.cam"
expect_error 1 raster --mesh "$dir/s.obj" --out-id /nonexistent-dir/x.id

# Empty meshes and NaN vertices render (nothing), they do not fail.
printf '# nothing\n' >"$dir/empty.obj"
"$tessera" raster --mesh "$dir/empty.obj" --size 16x16 --out-id "$dir/e.id" || fail "empty mesh"
printf 'v 0 0 0\nv nan 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n' >"$dir/nan.obj"
out=$("$tessera" raster --mesh "$dir/nan.obj" --size 16x16 --eye 0.3,0.3,2 --lookat 0.3,0.3,0 --stats) || fail "NaN mesh"
grep -q 'skipped_triangles=1' <<<"$out" || fail "NaN triangle not counted: $out"
echo "cli_raster: ok"
