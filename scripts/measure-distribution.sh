#!/usr/bin/env bash
# The cost of distribution on one machine: the same frames rendered by 1 rank x 2 threads,
# 2 MPI ranks x 1 thread (--distribute frames and tiles) and 1 rank x 1 thread, interleaved
# over several rounds so that load from other processes falls on every configuration alike.
# Prints per round: wall seconds (job start to end, scene build included), the frame loop's
# seconds as rank 0 reports it, and CPU seconds (user + system, every rank). Medians last.
#   scripts/measure-distribution.sh build/bin/tessera [SIZE] [FRAMES] [ROUNDS]
set -u
tessera=$1
size=${2:-640x360}
frames=${3:-1:12}
rounds=${4:-5}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mpirun=(mpirun --oversubscribe --allow-run-as-root -n 2)
common=(render --scene snakes --size "$size" --frames "$frames")
declare -A cmd
cmd[1x2]="$tessera ${common[*]} --threads 2"
cmd[2x1_frames]="${mpirun[*]} $tessera ${common[*]} --threads 1 --distribute frames"
cmd[2x1_tiles]="${mpirun[*]} $tessera ${common[*]} --threads 1 --distribute tiles"
cmd[1x1]="$tessera ${common[*]} --threads 1"
order=(1x2 2x1_frames 2x1_tiles 1x1)
for ((r = 1; r <= rounds; r++)); do
  for c in "${order[@]}"; do
    rm -rf "$dir/out"
    /usr/bin/time -f "%e %U %S" -o "$dir/time" ${cmd[$c]} --out "$dir/out/s_####.png" 2>"$dir/log" >/dev/null ||
      { echo "$c failed: $(tail -3 "$dir/log")"; exit 1; }
    read -r wall user sys <"$dir/time"
    loop=$(sed -n 's/^rendered [0-9]* frame(s) in \([0-9.]*\) s$/\1/p' "$dir/log" | sort -n | tail -1)
    printf '%s round %d wall %.2f loop %.2f cpu %.2f\n' "$c" "$r" "$wall" "$loop" "$(echo "$user + $sys" | bc)"
  done
done | tee "$dir/all"
echo "medians (seconds):"
for c in "${order[@]}"; do
  med() { grep "^$c " "$dir/all" | awk -v k="$1" '{for(i=1;i<=NF;i++) if($i==k) print $(i+1)}' | sort -n |
          awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
  printf '  %-11s wall %6s  loop %6s  cpu %6s\n' "$c" "$(med wall)" "$(med loop)" "$(med cpu)"
done
