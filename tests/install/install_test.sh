#!/usr/bin/env bash
# The installed package, used as its users would: installs this build into a temporary prefix,
# checks what is there (the public headers and nothing internal, the CLI, the version rule), then
# builds examples/ against the prefix with CMake (find_package(patchwork 0.1 CONFIG)) and with
# pkg-config and runs every example (each checks its own results and exits non-zero if one fails).
#
#   install_test.sh SOURCE_DIR BUILD_DIR CONFIG CMAKE GENERATOR MAKE_PROGRAM CXX
#
# Registered by cmake/PatchworkInstall.cmake; exits 77 (skipped) when pkg-config, which
# scripts/setup installs, is missing, and fails then when CI=true. The examples compile at -O0: their build is the test's cost.
set -euo pipefail
source_dir=$1 build_dir=$2 config=$3 cmake=$4 generator=$5 make_program=$6 cxx=$7

if ! command -v pkg-config > /dev/null; then
  if [ "${CI:-}" = true ]; then
    echo "install_test: pkg-config is not installed, and CI=true: scripts/setup installs it" >&2
    exit 1
  fi
  echo "install_test: pkg-config is not installed (scripts/setup installs it): skipped"
  exit 77
fi
started=$SECONDS
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
include="$prefix/include/patchwork"

fail() {
  echo "install_test: $*" >&2
  exit 1
}
# Runs a command with its output in $work/log, shown only when it fails.
quiet() {
  "$@" > "$work/log" 2>&1 || { cat "$work/log"; fail "failed: $*"; }
}

echo "== cmake --install into a temporary prefix"
quiet "$cmake" --install "$build_dir" --config "$config" --prefix "$prefix"

echo "== the installed modules, as docs/guide.md lists them"
"$source_dir/tests/install/installed_modules_test.sh" "$source_dir" "$build_dir" "$config" "$cmake" "$prefix"

echo "== the installed files"
# Every header of every module with a library (module_graph.txt lists the modules; tools is the
# CLI, report the speed-vs-error report program, python the Python module), except the internal headers that
# cmake/PatchworkInstall.cmake lists (patchwork_internal_headers); no header that includes what
# is not installed.
while IFS=: read -r module _; do
  case "$module" in "#"* | tools | report | python) continue ;; esac
  for header in "$source_dir/$module"/*.h; do
    name="$module/${header##*/}"
    case "$name" in
      subdivision/osd_refiner.h | curves/homogeneous.h | surfaces/tessellator_stages.h | surfaces/grid_bounds.h | \
        surfaces/patch_edge_geometry.h | io/obj_syntax.h | io/obj_freeform_checks.h) internal=1 ;;
      *) internal=0 ;;
    esac
    if [ "$internal" = 1 ]; then
      [ ! -e "$include/$name" ] || fail "the internal $name is installed"
    else
      cmp -s "$header" "$include/$name" || fail "$name is not installed as it is in the sources"
    fi
  done
done < "$build_dir/module_graph.txt"
[ ! -e "$include/tools" ] && [ ! -e "$include/report" ] && [ ! -e "$include/meshes/interop" ] || fail "tools/, report/ or meshes/interop installed"
headers=$(find "$include" -name '*.h' | wc -l)
grep -rhoE '^#include "[^"]+"' "$include" | sort -u | while read -r _ quoted; do
  target="${quoted//\"/}"
  [ -f "$include/$target" ] || fail "an installed header includes $target, which is not installed"
done
! grep -rlE '^#include <(opensubdiv|tiny_gltf|nlohmann|meshoptimizer)' "$include" || fail "a private dependency in a public header"
"$prefix/bin/patchwork" --version > /dev/null || fail "the installed CLI does not run"
pc_file="$(find "$prefix" -name patchwork.pc)"
config_file="$(find "$prefix" -name patchworkConfig.cmake)"
[ -n "$pc_file" ] && [ -n "$config_file" ] || fail "patchwork.pc or patchworkConfig.cmake not installed"
echo "$headers headers, $(find "$prefix" -name 'libpatchwork_*.a' | wc -l) libraries, bin/patchwork," \
  "${config_file#"$prefix/"}, ${pc_file#"$prefix/"}"

# The Python module, where this build has it (docs/python.md): the package in the prefix, imported
# by the Python it was built for with the PYTHONPATH the docs give, tessellating the teapot.
python=$(sed -n 's/^PATCHWORK_PYTHON:FILEPATH=//p' "$build_dir/CMakeCache.txt")
if [ -f "$build_dir/python/patchwork/__init__.py" ]; then
  package="$(find "$prefix" -type d -path '*/dist-packages/patchwork')"
  [ -n "$package" ] && [ -f "$package/_patchwork.pyi" ] && [ -f "$package/py.typed" ] ||
    fail "the Python package is not installed with its stubs"
  PYTHONPATH="$(dirname "$package")" "$python" -c 'import sys, patchwork as pw
assert pw.__file__.startswith(sys.argv[2]), pw.__file__
t = pw.tessellate(pw.read_bpt(sys.argv[1]), relative_tolerance=1e-3)
print("python module:", pw.__version__, t.triangle_count, "triangles of the teapot")' "$source_dir/data/teapot.bpt" "$package" ||
    fail "the installed Python module does not import from the prefix"
fi

echo "== find_package(patchwork 0.2) must fail: before 1.0 a minor version may break the API"
mkdir "$work/too_new"
printf 'cmake_minimum_required(VERSION 3.25)\nproject(too_new LANGUAGES NONE)\nfind_package(patchwork 0.2 CONFIG REQUIRED)\n' \
  > "$work/too_new/CMakeLists.txt"
if "$cmake" -S "$work/too_new" -B "$work/too_new/build" -DCMAKE_PREFIX_PATH="$prefix" > "$work/log" 2>&1; then
  fail "find_package(patchwork 0.2) accepted version 0.1"
fi
grep -q 'compatible with requested version "0.2"' "$work/log" || { cat "$work/log"; fail "0.2 refused for another reason"; }

echo "== examples/ with CMake against the prefix"
flags="-O0 -Wall -Wextra -Wpedantic -Werror"
quiet "$cmake" -S "$source_dir/examples" -B "$work/examples" -G "$generator" -DCMAKE_MAKE_PROGRAM="$make_program" \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE= -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_PREFIX_PATH="$prefix"
grep -qx "patchwork_DIR:PATH=$(dirname "$config_file")" "$work/examples/CMakeCache.txt" ||
  fail "examples/ found another patchwork: $(grep '^patchwork_DIR' "$work/examples/CMakeCache.txt")"
quiet "$cmake" --build "$work/examples" -j 1
"$work/examples/curve_split"
"$work/examples/mesh_check"
"$work/examples/teapot_tessellate" "$source_dir/data/teapot.bpt" "$work/teapot.glb" | tee "$work/teapot.txt"
"$work/examples/subdivide_cage"

# The installed CLI tessellates the teapot to the same triangles as the library did.
example_triangles=$(grep -oE '^[0-9]+ triangles' "$work/teapot.txt" | cut -d' ' -f1)
cli_triangles=$("$prefix/bin/patchwork" tessellate "$source_dir/data/teapot.bpt" -o "$work/cli.glb" \
  --relative-tolerance 1e-3 --json | grep -oE '"triangles": *[0-9]+' | grep -oE '[0-9]+$')
[ -n "$example_triangles" ] && [ "$example_triangles" = "$cli_triangles" ] ||
  fail "the CLI made ${cli_triangles:-no} triangles, the example ${example_triangles:-none}"
echo "the installed CLI: $cli_triangles triangles as well"

echo "== pkg-config"
export PKG_CONFIG_PATH
PKG_CONFIG_PATH="$(dirname "$pc_file")"
version=$(pkg-config --modversion patchwork)
grep -qx "CMAKE_PROJECT_VERSION:STATIC=$version" "$build_dir/CMakeCache.txt" || fail "patchwork.pc has version $version"
# Compiled with the file's Cflags; the other examples' objects from the CMake build linked with
# its Libs, which must name every library the static ones need.
read -ra cflags <<< "$(pkg-config --cflags patchwork)"
read -ra libs <<< "$(pkg-config --libs patchwork)"
read -ra warnings <<< "$flags"
quiet "$cxx" -std=c++20 "${warnings[@]}" "${cflags[@]}" "$source_dir/examples/curve_split.cpp" -o "$work/curve_split_pc" "${libs[@]}"
"$work/curve_split_pc" > /dev/null || fail "curve_split built with pkg-config failed"
for example in mesh_check teapot_tessellate subdivide_cage; do
  object="$(find "$work/examples" -name "$example.cpp.o")"
  [ -n "$object" ] || fail "no object file of $example in the CMake build"
  quiet "$cxx" "$object" -o "$work/${example}_pc" "${libs[@]}"
done
"$work/mesh_check_pc" > /dev/null || fail "mesh_check linked with pkg-config failed"
"$work/teapot_tessellate_pc" "$source_dir/data/teapot.bpt" "$work/teapot_pc.glb" > /dev/null ||
  fail "teapot_tessellate linked with pkg-config failed"
"$work/subdivide_cage_pc" > /dev/null || fail "subdivide_cage linked with pkg-config failed"
echo "pkg-config --modversion $version; curve_split compiled and linked, the others linked: all ran"

echo "== install_test: passed in $((SECONDS - started)) s"
