#!/usr/bin/env bash
# `tessera shadows` (issue 6): shadow maps against Embree shadow rays on the sphere grid; the
# agreement line, the diff image, and usage errors. With --scene (issue 17): the
# disagreement of rendered frames and the times; the shadow-map settings as flags and in a
# scene file, and their errors.
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
cat > "$dir/contact.json" <<'JSON'
{
  "camera": {"eye": [0.2, 1.1, 2.6], "lookat": [0, 0, 0], "fov": 45, "near": 0.1, "far": 60},
  "lights": [{"direction": [-0.6, 0.5, -0.4], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1],
              "shadow_map": {"size": 512, "cascades": 3, "split_blend": 0.7, "pcf": 1,
                             "normal_offset": 1.6, "depth_bias": 0.5}}],
  "materials": {"sand": {"model": "phong", "kd": [0.8, 0.6, 0.4]}},
  "objects": [
    {"name": "ground", "type": "box", "material": "sand", "size": [40, 0.1, 40], "transform": {"translate": [0, -0.05, 0]}},
    {"name": "slab", "type": "box", "material": "sand", "size": [0.6, 0.04, 0.5], "transform": {"translate": [-0.4, 0.02, 0.1]}}
  ]
}
JSON
out=$("$tessera" shadows --scene "$dir/contact.json" --size 160x90 --repeat 2 --diff "$dir/frames.png") ||
  fail "shadows --scene exited $?"
grep -Eq '^light 0: shadow maps 3 x 512\^2, split blend 0.70, PCF 3x3 box' <<<"$out" || fail "no settings line: $out"
grep -Eq '^disagreement: [0-9.]+% \([0-9]+ of [0-9]+ pixels' <<<"$out" || fail "no disagreement line: $out"
grep -Eq '^time map: wall [0-9.]+ ms, cpu [0-9.]+ ms per frame \(median of 2' <<<"$out" || fail "no map time: $out"
grep -Eq '^time rays: wall' <<<"$out" || fail "no rays time: $out"
[ -s "$dir/frames.png" ] || fail "no frame diff image"
out=$("$tessera" shadows --scene "$dir/contact.json" --size 160x90 --cascades 1 --map-size 64) || fail "flags exited $?"
grep -Eq '^light 0: shadow maps 1 x 64\^2' <<<"$out" || fail "flags did not override the scene: $out"

expect_error 2 shadows --cascades 9
expect_error 2 shadows --split-blend 1.5
expect_error 2 shadows --normal-offset -1
expect_error 2 shadows --frame 3
expect_error 2 render --scene flag --frames 1 --cascades 0 --out "$dir/x.png"
sed 's/"cascades": 3/"cascades": 12/' "$dir/contact.json" > "$dir/bad.json"
expect_error 1 render --scene "$dir/bad.json" --frames 1 --size 8x8 --shadows map --out "$dir/x.png"
grep -q 'shadow_map.*cascades 12 is outside 1 .. 8' <<<"$err" || fail "unclear error: $err"
echo "cli_shadows: ok"
