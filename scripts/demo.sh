#!/usr/bin/env bash
# `make demo`: renders three seconds of the default `snakes` scene into out/ (PNG frames at
# 854x480, 24 fps, shadow rays) and encodes them into out/snakes.mp4 with ffmpeg (installed by
# scripts/packages-demo.txt), then prints where both are.
# Environment: DEMO_SIZE, DEMO_FRAMES override the size and the frame range (A:B).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${TESSERA_BUILD:-$root/build}/bin
size=${DEMO_SIZE:-854x480}
frames=${DEMO_FRAMES:-1:72}
out=$root/out
mkdir -p "$out"
command -v ffmpeg >/dev/null 2>&1 || { echo "demo: ffmpeg is missing (make demo installs it)" >&2; exit 1; }
"$bin/tessera" render --scene snakes --size "$size" --frames "$frames" --fps 24 \
  --out "$out/snakes_####.png" --stats
first=${frames%%:*}
ffmpeg -loglevel error -y -framerate 24 -start_number "$first" -i "$out/snakes_%04d.png" \
  -c:v libx264 -pix_fmt yuv420p -crf 18 "$out/snakes.mp4"
echo "demo: video  $out/snakes.mp4"
echo "demo: frames $out/snakes_####.png (frames $frames, $size, 24 fps)"
