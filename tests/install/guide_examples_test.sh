#!/usr/bin/env bash
# docs/guide.md shows the example programs, and cannot drift from them: every fenced code block
# whose first line is a comment naming a file in examples/ ("// examples/NAME.cpp ..." or
# "# examples/CMakeLists.txt ...") must be that file byte for byte, and every file in examples/
# must be shown.
#
#   guide_examples_test.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
guide="$source_dir/docs/guide.md"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# Each fenced block's lines, without the fences, into $work/block_N.
awk -v out="$work/block_" '
  /^```/ { if (inside) { inside = 0; close(file) } else { inside = 1; file = out (++blocks); printf "" > file }; next }
  inside { print > file }
' "$guide"

status=0
declare -A shown
for block in "$work"/block_*; do
  first="$(head -n 1 "$block")"
  if [[ $first =~ ^(//|#)\ (examples/[A-Za-z0-9_.]+) ]]; then
    name="${BASH_REMATCH[2]}"
    shown[$name]=1
    if ! cmp -s "$block" "$source_dir/$name"; then
      echo "docs/guide.md: the block '$first' differs from $name (- file, + guide):"
      diff -u "$source_dir/$name" "$block" | tail -n +3 | head -n 20 || true
      status=1
    fi
  fi
done
for file in "$source_dir"/examples/*; do
  name="examples/${file##*/}"
  if [ -z "${shown[$name]:-}" ]; then
    echo "docs/guide.md does not show $name (a block starting with a comment naming it)"
    status=1
  fi
done
[ "$status" -ne 0 ] || echo "docs/guide.md shows all ${#shown[@]} files of examples/ as they are"
exit "$status"
