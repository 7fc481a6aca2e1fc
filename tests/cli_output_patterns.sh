#!/usr/bin/env bash
# Output patterns and output flags (issue 19): a #### in a directory component makes one
# folder per frame (with --resume too), all checked before any is made; a relative pattern
# into folders that do not exist yet works; an empty --out or --trace and a --fps that is not
# a positive finite number are usage errors (exit 2); and commands check that their outputs
# can be written before they do the work.
set -u
tessera=$(realpath "$1")
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"
# Work done before an output check could run for hours: every run has 30 s.
printf '#!/bin/sh\nexec timeout 30 "%s" "$@"\n' "$tessera" >"$dir/tessera"
chmod +x "$dir/tessera"
tessera=$dir/tessera
args=(render --scene flag --size 32x24 --quiet)

# --- One folder per frame
"$tessera" "${args[@]}" --frames 1:2 --out "$dir/seq/frame_####/beauty.png" || fail "per-frame folders exited $?"
out=$("$tessera" render --scene flag --size 32x24 --frames 1:3 --resume --out "$dir/seq/frame_####/beauty.png" 2>&1) ||
    fail "--resume into per-frame folders exited $?: $out"
grep -q 'resume: 2 complete frame(s) skipped' <<<"$out" || fail "per-frame folders: resume did not skip: $out"
for f in 1 2 3; do
    [ -f "$dir/seq/frame_000$f/beauty.png" ] || fail "frame $f missing: $(find "$dir/seq")"
done
# A frame folder that cannot be made (a file is in the way) fails before any frame.
mkdir -p "$dir/blocked" && : >"$dir/blocked/frame_0002"
expect_error 1 "${args[@]}" --frames 1:3 --out "$dir/blocked/frame_####/beauty.png"
grep -q "cannot write" <<<"$err" || fail "blocked frame folder: $err"
[ ! -e "$dir/blocked/frame_0001" ] || fail "blocked frame folder: frame 1 was written before the error"
# The default pattern, out/NAME_####.png, relative to a folder where out/ does not exist yet.
mkdir -p "$dir/relative" && cd "$dir/relative"
"$tessera" render --scene flag --size 32x24 --frames 1:1 --quiet || fail "the default --out exited $?"
[ -f out/flag_0001.png ] || fail "the default --out: $(find .)"

# --- Usage errors: exit 2, nothing written
mkdir -p "$dir/empty" && cd "$dir/empty"
expect_error 2 "${args[@]}" --frames 1:1 --out ''
grep -q -- '--out' <<<"$err" || fail "--out '': the error should name --out: $err"
expect_error 2 "${args[@]}" --frames 1:1 --fps nan --out "$dir/empty/f_####.png"
grep -q -- '--fps' <<<"$err" || fail "--fps nan: the error should name --fps: $err"
expect_error 2 "${args[@]}" --frames 1:1 --trace '' --out "$dir/empty/f_####.png"
[ -z "$(ls -A "$dir/empty")" ] || fail "usage errors left files: $(ls -A "$dir/empty")"
cd "$dir"

# --- Outputs checked before the work
mkdir -p "$dir/trace_dir" "$dir/t"
expect_error 1 "${args[@]}" --frames 1:2 --trace "$dir/trace_dir" --out "$dir/t/f_####.png"
grep -q "cannot write" <<<"$err" || fail "--trace DIR: $err"
[ -z "$(ls -A "$dir/t")" ] || fail "an unwritable --trace was found after rendering: $(ls "$dir/t")"
# quick CODE ARGS...: `tessera ARGS` exits CODE with one error line within 10 s (the work
# asked for takes far longer) and prints no result.
quick() {
    local code=$1 start=$SECONDS got
    shift
    out=$("$tessera" "$@" 2>"$dir/stderr"); got=$?
    [ $got -eq "$code" ] || fail "'$*' exited $got, expected $code: $(cat "$dir/stderr")"
    [ "$(grep -c '^tessera: error: ' "$dir/stderr")" -eq 1 ] || fail "'$*': expected one error line: $(cat "$dir/stderr")"
    [ -z "$out" ] || fail "'$*' did the work before checking its output: $out"
    [ $((SECONDS - start)) -lt 10 ] || fail "'$*' did the work before checking its output"
}
quick 1 shadows --triangles 16000000 --diff "$dir/missing/x.png"
quick 1 generate rd --preset spots --size 1024x1024 --steps 1000000 --frames 40 --out "$dir/missing/x_####.png"
quick 1 testmesh --kind sphere --count 20000000 --out "$dir/s.obj" --camera-out "$dir/missing/s.cam"
[ ! -e "$dir/s.obj" ] || fail "testmesh wrote its mesh before finding the camera output unwritable"
printf 'v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n' >"$dir/tri.obj"
quick 1 raster --mesh "$dir/tri.obj" --size 64x64 --repeat 100000 --out-color "$dir/ok.png" --out-depth "$dir/missing/d.pfm"
grep -q "missing/d.pfm" "$dir/stderr" || fail "raster: the error should name the depth output: $(cat "$dir/stderr")"
[ ! -e "$dir/ok.png" ] || fail "raster wrote one output before finding another unwritable"
echo "cli_output_patterns: ok"
