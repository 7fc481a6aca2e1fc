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

source "$(dirname "$0")/shell/expect_error.sh"
expect_error 2 shadows --lights 9
expect_error 2 shadows --map-size 8
expect_error 2 shadows --size 0x5
expect_error 1 shadows --triangles 100 --size 32x32 --diff /nonexistent-dir/d.png
[ ! -e /nonexistent-dir/d.png ] || fail "diff written"
echo "cli_shadows: ok"
