#!/bin/bash
# Render an animation on a Slurm cluster as a job array: task I of N renders shard I/N
# (frames I, I+N, I+2N, ... of the range), every task writing into one shared folder.
#   sbatch --array=0-63 scripts/slurm-render.sh        # 64 tasks
#   sbatch --array=0-63%16 scripts/slurm-render.sh     # at most 16 running at once
# --resume skips frames already complete (a resubmitted array finishes only what is missing);
# --claim makes a frame one task's alone even if tasks overlap (a resubmission while the first
# array still runs, or extra tasks started by hand), and with --resume takes over the claims of
# tasks that died on the same node; --claim-timeout takes over claims left by dead nodes.
# Scenes with growing skins read and write simulation checkpoints under OUT/.tessera-sim.
#SBATCH --job-name=tessera-render
#SBATCH --cpus-per-task=16
#SBATCH --time=04:00:00
#SBATCH --output=tessera-%A_%a.log
set -euo pipefail
SCENE=${SCENE:-snakes}
SIZE=${SIZE:-3840x2160}
FRAMES=${FRAMES:-1:1440}
OUT=${OUT:-$PWD/render/$SCENE/frame_####.png}
TASKS=${SLURM_ARRAY_TASK_COUNT:-1}
TASK=$(( ${SLURM_ARRAY_TASK_ID:-0} - ${SLURM_ARRAY_TASK_MIN:-0} ))
exec tessera render --scene "$SCENE" --size "$SIZE" --frames "$FRAMES" --out "$OUT" \
  --shard "$TASK/$TASKS" --threads "${SLURM_CPUS_PER_TASK:-0}" \
  --resume --claim --claim-timeout 7200 --quiet
