#!/usr/bin/env bash
# The peer comparison: `tessera raster` and `tessera-llvmpipe` (Mesa llvmpipe via OSMesa) on the
# same generated workloads, same size, same shading, same thread counts, in the same run.
#
#   scripts/peer.sh [--workload NAME]... [--size WxH] [--threads "1 2"] [--repeat K]
#                   [--rounds R] [--shade MODE] [--cpu] [--memory] [--no-ids]
#
# Workloads (generated once into build/workloads/ by `tessera testmesh` or gen-workload.py):
#   sphere-1m (default)   bench_raster's UV sphere, ~1M triangles, --shade phong, --cull back
#   spheres-1m            1,048,576-triangle field of 1024 small spheres, phong, --cull back
#   sphere-20k            the same sphere with ~20k triangles (for --memory: small load peak)
#   sphere-grid-10k sphere-grid-100k sphere-grid-1m sphere-grid-4m
#                         bench_raster's grid of spheres on a ground plane (BM_FrameSphereGrid),
#                         ~10k/100k/1M/4M triangles, phong, --cull none (the scene of issue 20)
#   grid-10px             1,048,576 triangles in 10 px grid quads, back to front, --shade id
#   fill-10px fill-25px fill-50px fill-100px fill-250px
#                         MSOC FillrateTest right triangles (counts as in its test), --shade id
#   (--shade id is a flat colour per triangle, as in the llvmpipe anchors of
#   research/rasterizer-anchors.md 1.1; the screen-space workloads use --cull none.)
#   --shade MODE overrides the workload's shading.
# For each workload and thread count it runs the two renderers alternately R times (default 3)
# with `--repeat K` (default 10) and prints each one's median over the rounds of its
# `frame_ms median`, and the ratio llvmpipe / tessera (how many times faster tessera is).
# --cpu adds CPU milliseconds per frame of each (all threads; see cpu_ms_per_frame).
# Then, unless --no-ids, it renders both with --shade id --out-id and counts differing pixels.
# --memory: peak resident memory (getrusage ru_maxrss of the process) of one frame at 1080p, 4K
# and 8K for each renderer on the first workload, and the same minus a 64x64 frame (what the
# frame itself costs; with a big mesh the OBJ loading peak can hide it: use sphere-20k).
# --threads "" skips the timing.
# Results go to stdout and, as JSON lines, to bench/results/<stamp>/peer.jsonl with machine.txt
# (or to $TESSERA_RESULTS/peer.jsonl).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${TESSERA_BUILD:-$root/build}/bin
workdir=${TESSERA_WORKLOADS:-${TESSERA_BUILD:-$root/build}/workloads}
workloads=() size=1920x1080 threads="1 2" repeat=10 rounds=3 memory=0 cpu=0 ids=1 shade_override=
while (($#)); do
  case $1 in
    --workload) workloads+=("$2"); shift 2 ;;
    --size) size=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --shade) shade_override=$2; shift 2 ;;
    --memory) memory=1; shift ;;
    --cpu) cpu=1; shift ;;
    --no-ids) ids=0; shift ;;
    -h|--help) sed -n '2,31p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "peer: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
((${#workloads[@]})) || workloads=(sphere-1m)

peer=$bin/tessera-llvmpipe
[[ -x $peer ]] || { echo "peer: $peer was not built (install libosmesa6-dev and rebuild)" >&2; exit 1; }
have_tessera=0
grep -q "^ *raster " <<<"$("$bin/tessera" --help 2>/dev/null)" && have_tessera=1
((have_tessera)) || echo "peer: 'tessera raster' is not in this build; timing llvmpipe alone"

# TESSERA_RESULTS=DIR adds to an existing run (scripts/bench.sh does, for one report).
out=${TESSERA_RESULTS:-$root/bench/results/$(date -u +%Y-%m-%dT%H%M%SZ)}
mkdir -p "$out" "$workdir"
[[ -s $out/machine.txt ]] ||
  { "$bin/tessera" info; echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"; echo "command: scripts/peer.sh $*"; } > "$out/machine.txt"
jsonl=$out/peer.jsonl

# workload NAME -> sets mesh, camera, shade, cull (generating the files if needed). The
# sphere and fill-rate meshes are bench_raster's own (`tessera testmesh`), so the peer ratios
# and the Google Benchmark figures measure the same triangles.
workload() {
  local name=$1 gen=() testmesh=()
  case $name in
    sphere-1m)  testmesh=(--kind sphere --count 1048576); shade=phong; cull=back ;;
    sphere-20k) testmesh=(--kind sphere --count 20000); shade=phong; cull=back ;;
    sphere-grid-10k)  testmesh=(--kind spheres --count 10000); shade=phong; cull=none ;;
    sphere-grid-100k) testmesh=(--kind spheres --count 100000); shade=phong; cull=none ;;
    sphere-grid-1m)   testmesh=(--kind spheres --count 1000000); shade=phong; cull=none ;;
    sphere-grid-4m)   testmesh=(--kind spheres --count 4000000); shade=phong; cull=none ;;
    spheres-1m) gen=(spheres --triangles 1048576); shade=phong; cull=back ;;
    grid-10px)  gen=(grid --triangles 1048576 --pixels 10 --size "$size"); shade=id; cull=none ;;
    fill-10px)  testmesh=(--kind fillrate --count 1048576 --leg 10 --size "$size"); shade=id; cull=none ;;
    fill-25px)  testmesh=(--kind fillrate --count 1048576 --leg 25 --size "$size"); shade=id; cull=none ;;
    fill-50px)  testmesh=(--kind fillrate --count 524288 --leg 50 --size "$size"); shade=id; cull=none ;;
    fill-100px) testmesh=(--kind fillrate --count 262144 --leg 100 --size "$size"); shade=id; cull=none ;;
    fill-250px) testmesh=(--kind fillrate --count 65536 --leg 250 --size "$size"); shade=id; cull=none ;;
    *) echo "peer: unknown workload '$name'" >&2; exit 2 ;;
  esac
  local prefix=$workdir/$name
  [[ $name == sphere* ]] || prefix=$workdir/$name-$size
  if [[ ! -s $prefix.obj || ! -s $prefix.cam ]]; then
    if ((${#testmesh[@]})); then
      "$bin/tessera" testmesh "${testmesh[@]}" --out "$prefix.obj" --camera-out "$prefix.cam" >&2
    else
      python3 "$root/scripts/gen-workload.py" "${gen[@]}" --out "$prefix" >&2
    fi
  fi
  mesh=$prefix.obj camera=$prefix.cam
  [[ -z $shade_override ]] || shade=$shade_override
}

# median_ms RENDERER ARGS... -> the median of the renderer's `frame_ms median=X ...` line
median_ms() {
  "$@" | sed -n 's/^frame_ms median=\([0-9.]*\).*/\1/p'
}

# median VALUES... -> their median (the mean of the middle two for an even count)
median() {
  printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { printf "%.3f", NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# cpu_s COMMAND... -> user + system CPU seconds the command used (all its threads)
cpu_s() {
  python3 -c 'import resource, subprocess, sys
r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL)
u = resource.getrusage(resource.RUSAGE_CHILDREN)
sys.exit(r.returncode) if r.returncode else print(u.ru_utime + u.ru_stime)' "$@"
}

# cpu_ms_per_frame RENDERER ARGS... -> CPU milliseconds per frame, from the difference between
# 1 and 1 + repeat frames (loading and start-up cancel out). Unlike wall time it barely depends
# on other processes sharing the cores, so on a busy machine it is the steadier measure of work.
cpu_ms_per_frame() {
  local one many
  one=$(cpu_s "$@" --repeat 1) many=$(cpu_s "$@" --repeat $((1 + repeat)))
  awk -v a="$one" -v b="$many" -v k="$repeat" 'BEGIN { printf "%.1f", (b - a) * 1000 / k }'
}

# peak_kb COMMAND... -> peak resident memory of the command in KiB (Linux ru_maxrss)
peak_kb() {
  python3 -c 'import resource, subprocess, sys
r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL)
sys.exit(r.returncode) if r.returncode else print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)' "$@"
}

printf '%-12s %-10s %7s %12s %12s %9s\n' workload size threads tessera_ms llvmpipe_ms ratio
for name in "${workloads[@]}"; do
  workload "$name"
  common=(--mesh "$mesh" --camera "$camera" --size "$size" --shade "$shade" --cull "$cull")
  for t in $threads; do
    # Alternate the renderers for --rounds rounds and take the median of each one's medians,
    # so that load from other processes (drifting over seconds) falls on both alike.
    lps=() tss=()
    for ((round = 0; round < rounds; round++)); do
      lps+=("$(median_ms "$peer" "${common[@]}" --threads "$t" --repeat "$repeat")")
      ((have_tessera)) && tss+=("$(median_ms "$bin/tessera" raster "${common[@]}" --threads "$t" --repeat "$repeat")")
    done
    lp=$(median "${lps[@]}") ts=nan ratio=nan
    if ((have_tessera)); then
      ts=$(median "${tss[@]}")
      ratio=$(awk -v a="$lp" -v b="$ts" 'BEGIN { printf "%.2f", a / b }')
    fi
    printf '%-12s %-10s %7s %12s %12s %9s\n' "$name" "$size" "$t" "$ts" "$lp" "$ratio"
    if ((cpu)); then
      lc=$(cpu_ms_per_frame "$peer" "${common[@]}" --threads "$t") tc=nan
      ((have_tessera)) && tc=$(cpu_ms_per_frame "$bin/tessera" raster "${common[@]}" --threads "$t")
      printf '%-12s %-10s %7s %12s %12s %9s  (CPU ms per frame)\n' "" "" "" "$tc" "$lc" \
        "$(awk -v a="$lc" -v b="$tc" 'BEGIN { if (b + 0 > 0) printf "%.2f", a / b; else print "nan" }')"
      printf '{"kind":"cpu","workload":"%s","size":"%s","shade":"%s","threads":%s,"tessera_cpu_ms":%s,"llvmpipe_cpu_ms":%s}\n' \
        "$name" "$size" "$shade" "$t" "${tc/nan/null}" "$lc" >> "$jsonl"
    fi
    printf '{"kind":"time","workload":"%s","size":"%s","shade":"%s","threads":%s,"repeat":%s,"rounds":%s,"tessera_ms":%s,"llvmpipe_ms":%s}\n' \
      "$name" "$size" "$shade" "$t" "$repeat" "$rounds" "${ts/nan/null}" "$lp" >> "$jsonl"
  done
  if ((ids && have_tessera)); then
    idargs=(--mesh "$mesh" --camera "$camera" --size "$size" --shade id --cull "$cull")
    "$bin/tessera" raster "${idargs[@]}" --out-id "$out/$name.tessera.id"
    "$peer" "${idargs[@]}" --out-id "$out/$name.llvmpipe.id"
    line=$(python3 "$root/scripts/compare-ids.py" "$out/$name.tessera.id" "$out/$name.llvmpipe.id")
    echo "$name: $line (A = tessera, B = llvmpipe)"
    differ=$(sed -n 's/.* \([0-9]*\) differ.*/\1/p' <<<"$line")
    printf '{"kind":"ids","workload":"%s","size":"%s","differing_pixels":%s}\n' "$name" "$size" "$differ" >> "$jsonl"
    rm -f "$out/$name.tessera.id" "$out/$name.llvmpipe.id"
  fi
done

if ((memory)); then
  name=${workloads[0]}
  echo
  printf '%-10s %-10s %14s %16s\n' renderer size peak_rss_MiB frame_MiB_vs_64x64
  renderers=(llvmpipe)
  ((have_tessera)) && renderers=(tessera llvmpipe)
  workload "$name"  # the same mesh at every size: only the frame's own memory changes
  for r in "${renderers[@]}"; do
    base=
    for s in 64x64 1920x1080 3840x2160 7680x4320; do
      args=(--mesh "$mesh" --camera "$camera" --size "$s" --shade "$shade" --cull "$cull" --threads 2)
      if [[ $r == tessera ]]; then kb=$(peak_kb "$bin/tessera" raster "${args[@]}")
      else kb=$(peak_kb "$peer" "${args[@]}"); fi
      [[ -n $base ]] || base=$kb
      awk -v r="$r" -v s="$s" -v kb="$kb" -v base="$base" \
        'BEGIN { printf "%-10s %-10s %14.1f %16.1f\n", r, s, kb / 1024, (kb - base) / 1024 }'
      printf '{"kind":"memory","renderer":"%s","workload":"%s","size":"%s","peak_rss_kib":%s,"frame_kib":%s}\n' \
        "$r" "$name" "$s" "$kb" "$((kb - base))" >> "$jsonl"
    done
  done
fi
echo "peer: results in $out"
