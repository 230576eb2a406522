#!/usr/bin/env bash
# The installed CMake package from a user's side: installs the build into a temporary
# prefix, builds examples/consumer against it with find_package(snapfit), runs it on
# the default scene, and checks that its energy and force equal `snapfit query`'s at
# the same pose and m', and that its rotation search finds `snapfit search`'s best pose.
#   tests/package_consumer.sh BUILD_DIR SNAPFIT_CLI
set -euo pipefail
build="$1"
cli="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export SNAPFIT_CACHE_DIR="$work/cache"

cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S examples/consumer -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null

scene=scenes/default.json
pose="1,0.5,-12"
consumer_out=$("$work/consumer/snapfit_consumer" "$scene" 4096 1 0.5 -12 2>/dev/null)
query_out=$("$cli" query "$scene" --modes 4096 --pose "$pose" 2>/dev/null)
echo "consumer: $consumer_out"
echo "query:    $query_out"

# The number after "key": in a JSON line (first element for arrays), outside the nested
# error_estimate object, whose keys have the same names.
field() {
  sed -E 's/"error_estimate": *\{[^}]*\},?//' <<<"$1" | grep -oE "\"$2\": *\[? *[-0-9.eE+]+" | head -n 1 |
    sed -E 's/.*[:[] *//'
}
for key in energy force; do
  a=$(field "$consumer_out" "$key")
  b=$(field "$query_out" "$key")
  awk -v a="$a" -v b="$b" -v k="$key" 'BEGIN {
    d = a - b; if (d < 0) d = -d; s = (b < 0 ? -b : b); if (s < 1e-30) s = 1e-30;
    if (d / s > 1e-9) { printf "package_consumer: %s differs: consumer %s, snapfit query %s\n", k, a, b; exit 1 }
  }'
done
# The rotation search from the library against `snapfit search`: the same best pose
# and map energy.
finder_out=$("$work/consumer/snapfit_fit_finder" "$scene" 8 2>/dev/null)
search_out=$("$cli" search "$scene" --rotations 8 --top 1 --map-fft clfft 2>/dev/null | grep '^{')
echo "fit finder: $finder_out"
echo "search:     $search_out"
for key in energy position; do
  a=$(field "$finder_out" "$key")
  b=$(field "$search_out" "$key")
  awk -v a="$a" -v b="$b" -v k="$key" 'BEGIN {
    d = a - b; if (d < 0) d = -d; s = (b < 0 ? -b : b); if (s < 1) s = 1;
    if (d / s > 1e-9) { printf "package_consumer: search %s differs: library %s, snapfit search %s\n", k, a, b; exit 1 }
  }'
done
# The installed tree holds the public headers only.
test -f "$work/prefix/include/snapfit/snapfit.h"
if find "$work/prefix/include" -name '*.h' | grep -v '/snapfit/' | grep -q .; then
  echo "package_consumer: private headers were installed" >&2
  exit 1
fi
# Private dependencies (OpenCASCADE, Assimp, OpenCL, ...) stay out of the package's
# requirements: a consumer links and finds Eigen only. (IMPORTED_LINK_DEPENDENT_LIBRARIES
# names them too, for the linker's search of the shared library's own dependencies.)
if grep -h -E 'INTERFACE_LINK_LIBRARIES|find_dependency\(' "$work"/prefix/lib*/cmake/snapfit/*.cmake |
  grep -E 'TK[A-Z][A-Za-z0-9]+|OpenCASCADE|opencascade|assimp|OpenCL|TBB|clFFT'; then
  echo "package_consumer: the installed CMake package names a private dependency" >&2
  exit 1
fi
# The Python module, where it was built: importable from the prefix as docs/python.md says,
# and the same energy as `snapfit query` at that pose (the installed module finds the
# installed library).
if [ -f "$build/python/snapfit/__init__.py" ]; then
  python_dir=$(find "$work/prefix" -type d -path '*/python3/dist-packages' | head -n 1)
  scene_file="$PWD/$scene"
  py_energy=$(cd "$work" && PYTHONPATH="$python_dir" /usr/bin/python3 -c '
import sys, numpy as np, snapfit
e = snapfit.Assembly(snapfit.load_scene(sys.argv[1])).query_engine(); e.modes = 4096
print(repr(float(e.query(np.array([[1, 0.5, -12, 1, 0, 0, 0]]))["energy"][0])))' "$scene_file")
  q_energy=$(field "$query_out" energy)
  echo "python (installed): energy $py_energy"
  awk -v a="$py_energy" -v b="$q_energy" 'BEGIN {
    d = a - b; if (d < 0) d = -d; s = (b < 0 ? -b : b); if (s < 1e-30) s = 1e-30;
    if (a == "" || d / s > 1e-9) { printf "package_consumer: the installed Python module gives %s, snapfit query %s\n", a, b; exit 1 }
  }'
fi
echo "package_consumer: ok"
