#!/usr/bin/env bash
# `tessera raster --renderer raytrace` (issue 6): Embree primary rays produce the rasterizer's
# outputs (same formats, same shading); triangle ids differ only on exact edges (a handful of
# pixels); broken meshes still render and their defects are reported; misuse exits 2.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

"$tessera" testmesh --kind sphere --count 20000 --out "$dir/s.obj" --camera-out "$dir/s.cam" >/dev/null ||
    fail "testmesh exited $?"
for renderer in raster raytrace; do
    "$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 320x200 --renderer $renderer \
        --out-color "$dir/$renderer.png" --out-id "$dir/$renderer.id" --out-depth "$dir/$renderer.pfm" \
        >/dev/null || fail "--renderer $renderer exited $?"
done
[ "$(head -n 1 "$dir/raytrace.id")" = "TSID 320 200" ] || fail "bad TSID header from raytrace"
[ "$(stat -c %s "$dir/raytrace.id")" -eq "$(stat -c %s "$dir/raster.id")" ] || fail "id files differ in size"
# Differing bytes of the id files: at most 4 per differing pixel; allow 0.5% of the pixels.
differ=$(cmp -l "$dir/raster.id" "$dir/raytrace.id" | wc -l)
[ "$differ" -le $((4 * 320 * 200 / 200)) ] || fail "$differ id bytes differ between the renderers"
[ -s "$dir/raytrace.png" ] || fail "no colour image from raytrace"

out=$("$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 64x64 --renderer raytrace \
      --repeat 2 --stats) || fail "raytrace --stats exited $?"
grep -Eq '^frame_ms median=[0-9.]+ min=[0-9.]+ max=[0-9.]+$' <<<"$out" || fail "no frame_ms line: $out"
grep -q '^stats: bvh_build_ms=' <<<"$out" || fail "no BVH time: $out"

# A mesh with a NaN vertex and an out-of-range index renders; the defects are counted.
printf 'v 0 0 0\nv nan 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n' >"$dir/nan.obj"
out=$("$tessera" raster --mesh "$dir/nan.obj" --size 16x16 --eye 0.3,0.3,2 --lookat 0.3,0.3,0 \
      --renderer raytrace --stats --out-id "$dir/nan.id") || fail "NaN mesh exited $?"
grep -q 'triangles_in=2' <<<"$out" || fail "no defect counts: $out"
[ -s "$dir/nan.id" ] || fail "NaN mesh wrote no ids"

source "$(dirname "$0")/shell/expect_error.sh"
expect_error 2 raster --mesh "$dir/s.obj" --renderer rays
expect_error 2 raster --mesh "$dir/s.obj" --renderer raytrace --cull back
expect_error 1 raster --mesh "$dir/missing.obj" --renderer raytrace
echo "cli_raytrace: ok"
