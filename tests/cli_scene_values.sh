#!/usr/bin/env bash
# Scene values at their extremes (issue 19). A direction is a direction whatever its length:
# a rotation axis, light direction, spin axis, camera up, sun direction or dune wind of
# [3e38, 3e38, 3e38] or [1e-30, 1e-30, 1e-30] renders exactly as [1, 1, 1] (normalised by
# scaling first, never squared into Inf or 0). A value whose products would overflow (a
# radiance of 3e38, a point light or eye beyond 1e18) is refused, never written as Inf. A scene content error exits 1 with "FILE: /json/pointer: ..." (never a usage error),
# and leaves no file behind.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"

# scene NAME CAMERA LIGHTS OBJECTS [EXTRA]: a scene file from its parts (JSON fragments).
scene() {
    printf '{"materials": {"m": {"kd": [0.8, 0.5, 0.3], "ks": [0.5, 0.5, 0.5], "shine": 20},
             "n": {"kd": [0.8, 0.8, 0.8], "normal_texture": "bumps"}},
 "textures": {"bumps": {"type": "relief_normals", "size": 32}},
 "camera": {%s}, "lights": [%s], "objects": [%s]%s}\n' "$2" "$3" "$4" "${5:-}" >"$dir/$1.json"
}
eye='"eye": [0.5, 1.2, 4], "lookat": [0, 0, 0]'
light='{"direction": [1, 1, 1], "La": [0.1, 0.1, 0.1], "Le": [1, 1, 1]}'
box='{"type": "box", "material": "m", "transform": {"axis": [1, 1, 1], "angle": 30}}'

# render NAME [ARGS...]: scene NAME as $dir/NAME.png, frame 5 unless ARGS say --frames.
render() {
    local name=$1
    shift
    local frames=(--frames 5:5)
    [[ " $* " == *" --frames "* ]] && frames=()
    "$tessera" render --scene "$dir/$name.json" --size 48x32 "${frames[@]}" --quiet --out "$dir/$name.png" "$@" ||
        fail "$name exited $?"
}
# same A B: scenes A and B render identical bytes (A is rendered once).
same() {
    [ -f "$dir/$1.png" ] || render "$1"
    render "$2"
    cmp -s "$dir/$1.png" "$dir/$2.png" || fail "$2 renders differently from $1"
}

# --- Directions of any length ------------------------------------------------------------------
scene unit "$eye" "$light" "$box"
for big in '3e38, 3e38, 3e38' '1e-30, 1e-30, 1e-30' '1e-44, 1e-44, 1e-44' '-3e38, -3e38, -3e38'; do
    # A negative axis turns the other way: its angle is negated to keep the same rotation.
    angle=30
    case $big in -*) angle=-30 ;; esac
    scene axis "$eye" "$light" "{\"type\": \"box\", \"material\": \"m\", \"transform\": {\"axis\": [$big], \"angle\": $angle}}"
    same unit axis
    case $big in -*) continue ;; esac
    scene light_dir "$eye" "{\"direction\": [$big], \"La\": [0.1, 0.1, 0.1], \"Le\": [1, 1, 1]}" "$box"
    same unit light_dir
    scene up "$eye, \"up\": [0, ${big%%,*}, 0]" "$light" "$box"
    same unit up
done
spin='{"type": "box", "material": "m", "spin": {"axis": [%s], "speed": 40}}'
scene spin_unit "$eye" "$light" "$(printf "$spin" '1, 2, 0')"
scene spin_big "$eye" "$light" "$(printf "$spin" '1.5e38, 3e38, 0')"
same spin_unit spin_big
scene spin_tiny "$eye" "$light" "$(printf "$spin" '1e-30, 2e-30, 0')"
same spin_unit spin_tiny
sky='"background": {"type": "sky", "sun_direction": [%s], "sun": [5, 5, 5]}'
scene sun_unit "$eye" "$light" "$box" ", $(printf "$sky" '0, 0.25, -1')"
scene sun_big "$eye" "$light" "$box" ", $(printf "$sky" '0, 7.5e37, -3e38')"
same sun_unit sun_big
dunes='{"type": "heightfield", "material": "m", "samples": [24, 24], "relief": "dunes", "wind": [%s]}'
scene wind_unit "$eye" "$light" "$(printf "$dunes" '1, 1')"
scene wind_big "$eye" "$light" "$(printf "$dunes" '3e38, 3e38')"
same wind_unit wind_big
scene wind_tiny "$eye" "$light" "$(printf "$dunes" '1e-39, 1e-39')"
same wind_unit wind_tiny
# A normal map's strength only tilts normals further: at 1e38 they are the same as at 1e30
# (nearly horizontal), never zero-length (encoded 128, 128, 128).
strong='"textures": {"bumps": {"type": "relief_normals", "size": 32, "strength": %s}}'
for s in 1e30 1e38; do
    printf '{"materials": {"n": {"kd": [0.8, 0.8, 0.8], "normal_texture": "bumps"}}, %s,
      "camera": {%s}, "lights": [%s], "objects": [{"type": "sphere", "material": "n"}]}' \
        "$(printf "$strong" $s)" "$eye" "$light" >"$dir/strength_$s.json"
done
same strength_1e30 strength_1e38
"$tessera" generate heightfield --size 64x64 --seed 3 --out "$dir/h.png" >/dev/null || fail "heightfield exited $?"
for s in 1e30 1e38; do
    "$tessera" generate normalmap --in "$dir/h.png" --out "$dir/n_$s.png" --strength $s >/dev/null ||
        fail "normalmap --strength $s exited $?"
done
cmp -s "$dir/n_1e30.png" "$dir/n_1e38.png" || fail "normalmap --strength 1e38 differs from 1e30"
stats=$(oiiotool "$dir/n_1e38.png" --printstats 2>&1)
grep -q 'Stats Max: 128 128 128' <<<"$stats" && fail "normalmap --strength 1e38 wrote flat or zero-length normals: $stats"

# --- Values whose products overflow: refused, naming the value -------------------------------
# scene_error NAME POINTER [ARGS...]: scene NAME fails with exit 1 and one error line
# "NAME.json: POINTER[/deeper]: ..." (no usage hint), and writes no file.
scene_error() {
    local name=$1 pointer=$2
    shift 2
    local frames=(--frames 1:3)
    [[ " $* " == *" --frames "* ]] && frames=()
    rm -rf "$dir/out"
    expect_error 1 render --scene "$dir/$name.json" --size 48x32 "${frames[@]}" --quiet --out "$dir/out/f_####.exr" "$@"
    grep -Eq "^tessera: error: $dir/$name.json: $pointer(/[^ :]*)?: " <<<"$err" ||
        fail "$name: expected '$name.json: $pointer...: ...': $err"
    grep -q '^hint:' <<<"$err" && fail "$name: a scene error is not a usage error: $err"
    [ -z "$(ls -A "$dir/out" 2>/dev/null)" ] || fail "$name left files: $(ls -A "$dir/out")"
}
for key in Le La; do
    scene "big_$key" "$eye" "{\"direction\": [0, 1, 1], \"$key\": [3e38, 3e38, 3e38]}" "$box"
    scene_error "big_$key" "/lights/0/$key"
    scene "negative_$key" "$eye" "{\"direction\": [0, 1, 1], \"$key\": [-1, 0, 0]}" "$box"
    scene_error "negative_$key" "/lights/0/$key"
done
scene far_light "$eye" '{"position": [3e38, 1, 1]}' "$box"
scene_error far_light /lights/0/position
scene big_kd "$eye" "$light" "$box"
sed -i 's/"kd": \[0.8, 0.5, 0.3\]/"kd": [3e38, 3e38, 3e38]/' "$dir/big_kd.json"
scene_error big_kd /materials/m/kd
scene big_background "$eye" "$light" "$box" ', "background": {"colour": [3e38, 0, 0]}'
scene_error big_background /background/colour
scene big_sun "$eye" "$light" "$box" ", $(printf "$sky" '0, 1, 0' | sed 's/"sun": \[5, 5, 5\]/"sun": [3e38, 1, 1]/')"
scene_error big_sun /background/sun
scene far_eye '"eye": [3e38, 0, 0], "lookat": [-3e38, 0, 0]' "$light" "$box"
scene_error far_eye /camera/eye
scene zero_direction "$eye" '{"direction": [0, 0, 0]}' "$box"
scene_error zero_direction /lights/0/direction
scene zero_up "$eye, \"up\": [0, 0, 0]" "$light" "$box"
scene_error zero_up /camera/up
# A radiance just within range and many lights: either refused or finite, never Inf.
many=$(printf '{"direction": [0, 1, 1], "La": [1e12, 1e12, 1e12], "Le": [1e12, 1e12, 1e12]},%.0s' $(seq 1 8))
scene many_lights "$eye" "${many%,}" "$box"
sed -i 's/"kd": \[0.8, 0.5, 0.3\]/"kd": [1e6, 1e6, 1e6], "ka": [1e6, 1e6, 1e6]/' "$dir/many_lights.json"
if "$tessera" render --scene "$dir/many_lights.json" --size 48x32 --frames 5:5 --quiet --out "$dir/many.exr" 2>"$dir/err"; then
    stats=$(oiiotool "$dir/many.exr" --printstats 2>&1)
    grep -E 'Stats (NanCount|InfCount): 0 0 0 0' <<<"$stats" | grep -c . | grep -q 2 ||
        fail "many bright lights wrote NaN or Inf: $stats"
else
    [ "$(grep -c '^tessera: error: ' "$dir/err")" -eq 1 ] || fail "many bright lights: $(cat "$dir/err")"
fi

# --- Scene content errors found while building: exit 1 with the value's pointer ---------------
scene flag_size "$eye" "$light" '{"type": "flag", "material": "m", "size": [0, -2]}'
scene_error flag_size /objects/0/size
scene torus "$eye" "$light" '{"type": "box", "material": "m"}, {"type": "torus", "material": "m", "major": 0.2, "minor": 0.5}'
scene_error torus /objects/1
scene anisotropy "$eye" "$light" "$box"
sed -i 's/"type": "relief_normals", "size": 32}/"type": "reaction_diffusion", "size": 16, "steps": 10, "anisotropy": 5}/' "$dir/anisotropy.json"
scene_error anisotropy /textures/bumps/anisotropy
scene gain "$eye" "$light" '{"type": "heightfield", "material": "m", "samples": [8, 8], "gain": 2}'
scene_error gain /objects/0/gain
scene same_point '"eye": [1, 2, 3], "lookat": [1, 2, 3]' "$light" "$box"
scene_error same_point /camera
scene up_along_view '"eye": [0, 5, 0], "lookat": [0, 0, 0]' "$light" "$box"
scene_error up_along_view /camera
scene terrain_frequency "$eye" "$light" "$box" ', "passes": [{"type": "terrain", "frequency": 3e38}]'
scene_error terrain_frequency /passes/0
shadow_lights=$(printf '{"direction": [0, 1, %d]},' 1 2 3 4 5)
scene five_shadowed "$eye" "${shadow_lights%,}" "$box" ', "render": {"shadows": "map"}'
scene_error five_shadowed /lights
# ... while the same lights without shadows render, and --shadows on the command line is a
# usage error (exit 2).
render five_shadowed --shadows none
expect_error 2 render --scene "$dir/five_shadowed.json" --size 48x32 --frames 1:1 --quiet --shadows rays --out "$dir/x.png"

# --- Animated values: every keyframe, the whole spline, every frame time, before any frame -----
keys() { scene "$1" "$eye, \"keyframes\": [$2]" "$light" "$box"; }
keys key_fov '{"time": 0}, {"time": 1, "fov": 190}'
scene_error key_fov /camera/keyframes/1/fov
keys key_fov_zero '{"time": 0, "fov": 0}, {"time": 1}'
scene_error key_fov_zero /camera/keyframes/0/fov
# 10, 170, 170, 10: the spline overshoots past 180 between the two 170s (frames 12-18 at 24 fps)
keys overshoot '{"time": 0, "fov": 10}, {"time": 0.5, "fov": 170}, {"time": 1, "fov": 170}, {"time": 1.5, "fov": 10}'
scene_error overshoot /camera/keyframes
# ... and is refused even when the frames rendered miss the overshoot: the spline is checked.
scene_error overshoot /camera/keyframes --frames 1:2
keys undershoot '{"time": 0, "fov": 170}, {"time": 0.5, "fov": 4}, {"time": 1, "fov": 4}, {"time": 1.5, "fov": 170}'
scene_error undershoot /camera/keyframes
keys key_same_point '{"time": 0}, {"time": 2, "eye": [0, 0, 0]}'
scene_error key_same_point /camera/keyframes/1
keys key_up '{"time": 0}, {"time": 2, "eye": [0, 3, 0]}'
scene_error key_up /camera/keyframes/1
# The eye passes through the lookat point between two good keys (at t = 1 s, frame 24).
keys crossing '{"time": 0, "eye": [0, 0, 4]}, {"time": 2, "eye": [0, 0, -4]}'
rm -rf "$dir/out"
expect_error 1 render --scene "$dir/crossing.json" --size 48x32 --frames 1:48 --quiet --out "$dir/out/f_####.png"
grep -q "crossing.json: /camera" <<<"$err" || fail "crossing: $err"
grep -q "frame 24" <<<"$err" || fail "crossing: the error should name frame 24: $err"
[ -z "$(ls -A "$dir/out" 2>/dev/null)" ] || fail "crossing wrote frames before failing: $(ls "$dir/out" | wc -l)"
# A sane spline renders (a small overshoot within range is fine).
keys sane '{"time": 0, "fov": 40}, {"time": 0.5, "fov": 70}, {"time": 1, "fov": 70}, {"time": 1.5, "fov": 40}'
"$tessera" render --scene "$dir/sane.json" --size 48x32 --frames 1:40 --quiet --out "$dir/sane/f_####.png" ||
    fail "a sane spline exited $?"
echo "cli_scene_values: ok"
