#!/usr/bin/env bash
# Runs a test program's RapidCheck properties once more with a fresh seed. Every ctest run of a
# property uses the fixed seed 20261123 (reproducible); this second run explores new cases each
# time and prints its seed, so that a failure it finds can be reproduced:
#
#   RC_PARAMS=seed=N PROGRAM --gtest_filter=SUITE.NAME
#
#   fresh_seed.sh PROGRAM FILTER     (FILTER: the program's properties, a gtest filter)
#
# The seed is PATCHWORK_FRESH_SEED when set (scripts/test draws one and prints it), else 64 bits
# from /dev/urandom. Registered by tests/CMakeLists.txt (label fresh_seed). Fails when the filter
# runs no test.
set -euo pipefail
program=$1 filter=$2
seed=${PATCHWORK_FRESH_SEED:-$(od -An -N8 -tu8 /dev/urandom | tr -d ' ')}
echo "fresh RapidCheck seed $seed: a failure reproduces with RC_PARAMS=seed=$seed $program --gtest_filter=SUITE.NAME"
status=0
output=$(RC_PARAMS="seed=$seed" "$program" --gtest_filter="$filter" --gtest_brief=1 2>&1) || status=$?
printf '%s\n' "$output"
# A filter that matches nothing (a renamed suite) would pass without testing anything.
if ! grep -qE '^\[==========\] [1-9][0-9]* tests? from' <<< "$output"; then
  echo "fresh_seed.sh: the filter '$filter' runs no test of $program" >&2
  exit 1
fi
exit "$status"
