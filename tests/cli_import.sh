#!/usr/bin/env bash
# Models imported through Assimp (issue 18), as `tessera raster` renders them: glTF 2.0 with
# node transforms and materials, OBJ + MTL with a texture, PLY without normals. Without a
# camera the model is framed and the camera printed, and rendering again with the printed flags
# gives the same ids; both renderers agree on ids up to edge ties; --shade material shows the
# base colours, the texture and the alpha mask; a missing texture is one warning; bad files are
# one-line errors.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
command -v python3 >/dev/null || { echo "SKIPPED: python3 is not installed"; exit 77; }
scripts=$(cd "$(dirname "$0")/../scripts" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"

# The models: written here, so the test owns every byte it reads.
python3 - "$dir" <<'EOF' || fail "cannot write the test models"
import base64, json, math, struct, sys, zlib
d = sys.argv[1]

def png(path, w, h, pixel):  # RGBA8, pixel(x, y) -> (r, g, b, a), rows top to bottom
    raw = b"".join(b"\0" + b"".join(bytes(pixel(x, y)) for x in range(w)) for y in range(h))
    chunk = lambda t, data: struct.pack(">I", len(data)) + t + data + struct.pack(">I", zlib.crc32(t + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

# A blue-and-white checker of 4 x 4 texels; its blue texels have alpha 0 on the left half
# (where the mask cuts them away).
png(f"{d}/checker.png", 4, 4, lambda x, y: (255, 255, 255, 255) if (x + y) % 2 else (0, 0, 255, 255 if x >= 2 else 0))

# glTF: one unit quad (positions, normals, uv, indices) used by three nodes: a red quad, the
# textured quad moved right by a node translation, and the masked quad moved left under a
# parent node that scales it (node transforms compose).
pos = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
nrm = [0, 0, 1] * 4
uv = [0, 1, 1, 1, 1, 0, 0, 0]
idx = [0, 1, 2, 0, 2, 3]
blob = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + struct.pack("<6H", *idx)
with open(f"{d}/quads.bin", "wb") as f:
    f.write(blob)
def view(offset, length): return {"buffer": 0, "byteOffset": offset, "byteLength": length}
gltf = {
  "asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0, 1, 2]}],
  "nodes": [{"mesh": 0}, {"mesh": 1, "translation": [1.5, 0, 0]},
            {"scale": [1, 0.5, 1], "children": [3]}, {"mesh": 2, "translation": [-1.5, 0, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": m}]}
             for m in range(3)],
  "materials": [
    {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0}},
    {"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}},
    {"name": "masked", "alphaMode": "MASK", "alphaCutoff": 0.5,
     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
  "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "checker.png"}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "buffers": [{"uri": "quads.bin", "byteLength": len(blob)}],
  "bufferViews": [view(0, 48), view(48, 48), view(96, 32), view(128, 12)],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
json.dump(gltf, open(f"{d}/quads.gltf", "w"))

# OBJ + MTL: a cube with the checker on every face; and one whose texture is missing.
obj = ["mtllib cube.mtl", "usemtl checker"]
for x in (0, 1):
    for y in (0, 1):
        for z in (0, 1):
            obj.append(f"v {x} {y} {z}")
obj += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
for f in ((1, 5, 7, 3), (2, 4, 8, 6), (1, 2, 6, 5), (3, 7, 8, 4), (1, 3, 4, 2), (5, 6, 8, 7)):
    obj.append("f " + " ".join(f"{v}/{k + 1}" for k, v in enumerate(f)))
open(f"{d}/cube.obj", "w").write("\n".join(obj) + "\n")
open(f"{d}/cube.mtl", "w").write("newmtl checker\nKd 0.8 0.8 0.8\nKs 0.2 0.2 0.2\nNs 20\nmap_Kd checker.png\n")
open(f"{d}/lost.obj", "w").write("\n".join(obj).replace("cube.mtl", "lost.mtl") + "\n")
open(f"{d}/lost.mtl", "w").write("newmtl checker\nKd 0.8 0.8 0.8\nmap_Kd textures/nowhere.png\n")

# PLY without normals: an octahedron subdivided into a sphere (smooth normals are generated).
verts = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
for _ in range(3):
    mids, nf = {}, []
    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            p = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
            n = math.sqrt(sum(c * c for c in p))
            verts.append(tuple(c / n for c in p))
            mids[key] = len(verts) - 1
        return mids[key]
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        nf += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    faces = nf
with open(f"{d}/ball.ply", "w") as f:
    f.write(f"ply\nformat ascii 1.0\nelement vertex {len(verts)}\nproperty float x\nproperty float y\n"
            f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    f.writelines(f"{x} {y} {z}\n" for x, y, z in verts)
    f.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
EOF

# Framing: no camera given, the chosen one is printed as flags; they reproduce the picture.
for model in quads.gltf cube.obj ball.ply; do
    err=$("$tessera" raster --mesh "$dir/$model" --size 96x64 --shade id --out-id "$dir/framed.id" 2>&1 >/dev/null) ||
        fail "$model: exited $?: $err"
    flags=$(sed -n 's/^tessera: camera (framed): //p' <<<"$err")
    [ -n "$flags" ] || fail "$model: the framed camera was not printed: $err"
    # shellcheck disable=SC2086
    "$tessera" raster --mesh "$dir/$model" --size 96x64 --shade id $flags --out-id "$dir/again.id" 2>/dev/null ||
        fail "$model: the printed camera was not accepted: $flags"
    cmp -s "$dir/framed.id" "$dir/again.id" || fail "$model: the printed camera gives another picture"
    # Framed means in view and filling it: at least 10% of the pixels covered, and none on the
    # image's border (the 5% margin keeps the whole box inside).
    python3 - "$dir/framed.id" <<'PY' || fail "$model: not framed"
import struct, sys
data = open(sys.argv[1], "rb").read()
end = data.index(b"\n")
_, w, h = data[:end].split()
w, h = int(w), int(h)
ids = struct.unpack(f"<{w * h}I", data[end + 1:end + 1 + 4 * w * h])
covered = sum(1 for i in ids if i != 0xFFFFFFFF)
border = [ids[x] for x in range(w)] + [ids[(h - 1) * w + x] for x in range(w)] + \
         [ids[y * w] for y in range(h)] + [ids[y * w + w - 1] for y in range(h)]
if covered < w * h // 10 or any(i != 0xFFFFFFFF for i in border):
    sys.exit(f"{covered} of {w * h} pixels covered, {sum(i != 0xFFFFFFFF for i in border)} on the border")
PY
    # Both renderers, same ids up to edge ties.
    "$tessera" raster --mesh "$dir/$model" --size 96x64 --shade id $flags --renderer raytrace \
        --out-id "$dir/rays.id" 2>/dev/null || fail "$model: raytrace exited $?"
    python3 "$scripts/compare-ids.py" "$dir/framed.id" "$dir/rays.id" --max-fraction 0.01 >/dev/null ||
        fail "$model: raster and raytrace disagree: $(python3 "$scripts/compare-ids.py" "$dir/framed.id" "$dir/rays.id")"
done

# --shade material: the model's own materials through the frame renderer, both renderers alike.
command -v oiiotool >/dev/null || { echo "SKIPPED: oiiotool is not installed"; exit 77; }
stats() {  # stats PNG -> "red blue white" pixel counts (8-bit sRGB)
    oiiotool "$1" --ch R,G,B -d uint8 -o "$1.ppm" >/dev/null || fail "oiiotool cannot convert $1"
    python3 - "$1.ppm" <<'EOF'
import sys
data = open(sys.argv[1], "rb").read()
fields = data.split(maxsplit=4)
w, h, body = int(fields[1]), int(fields[2]), fields[4]
px = [body[i:i + 3] for i in range(0, 3 * w * h, 3)]
red = sum(1 for r, g, b in px if r > 150 and g < 60 and b < 60)
blue = sum(1 for r, g, b in px if b > 150 and r < 90 and g < 90)
white = sum(1 for r, g, b in px if min(r, g, b) > 170)
print(red, blue, white)
EOF
}
for renderer in raster raytrace; do
    "$tessera" raster --mesh "$dir/quads.gltf" --size 320x160 --shade material --renderer $renderer \
        --out-color "$dir/quads_$renderer.png" 2>/dev/null || fail "quads.gltf --shade material --renderer $renderer"
done
read -r red blue white <<<"$(stats "$dir/quads_raster.png")"
# The red quad, the checker's blue and white texels; the masked quad shows only its right half.
[ "$red" -gt 200 ] && [ "$blue" -gt 100 ] && [ "$white" -gt 100 ] ||
    fail "quads.gltf: expected red, blue and white pixels, got $red $blue $white"
read -r red2 blue2 white2 <<<"$(stats "$dir/quads_raytrace.png")"
for pair in "$red $red2" "$blue $blue2" "$white $white2"; do
    set -- $pair
    [ $(( ($1 - $2) * ($1 - $2) )) -le $(( ($1 / 20 + 5) * ($1 / 20 + 5) )) ] ||
        fail "raster and raytrace differ: $red/$red2 red, $blue/$blue2 blue, $white/$white2 white"
done
"$tessera" raster --mesh "$dir/cube.obj" --size 96x64 --shade material --shadows map --out-color "$dir/cube.png" \
    2>/dev/null || fail "cube.obj --shade material"
read -r red blue white <<<"$(stats "$dir/cube.png")"
[ "$blue" -gt 50 ] || fail "cube.obj: the MTL texture does not show ($blue blue pixels)"
"$tessera" raster --mesh "$dir/ball.ply" --size 96x64 --shade material --renderer raytrace --shadows rays \
    --repeat 2 --stats --out-color "$dir/ball.png" >"$dir/ball.out" 2>/dev/null || fail "ball.ply --shade material"
grep -q 'model_triangles=512 ' "$dir/ball.out" || fail "ball.ply: $(cat "$dir/ball.out")"
grep -Eq '^frame_ms median=' "$dir/ball.out" || fail "ball.ply: no frame_ms line"
# The tile stage by pass (thread ms), every one >= 0, together at most the whole tiles' time.
awk '/^stats: tiles_thread_ms=/ {
    found = 1; split($2, t, "="); sum = 0
    for (i = 3; i <= NF; i++) { split($i, kv, "="); if (kv[1] !~ /_ms$/ || kv[2] < 0) exit 1; sum += kv[2] }
    if (NF != 10 || sum > t[2] + 0.001 * NF) exit 1
} END { exit !found }' "$dir/ball.out" || fail "ball.ply: no tile pass times: $(cat "$dir/ball.out")"

# A missing texture is one warning naming it; the model still renders.
err=$("$tessera" raster --mesh "$dir/lost.obj" --size 32x32 --shade material --out-color "$dir/lost.png" 2>&1 >/dev/null) ||
    fail "lost.obj: a missing texture failed the run: $err"
[ "$(grep -c '^tessera: warning: .*nowhere.png' <<<"$err")" -eq 1 ] || fail "lost.obj: no warning naming the texture: $err"
[ -s "$dir/lost.png" ] || fail "lost.obj: nothing written"

# A scene file's mesh objects: their own materials, or one for all of them; no camera and no
# lights in the file: framed (and printed) and lit by the rig.
cat >"$dir/scene.json" <<EOF
{"materials": {"gold": {"kd": [0.8, 0.6, 0.1]}},
 "objects": [{"type": "mesh", "file": "quads.gltf"},
             {"type": "mesh", "file": "ball.ply", "material": "gold", "transform": {"translate": [0, 2, 0]}}],
 "render": {"size": [64, 48]}}
EOF
err=$("$tessera" render --scene "$dir/scene.json" --frames 1 --out "$dir/scene_#.png" --quiet 2>&1) ||
    fail "scene with mesh objects: $err"
grep -q '^tessera: camera (framed): --eye ' <<<"$err" || fail "scene: the framed camera was not printed: $err"
[ -s "$dir/scene_1.png" ] || fail "scene: no frame written"

# Bad files: one line, exit 1, nothing written.
printf 'glTF\002\000\000\000\377\377\377\377' >"$dir/truncated.glb"
printf 'ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n0\n' >"$dir/huge.ply"
printf 'v 0 0 0\nv 1 0 0\nl 1 2\n' >"$dir/lines.obj"
for bad in truncated.glb huge.ply missing.gltf; do
    for shade in id material; do
        expect_error 1 raster --mesh "$dir/$bad" --shade $shade --size 16x16 --out-color "$dir/bad.png"
        grep -q "$bad" <<<"$err" || fail "$bad: the error does not name the file: $err"
        [ ! -e "$dir/bad.png" ] || fail "$bad: an image was written"
    done
done
expect_error 1 raster --mesh "$dir/lines.obj" --shade material --size 16x16
grep -q "no triangles" <<<"$err" || fail "lines.obj: $err"
expect_error 2 raster --mesh "$dir/quads.gltf" --shade material --out-id "$dir/x.id"
expect_error 2 raster --mesh "$dir/quads.gltf" --shadows rays
echo "cli_import: ok"
