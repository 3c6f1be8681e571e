#!/usr/bin/env bash
# From a fresh clone: installs missing Debian packages, builds, runs every test with CTest.
#   scripts/test.sh             the Release build in build/
#   scripts/test.sh --sanitize  the whole suite built with AddressSanitizer and
#                               UndefinedBehaviorSanitizer in build-sanitize/
#                               (LeakSanitizer suppressions: scripts/lsan_suppressions.txt)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
jobs="$(nproc)"
if [ "${1:-}" = "--sanitize" ]; then
  # set before the build too: gtest_discover_tests runs every test program
  # at build time to list its tests.
  # symbolize=0: to match leaked blocks against the suppressions (the few
  # that CLN and OpenMPI keep in every process), LeakSanitizer otherwise
  # symbolizes their stacks at the exit of every process, 0.15-0.35 s each,
  # most of the time of the tests that run the program many times
  # (docs/performance.md, "CI"). The suppressions name libraries, which
  # match without symbols. Failed tests run again with symbols, below.
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:symbolize=0"
  export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan_suppressions.txt:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  # -O0 -g1: optimising the instrumented code is what made the sanitized
  # build slow (-O1: about half an hour on 2 cores); at -O0 it fits CI beside
  # the Release build, and the suite still runs in minutes (measured in
  # docs/simulation.md, "Sanitizers, fuzzing and the property test")
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O0 -g1 -DNDEBUG" -DIMPACTLAB_SANITIZE=ON \
    -DIMPACTLAB_BUILD_BENCHMARKS=OFF -DIMPACTLAB_BUILD_PYTHON=OFF > build-sanitize.log 2>&1 || { cat build-sanitize.log; exit 1; }
  cmake --build build-sanitize -j"$jobs" >> build-sanitize.log 2>&1 || { tail -50 build-sanitize.log; exit 1; }
  echo "build-sanitize: ok (log in build-sanitize.log)"
  cd build-sanitize
  # Run in the Release suite only: tests that repeat a path the sanitized
  # suite already runs in smaller tests, many times over, and cost 20 s to
  # 325 s each unoptimised and instrumented (docs/simulation.md, "Sanitizers,
  # fuzzing and the property test", says which smaller tests keep each path
  # under the sanitizers).
  release_only=(
    'SweepClassificationTolerance\.Jin2003StatesNoneBecauseALooserToleranceChangesMoreClasses'
    'QuickReproduction\.RangesResidualsSlipsAndThreadIndependence'
    'Steppers/PendulumWallsContact\.Jin2003ContactPhasesMatchClosedForms/rkf78'
    'ContinueCommand\.SwitchWithACurveWritesTheDoubledBranchsCurveToo'
    'Sweep\.KilledSweepLeavesNoDataFileAndResumes'
    'HardCase\.MillionImpactsKeepAnExactCount'
    'SceneFuzz\.ProgramKeepsItsPromiseOnRandomSetPairs'
    'SceneFuzz\.ProgramKeepsItsPromiseOnMutatedSceneFiles'
    'SweepFiles\.PeakMemoryDoesNotGrowWithTheNumberOfValues'
    'PoincareFiles\.PeakMemoryDoesNotGrowWithThePointCount'
    'BenchQuick\.WritesTheDataItsSidecarAndOnePlotPerCase'
    'BenchQuick\.ErrorsFallAsTheToleranceTightens'
    'RigidPendulumSpin\.PeriodicAndContinuedOrbitsAreTheBruteForceSections'
    'RigidPendulumSpin\.LockedSpinWithoutRadiusContinuesAsModelN'
    'AttractorsCli\.IdsPersistAlongTheRangeAndBirthsAndDeathsAreReportedWhereTheyHappen'
    'AttractorsCli\.AnAsymmetricOrbitAndItsMirrorImageAreTwoAttractorsOfEqualBasins'
    'AttractorsCli\.SerialThreadedAndResumedRunsWriteIdenticalFiles'
    'BoxStack\.StackAtRestStaysWithinTheStatedBound'
    'explore_browser'
    'CommittedReproduction\.RangesAreRederivedFromTheCsv'
    'installed_library_build_example'
    'installed_library_run_example'
    'RigidPendulumSpin\.ThroughTheStickEndTheBranchFollowsTheImpulseOnTheConesEdge'
  )
  exclude="^($(IFS='|'; echo "${release_only[*]}"))( |$)"
  # sanitized code runs several times slower: a longer per-test limit
  if ! ctest --output-on-failure -j"$jobs" --timeout 900 -E "$exclude"; then
    echo "sanitized suite: the failed tests again, with symbolized reports"
    ASAN_OPTIONS="${ASAN_OPTIONS%:symbolize=0}" ctest --rerun-failed --output-on-failure --timeout 900 || true
    exit 1
  fi
  exit 0
fi
scripts/build.sh
cd build
ctest --output-on-failure -j"$jobs" --timeout 300
