#!/usr/bin/env bash
# Builds coinroll and its tests with AddressSanitizer + UndefinedBehaviorSanitizer in
# build-sanitize/ and runs the unit and cli tiers there (ctest labels; tests/CMakeLists.txt):
# every library code path the in-process tests, the bad-input table, the scene parser, the
# integrators, the sliding switch and the encoders take. Any report fails the run: UBSan does not
# recover, and LeakSanitizer is on (OSMesa's own one-time allocations are suppressed).
# Left out, as gaining nothing from instrumentation: the slow tier (long runs of code the other
# tiers run short), the SymPy derivations and layering (they never run the program), and the docs
# tier (the README's renders, install, Python and Slurm run uninstrumented code or the same paths).
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-sanitize

# clang, not the main build's GCC: at -O1 with ASan GCC took 3-5 times as long on the
# template-heavy translation units (the integrators' tests: 95 s against 19 s), and a second
# compiler's warnings and diagnostics are worth having. -O1 keeps the sanitized tests quick; the
# physics tests' tolerances hold at any -O.
tools/apt_install.sh clang libclang-rt-14-dev  # the sanitizer and fuzz stages build with clang 14
CXX=clang++ cmake -B "$build" -DCOINROLL_SANITIZE=ON -DCMAKE_COMPILE_WARNING_AS_ERROR=ON \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" >/dev/null
cmake --build "$build" -j"$(nproc)"

# intercept_tls_get_addr=0: clang 14's runtime takes any dynamic TLS block at 16 mod 4096 for one
# with glibc 2.19's header and records the two words before it as the block's range. Since glibc
# 2.25 there is no header: in the render tests Mesa's block sits at 0x603000021010 and the range read
# is {0xead, 0x1800001102}, which LeakSanitizer's tracer scans at exit ("Tracer caught signal 11:
# addr=0xea8" in CI, 10 render tests, where the thread holding it was still alive). Off, the blocks
# are still scanned as the heap chunks they are, reached from the thread's DTV.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/.ci/lsan.supp:print_suppressions=0
# A test's time limit here is the sanitized build's, not a speed check: the slowest test of these
# tiers (cli_bad_inputs.signals) takes 25 s under ASan at -O1 on a quiet machine, so five minutes
# leave room for a loaded one.
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" --timeout 300 -L '^(unit|cli)$'
