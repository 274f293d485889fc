#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time: new inputs go to SCRATCH (libFuzzer writes to its
# first corpus folder), the committed seed and regression folders are only read (every file in
# them runs first, so a past crash that comes back fails at once). Prints the executions run; a
# finding fails with libFuzzer's report, the crashing input saved as SCRATCH-crash-*.
#   run_fuzzer.sh TARGET SCRATCH SECONDS FOLDER...
set -euo pipefail
target="$1" scratch="$2" seconds="$3"
shift 3
folders=()
for folder in "$@"; do
  [ -d "$folder" ] && folders+=("$folder")
done
# fuzz_bpt: inputs up to 2 KB (a few patches with shared edges, as the seeds' rim and one-patch
# files; the 32-patch teapot seed is read cut to its first 2 KB): mutating the whole teapot ran
# the full adjacency analysis on every input, 250 executions a second against 670 now.
extra=()
case "$(basename "$target")" in
  fuzz_bpt) extra=(-max_len=2048) ;;
esac
mkdir -p "$scratch"
log="$scratch.log"
set +e
"$target" "$scratch" "${folders[@]}" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 \
  -artifact_prefix="$scratch-" -print_final_stats=1 "${extra[@]}" > "$log" 2>&1
status=$?
set -e
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
echo "$(basename "$target"): $runs executions in $seconds s, exit $status"
if [ "$status" -ne 0 ]; then
  tail -n 60 "$log"
fi
exit "$status"
