#!/usr/bin/env bash
# The bad-input matrix (issue 10): the real command on missing, empty, binary-garbage,
# truncated and huge-index OBJ and JSON scene files, non-finite and huge coordinates,
# degenerate triangles, extreme sizes, bad frame ranges and unwritable outputs. Every case
# states its exit code (0 fine, 1 runtime failure, 2 usage) and, for failures, a word the one
# `tessera: error:` line must contain; a failed run must leave the output directory empty
# (no partial frame, no temporary). README's "Bad input" table lists the same cases.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'chmod -R u+w "$dir"; rm -rf "$dir"' EXIT
in=$dir/in
mkdir -p "$in"

# expect CODE WORD -- ARGS...: runs `tessera ARGS` with a fresh, empty $out.
cases=0
expect() {
    local code=$1 word=$2; shift 3
    out=$dir/out$cases
    rm -rf "$out"; mkdir -p "$out"
    local args=("${@//@OUT@/$out}")
    err=$(timeout 120 "$tessera" "${args[@]}" 2>&1 >/dev/null); got=$?
    cases=$((cases + 1))
    [ $got -eq "$code" ] || fail "'${args[*]}' exited $got, expected $code: $err"
    if [ "$code" -ne 0 ]; then
        [ "$(grep -c '^tessera: error: ' <<<"$err")" -eq 1 ] || fail "'${args[*]}': expected one error line: $err"
        grep '^tessera: error: ' <<<"$err" | grep -qi -- "$word" || fail "'${args[*]}': error should mention '$word': $err"
        [ -z "$(ls -A "$out")" ] || fail "'${args[*]}' left files behind: $(ls -A "$out")"
    fi
}

# --- OBJ files through `tessera raster`
raster() { expect "$1" "$2" -- raster --mesh "$3" --size 32x24 --eye 0,0,3 --out-color @OUT@/c.png --out-id @OUT@/i.id "${@:4}"; }
tri='v -1 -1 0\nv 1 -1 0\nv 0 1 0\n'
printf "${tri}f 1 2 3\n" >"$in/ok.obj"
: >"$in/empty.obj"
head -c 3000 "$tessera" >"$in/garbage.obj"
printf "${tri}f 1 2 3\nv 0.5 0.5" >"$in/truncated_v.obj"
printf "${tri}f 1 2" >"$in/truncated_f.obj"
printf "${tri}f 1 2 4000000000\n" >"$in/huge_index.obj"
printf "${tri}f 1 2 -99\n" >"$in/negative_index.obj"
printf "v nan 0 0\nv inf 1 0\nv 1e30 0 0\n${tri}f 1 2 3\nf 4 5 6\nf 1 5 6\n" >"$in/nonfinite.obj"
printf "v 0 0 0\nv 0 0 0\nv 0 0 0\nv -1 -1 0\nv 0 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 6\n" >"$in/degenerate.obj"

raster 1 "no such file" "$in/missing.obj"
raster 0 "" "$in/empty.obj"                  # an empty mesh is an empty image
raster 1 "binary data" "$in/garbage.obj"
raster 1 "line 5: expected 3 numbers" "$in/truncated_v.obj"
raster 1 "line 4: a face needs" "$in/truncated_f.obj"
raster 1 "out of range" "$in/huge_index.obj"
raster 1 "out of range" "$in/negative_index.obj"
raster 0 "" "$in/nonfinite.obj"              # bad vertices: their triangles are skipped, counted
raster 0 "" "$in/degenerate.obj"             # zero-area and collinear triangles cover nothing
expect 2 "size" -- raster --mesh "$in/ok.obj" --size 0x0 --out-id @OUT@/i.id
expect 0 "" -- raster --mesh "$in/ok.obj" --size 1x1 --out-id @OUT@/i.id
expect 2 "100000x100000" -- raster --mesh "$in/ok.obj" --size 100000x100000 --out-id @OUT@/i.id
expect 1 "cannot write" -- raster --mesh "$in/ok.obj" --size 8x8 --out-id "$dir/no/such/dir/i.id"
expect 1 "cannot write" -- raster --mesh "$in/ok.obj" --size 8x8 --out-id /dev/full
expect 1 "cannot write" -- raster --mesh "$in/ok.obj" --size 8x8 --out-color "$in/ok.obj/c.png"

# --- JSON scene files through `tessera render`
render() { expect "$1" "$2" -- render --scene "$3" --size 16x12 --frames 1:1 --quiet --out @OUT@/f_####.png "${@:4}"; }
scene() {  # a one-sphere scene; $1 replaces the object list
    printf '{"materials": {"m": {"kd": [1, 0.5, 0.2]}}, "camera": {"eye": [0, 0, 4]},\n "objects": [%s]}\n' "$1"
}
scene '{"type": "sphere", "material": "m"}' >"$in/ok.json"
: >"$in/empty.json"
head -c 3000 "$tessera" >"$in/garbage.json"
head -c 60 "$in/ok.json" >"$in/truncated.json"
scene '{"type": "sphere", "material": "m", "tessellation": [4000000000, 8]}' >"$in/huge_index.json"
printf '{"animation": {"frames": [0, 99999999999999999999]}, "objects": []}' >"$in/huge_frames.json"
scene '{"type": "sphere", "material": "m", "centre": [1e30, 0, 0]}' >"$in/huge_coordinate.json"
scene '{"type": "sphere", "material": "m", "radius": 1e999}' >"$in/infinite.json"
scene '{"type": "sphere", "material": "m", "radius": NaN}' >"$in/nan.json"
scene '{"type": "box", "material": "m", "size": [1, 0, 1]}' >"$in/zero_area.json"
scene '{"type": "ellipsoid", "material": "m", "radii": [1, 1e-30, 1]}' >"$in/collinear.json"

render 1 "no such file" "$in/missing.json"
render 1 "malformed JSON" "$in/empty.json"
render 1 "malformed JSON" "$in/garbage.json"
render 1 "malformed JSON" "$in/truncated.json"
render 1 "tessellation" "$in/huge_index.json"
render 1 "frames" "$in/huge_frames.json"
render 0 "" "$in/huge_coordinate.json"       # renders (the sphere is far out of view)
render 1 "number overflow" "$in/infinite.json"
render 1 "malformed JSON" "$in/nan.json"
render 1 "size" "$in/zero_area.json"
render 0 "" "$in/collinear.json"             # a flat ellipsoid: edge-on triangles cover nothing
render 0 "" "$in/ok.json"
expect 2 "size" -- render --scene "$in/ok.json" --size 0x0 --frames 1:1 --out @OUT@/f_####.png
expect 0 "" -- render --scene "$in/ok.json" --size 1x1 --frames 1:1 --quiet --out @OUT@/f_####.png
expect 2 "size" -- render --scene "$in/ok.json" --size 100000x100000 --frames 1:1 --out @OUT@/f_####.png
expect 2 "frames" -- render --scene "$in/ok.json" --size 8x8 --frames 5:1 --out @OUT@/f_####.png
expect 2 "frames" -- render --scene "$in/ok.json" --size 8x8 --frames -3:2 --out @OUT@/f_####.png
expect 2 "frames" -- render --scene "$in/ok.json" --size 8x8 --frames -5:-9 --out @OUT@/f_####.png
expect 1 "cannot write" -- render --scene "$in/ok.json" --size 8x8 --frames 1:1 --out "$in/ok.json/f_####.png"
ln -s /dev/full "$in/full.png"
expect 1 "cannot write" -- render --scene "$in/ok.json" --size 8x8 --frames 1:1 --quiet --out "$in/full.png"
if [ "$(id -u)" -ne 0 ]; then  # root writes through permission bits
    mkdir "$dir/readonly" && chmod 555 "$dir/readonly"
    expect 1 "cannot write" -- render --scene "$in/ok.json" --size 8x8 --frames 1:1 --out "$dir/readonly/f_####.png"
    [ -z "$(ls -A "$dir/readonly")" ] || fail "files left in the read-only directory"
fi
echo "cli_bad_input: ok ($cases cases)"
