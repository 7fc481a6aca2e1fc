#!/usr/bin/env bash
# `tessera compare` (issue 18): a small generated mesh through both renderers at two tiny
# sizes and two thread counts, with a sweep, then a scene file. Checks the table against the
# JSON file (same figures), the JSON's facts, the id agreement between the renderers, that the
# sweep's triangle counts are exact multiples, that the plots are valid PNG files, and the
# one-line errors. Few runs: every tessera process costs start-up time, more so under ASan.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
command -v python3 >/dev/null || { echo "SKIPPED: python3 is not installed"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"

# A box standing on a floor (14 triangles): the default light rig casts its shadow there.
cat > "$dir/box.obj" <<'OBJ'
v -2 0 -2
v 2 0 -2
v 2 0 2
v -2 0 2
v -0.5 0 -0.5
v 0.5 0 -0.5
v 0.5 1 -0.5
v -0.5 1 -0.5
v -0.5 0 0.5
v 0.5 0 0.5
v 0.5 1 0.5
v -0.5 1 0.5
f 1 4 3 2
f 9 10 11 12
f 6 5 8 7
f 5 9 12 8
f 10 6 7 11
f 12 11 7 8
f 5 6 10 9
OBJ

# Small single shadow maps: the default cascades of 2048^2 cost more than the rest of the run.
out=$("$tessera" compare --mesh "$dir/box.obj" --size 64x48,96x72 --threads 1,2 --repeat 1 --sweep 4,1 \
      --map-size 256 --cascades 1 --json "$dir/c.json" --plots "$dir/plots" 2>"$dir/err") || fail "compare exited $?: $(cat "$dir/err")"
grep -q '^tessera compare: .*box.obj: 14 triangles, 2 light(s); medians of 1 run(s)$' <<<"$out" || fail "no header: $out"
grep -q '^tessera: camera (framed): --eye ' "$dir/err" || fail "the framed camera is not printed: $(cat "$dir/err")"
for config in '64x48, 1 thread' '64x48, [12] thread' '96x72, 1 thread' '96x72, [12] thread'; do
    grep -Eq "^$config" <<<"$out" || fail "no block for $config: $out"
done
for row in 'visibility ms' 'shading ms' 'bvh ms' 'frame ms' 'shadows ms' 'peak resident MiB' 'bvh build ms' \
           'ids agree' 'shadows agree'; do
    [ "$(grep -c "^  $row " <<<"$out")" -eq 4 ] || fail "expected 4 '$row' rows: $out"
done
ls "$dir/plots" > "$dir/plot_list"
printf '%s\n' "$out" > "$dir/table"

python3 - "$dir" <<'EOF' || fail "the JSON file does not match the table"
import json, re, struct, sys, zlib
d = sys.argv[1]
table = open(f"{d}/table").read()
with open(f"{d}/c.json") as f:
    j = json.load(f)

def check(cond, what):
    if not cond:
        sys.exit(f"{what}\n{table}\n{json.dumps(j, indent=1)}")

for key in ("command", "date", "machine", "content", "repeat", "configurations", "sweep", "crossover"):
    check(key in j, f"no '{key}' in the JSON")
check(" compare " in j["command"] and "--sweep 4,1" in j["command"], "command: " + j["command"])
check(re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", j["date"]), "date: " + j["date"])
check(j["machine"]["cpu"] and j["machine"]["hardware_threads"] >= 1 and j["machine"]["simd"], "machine")
check(j["content"]["triangles"] == 14 and j["content"]["lights"] == 2 and j["repeat"] == 1, "content")

# Each configuration block of the table against its JSON entry: the same rounded numbers.
blocks = re.split(r"^(?=\d+x\d+, \d+ thread)", table, flags=re.M)[1:]
configs = j["configurations"]
check(len(blocks) >= 4 and len(configs) == 4, f"{len(blocks)} blocks, {len(configs)} configurations")
for block, c in zip(blocks, configs):
    head = re.match(r"(\d+)x(\d+), (\d+) thread", block)
    check([int(head[1]), int(head[2]), int(head[3])] == [c["width"], c["height"], c["threads"]], "config " + head[0])
    def row(label):
        m = re.search(r"^  " + re.escape(label) + r" +(\S+) +(\S+)", block, re.M)
        check(m, f"no row {label}")
        return m[1], m[2]
    def same(text, value):
        check(text == "-" or abs(float(text.rstrip("%")) - value) <= 1e-9 + 1e-6 * abs(value),
              f"{head[0]}: table {text} != JSON {value}")
    for label, key in (("visibility ms", "visibility_ms"), ("shading ms", "shading_ms"), ("frame ms", "frame_ms"),
                       ("peak resident MiB", "peak_resident_mib")):
        a, b = row(label)
        same(a, c["raster"][key]); same(b, c["raytrace"][key])
    same(row("bvh ms")[1], c["raytrace"]["bvh_ms"])
    same(row("bvh build ms")[0], c["bvh"]["build_ms"])
    same(row("shadows ms")[0], c["shadows"]["maps_ms"]); same(row("shadows ms")[1], c["shadows"]["rays_ms"])
    same(row("ids agree")[0], c["ids"]["agree_percent"])
    same(row("shadows agree")[0], c["shadows"]["all"]["agree_percent"])
    check(c["ids"]["pixels"] == c["width"] * c["height"], "id pixels")
    # The renderers differ only at exact edge ties: a few pixels of a 64x48 image at most.
    check(c["ids"]["agree_percent"] >= 97.0, f"ids agree on {c['ids']['agree_percent']}% only")
    check(c["shadows"]["lights"] == 2 and c["shadows"]["all"]["compared_pixels"] > 0, "shadows compared")
    for r in ("raster", "raytrace"):
        check(all(c[r][k] >= 0 for k in ("visibility_ms", "shading_ms", "frame_ms")), "negative time")
        check(c[r]["frame_ms"] >= c[r]["visibility_ms"], "a frame shorter than its visibility")
check({c["threads"] for c in configs[:2]} == {configs[0]["threads"], configs[1]["threads"]}, "threads")

# The sweep: copies sorted, triangles exactly 14 per copy.
sweep = j["sweep"]
check([p["copies"] for p in sweep] == [1, 4], "sweep copies")
check([p["triangles"] for p in sweep] == [14, 56], "sweep triangles")
check(re.search(r"^ +4 copies +56 tris", table, re.M), "no sweep row")
check(re.search(r"^  crossover \(frame ms\): ", table, re.M), "no crossover line")
check(set(j["crossover"]) == {"frame", "visibility"}, "crossover keys")

# The plots: PNG files whose chunks' CRCs hold and whose pixels inflate to the right size.
plots = open(f"{d}/plot_list").read().split()
check(plots == ["time_vs_resolution.png", "time_vs_threads.png", "time_vs_triangles.png"], f"plots: {plots}")
for name in plots:
    data = open(f"{d}/plots/{name}", "rb").read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", name + ": not a PNG")
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        check(struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0] == zlib.crc32(kind + body), name + ": bad CRC")
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        idat += body if kind == b"IDAT" else b""
        pos += 12 + n
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[colour]
    check(width > 100 and len(zlib.decompress(idat)) == height * (1 + (width * channels * depth + 7) // 8),
          name + ": pixels do not inflate to the image size")
EOF

# A scene file: its own camera and light; the sweep copies its objects.
cat > "$dir/scene.json" <<'JSON'
{
  "camera": {"eye": [0.0, 2.0, 5.0], "lookat": [0.0, 0.0, 0.0], "fov": 40},
  "lights": [{"position": [2.5, 4.0, 3.0], "La": [0.1, 0.1, 0.1], "Le": [1, 1, 1]}],
  "materials": {"m": {"model": "phong", "kd": [0.8, 0.6, 0.4], "ka": [0.2, 0.2, 0.2], "ks": [0.3, 0.3, 0.3], "shine": 16}},
  "objects": [
    {"type": "box", "material": "m", "size": [1, 1, 1]},
    {"type": "box", "material": "m", "size": [4, 0.1, 4], "transform": {"translate": [0, -0.6, 0]}}
  ]
}
JSON
out=$("$tessera" compare --scene "$dir/scene.json" --size 64x48 --threads 1 --repeat 1 --sweep 1,3 --map-size 256 \
      --json "$dir/s.json" 2>"$dir/err") || fail "compare --scene exited $?: $(cat "$dir/err")"
grep -q '^tessera compare: .*scene.json: 24 triangles, 1 light(s)' <<<"$out" || fail "no scene header: $out"
python3 -c '
import json, sys
j = json.load(open(sys.argv[1]))
assert [p["triangles"] for p in j["sweep"]] == [24, 72], j["sweep"]
assert j["configurations"][0]["shadows"]["lights"] == 1 and j["configurations"][0]["ids"]["agree_percent"] >= 97
' "$dir/s.json" || fail "scene JSON: $(cat "$dir/s.json")"

expect_error 2 compare --mesh "$dir/box.obj" --scene snakes
expect_error 2 compare --mesh "$dir/box.obj" --size 64x48,0x5
echo "cli_compare: ok"
