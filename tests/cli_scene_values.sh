#!/usr/bin/env bash
# Scene values at their extremes (issue 19), through the command. A direction is a direction
# whatever its length: rotation and spin axes, light and sun directions, camera up and dune
# wind of [3e38, 3e38, 3e38] or [1e-30, 1e-30, 1e-30] render exactly as [1, 1, 1] (normalised
# by scaling first, never squared into Inf or 0), and a normal map's strength of 1e38 as 1e30.
# A scene content error exits 1 with "FILE: /json/pointer: ..." (never a usage error) and
# leaves no file behind, also when only the camera at one frame time is wrong. Every refused
# value is listed in tests/scene_values_test.cpp, which checks them in process.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"

# scene NAME CAMERA LIGHTS OBJECTS [EXTRA [STRENGTH]]: a scene file from its parts (JSON fragments).
scene() {
    printf '{"materials": {"m": {"kd": [0.8, 0.5, 0.3], "ks": [0.5, 0.5, 0.5], "shine": 20},
             "n": {"kd": [0.8, 0.8, 0.8], "normal_texture": "bumps"}},
 "textures": {"bumps": {"type": "relief_normals", "size": 32, "strength": %s}},
 "camera": {%s}, "lights": [%s], "objects": [%s]%s}\n' "${6:-1}" "$2" "$3" "$4" "${5:-}" >"$dir/$1.json"
}
eye='"eye": [0.5, 1.2, 4], "lookat": [0, 0, 0]'
light='{"direction": [1, 1, 1], "La": [0.1, 0.1, 0.1], "Le": [1, 1, 1]}'
box='{"type": "box", "material": "m", "transform": {"axis": [1, 1, 1], "angle": 30}}'

# --- Directions of any length: one scene holds every kind, at unit, huge and tiny length --------
# directions NAME AXIS UP SPIN SUN WIND STRENGTH
directions() {
    scene "$1" "$eye, \"up\": [$3]" "{\"direction\": [$2], \"La\": [0.1, 0.1, 0.1], \"Le\": [1, 1, 1]}" \
        "{\"type\": \"box\", \"material\": \"m\", \"transform\": {\"axis\": [$2], \"angle\": 30}},
         {\"type\": \"box\", \"material\": \"m\", \"transform\": {\"translate\": [1.5, 0, 0]}, \"spin\": {\"axis\": [$4], \"speed\": 40}},
         {\"type\": \"sphere\", \"material\": \"n\", \"radius\": 0.6, \"centre\": [-1.5, 0, 0]},
         {\"type\": \"heightfield\", \"material\": \"m\", \"samples\": [24, 24], \"relief\": \"dunes\", \"wind\": [$6],
          \"transform\": {\"translate\": [0, -1.5, 0]}}" \
        ", \"background\": {\"type\": \"sky\", \"sun_direction\": [$5], \"sun\": [5, 5, 5]}" "$7"
}
directions unit '1, 1, 1' '0, 1, 0' '1, 2, 0' '0, 0.25, -1' '1, 1' 1e30
directions huge '3e38, 3e38, 3e38' '0, 3e38, 0' '1.5e38, 3e38, 0' '0, 7.5e37, -3e38' '3e38, 3e38' 1e38
directions tiny '1e-30, 1e-30, 1e-30' '0, 1e-30, 0' '1e-30, 2e-30, 0' '0, 2.5e-31, -1e-30' '1e-39, 1e-39' 1e38
for name in unit huge tiny; do
    "$tessera" render --scene "$dir/$name.json" --size 48x32 --frames 5:5 --quiet --out "$dir/$name.png" ||
        fail "$name exited $?"
done
cmp -s "$dir/unit.png" "$dir/huge.png" || fail "directions of 3e38 render differently from unit ones"
cmp -s "$dir/unit.png" "$dir/tiny.png" || fail "directions of 1e-30 render differently from unit ones"
# `generate normalmap`: at a strength of 1e38 the normals are those of 1e30 (nearly
# horizontal), never zero-length (encoded 128, 128, 128). The rendered frame is the height.
for s in 1e30 1e38; do
    "$tessera" generate normalmap --in "$dir/unit.png" --out "$dir/n_$s.png" --strength $s >/dev/null ||
        fail "normalmap --strength $s exited $?"
done
cmp -s "$dir/n_1e30.png" "$dir/n_1e38.png" || fail "normalmap --strength 1e38 differs from 1e30"

# --- Scene content errors: exit 1, "FILE: /pointer: ...", no usage hint, no file ---------------
# scene_error NAME POINTER [ARGS...]: scene NAME fails with exit 1 and one error line
# "NAME.json: POINTER[/deeper]: ..." (no usage hint), and writes no file.
scene_error() {
    local name=$1 pointer=$2
    shift 2
    local frames=(--frames 1:3)
    [[ " $* " == *" --frames "* ]] && frames=()
    rm -rf "$dir/out"
    expect_error 1 render --scene "$dir/$name.json" --size 48x32 "${frames[@]}" --quiet --out "$dir/out/f_####.png" "$@"
    grep -Eq "^tessera: error: $dir/$name.json: $pointer(/[^ :]*)?: " <<<"$err" ||
        fail "$name: expected '$name.json: $pointer...: ...': $err"
    grep -q '^hint:' <<<"$err" && fail "$name: a scene error is not a usage error: $err"
    [ -z "$(ls -A "$dir/out" 2>/dev/null)" ] || fail "$name left files: $(ls -A "$dir/out")"
}
# Found while the scene is built (was a usage error, exit 2, with no file named).
scene flag_size "$eye" "$light" '{"type": "flag", "material": "m", "size": [0, -2]}'
scene_error flag_size /objects/0/size
# More than 4 shadowed lights: the scene's error, or --shadows's (a usage error, exit 2).
shadow_lights=$(printf '{"direction": [0, 1, %d]},' 1 2 3 4 5)
scene five_shadowed "$eye" "${shadow_lights%,}" "$box" ', "render": {"shadows": "map"}'
scene_error five_shadowed /lights
expect_error 2 render --scene "$dir/five_shadowed.json" --size 48x32 --frames 1:1 --quiet --shadows rays --out "$dir/x.png"
# The eye passes through the lookat point between two good keys (at t = 1 s, frame 24): found
# before the first frame is written.
scene crossing "$eye, \"keyframes\": [{\"time\": 0, \"eye\": [0, 0, 4]}, {\"time\": 2, \"eye\": [0, 0, -4]}]" "$light" "$box"
scene_error crossing /camera --frames 1:48
grep -q "frame 24" <<<"$err" || fail "crossing: the error should name frame 24: $err"
echo "cli_scene_values: ok"
