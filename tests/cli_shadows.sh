#!/usr/bin/env bash
# `tessera shadows` (issue 6): shadow maps against Embree shadow rays on the sphere grid; the
# agreement line, the diff image, and usage errors.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

out=$("$tessera" shadows --triangles 5000 --size 320x180 --lights 2 --map-size 1024 \
      --diff "$dir/diff.png") || fail "shadows exited $?"
grep -Eq '^agreement: [0-9.]+% of [0-9]+ covered pixels' <<<"$out" || fail "no agreement line: $out"
grep -Eq 'triangle ids differ at [0-9]+ of 57600 pixels' <<<"$out" || fail "no id comparison: $out"
[ -s "$dir/diff.png" ] || fail "no diff image"

expect_error() {
    local code=$1; shift
    err=$("$tessera" shadows "$@" 2>&1 >/dev/null); got=$?
    [ $got -eq "$code" ] || fail "'$*' exited $got, expected $code: $err"
    [ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "'$*': expected one error line: $err"
}
expect_error 2 --lights 9
expect_error 2 --map-size 8
expect_error 2 --size 0x5
expect_error 1 --triangles 100 --size 32x32 --diff /nonexistent-dir/d.png
[ ! -e /nonexistent-dir/d.png ] || fail "diff written"
echo "cli_shadows: ok"
