#!/usr/bin/env bash
# Builds servoloop with its benchmarks, runs them all and rewrites
# docs/benchmarks.md from their figures (bench/report/benchmarks_report.py).
#
#   scripts/run_benchmarks.sh [--quick] [--only SECTION[,SECTION]]
#
# Environment:
#   BUILD_DIR    build folder (default: <repo>/build, the README's), configured
#                with SERVOLOOP_BUILD_BENCHMARKS=ON
#   RESULTS_DIR  where the outputs and figures.json go (default:
#                $BUILD_DIR/benchmark-results/<UTC time>; with --only, give the
#                folder of an earlier run to keep its other sections' figures)
#   JOBS         parallel build jobs (default 2)
#   WRITE        the page to write (default <repo>/docs/benchmarks.md, none with
#                --quick; empty: none)
# --quick: fewer repetitions and shorter runs, to check that everything runs.
# Nothing else should run on the machine meanwhile: every figure is a time.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
JOBS="${JOBS:-2}"
# A quick run checks that everything runs; its figures do not replace the page's.
if [[ " $* " == *" --quick "* ]]; then WRITE="${WRITE-}"; else WRITE="${WRITE-$ROOT/docs/benchmarks.md}"; fi

echo "== configuring $BUILD_DIR with the benchmarks" >&2
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DSERVOLOOP_BUILD_BENCHMARKS=ON >/dev/null
echo "== building with -j$JOBS" >&2
cmake --build "$BUILD_DIR" -j"$JOBS" >/dev/null

args=(--bin "$BUILD_DIR/bin" "$@")
[[ -n "${RESULTS_DIR:-}" ]] && args+=(--results "$RESULTS_DIR")
[[ -n "$WRITE" ]] && args+=(--write "$WRITE")
exec /usr/bin/python3 "$ROOT/bench/report/benchmarks_report.py" "${args[@]}"
