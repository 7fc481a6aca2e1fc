#!/usr/bin/env bash
# The benchmark tooling on small hand-written Google Benchmark results: bench-compare.py takes
# the median aggregate (or the median of plain repetitions) and prints new/old ratios;
# bench-report.py writes the tables (and the plots when gnuplot is installed).
set -u
scripts=$(cd "$(dirname "$0")/../scripts" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
command -v python3 >/dev/null || { echo "SKIPPED: python3 is not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/old" "$tmp/new"

row() {  # name run_type aggregate real_ms
  printf '{"name":"%s%s","run_name":"%s","run_type":"%s","aggregate_name":"%s","real_time":%s,"cpu_time":%s,"time_unit":"ms","iterations":1}' \
    "$1" "${3:+_$3}" "$1" "$2" "$3" "$4" "$4"
}
# old: three plain repetitions (median 20 ms) per benchmark; new: median aggregates
cat > "$tmp/old/bench_x.json" <<JSON
{"context":{"date":"2026-01-01","host_name":"box"},"benchmarks":[
$(row "BM_Frame/ktris:10/threads:1/real_time" iteration "" 30), $(row "BM_Frame/ktris:10/threads:1/real_time" iteration "" 20),
$(row "BM_Frame/ktris:10/threads:1/real_time" iteration "" 10),
$(row "BM_Frame/ktris:100/threads:1/real_time" iteration "" 200),
$(row "BM_Frame/ktris:10/threads:2/real_time" iteration "" 12), $(row "BM_Gone" iteration "" 1)]}
JSON
cat > "$tmp/new/bench_x.json" <<JSON
{"context":{"date":"2026-01-02","host_name":"box"},"benchmarks":[
$(row "BM_Frame/ktris:10/threads:1/real_time" aggregate mean 99), $(row "BM_Frame/ktris:10/threads:1/real_time" aggregate median 5),
$(row "BM_Frame/ktris:100/threads:1/real_time" aggregate median 100),
$(row "BM_Frame/ktris:10/threads:2/real_time" aggregate median 3)]}
JSON
out=$(python3 "$scripts/bench-compare.py" "$tmp/old" "$tmp/new/bench_x.json") || fail "bench-compare exited $?: $out"
grep -q '^| BM_Frame/ktris:10/threads:1/real_time | 20 ms | 5 ms | 0.25 |$' <<<"$out" || fail "median/ratio: $out"
grep -q '^| BM_Frame/ktris:100/threads:1/real_time | 200 ms | 100 ms | 0.50 |$' <<<"$out" || fail "ratio: $out"
grep -q '^| BM_Gone | 1 ms | - | - |$' <<<"$out" || fail "one-sided benchmark: $out"

printf 'cpu: Test CPU\ndate: 2026-01-02 10:00 UTC\ncommand: scripts/bench.sh\n' > "$tmp/new/machine.txt"
echo '{"kind":"time","workload":"w","size":"8x8","shade":"id","threads":1,"repeat":1,"rounds":1,"tessera_ms":2,"llvmpipe_ms":10}' > "$tmp/new/peer.jsonl"
python3 "$scripts/bench-report.py" "$tmp/new" >/dev/null || fail "bench-report exited $?"
report=$tmp/new/report.md
grep -q "Machine: Test CPU" "$report" || fail "report does not name the machine"
grep -q '| BM_Frame/ktris:10/threads:2/real_time | 3 ms |' "$report" || fail "report table: $(cat "$report")"
grep -q '| BM_Frame (ktris=10) | 2 | 1.67 | 0.83 |' "$report" || fail "thread scaling: $(cat "$report")"
grep -q '| w | 8x8 | id | 1 | 2 | 10 | 5.00 |' "$report" || fail "peer table: $(cat "$report")"
if command -v gnuplot >/dev/null; then
  [[ -s $tmp/new/plots/time_vs_triangles.png && -s $tmp/new/plots/speedup_vs_threads.png ]] ||
    fail "plots missing: $(ls "$tmp/new/plots" 2>&1)"
fi
echo "cli_bench_scripts: ok"
