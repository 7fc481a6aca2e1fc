#!/usr/bin/env bash
# Same bytes between builds for different SIMD widths (`make same-bytes`; not in CI): two
# `tessera` binaries, e.g. the release build (-march=native: AVX-512 where the CPU has it) and
# the portable one (x86-64-v3: AVX2), must write identical files: a mid-animation frame of
# every example scene in every shadow mode and with both renderers, in PNG and EXR, 4-sample
# frames of the marched and the default scenes, a scene with transparent triangles at 1 and
# 4 samples, the raster
# command's colour, ids and depth, and the generators' images.
#   bash tests/builds_same_bytes.sh build/bin/tessera build-portable/bin/tessera
set -u
first=$1 second=$2
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scenes=$(cd "$(dirname "$0")/../examples/scenes" && pwd)
"$first" info | grep -i 'simd\|built for' | head -2 | sed 's/^/first:  /'
"$second" info | grep -i 'simd\|built for' | head -2 | sed 's/^/second: /'

# both NAME EXT ARGS...: runs `tessera ARGS` with each binary (@OUT@ is the output stem) and
# compares the NAME.EXT files they write.
count=0
both() {
    local name=$1 ext=$2
    shift 2
    "$first" "${@//@OUT@/$dir/1_$name}" >/dev/null || fail "$name: the first build exited $?"
    "$second" "${@//@OUT@/$dir/2_$name}" >/dev/null || fail "$name: the second build exited $?"
    for f in "$dir/1_$name".* "$dir/1_${name}"_[0-9]*; do
        [ -e "$f" ] || continue
        cmp -s "$f" "$dir/2_${f#"$dir/1_"}" || fail "$(basename "$f"): the builds differ"
        count=$((count + 1))
    done
}

for scene in "$scenes"/*.json; do
    name=$(basename "$scene" .json)
    size=96x54
    [ "$name" = stress ] && size=64x36
    for shadows in none map rays; do
        both "${name}_raster_$shadows" png render --scene "$scene" --size $size --frames 7:8 --shadows $shadows \
            --quiet --out "@OUT@_####.png"
    done
    both "${name}_raster" exr render --scene "$scene" --size $size --frames 7:7 --quiet --out "@OUT@.exr"
    [ "$name" = stress ] ||
        both "${name}_raytrace" png render --scene "$scene" --size $size --frames 7:7 --renderer raytrace --quiet \
            --out "@OUT@.png"
done
# Multisampled: the layers and the marched silhouettes' sample rays (packets of 16 or 8 lanes).
for name in metaballs terrain snakes; do
    for renderer in raster raytrace; do
        both "${name}_msaa_$renderer" png render --scene "$scenes/$name.json" --size 160x90 --frames 7:7 \
            --samples 4 --renderer $renderer --quiet --out "@OUT@.png"
    done
done
# Transparent triangles, blended and over opaque ones, at one sample and at four (their
# coverage and depth tests per sample in lanes, the split of edge pixels).
cat > "$dir/glass.json" <<'JSON'
{"camera": {"eye": [0, 2, 4], "lookat": [0, 0, 0], "fov": 45},
 "lights": [{"direction": [0.3, 1, 0.2], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
 "materials": {"grey": {"kd": [0.6, 0.6, 0.6]}, "red": {"kd": [0.9, 0.1, 0.1]},
               "glass": {"kd": [0.3, 0.6, 0.9], "opacity": 0.4}, "tint": {"kd": [0.9, 0.8, 0.2], "opacity": 0.6}},
 "objects": [
   {"type": "box", "material": "grey", "size": [3, 0.2, 3], "transform": {"translate": [0, -1.1, 0]}},
   {"type": "sphere", "material": "red", "radius": 0.7, "centre": [0, 0, 0]},
   {"type": "sphere", "material": "glass", "radius": 0.5, "centre": [0.9, 0.3, 0.8]},
   {"type": "box", "material": "tint", "size": [0.8, 1.2, 0.1], "transform": {"translate": [-0.8, -0.3, 1.0]}}]}
JSON
for samples in 1 4; do
    for renderer in raster raytrace; do
        both "glass_${samples}_$renderer" png render --scene "$dir/glass.json" --size 160x90 --frames 1:1 \
            --samples $samples --shadows rays --renderer $renderer --quiet --out "@OUT@_####.png"
    done
done
"$first" testmesh --kind sphere --count 5000 --out "$dir/s.obj" --camera-out "$dir/s.cam" >/dev/null || fail "testmesh exited $?"
for shade in id depth normal phong; do
    for renderer in raster raytrace; do
        both "raster_${shade}_$renderer" png raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 160x90 \
            --shade $shade --renderer $renderer --out-color "@OUT@.png" --out-id "@OUT@.id" --out-depth "@OUT@.pfm"
    done
done
both heightfield exr generate heightfield --size 128x128 --relief warped --erode 20 --out "@OUT@.exr"
both rd png generate rd --preset spots --size 96x96 --steps 500 --out "@OUT@.png"
"$first" generate heightfield --size 96x96 --relief dunes --out "$dir/h.exr" >/dev/null || fail "heightfield exited $?"
both normalmap png generate normalmap --in "$dir/h.exr" --out "@OUT@.png"
for scene in terrain metaballs sine-noise noise-volume gradient-noise; do
    both "march_$scene" png march --scene $scene --size 96x54 -o "@OUT@.png"
done
echo "builds_same_bytes: ok ($count files identical)"
