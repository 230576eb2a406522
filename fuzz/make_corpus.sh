#!/bin/bash
# Seed corpora for fuzz/: the shipped scenes, and every Assimp test model under 20 kB in
# a format fuzz_mesh knows, prefixed with the byte that selects its extension.
set -euo pipefail
out=${1:?usage: make_corpus.sh OUT_DIR}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/scene_corpus" "$out/mesh_corpus"
cp "$here"/scenes/*.json "$out/scene_corpus/"
exts=(stl obj ply off gltf glb 3ds dae fbx x)
n=0
for i in "${!exts[@]}"; do
  while IFS= read -r -d '' f; do
    [ "$(stat -c %s "$f")" -lt 20000 ] || continue
    { printf "\\x$(printf %02x "$i")"; cat "$f"; } > "$out/mesh_corpus/seed_$n"
    n=$((n + 1))
  done < <(find /usr/share/assimp/models -type f -iname "*.${exts[$i]}" -print0)
done
echo "$n mesh seeds in $out/mesh_corpus"
