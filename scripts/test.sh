#!/usr/bin/env bash
# Installs what is missing, builds servoloop with Ninja, and runs every test suite.
#   BUILD_DIR   build folder (default: build)
#   CMAKE_ARGS  extra configure arguments (e.g. -DSERVOLOOP_SANITIZE=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
# Chromium: the browser view's tests run the page in Debian's headless Chromium.
bash scripts/install_deps.sh chromium
build_dir=${BUILD_DIR:-build}
# shellcheck disable=SC2086
cmake -S . -B "$build_dir" -G Ninja ${CMAKE_ARGS:-}
cmake --build "$build_dir" --parallel 2
ctest --test-dir "$build_dir" --output-on-failure --parallel 2 ${CTEST_ARGS:-}
