#!/usr/bin/env bash
# Determinism (issue 10): the same frame is byte-identical whatever the thread count or tile
# size. `tessera render` renders one frame of every example scene (examples/scenes/*.json)
# at a small size with --threads 1 and --threads 2 (both renderers for the scenes cheap
# enough); `tessera raster` renders one mesh with --tile 16, 64 and 256 and 1 or 2 threads,
# comparing colour, ids and depth. A scene time mid-animation is used so moving parts move.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scenes=$(cd "$(dirname "$0")/../examples/scenes" && pwd)

count=0
for scene in "$scenes"/*.json; do
    name=$(basename "$scene" .json)
    renderers=raster
    [ "$name" = snakes ] || [ "$name" = stress ] || renderers="raster raytrace"
    for renderer in $renderers; do
        for threads in 1 2; do
            "$tessera" render --scene "$scene" --size 48x32 --frames 7:7 --renderer $renderer \
                --threads $threads --quiet --out "$dir/${name}_${renderer}_t$threads.png" ||
                fail "$name ($renderer, $threads threads) exited $?"
        done
        cmp -s "$dir/${name}_${renderer}_t1.png" "$dir/${name}_${renderer}_t2.png" ||
            fail "$name ($renderer): frame differs between 1 and 2 threads"
        count=$((count + 1))
    done
done
[ $count -ge 1 ] || fail "no example scenes found in $scenes"

"$tessera" testmesh --kind sphere --count 3000 --out "$dir/s.obj" --camera-out "$dir/s.cam" >/dev/null ||
    fail "testmesh exited $?"
for tile in 16 64 256; do
    for threads in 1 2; do
        "$tessera" raster --mesh "$dir/s.obj" --camera "$dir/s.cam" --size 200x120 --tile $tile \
            --threads $threads --out-color "$dir/c_${tile}_$threads.png" --out-id "$dir/i_${tile}_$threads.id" \
            --out-depth "$dir/d_${tile}_$threads.pfm" || fail "raster --tile $tile --threads $threads exited $?"
    done
done
for tile in 16 64 256; do
    for threads in 1 2; do
        for kind in c i d; do
            case $kind in c) ext=png ;; i) ext=id ;; d) ext=pfm ;; esac
            cmp -s "$dir/${kind}_16_1.$ext" "$dir/${kind}_${tile}_$threads.$ext" ||
                fail "raster --tile $tile --threads $threads: $ext differs from --tile 16 --threads 1"
        done
    done
done
echo "cli_determinism: ok ($count scene/renderer pairs, 3 tile sizes)"
