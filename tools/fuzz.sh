#!/usr/bin/env bash
# Fuzzes scene parsing, validation and --set overrides with libFuzzer (clang from Debian) under
# AddressSanitizer and UndefinedBehaviorSanitizer, for FUZZ_SECONDS (default 120).
# Seeds: examples/*.json and tests/fuzz/seeds/. A finding is written to build-fuzz/findings/;
# copy it into tests/fuzz/seeds/ once fixed, so scene_fuzz_replay keeps it as a regression test.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-120}
build=build-fuzz

tools/apt_install.sh clang libclang-rt-14-dev  # the sanitizer and fuzz stages build with clang 14

CXX=clang++ cmake -B "$build" -DCOINROLL_FUZZ=ON -DCOINROLL_BENCHMARKS=OFF -DCOINROLL_HEADER_CHECK=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j"$(nproc)" --target scene_fuzzer

corpus="$build/corpus"
mkdir -p "$corpus" "$build/findings"
cp examples/*.json tests/fuzz/seeds/* "$corpus/"
log="$build/fuzz.log"
status=0
"$build/tests/fuzz/scene_fuzzer" "$corpus" -dict=tests/fuzz/scene.dict -max_total_time="$seconds" \
  -max_len=8192 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$build/findings/" >"$log" 2>&1 || status=$?
executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
coverage=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
echo "fuzz: ${executions:-?} executions in ${seconds} s, ${coverage:-cov: ?} edges, corpus $(ls "$corpus" | wc -l) inputs"
if [ "$status" -ne 0 ]; then
  echo "fuzz: FINDING (exit $status); the report:" >&2
  grep -A40 -m1 -E 'ERROR|runtime error|deadly signal|Timeout|out-of-memory' "$log" >&2 || tail -40 "$log" >&2
  ls "$build/findings" >&2
  exit 1
fi
