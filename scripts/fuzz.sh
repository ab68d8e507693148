#!/bin/sh
# Builds the libFuzzer targets of tests/fuzz (clang, ASan+UBSan) in BUILD and runs each for SECONDS
# on its corpus copied to BUILD/fuzz-corpus/<name> (the repository's seeds are never written),
# one fuzzer process at a time. Prints each target's executions; crashes go to BUILD/fuzz-artifacts.
# Usage: scripts/fuzz.sh [BUILD [SECONDS [JOBS]]]   (make fuzz FUZZ_SECONDS=600)
set -eu
BUILD=${1:-build-fuzz}
SECONDS_PER_TARGET=${2:-60}
JOBS=${3:-1}
CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DRPVIO_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$BUILD" -j"$JOBS" --target fuzzers
failed=""
for seeds in tests/fuzz/corpus/*/; do
  name=$(basename "$seeds")
  corpus="$BUILD/fuzz-corpus/$name"
  artifacts="$BUILD/fuzz-artifacts/$name/"
  log="$BUILD/fuzz-$name.log"
  mkdir -p "$corpus" "$artifacts"
  cp "$seeds"* "$corpus/"
  echo "== $name: fuzzing for $SECONDS_PER_TARGET s (log $log)"
  if "$BUILD/bin/${name}_fuzz" -max_total_time="$SECONDS_PER_TARGET" -print_final_stats=1 \
    -dict=tests/fuzz/numbers.dict -artifact_prefix="$artifacts" "$corpus" >"$log" 2>&1; then
    status=ok
  else
    status="FINDING (see $log, input in $artifacts)"
    failed="$failed $name"
  fi
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  echo "$name: ${executions:-?} executions, $status"
done
if [ -n "$failed" ]; then
  echo "fuzz findings in:$failed"
  exit 1
fi
