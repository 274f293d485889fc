#!/usr/bin/env bash
# The set of modules the package installs is the same in every build type and is the table of
# docs/guide.md ("| `patchwork::<module>` | ..."): installs this build into a temporary prefix
# and compares, for each way a module shows, the set found with the guide's:
#   the libraries lib/libpatchwork_<module>.a, the header folders include/patchwork/<module>/,
#   the exported targets patchwork::<module> (patchworkTargets.cmake, besides patchwork::patchwork
#   and patchwork::build_flags) and the -lpatchwork_<module> of patchwork.pc.
# Registered in both builds by cmake/PatchworkInstall.cmake; install_test.sh runs it too.
#
#   installed_modules_test.sh SOURCE_DIR BUILD_DIR CONFIG CMAKE [PREFIX]
#
# With PREFIX (an install already made there) nothing is installed.
set -euo pipefail
source_dir=$1 build_dir=$2 config=$3 cmake=$4 prefix=${5:-}
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
if [ -z "$prefix" ]; then
  prefix="$work/prefix"
  "$cmake" --install "$build_dir" --config "$config" --prefix "$prefix" > "$work/log" 2>&1 ||
    { cat "$work/log"; echo "installed_modules_test: cmake --install failed" >&2; exit 1; }
fi

# One module a line, sorted.
sorted() { tr ' ' '\n' | sed '/^$/d' | sort -u; }
expected=$(grep -oE '^\| `patchwork::[a-z_]+` \|' "$source_dir/docs/guide.md" | grep -oE '::[a-z_]+' | cut -c3- | sorted)
[ -n "$expected" ] || { echo "installed_modules_test: no table of modules in docs/guide.md" >&2; exit 1; }

targets_file="$(find "$prefix" -name patchworkTargets.cmake)"
pc_file="$(find "$prefix" -name patchwork.pc)"
[ -n "$targets_file" ] && [ -n "$pc_file" ] || { echo "installed_modules_test: no patchworkTargets.cmake or patchwork.pc" >&2; exit 1; }
declare -A found
found[libraries]=$(find "$prefix" -name 'libpatchwork_*.a' -printf '%f\n' | sed -E 's/^libpatchwork_(.*)\.a$/\1/' | sorted)
found[header folders]=$(find "$prefix/include/patchwork" -mindepth 1 -maxdepth 1 -type d -printf '%f\n' | sorted)
found[exported targets]=$(grep -oE 'add_library\(patchwork::[a-z_]+ ' "$targets_file" | grep -oE '::[a-z_]+' | cut -c3- |
  grep -vxE 'patchwork|build_flags' | sorted)
found[patchwork.pc libraries]=$(grep -E '^Libs:' "$pc_file" | grep -oE -- '-lpatchwork_[a-z_]+' | cut -c13- | sorted)

status=0
for what in libraries "header folders" "exported targets" "patchwork.pc libraries"; do
  if [ "${found[$what]}" != "$expected" ]; then
    echo "installed_modules_test: the installed $what differ from docs/guide.md's modules (- guide, + installed):" >&2
    diff <(echo "$expected") <(echo "${found[$what]}") | grep -E '^[<>]' | sed 's/^</-/; s/^>/+/' >&2 || true
    status=1
  fi
done
[ "$status" -ne 0 ] || echo "installed_modules_test: $(echo "$expected" | wc -l) modules, as docs/guide.md lists them:" $expected
exit "$status"
