#!/usr/bin/env bash
# The layers, three ways, must tell one story (README.md "Layers"):
# 1. the table in README.md between the "layers:begin" and "layers:end" markers (each layer,
#    its folder, the layers it may include directly);
# 2. the include tree the build made for each layer (cmake/TesseraLayers.cmake: links to the
#    folders the layer may include, transitively);
# 3. the compiler: from a layer's include tree, a header of every folder in the tree can be
#    included and one of any other folder cannot.
# usage: layering.sh LAYER_ROOT SOURCE_DIR CXX
set -u
root=$(cd "$1" && pwd) src=$(cd "$2" && pwd) cxx=$3
fail() { echo "FAIL: $*"; exit 1; }
[ -d "$root" ] || fail "no include trees under $root"

# 1. The README's table: "layer  folder  uses...".
declare -A folder uses
table=$(sed -n '/layers:begin/,/layers:end/p' "$src/README.md" | grep -v 'layers:\|^```\|^layer ')
[ -n "$table" ] || fail "README.md has no layer table between layers:begin and layers:end"
while read -r layer dir rest; do
    [ -n "$layer" ] || continue
    folder[$layer]=$dir
    uses[$layer]=$(echo "$rest" | sed 's/—//')
done <<<"$table"

# The folders a layer may include: its own and, transitively, those of the layers it uses.
closure() {
    local l=$1 out=${folder[$1]} u
    for u in ${uses[$l]}; do
        [ -n "${folder[$u]:-}" ] || fail "README: layer $l uses '$u', which the table does not define"
        out="$out $(closure "$u")"
    done
    echo "$out" | tr ' ' '\n' | grep -v '^$' | sort -u | tr '\n' ' '
}

# Compile from an empty folder: a quoted include also searches the current directory.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
all_folders=$(for l in "${!folder[@]}"; do echo "${folder[$l]}"; done | sort -u)
# One header of each folder, probed with __has_include from each layer's tree.
probe=""
for dir in $all_folders; do
    header=$(cd "$src" && ls "$dir"/*.h 2>/dev/null | head -1)
    [ -n "$header" ] || continue
    probe+=$(printf '#if __has_include("%s")\nyes %s\n#else\nno %s\n#endif\n' "$header" "$dir" "$dir")$'\n'
done
checked=0
for layer in "${!folder[@]}"; do
    tree=$root/$layer
    [ -d "$tree" ] || fail "layer $layer has no include tree ($tree): README and CMake disagree"
    # 2. The tree holds exactly the closure.
    want=$(closure "$layer")
    have=$(cd "$tree" && find . -type l | sed 's|^\./||' | sort | tr '\n' ' ')
    [ "$want" = "$have" ] || fail "layer $layer: README says it may include [$want], its include tree holds [$have]"
    # 3. The compiler agrees (one preprocessor run per layer).
    answers=$(cd "$scratch" && printf '%s' "$probe" | "$cxx" -std=c++20 -E -P -x c++ -I "$tree" -) ||
        fail "the compiler could not run the include probe for layer $layer"
    while read -r answer dir; do
        [ -n "$answer" ] || continue
        case " $want " in
            *" $dir "*) [ "$answer" = yes ] || fail "layer $layer cannot include $dir, which its tree holds" ;;
            *) [ "$answer" = no ] || fail "layer $layer can include $dir, which is above or beside it" ;;
        esac
        checked=$((checked + 1))
    done <<<"$answers"
done
# Every library folder is a layer.
for dir in $(cd "$src" && ls -d raster/*/ procedural/ | sed 's|/$||'); do
    echo "$all_folders" | grep -qx "$dir" || fail "folder $dir is in no layer of the README's table"
done
echo "layering: ${#folder[@]} layers agree in README, CMake and the compiler ($checked include checks)"
