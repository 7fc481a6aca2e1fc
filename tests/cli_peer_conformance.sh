#!/usr/bin/env bash
# Conformance against a production rasterizer: `tessera raster` and Mesa's llvmpipe
# (tessera-llvmpipe, beside the tessera binary) must give the same triangle id at every pixel
# of the same workloads, up to a tiny fraction (MAX_FRACTION below) of pixels. Both use 8
# sub-pixel bits, pixel centres at (x+0.5, y+0.5) and the top-left rule in top-down rows, so
# only float rounding before snapping (vertices within 1/512 px of a snapping boundary) and
# depth near-ties can differ.
# First, the peer's own conventions are checked (rows top to bottom, top-left rule, culling).
# Then the same at 4 samples per pixel (issue 17): `tessera raster --shade id --samples 4` and
# the peer's multisample targets give every sample's id, in the order of tessera's sample
# pattern (the D3D/Vulkan standard positions, which llvmpipe's GL_SAMPLE_POSITION must equal:
# the peer refuses the per-sample ids otherwise), compared sample for sample up to the same
# MAX_FRACTION of samples.
# Exits 77 (ctest: skipped) when tessera-llvmpipe was not built (no OSMesa at configure time).
set -u
tessera=$1
peer=$(dirname "$tessera")/tessera-llvmpipe
scripts=$(cd "$(dirname "$0")/../scripts" && pwd)
MAX_FRACTION=0.0005
fail() { echo "FAIL: $*"; exit 1; }
if [[ ! -x $peer ]]; then
  echo "SKIPPED: tessera-llvmpipe was not built (OSMesa not found at configure time: install libosmesa6-dev)"
  exit 77
fi
command -v python3 >/dev/null || { echo "SKIPPED: python3 is not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Sanitize build: OSMesa's own leaks are suppressed (lsan_osmesa.supp says which).
export LSAN_OPTIONS="${LSAN_OPTIONS:+$LSAN_OPTIONS:}suppressions=$(cd "$(dirname "$0")" && pwd)/lsan_osmesa.supp:print_suppressions=0"

# samples FILE X Y [X Y...] -> per pixel (X, Y), one line of its sample ids (multisampled TSID)
samples() {
  python3 -c 'import sys
from array import array
d = open(sys.argv[1], "rb").read(); e = d.index(b"\n"); w, h, n = map(int, d[:e].split()[1:])
a = array("I"); a.frombytes(d[e + 1:]); xy = list(map(int, sys.argv[2:]))
for p in (y * w + x for x, y in zip(xy[::2], xy[1::2])):
    print(" ".join("." if v == 0xFFFFFFFF else str(v) for v in a[p * n:(p + 1) * n]))' "$@"
}

# ids FILE -> rows of the TSID image, '.' where empty
ids() {
  python3 -c 'import sys
from array import array
d = open(sys.argv[1], "rb").read(); e = d.index(b"\n"); w, h = map(int, d[:e].split()[1:])
a = array("I"); a.frombytes(d[e + 1:])
for y in range(h): print(" ".join("." if v == 0xFFFFFFFF else str(v) for v in a[y * w:(y + 1) * w]))' "$1"
}

# Two counter-clockwise triangles sharing a horizontal edge through the centres of row 3 of
# an 8x8 image (y_ndc = 0.125), and two sharing a vertical edge through column 3's centres.
printf 'eye 0 0 1\nlookat 0 0 0\nup 0 1 0\nfovy_deg 90\nnear 0.1\nfar 10\n' > "$tmp/cam.txt"
printf 'v -0.9 0.125 0\nv 0.9 0.125 0\nv 0 0.9 0\nv 0 -0.9 0\nf 1 2 3\nf 2 1 4\n' > "$tmp/h.obj"
printf 'v -0.125 -0.9 0\nv -0.125 0.9 0\nv 0.9 0 0\nv -0.9 0 0\nf 1 3 2\nf 1 2 4\n' > "$tmp/v.obj"
"$peer" --mesh "$tmp/h.obj" --camera "$tmp/cam.txt" --size 8x8 --out-id "$tmp/h.id" || fail "peer exited $?"
row3=$(ids "$tmp/h.id" | sed -n 4p)
[[ $row3 == "1 1 1 1 1 1 1 1" ]] || fail "top-left rule: row 3 should belong to the lower triangle (1): '$row3'"
[[ $(ids "$tmp/h.id" | sed -n 2p) == ". . . 0 0 . . ." ]] || fail "rows are not top to bottom: $(ids "$tmp/h.id")"
"$peer" --mesh "$tmp/v.obj" --camera "$tmp/cam.txt" --size 8x8 --out-id "$tmp/v.id" || fail "peer exited $?"
col3=$(ids "$tmp/v.id" | awk '{ printf "%s", $4 }')
[[ $col3 == 00000000 ]] || fail "top-left rule: column 3 should belong to the right triangle (0): '$col3'"
"$peer" --mesh "$tmp/h.obj" --camera "$tmp/cam.txt" --size 8x8 --cull front --out-id "$tmp/f.id" || fail "peer exited $?"
[[ $(ids "$tmp/f.id" | tr -d ' .\n') == "" ]] || fail "--cull front kept counter-clockwise triangles"
"$peer" --mesh "$tmp/none.obj" --camera "$tmp/cam.txt" 2>"$tmp/err"; code=$?
[[ $code -eq 1 && $(wc -l <"$tmp/err") -eq 1 ]] || fail "missing mesh: exit $code, '$(cat "$tmp/err")'"
echo "peer conventions: ok"

# 4 samples: the edges above run through the centres of row 3 and column 3, and sample s of
# tessera's pattern sits at (x, y) = (-2,-6) (6,-2) (-6,2) (2,6)/16 px from the centre (y down):
# samples 0 and 1 above the horizontal edge, 0 and 2 left of the vertical one. A flipped or
# reordered pattern fails here. Each renderer is checked on its own.
msaa_conventions() {  # NAME COMMAND...: COMMAND renders $tmp/{h,v}.obj at 8x8 with --out-id
  local name=$1; shift
  "$@" --mesh "$tmp/h.obj" --camera "$tmp/cam.txt" --size 8x8 --shade id --samples 4 --out-id "$tmp/h4.id" ||
    fail "$name --samples 4 exited $?"
  [[ $(head -n 1 "$tmp/h4.id") == "TSID 8 8 4" ]] || fail "$name: multisampled TSID header '$(head -n 1 "$tmp/h4.id")'"
  # pixels (3,3) (4,3) across the horizontal edge: samples 0 1 above (0), 2 3 below (1);
  # (3,2) (4,2) above it
  got=$(samples "$tmp/h4.id" 3 3 4 3 3 2 4 2 | tr '\n' ,)
  [[ $got == "0 0 1 1,0 0 1 1,0 0 0 0,0 0 0 0," ]] || fail "$name: samples across the horizontal edge: '$got'"
  "$@" --mesh "$tmp/v.obj" --camera "$tmp/cam.txt" --size 8x8 --shade id --samples 4 --out-id "$tmp/v4.id" ||
    fail "$name --samples 4 exited $?"
  # pixels (3,3) (3,4) across the vertical edge: samples 0 2 left (1), 1 3 right (0)
  got=$(samples "$tmp/v4.id" 3 3 3 4 | tr '\n' ,)
  [[ $got == "1 0 1 0,1 0 1 0," ]] || fail "$name: samples across the vertical edge: '$got'"
  echo "$name conventions at 4 samples: ok"
}
msaa_conventions tessera-llvmpipe "$peer"
positions=$("$peer" --mesh "$tmp/h.obj" --camera "$tmp/cam.txt" --size 8x8 --samples 4 --stats | grep '^peer: 4 samples') ||
  fail "peer --samples 4 --stats printed no sample positions"
echo "$positions"
# Counts llvmpipe does not have are refused in one line (exit 1), not rendered with another.
for n in 8 16; do
  if ! "$peer" --mesh "$tmp/h.obj" --camera "$tmp/cam.txt" --size 8x8 --samples $n --out-id "$tmp/n.id" 2>"$tmp/err"; then
    [[ $(wc -l <"$tmp/err") -eq 1 ]] && grep -q -- "--samples $n" "$tmp/err" || fail "--samples $n: '$(cat "$tmp/err")'"
    [[ -e $tmp/n.id ]] && fail "--samples $n: refused, yet wrote $tmp/n.id"
    echo "peer --samples $n: $(cat "$tmp/err")"
  else
    [[ $(head -n 1 "$tmp/n.id") == "TSID 8 8 $n" ]] || fail "peer --samples $n: header '$(head -n 1 "$tmp/n.id")'"
  fi
done

if ! "$tessera" --help 2>/dev/null | grep -q '^ *raster '; then
  echo "SKIPPED: this tessera has no 'raster' command, nothing to compare"
  exit 77
fi
msaa_conventions tessera "$tessera" raster

# compare NAME CULL [SAMPLES]: both renderers on $tmp/NAME.{obj,cam}, the same ids up to
# MAX_FRACTION of the pixels (of the samples, when multisampled)
compare() {
  local name=$1 cull=$2 samples=${3:-1}
  local args=(--mesh "$tmp/$name.obj" --camera "$tmp/$name.cam" --size 320x180 --shade id --cull "$cull")
  ((samples > 1)) && args+=(--samples "$samples")
  "$tessera" raster "${args[@]}" --threads 2 --out-id "$tmp/$name.t.id" || fail "tessera raster $name exited $?"
  "$peer" "${args[@]}" --threads 2 --out-id "$tmp/$name.p.id" || fail "tessera-llvmpipe $name exited $?"
  local line code
  line=$(python3 "$scripts/compare-ids.py" "$tmp/$name.t.id" "$tmp/$name.p.id" --max-fraction $MAX_FRACTION --show 5)
  code=$?
  echo "$name --cull $cull --samples $samples: $(head -1 <<<"$line")"
  ((code == 0)) || fail "$name --samples $samples: more than $MAX_FRACTION differ (A = tessera, B = llvmpipe): $line"
}
gen() { python3 "$scripts/gen-workload.py" "$@" >/dev/null || fail "gen-workload.py $*"; }
testmesh() { "$tessera" testmesh "$@" >/dev/null || fail "tessera testmesh $*"; }

# Each workload at one sample, then at 4 (every sample compared).
gen grid --triangles 10000 --pixels 4 --size 320x180 --out "$tmp/grid"   # diagonals on centres
compare grid none; compare grid none 4
testmesh --kind fillrate --count 3000 --leg 10 --size 320x180 --out "$tmp/fill.obj" --camera-out "$tmp/fill.cam"
compare fill none; compare fill none 4                                    # overlaps, back to front
testmesh --kind random --count 3000 --leg 60 --size 320x180 --out "$tmp/random.obj" --camera-out "$tmp/random.cam"
compare random none; compare random none 4                                # any orientation, depth
testmesh --kind sphere --count 20000 --out "$tmp/sphere.obj" --camera-out "$tmp/sphere.cam"
compare sphere back; compare sphere back 4                                # perspective, culling
gen spheres --triangles 16384 --out "$tmp/spheres"
compare spheres back; compare spheres back 4
compare spheres none; compare spheres none 4                              # depth hides back faces

# --shade phong is one shader in two languages: the colours must agree to 1/255 except where a
# pixel's triangle or checker cell differs (a tiny fraction, as for the ids).
for r in "$tessera raster" "$peer"; do
  $r --mesh "$tmp/sphere.obj" --camera "$tmp/sphere.cam" --size 320x180 --shade phong --cull back \
     --out-color "$tmp/phong.$(basename "${r%% *}").png" || fail "$r --shade phong exited $?"
done
diff=$(oiiotool "$tmp/phong.tessera.png" "$tmp/phong.tessera-llvmpipe.png" --fail 0.0040 --failpercent 0.5 --diff 2>&1)
grep -q "^PASS\|WARNING" <<<"$diff" || fail "phong colours differ: $diff"
echo "phong colours: $(grep -m1 'over\|PASS' <<<"$diff")"
echo "cli_peer_conformance: ok"
