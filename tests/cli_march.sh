#!/usr/bin/env bash
# `tessera march`: every scene renders a readable image; bad parameters are one error line and
# exit 2 without leaving a file; an unwritable output is exit 1.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

for scene in metaballs terrain sine-noise noise-volume gradient-noise; do
    "$tessera" march --scene "$scene" --size 64x36 --strategy geometric --fog-density 0.02 \
        -o "$dir/$scene.png" >/dev/null || fail "$scene exited $?"
    [ -s "$dir/$scene.png" ] || fail "$scene wrote no image"
done
"$tessera" march --scene metaballs --kernel blinn --normals differences --reflectivity 0.5 \
    --fog-density 0.1,0.2,0.3 --fog-colour 0 --fog-falloff 0.5 --size 32x32 -o "$dir/b.exr" \
    >/dev/null || fail "blinn/exr exited $?"

expect_usage() {
    local err code
    err=$("$tessera" march --size 16x16 -o "$dir/bad.png" "$@" 2>&1 >/dev/null); code=$?
    [ $code -eq 2 ] || fail "'$*' exited $code, expected 2"
    [ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "'$*': expected one error line, got: $err"
    [ ! -e "$dir/bad.png" ] || fail "'$*' left an image behind"
}
expect_usage --steps 0
expect_usage --fog-density -1
expect_usage --fog-density 0.1,x,0.1
expect_usage --tolerance nan
expect_usage --balls 2
expect_usage --scene bogus
expect_usage --kernel gauss
expect_usage --strategy random
expect_usage --normal-step 0 --normals differences

"$tessera" march --size 16x16 -o "$dir/missing/dir/x.png" >/dev/null 2>&1; code=$?
[ $code -eq 1 ] || fail "unwritable output exited $code, expected 1"
echo "cli_march: ok"
