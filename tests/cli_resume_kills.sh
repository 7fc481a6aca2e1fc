#!/usr/bin/env bash
# --resume completes a frame set whatever happened to it (issue 19). Runs are killed at random
# moments of their frame loop by SIGKILL, SIGTERM, SIGINT or SIGHUP; the non-KILL ones must exit
# 128 + N and leave no temporary. Then frames on disk are damaged in every way a crash or a bad
# copy leaves them (cut to the header, to half, one byte short, bytes overwritten in the middle
# and near the end, empty), and a last --resume must complete the set equal byte for byte to an
# uninterrupted run, in PNG and EXR (image_completeness_test checks TIFF and every cut point).
# TRIALS (default 20: about 13 s on a loaded 2-core machine) sets the number of killed runs.
set -u
tessera=$1
trials=${TRIALS:-20}
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

cat >"$dir/spin.json" <<'JSON'
{"animation": {"fps": 24, "frames": [1, 40]},
 "camera": {"eye": [0, 1.5, 4], "lookat": [0, 0, 0], "orbit": 0.5},
 "lights": [{"direction": [0.3, 1, 0.5], "La": [0.1, 0.1, 0.1], "Le": [1, 1, 1]}],
 "materials": {"m": {"kd": [0.9, 0.5, 0.2], "ks": [0.4, 0.4, 0.4], "shine": 30}},
 "objects": [{"type": "torus", "material": "m", "major": 1, "minor": 0.35, "tessellation": [64, 32],
              "spin": {"axis": [1, 1, 0], "speed": 40}}]}
JSON
frames=40
args=(render --scene "$dir/spin.json" --size 40x30 --frames 1:$frames --threads 2 --quiet)

RANDOM=$$
trial=0
for ext in png exr; do
    "$tessera" "${args[@]}" --out "$dir/ref_$ext/f_####.$ext" || fail "reference $ext exited $?"
    out=$dir/run_$ext
    mkdir -p "$out"
    limit=$trials
    [ "$ext" = png ] && limit=$((trials / 2))  # half of the trials on each format
    while [ $trial -lt $limit ]; do
        trial=$((trial + 1))
        signal=$(printf 'KILL\nTERM\nINT\nHUP\n' | sed -n "$((RANDOM % 4 + 1))p")
        "$tessera" "${args[@]}" --resume --out "$out/f_####.$ext" 2>>"$dir/log" &
        pid=$!
        # Into the frame loop (a new frame appears, or the run ends), then a random moment of it.
        count=$(ls "$out" | wc -l)
        while kill -0 $pid 2>/dev/null && [ "$(ls "$out" | wc -l)" -eq "$count" ]; do sleep 0.01; done
        sleep "0.$((RANDOM % 3))$((RANDOM % 10))"
        kill -s "$signal" $pid 2>/dev/null
        wait $pid 2>/dev/null
        code=$?
        case $signal:$code in
            *:0 | KILL:137 | TERM:143 | INT:130 | HUP:129) ;;
            *) fail "trial $trial: SIG$signal gave exit $code: $(tail -2 "$dir/log")" ;;
        esac
        if [ "$signal" != KILL ]; then
            [ -z "$(ls -A "$out" | grep '^\.')" ] || fail "trial $trial: SIG$signal left $(ls -A "$out" | grep '^\.')"
        fi
    done
    # Every kind of damage, each on a frame that is there (put back from the reference if the
    # killed runs did not get to it).
    for f in 1 2 3 4 5 6; do
        name=$(printf 'f_%04d.%s' "$f" "$ext")
        [ -f "$out/$name" ] || cp "$dir/ref_$ext/$name" "$out/$name"
    done
    size=$(stat -c %s "$out/f_0001.$ext")
    truncate -s 64 "$out/f_0001.$ext"                                   # just the header
    truncate -s $(($(stat -c %s "$out/f_0002.$ext") / 2)) "$out/f_0002.$ext"  # half
    truncate -s $(($(stat -c %s "$out/f_0003.$ext") - 1)) "$out/f_0003.$ext"  # one byte short
    size=$(stat -c %s "$out/f_0004.$ext")
    printf 'XXXX' | dd of="$out/f_0004.$ext" bs=1 seek=$((size / 2)) conv=notrunc status=none
    size=$(stat -c %s "$out/f_0005.$ext")
    printf 'U\252U\252' | dd of="$out/f_0005.$ext" bs=1 seek=$((size - 20)) conv=notrunc status=none
    : >"$out/f_0006.$ext"                                                # empty
    "$tessera" "${args[@]}" --resume --out "$out/f_####.$ext" 2>>"$dir/log" || fail "final --resume ($ext) exited $?"
    for f in $(seq 1 $frames); do
        name=$(printf 'f_%04d.%s' "$f" "$ext")
        cmp -s "$dir/ref_$ext/$name" "$out/$name" || fail "$name differs from the uninterrupted render after resume"
    done
    [ "$(ls -A "$out" | wc -l)" -eq $frames ] || fail "$ext: extra files: $(ls -A "$out" | grep -v '^f_')"
done
echo "cli_resume_kills: $trial interrupted runs, ok"
