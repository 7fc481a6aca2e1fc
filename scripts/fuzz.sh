#!/usr/bin/env bash
# Runs every libFuzzer target of build-fuzz/bin (make fuzz builds them) for SECONDS each
# (default 15: about a minute and a quarter for the five targets), starting from the committed seeds in
# tests/fuzz/corpus/<target>/. New interesting inputs go to a scratch corpus, never into the
# repository; a crash or broken property stops with the input saved under
# build-fuzz/findings/<target>/ — copy it into tests/fuzz/corpus/<target>/ once fixed, so
# fuzz_regression_test replays it in every build.
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 300 fuzz_obj
# FUZZ_SEED=N fixes libFuzzer's random seed (0, the default, draws one): with a fixed seed a
# run replays the same input sequence, so CI explores a known prefix that was checked before
# landing instead of failing at random on a new finding (findings come from longer runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-15}
shift || true
bin=$root/build-fuzz/bin
targets=("$@")
if ((${#targets[@]} == 0)); then
  for f in "$root"/tests/fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# ASan's leak check at exit is on; halt at the first UBSan report so it is saved as a crash.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
status=0
for target in "${targets[@]}"; do
  [[ -x $bin/$target ]] || { echo "fuzz: $bin/$target missing (run: make fuzz)" >&2; exit 1; }
  name=${target#fuzz_}
  findings=$root/build-fuzz/findings/$name
  mkdir -p "$findings" "$scratch/$name"
  echo "== $target for ${seconds}s"
  # -rss_limit_mb: a loader asking for gigabytes on a tiny input is a finding, not a pass.
  if ! "$bin/$target" -seed="${FUZZ_SEED:-0}" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -max_len=8192 \
       -print_final_stats=1 -artifact_prefix="$findings/" "$scratch/$name" "$root/tests/fuzz/corpus/$name" \
       2> "$scratch/$name.log"; then
    tail -40 "$scratch/$name.log" >&2
    echo "fuzz: $target found a problem; the input is in $findings/" >&2
    status=1
  else
    grep -E '^stat::number_of_executed_units|^Done' "$scratch/$name.log" || true
  fi
done
exit $status
