#!/usr/bin/env bash
# Runs every Google Benchmark suite (build/bin/bench_*) and writes one JSON file per suite
# under bench/results/<UTC date and time>/, next to a machine.txt that says where, when and with
# which arguments it ran (scripts/bench-report.py turns the directory into tables and plots).
# Extra arguments go to every suite, e.g.: scripts/bench.sh --benchmark_filter=Fill
# When tessera-llvmpipe was built, the llvmpipe peer comparison runs last, into the same folder.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${TESSERA_BUILD:-$root/build}/bin
stamp=$(date -u +%Y-%m-%dT%H%M%SZ)
out=$root/bench/results/$stamp
mkdir -p "$out"
{ "$bin/tessera" info; echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"; echo "command: scripts/bench.sh $*"; } > "$out/machine.txt"
shopt -s nullglob
suites=("$bin"/bench_*)
((${#suites[@]})) || { echo "bench: no suites in $bin (build first: make build)" >&2; exit 1; }
for suite in "${suites[@]}"; do
  name=$(basename "$suite")
  echo "== $name"
  "$suite" --benchmark_out="$out/$name.json" --benchmark_out_format=json "$@"
done
# The peer in the same run: tessera raster against Mesa llvmpipe on bench_raster's 1M-triangle
# sphere (Phong) and 10 px fill-rate meshes (TESSERA_PEER=0 skips it; see scripts/peer.sh).
if [[ ${TESSERA_PEER:-1} != 0 && -x $bin/tessera-llvmpipe ]]; then
  echo "== peer: tessera raster vs llvmpipe"
  TESSERA_RESULTS=$out bash "$root/scripts/peer.sh" --workload sphere-1m --workload fill-10px --repeat 5 --cpu
fi
echo "bench: results in $out"
