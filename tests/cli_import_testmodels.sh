#!/usr/bin/env bash
# Third-party models (Debian's assimp-testmodels) through `tessera raster`: a selection of good
# ones render with their materials in both renderers; the package's bad variants (wrong JSON
# types, broken references, crash reproductions, empty files, a header claiming 10^11
# vertices) each end in one error line naming the file, exit 1, never a crash.
set -u
tessera=$1
fail() { echo "FAIL: $*"; exit 1; }
models=/usr/share/assimp/models
[ -d "$models" ] || { echo "SKIPPED: assimp-testmodels is not installed ($models)"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/shell/expect_error.sh"

# One or two of each format; the ray caster on a few (each run costs the command's start-up,
# which the sanitizer builds multiply).
good=(OBJ/spider.obj PLY/Wuson.ply PLY/cube_binary.ply STL/Spider_binary.stl
      glTF2/BoxTextured-glTF/BoxTextured.gltf glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf
      glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb)
raytraced=" OBJ/spider.obj PLY/Wuson.ply glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb "
for model in "${good[@]}"; do
    [ -f "$models/$model" ] || fail "$model is not in $models"
    renderers=raster
    [[ $raytraced == *" $model "* ]] && renderers="raster raytrace"
    for renderer in $renderers; do
        "$tessera" raster --mesh "$models/$model" --size 48x32 --shade material --renderer $renderer \
            --out-color "$dir/out.png" 2>"$dir/err" || fail "$model ($renderer) exited $?: $(cat "$dir/err")"
        [ -s "$dir/out.png" ] || fail "$model: nothing written"
        ! grep -v -e '^tessera: warning: ' -e '^tessera: camera (framed): ' "$dir/err" | grep -q . ||
            fail "$model: unexpected output: $(cat "$dir/err")"
    done
done

bad=(glTF2/wrongTypes/badArray.gltf glTF2/wrongTypes/badUint.gltf
     glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf glTF2/MissingBin/BoxTextured.gltf
     glTF2/RecursiveNodes/RecursiveNodes.gltf glTF2/TestNoRootNode/NoScene.gltf
     glTF2/issue_3269/texcoord_crash.gltf OBJ/testline.obj PLY/points.ply
     invalid/OutOfMemory.off invalid/empty.obj invalid/malformed.obj)
for model in "${bad[@]}"; do
    [ -f "$models/$model" ] || fail "$model is not in $models"
    expect_error 1 raster --mesh "$models/$model" --shade material --size 16x16
    grep -q "cannot read '$models/$model': " <<<"$err" || fail "$model: the error does not name the file: $err"
done
echo "cli_import_testmodels: ok"
