#!/usr/bin/env bash
# OpenImageIO is loaded only when an image needs it (raster/io/image_codec.h): a procedural
# scene rendered to PNG (tessera's own encoder) never loads it, an EXR does, and a codec module
# that cannot be loaded is one clear error, with nothing written.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

loaded() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -c 'file=libOpenImageIO\.so' || true; }

n=$(loaded "$tessera" render --scene flag --size 64x36 --frames 1:1 --quiet --out "$dir/f_####.png")
[ -s "$dir/f_0001.png" ] || fail "no PNG frame written"
[ "$n" -eq 0 ] || fail "a PNG frame of a procedural scene loaded OpenImageIO"

n=$(loaded "$tessera" render --scene flag --size 64x36 --frames 1:1 --quiet --out "$dir/f_####.exr")
[ -s "$dir/f_0001.exr" ] || fail "no EXR frame written"
[ "$n" -gt 0 ] || fail "an EXR frame was written without the image codec"

err=$(TESSERA_IMAGE_CODEC=$dir/missing.so "$tessera" render --scene flag --size 64x36 --frames 1:1 --quiet \
      --out "$dir/g_####.exr" 2>&1 >/dev/null); code=$?
[ $code -eq 1 ] || fail "a missing codec module exited $code, expected 1: $err"
grep -q "cannot load the image codec.*missing.so: no such file" <<<"$err" || fail "message: $err"
[ -z "$(ls "$dir" | grep '^g_')" ] || fail "a file was left behind: $(ls "$dir")"

echo "cli_image_codec: ok"
