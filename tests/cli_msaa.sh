#!/usr/bin/env bash
# MSAA through the command (--samples, "render": {"samples": N}): example scenes render with
# --samples 4 (small, one frame) and differ from one sample; the scene file's count is used
# unless the flag overrides it, with the same bytes for 1 and 2 threads; bad counts are
# usage errors naming --samples. `raster --shade id --samples N` writes per-sample ids.
# (Every example scene at full size: BENCHMARKS.md.)
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scenes=$(cd "$(dirname "$0")/../examples/scenes" && pwd)
frame() { "$tessera" render --size 48x32 --frames 7:7 --quiet "$@"; }

frame --scene flag --samples 4 --threads 1 --out "$dir/flag_4.png" || fail "flag --samples 4 exited $?"
frame --scene flag --samples 1 --out "$dir/flag_1.png" || fail "flag --samples 1 exited $?"
cmp -s "$dir/flag_1.png" "$dir/flag_4.png" && fail "flag: --samples 4 gave the same frame as --samples 1"
# A ray-marched surface and fog on the layers (shadow rays: tests/render_msaa_test.cpp).
for name in terrain; do
    frame --scene $name --samples 4 --out "$dir/${name}_4.png" || fail "$name --samples 4 exited $?"
done

# "render": {"samples": 4} in the scene file (and 2 threads: the same bytes); --samples
# overrides it.
sed 's/"render": {/"render": {"samples": 4, /' "$scenes/flag.json" >"$dir/flag4.json"
frame --scene "$dir/flag4.json" --threads 2 --out "$dir/file4.png" || fail "scene file with samples exited $?"
cmp -s "$dir/file4.png" "$dir/flag_4.png" || fail "the scene file's samples were not used (or threads changed the frame)"
frame --scene "$dir/flag4.json" --samples 1 --out "$dir/file1.png" || fail "--samples 1 over the scene file exited $?"
cmp -s "$dir/file1.png" "$dir/flag_1.png" || fail "--samples 1 did not override the scene file"

# Bad counts: usage errors (exit 2) that name the option; a bad count in a file is named too.
for bad in 3 x; do
    err=$(frame --scene flag --samples $bad --out "$dir/bad.png" 2>&1)
    [ $? -eq 2 ] || fail "--samples $bad should be a usage error"
    grep -q -- "--samples" <<<"$err" || fail "--samples $bad: error should name --samples: $err"
done
sed 's/"render": {/"render": {"samples": 5, /' "$scenes/flag.json" >"$dir/flag5.json"
err=$(frame --scene "$dir/flag5.json" --out "$dir/bad.png" 2>&1)
[ $? -ne 0 ] || fail "samples 5 in a scene file should fail"
grep -q "samples" <<<"$err" || fail "a bad samples value in a file should be named: $err"
[ -e "$dir/bad.png" ] && fail "a failed run left a frame behind"
err=$("$tessera" raster --mesh "$dir/none.obj" --shade phong --samples 4 2>&1)
[ $? -eq 2 ] || fail "raster --shade phong --samples 4 should be a usage error"
grep -q "samples" <<<"$err" || fail "raster --samples with --shade phong: $err"

# raster --shade id --samples N: every sample's id ("TSID W H N", N ids per pixel), from the
# rasterizer and from the ray caster, the same for 1 and 2 threads; one sample keeps the
# three-field header; no colour or depth image with it.
"$tessera" testmesh --kind sphere --count 800 --out "$dir/s.obj" --camera-out "$dir/s.cam" >/dev/null || fail "testmesh exited $?"
ids() { "$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 40x24 --shade id "$@"; }
ids --samples 4 --threads 1 --out-id "$dir/r1.id" || fail "raster --shade id --samples 4 exited $?"
ids --samples 4 --threads 2 --out-id "$dir/r2.id" || fail "raster --shade id --samples 4 --threads 2 exited $?"
[ "$(head -n 1 "$dir/r1.id")" = "TSID 40 24 4" ] || fail "multisampled TSID header: $(head -n 1 "$dir/r1.id")"
[ "$(stat -c %s "$dir/r1.id")" -eq $((13 + 40 * 24 * 4 * 4)) ] || fail "multisampled TSID size $(stat -c %s "$dir/r1.id")"
cmp -s "$dir/r1.id" "$dir/r2.id" || fail "per-sample ids differ between 1 and 2 threads"
ids --samples 16 --renderer raytrace --out-id "$dir/rt.id" || fail "raytrace --samples 16 exited $?"
[ "$(head -n 1 "$dir/rt.id")" = "TSID 40 24 16" ] || fail "ray-cast multisampled TSID header: $(head -n 1 "$dir/rt.id")"
ids --samples 1 --out-id "$dir/one.id" || fail "raster --shade id --samples 1 exited $?"
[ "$(head -n 1 "$dir/one.id")" = "TSID 40 24" ] || fail "one sample changed the TSID header: $(head -n 1 "$dir/one.id")"
for out in --out-color=$dir/c.png --out-depth=$dir/d.pfm; do
    err=$(ids --samples 4 "$out" 2>&1)
    [ $? -eq 2 ] || fail "raster --shade id --samples 4 $out should be a usage error"
    grep -q -- "--out-id" <<<"$err" || fail "raster --samples 4 $out: $err"
    [ -e "$dir/c.png" ] || [ -e "$dir/d.pfm" ] && fail "a refused run wrote ${out#*=}"
done
echo "ok"
