#!/usr/bin/env bash
# Input that is not what it claims to be (issue 19), through the command: a scene, a mesh in a
# scene, a texture or `raster`'s mesh that is a device, a FIFO (which would block forever) or a
# directory is refused at once with exit 1, naming the file and, in a scene, the value's JSON
# Pointer, and nothing is written; a JSON key given twice is a warning naming its pointer.
# Every reader is checked against every kind of file in tests/input_file_test.cpp.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"
in=$dir/in
mkdir -p "$in"
mkfifo "$in/fifo.obj"

# A FIFO or a device read to its end would hang the test: every run has 20 s.
real_tessera=$tessera
tessera=$dir/tessera
printf '#!/bin/sh\nexec timeout 20 "%s" "$@"\n' "$real_tessera" >"$tessera"
chmod +x "$tessera"

# refused WORD ARGS...: `tessera ARGS` exits 1 with one error line containing WORD, and
# writes nothing.
refused() {
    local word=$1
    shift
    rm -rf "$dir/out"
    mkdir -p "$dir/out"
    expect_error 1 "$@"
    grep '^tessera: error: ' <<<"$err" | grep -qi -- "$word" || fail "'$*': error should say '$word': $err"
    [ -z "$(ls -A "$dir/out")" ] || fail "'$*' left files: $(ls -A "$dir/out")"
}
render=(render --size 16x12 --frames 1:1 --quiet --out "$dir/out/f_####.png")

refused "not a regular file" "${render[@]}" --scene /dev/zero
printf '{"materials": {"m": {"kd": [1, 1, 1]}}, "camera": {"eye": [0, 0, 4]},
 "objects": [{"type": "mesh", "material": "m", "file": "%s"}]}\n' "$in/fifo.obj" >"$in/mesh.json"
refused "not a regular file" "${render[@]}" --scene "$in/mesh.json"
grep -q "mesh.json: /objects/0/file: " <<<"$err" || fail "a FIFO mesh: the error should name the value: $err"
printf '{"textures": {"t": {"type": "file", "file": "/dev/urandom"}}, "camera": {"eye": [0, 0, 4]},
 "materials": {"m": {"kd": [1, 1, 1], "diffuse_texture": "t"}}, "objects": [{"type": "sphere", "material": "m"}]}\n' \
    >"$in/tex.json"
refused "not a regular file" "${render[@]}" --scene "$in/tex.json"
grep -q "tex.json: /textures/t" <<<"$err" || fail "a /dev/urandom texture: the error should name the texture: $err"
refused "directory" raster --mesh "$in" --size 16x16 --out-color "$dir/out/c.png"

# A key given twice: a warning naming its pointer (the last value is the one used).
printf '{"objects": [], "materials": {"m": {"kd": [1, 1, 1], "kd": [0, 1, 0]}},
 "objects": [{"type": "sphere", "material": "m"}]}\n' >"$in/twice.json"
rm -rf "$dir/out"
warnings=$("$real_tessera" "${render[@]}" --scene "$in/twice.json" 2>&1 >/dev/null) || fail "twice.json exited $?: $warnings"
grep -q "^tessera: warning: $in/twice.json: /objects: .*twice" <<<"$warnings" || fail "no warning for /objects: $warnings"
grep -q "^tessera: warning: $in/twice.json: /materials/m/kd: .*twice" <<<"$warnings" || fail "no warning for kd: $warnings"
[ -f "$dir/out/f_0001.png" ] || fail "twice.json: the last 'objects' should be rendered"
echo "cli_input_files: ok"
