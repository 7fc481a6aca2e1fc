#!/usr/bin/env bash
# Same bytes (issue 19): a frame's file depends on the scene and the flags only. EXR and TIFF
# frames, rendered in memory or streamed band by band, carry no time stamp, so they are
# byte-identical across runs and thread counts (checked by the absence of the DateTime
# attribute, which is what varied, rather than by waiting for the clock to move); with
# SOURCE_DATE_EPOCH set (the reproducible-builds convention) their DateTime is that time.
# (PNG frames across thread counts: tests/cli_determinism.sh.)
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# twice NAME ARGS...: runs `tessera ARGS` with --threads 1 and with --threads 2 (@OUT@ is the
# output file's stem) and compares the two files byte for byte.
twice() {
    local name=$1
    shift
    local ext=${name##*.}
    "$tessera" "${@//@OUT@/$dir/a_$name}" --threads 1 >/dev/null || fail "$name: exited $?"
    "$tessera" "${@//@OUT@/$dir/b_$name}" --threads 2 >/dev/null || fail "$name: exited $?"
    cmp -s "$dir/a_$name.$ext" "$dir/b_$name.$ext" || fail "$name: the two runs differ"
}
for ext in exr tif; do
    twice "frame.$ext" render --scene flag --size 64x48 --frames 3:3 --quiet --out "@OUT@.$ext"
    # Streamed band by band (beyond one 8192 pass): tiled, through another writer.
    "$tessera" render --scene flag --size 8200x16 --frames 1:1 --quiet --out "$dir/band.$ext" || fail "band.$ext exited $?"
done
# What varied between runs was the DateTime attribute: none of the files carries one.
files=("$dir"/a_frame.exr.exr "$dir"/a_frame.tif.tif "$dir"/band.exr "$dir"/band.tif)
info=$(iinfo -v "${files[@]}" 2>&1) || fail "iinfo: $info"
[ "$(grep -c ' : *[0-9]* x *[0-9]*' <<<"$info")" -eq 4 ] || fail "iinfo did not read the 4 files: $info"
dated=$(grep -i datetime <<<"$info")
[ -z "$dated" ] || fail "files carry a DateTime: $dated"

# SOURCE_DATE_EPOCH: the stated time; a malformed one is refused before any work.
SOURCE_DATE_EPOCH=1700000000 "$tessera" render --scene flag --size 32x24 --frames 1:1 --quiet \
    --out "$dir/epoch.exr" || fail "SOURCE_DATE_EPOCH render exited $?"
iinfo -v "$dir/epoch.exr" | grep -q 'DateTime: "2023:11:14 22:13:20"' ||
    fail "SOURCE_DATE_EPOCH: DateTime: $(iinfo -v "$dir/epoch.exr" | grep -i datetime)"
SOURCE_DATE_EPOCH=yesterday "$tessera" render --scene flag --size 32x24 --frames 1:1 --quiet \
    --out "$dir/bad_epoch.exr" 2>"$dir/err" && fail "a malformed SOURCE_DATE_EPOCH was accepted"
grep -q 'SOURCE_DATE_EPOCH' "$dir/err" || fail "a malformed SOURCE_DATE_EPOCH: $(cat "$dir/err")"
[ ! -e "$dir/bad_epoch.exr" ] || fail "a malformed SOURCE_DATE_EPOCH still wrote the frame"
echo "cli_same_bytes: ok"
