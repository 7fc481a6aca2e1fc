#!/usr/bin/env bash
# `make demo`: renders three seconds of the default `snakes` scene into out/ (PNG frames at
# 854x480, 24 fps, shadow rays) and, when ffmpeg is installed, encodes out/snakes.mp4.
# Environment: DEMO_SIZE, DEMO_FRAMES override the size and the frame range (A:B).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${TESSERA_BUILD:-$root/build}/bin
size=${DEMO_SIZE:-854x480}
frames=${DEMO_FRAMES:-1:72}
out=$root/out
mkdir -p "$out"
"$bin/tessera" render --scene snakes --size "$size" --frames "$frames" --fps 24 \
  --out "$out/snakes_####.png" --stats
first=${frames%%:*}
if command -v ffmpeg >/dev/null 2>&1; then
  ffmpeg -loglevel error -y -framerate 24 -start_number "$first" -i "$out/snakes_%04d.png" \
    -c:v libx264 -pix_fmt yuv420p -crf 18 "$out/snakes.mp4"
  echo "demo: $out/snakes.mp4 and the frames in $out/"
else
  echo "demo: frames in $out/ (install ffmpeg for an MP4: apt-get install ffmpeg)"
fi
