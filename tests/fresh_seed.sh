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
# from /dev/urandom. Registered by tests/CMakeLists.txt (label fresh_seed).
set -euo pipefail
program=$1 filter=$2
seed=${PATCHWORK_FRESH_SEED:-$(od -An -N8 -tu8 /dev/urandom | tr -d ' ')}
echo "fresh RapidCheck seed $seed: a failure reproduces with RC_PARAMS=seed=$seed $program --gtest_filter=SUITE.NAME"
RC_PARAMS="seed=$seed" exec "$program" --gtest_filter="$filter" --gtest_brief=1
