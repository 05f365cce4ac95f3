#!/usr/bin/env bash
# Sanitizers and fuzzing, as CI runs them (docs/fuzzing.md):
#   1. AddressSanitizer + UndefinedBehaviorSanitizer (clang 14, -O0 (one
#      program -O1, below), line tables, every check on but null, pointer-overflow, object-size,
#      alignment and vptr (below), none
#      recovered from) over the unit-test programs listed below,
#      which between them include every public header and run every algorithm;
#   2. ThreadSanitizer over tests/thread_safety_test.cpp (a scene and an
#      ensemble study shared by four threads);
#   3. the libFuzzer targets (fuzz/), each for FUZZ_SECONDS (20 by default)
#      from the committed seed corpus, built with ASan + UBSan too.
# Any finding fails the script. Needs tools/install-deps.sh --sanitizers.
#
#   tools/sanitizers.sh                  everything
#   FUZZ_SECONDS=600 tools/sanitizers.sh a longer fuzz run
#   tools/sanitizers.sh asan|tsan|fuzz   one part
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${SAN_DIR:-$root/build-san}
fuzz_seconds=${FUZZ_SECONDS:-20}
jobs=${JOBS:-2}
parts=${1:-all}
cxx=${SAN_CXX:-clang++-14}

# The ASan + UBSan subset (tests/*.cpp). Each program is a few GB and a few
# minutes of compiler under ASan, so not all of them: these, with the fuzz
# target (built with the same sanitizers, below), cover every header (the
# umbrella header and every model, joint and force element) and every
# algorithm (Newton–Euler, mass matrix and LDLᵀ, articulated body, recovery
# and residual, loops and projection, dual-number Jacobian and rosenbrock4,
# checked stepping and simulate, ensembles, viewer).
# What the fuzz target runs on random scenes is not repeated here: its
# random trees mix every joint kind and force element (tree_test,
# tree_joints_test, joints_physics_test, joints_equivalence_test,
# force_elements_test), its loops are a four-bar and a slider-crank through
# the derivative, the projection, simulate and recover (loops_test; loops
# also run here in simulate_test, a four-bar, and jacobian_test, a row of
# loop windows; loops_test's spatial loops and ball cut joints run under no
# sanitizer); names_test's lookups run in every program's recover. no_heap_test is
# not among them: what it runs of flange (the derivative, simulate, the
# residual, the Jacobian, ensembles) the programs above run too, and what it
# adds, Odeint's other steppers driving a scene through the same system, is
# Boost's code. Fewer programs keep the CI run under 45 minutes (loops_test
# was the longest unit under ASan, about 100 s of compiler).
asan_tests=(paper_equations_test simulate_test parameters_test jacobian_test body_shape_test
            ensemble_test viewer_test)

say() { printf 'sanitizers: %s\n' "$*"; }
elapsed() { echo $(( $(date +%s) - $1 ))s; }

# Debug information as line tables only (-gline-tables-only, and no -g from
# the Debug build type): a report's stack still names every file, line and
# function, and loops_test compiles in 100 s instead of 120. Inlining is
# left to the compiler (FLANGE_NO_FORCED_INLINE, detail/inline.hpp), as in
# the unit tests: the same code paths, a quarter less compiler time. The
# ASan and TSan programs build at -O0, where clang takes about half the time
# (jacobian_test under ASan + UBSan: 117 → 56 s of compiler) and the
# sanitizers check every access the source makes; their checks then run in
# seconds (jacobian_test 0.3 → 2.2 s, TSan's program 3 s), except
# ensemble_test's (76 s against 1 s), which builds at -O1
# (FLANGE_TEST_OPTIMIZE, tests/CMakeLists.txt). The fuzz targets build at
# -O1: they run for a fixed time, and an unoptimised target tries a fraction
# of the inputs.
configure() {  # dir, optimisation, flags, extra cmake args…
  local dir=$1 opt=$2 flags=$3
  shift 3
  cmake -S "$root" -B "$dir" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG= \
        -DCMAKE_CXX_FLAGS="$opt -gline-tables-only -fno-omit-frame-pointer -DFLANGE_NO_FORCED_INLINE $flags" \
        -DCMAKE_EXE_LINKER_FLAGS="$flags" -DFLANGE_BUILD_EXAMPLES=OFF -DFLANGE_BUILD_BENCHMARKS=OFF "$@" >/dev/null
}

# Five of UBSan's checks are left out, each covered otherwise; they
# instrument every Eigen access, and the five together are a third of a
# sanitized unit's compile (fuzz/scenes_chain.cpp: 78 → 49 s; docs/fuzzing.md):
#   null, pointer-overflow, object-size: AddressSanitizer reports a
#     dereference of null, or of any address outside an object, where it
#     happens, and flange does no pointer arithmetic that could wrap;
#   alignment: Eigen's own assertion (on here: the Debug build defines no
#     NDEBUG) checks the alignment of every fixed-size vectorizable array it
#     constructs, and flange's Eigen::Maps are unaligned ones;
#   vptr: flange has no virtual functions.
# Bounds, integer and float-cast overflow, shifts, division by zero, enums,
# bools, returns and the rest stay on. The list is cmake/ubsan_off.txt, which
# fuzz/CMakeLists.txt reads too.
ubsan_off=$(<"$root/cmake/ubsan_off.txt")
asan_flags="-fsanitize=address,undefined -fno-sanitize=$ubsan_off -fno-sanitize-recover=all"

asan_targets=()
asan_t0=0

configure_asan() {
  local dir=$out/asan
  # The programs build as one target, selected_tests (tests/CMakeLists.txt),
  # so that two compile at a time: `--target a b …` builds them one by one.
  local selection
  selection=$(IFS=';'; echo "${asan_tests[*]}")
  configure "$dir" -O0 "$asan_flags" -DFLANGE_TEST_SELECTION="$selection" -DFLANGE_TEST_OPTIMIZE=ensemble_test
  local known t
  known=$(cmake --build "$dir" --target help)
  for t in "${asan_tests[@]}"; do
    if grep -q "\.\.\. $t\$" <<<"$known"; then asan_targets+=("$t"); else say "ASan + UBSan: $t is not configured here (oneTBB missing?), left out"; fi
  done
}

run_asan_build() {
  asan_t0=$(date +%s)
  configure_asan
  say "ASan + UBSan: building ${#asan_targets[@]} test programs with $cxx"
  local dir=$out/asan
  cmake --build "$dir" -j"$jobs" --target selected_tests >"$dir/build.log" 2>&1 || { tail -50 "$dir/build.log"; exit 1; }
  say "ASan + UBSan: built in $(elapsed "$asan_t0")"
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}

run_asan_test() {  # one program; 1 on a finding
  local dir=$out/asan t=$1
  if ! "$dir/tests/$t" >"$dir/$t.log" 2>&1; then
    tail -60 "$dir/$t.log"
    say "ASan + UBSan: $t FAILED (log: $dir/$t.log)"
    return 1
  fi
  say "ASan + UBSan: $t passed ($(grep -Eo '[0-9]+ assertions? in [0-9]+ test cases?' "$dir/$t.log" | tail -1))"
}

run_asan_tests() {
  local t t1; t1=$(date +%s)
  for t in "${asan_targets[@]}"; do run_asan_test "$t" || exit 1; done
  say "ASan + UBSan: ${#asan_targets[@]} programs passed, no finding (tests ran in $(elapsed "$t1"), in all $(elapsed "$asan_t0"))"
}

run_asan() { run_asan_build; run_asan_tests; }

# ThreadSanitizer's program is one translation unit; in a whole run it builds
# with the others (build_all) and runs beside the ASan programs
# (run_checks_in_pairs).
configure_tsan() { configure "$out/tsan" -O0 "-fsanitize=thread"; }

build_tsan() {
  local dir=$out/tsan
  configure_tsan
  cmake --build "$dir" -j"$jobs" --target thread_safety_test >"$dir/build.log" 2>&1 || { tail -50 "$dir/build.log"; return 1; }
}

test_tsan() {  # t0; 1 on a finding
  local dir=$out/tsan
  if ! "$dir/tests/thread_safety_test" >"$dir/thread_safety_test.log" 2>&1; then
    tail -80 "$dir/thread_safety_test.log"
    say "ThreadSanitizer: thread_safety_test FAILED"
    return 1
  fi
  say "ThreadSanitizer: thread_safety_test passed, no data race ($(elapsed "$1"))"
}

run_tsan() {
  local t0; t0=$(date +%s)
  build_tsan || exit 1
  test_tsan "$t0" || exit 1
}

configure_fuzz() { configure "$out/fuzz" -O1 "" -DFLANGE_BUILD_TESTS=OFF -DFLANGE_BUILD_FUZZERS=ON; }

run_fuzz() {
  local t0; t0=$(date +%s)
  local dir=$out/fuzz
  configure_fuzz
  cmake --build "$dir" -j"$jobs" --target fuzzers >"$dir/build.log" 2>&1 || { tail -50 "$dir/build.log"; exit 1; }
  say "fuzz: built in $(elapsed "$t0")"
  run_fuzz_targets
}

run_fuzz_targets() {
  local dir=$out/fuzz
  # The two targets run side by side, one core each (libFuzzer runs one
  # process): the same seconds of fuzzing each, in half the wall time.
  local f pids=() targets=(scenes urdf)
  for f in "${targets[@]}"; do
    local work=$dir/run_$f
    rm -rf "$work" && mkdir -p "$work/corpus"
    # New inputs go to the work corpus; the committed seeds are only read.
    (cd "$work" && exec "$dir/fuzz/${f}_fuzz" -max_total_time="$fuzz_seconds" -max_len=4096 -timeout=10 \
        -rss_limit_mb=4096 -print_final_stats=1 corpus "$root/fuzz/corpus/$f" >"$work/log" 2>&1) &
    pids+=($!)
  done
  local i=0 failed=0
  for f in "${targets[@]}"; do
    local work=$dir/run_$f
    if ! wait "${pids[$i]}"; then
      tail -60 "$work/log"
      say "fuzz: ${f}_fuzz found a failure; the input is in $work (crash-*, timeout-*, oom-*)"
      failed=1
    else
      say "fuzz: ${f}_fuzz ran $(grep -Eo 'Done [0-9]+ runs in [0-9]+ second' "$work/log") with no finding"
    fi
    i=$((i + 1))
  done
  ((failed == 0)) || exit 1
}

# Everything at once (CI): the three builds under one make jobserver, so
# that two compilers run until the last unit of all three is done (built one
# after the other, each build ended on one core while the other idled). The
# fuzz build starts first, its longest units first (fuzz/CMakeLists.txt):
# started last, they ended the build on one core (scenes_legged.cpp alone
# for its last 80 s); then
# the ASan programs and TSan's, two at a time; then the fuzz targets side by
# side. The makefiles are CMake's (`make -C dir target`), each build's output
# in its build.log.
build_all() {
  local t0; t0=$(date +%s)
  configure_asan
  configure_tsan
  configure_fuzz
  say "building ${#asan_targets[@]} ASan + UBSan test programs, the TSan program and the fuzz targets with $cxx"
  local mk=$out/all.mk
  {
    printf 'all: fuzz asan tsan\n'
    printf 'asan:\n\t+$(MAKE) --no-print-directory -C %s selected_tests >%s/build.log 2>&1\n' "$out/asan" "$out/asan"
    printf 'tsan:\n\t+$(MAKE) --no-print-directory -C %s thread_safety_test >%s/build.log 2>&1\n' "$out/tsan" "$out/tsan"
    printf 'fuzz:\n\t+$(MAKE) --no-print-directory -C %s fuzzers >%s/build.log 2>&1\n' "$out/fuzz" "$out/fuzz"
    printf '.PHONY: all asan tsan fuzz\n'
  } >"$mk"
  if ! make -j"$jobs" -k -f "$mk" >"$out/all.log" 2>&1; then
    local d
    for d in asan tsan fuzz; do
      if grep -q -E "error|Error" "$out/$d/build.log"; then tail -50 "$out/$d/build.log"; fi
    done
    say "the sanitizer builds failed (logs: $out/{asan,tsan,fuzz}/build.log)"
    exit 1
  fi
  say "built in $(elapsed "$t0")"
}

run_checks_in_pairs() {  # the ASan programs and TSan's, $jobs at a time
  local t0; t0=$(date +%s)
  local name running=0 failed=0
  for name in "${asan_targets[@]}" tsan; do
    if ((running >= jobs)); then
      wait -n || failed=1
      running=$((running - 1))
    fi
    if [[ $name == tsan ]]; then test_tsan "$t0" & else run_asan_test "$name" & fi
    running=$((running + 1))
  done
  while ((running > 0)); do
    wait -n || failed=1
    running=$((running - 1))
  done
  ((failed == 0)) || { say "a sanitizer found something (above)"; exit 1; }
  say "ASan + UBSan: ${#asan_targets[@]} programs passed, and TSan's, no finding ($(elapsed "$t0"))"
}

case $parts in
  all)
    mkdir -p "$out"
    build_all
    run_checks_in_pairs
    run_fuzz_targets ;;
  asan) run_asan ;;
  tsan) run_tsan ;;
  fuzz) run_fuzz ;;
  *) echo "usage: tools/sanitizers.sh [all|asan|tsan|fuzz]" >&2; exit 2 ;;
esac
