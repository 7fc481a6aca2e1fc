#!/usr/bin/env bash
# `mpirun -n 2 tessera render --distribute frames|tiles` writes exactly the bytes of a
# single-process render; a rank that fails makes the job exit non-zero naming the rank and
# the frame, and --resume completes the set with every frame complete and right.
# Registered only in an MPI build: $1 = tessera, $2 = mpirun (mpiexec).
set -u
tessera=$1
mpirun=${2:-mpirun}
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mpi() { "$mpirun" --oversubscribe --allow-run-as-root -n 2 "$tessera" render --quiet --threads 1 "$@"; }
export OMPI_MCA_rmaps_base_oversubscribe=1
# In the sanitize build: Open MPI's runtime and its dlopen'ed components leak at MPI_Finalize
# (frames in libmpi, or in components already unloaded, so no suppression can name them).
# tessera's own code on these paths is leak-checked by the single-process render tests.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"

# toon with shadow rays: every stage of a frame, without the seconds of reaction-diffusion
# synthesis that snakes spends in each of the three processes before its first frame.
args=(--scene toon --shadows rays --size 160x300 --frames 1:6)  # tall: 3 bands of 128 rows over 2 ranks
"$tessera" render --quiet "${args[@]}" --out "$dir/ref/s_####.png" || fail "single-process run exited $?"

mpi "${args[@]}" --distribute frames --out "$dir/frames/s_####.png" || fail "--distribute frames exited $?"
mpi "${args[@]}" --distribute tiles --out "$dir/tiles/s_####.png" || fail "--distribute tiles exited $?"
for m in frames tiles; do
  [ "$(ls "$dir/$m")" = "$(ls "$dir/ref")" ] || fail "$m wrote $(ls "$dir/$m")"
  for f in "$dir"/ref/*.png; do cmp -s "$f" "$dir/$m/$(basename "$f")" || fail "$m: $(basename "$f") differs"; done
done

# Frames beyond one pass: bands streamed into the file; in tiles mode band b is rendered by
# rank b % 2 and rank 0 writes them all, in order.
big=(--scene flag --size 64x8320 --frames 1:2)  # two bands: 8192 + 128 rows
"$tessera" render --quiet "${big[@]}" --out "$dir/bigref/b_####.png" || fail "single-process banded run exited $?"
for m in frames tiles; do
  mpi "${big[@]}" --distribute $m --out "$dir/big$m/b_####.png" || fail "banded --distribute $m exited $?"
  for f in "$dir"/bigref/*.png; do cmp -s "$f" "$dir/big$m/$(basename "$f")" || fail "banded $m: $(basename "$f") differs"; done
done
mkdir -p "$dir/bigfail/b_0001.png"
err=$(mpi "${big[@]}" --distribute tiles --out "$dir/bigfail/b_####.png" 2>&1) && fail "banded tiles: a failed write did not fail the job"
grep -q "rank 0 failed on frame 1: " <<<"$err" || fail "banded tiles: error does not name rank 0 and frame 1: $err"
[ "$(ls -A "$dir/bigfail")" = "b_0001.png" ] || fail "banded tiles failure left: $(ls -A "$dir/bigfail")"

# A growing skin (state carried from frame to frame) over ranks that get frames on demand.
scene=$(dirname "$0")/data/growing_skin.json
"$tessera" render --quiet --scene "$scene" --frames 0:9 --out "$dir/gref/g_####.png" || fail "growing reference"
mpi --scene "$scene" --frames 0:9 --distribute frames --out "$dir/grow/g_####.png" || fail "growing frames exited $?"
for f in "$dir"/gref/*.png; do cmp -s "$f" "$dir/grow/$(basename "$f")" || fail "growing: $(basename "$f") differs"; done

# Failure: frame 4's file cannot be written (a directory is in the way).
mkdir -p "$dir/fail/s_0004.png"
err=$(mpi "${args[@]}" --distribute frames --out "$dir/fail/s_####.png" 2>&1) && fail "a failing rank did not fail the job"
grep -q "rank [01] failed on frame 4: " <<<"$err" || fail "error does not name the rank and frame 4: $err"
rmdir "$dir/fail/s_0004.png"
[ -z "$(ls -A "$dir/fail" | grep '^\.')" ] || fail "temporaries or claims left: $(ls -A "$dir/fail" | grep '^\.')"
mpi "${args[@]}" --distribute frames --resume --out "$dir/fail/s_####.png" || fail "--resume after the failure exited $?"
for f in "$dir"/ref/*.png; do cmp -s "$f" "$dir/fail/$(basename "$f")" || fail "after resume: $(basename "$f") differs"; done
# Tiles: the failure reaches every rank (no rank waits for a band that never comes).
mkdir -p "$dir/tfail/s_0002.png"
err=$(mpi "${args[@]}" --distribute tiles --out "$dir/tfail/s_####.png" 2>&1) && fail "tiles: a failed write did not fail the job"
grep -q "rank 0 failed on frame 2: " <<<"$err" || fail "tiles: error does not name rank 0 and frame 2: $err"
echo "mpi_render: ok"
