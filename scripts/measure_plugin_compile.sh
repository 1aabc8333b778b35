#!/usr/bin/env bash
# How long a plugin author waits: installs BUILD_DIR into a temporary prefix,
# then configures and builds bench/plugin_compile/fifty_line_controller.cpp (a
# 50-line controller) as an out-of-tree plugin with find_package(servoloop)
# and servoloop_add_plugin(), no build type given, and prints the build time
# (compile and link, configure excluded) of RUNS clean builds, plus the
# preprocessed size of the source.
# Usage: scripts/measure_plugin_compile.sh BUILD_DIR [RUNS]   (default 3 runs)
set -euo pipefail
build_dir=$(cd "${1:?usage: $0 BUILD_DIR [RUNS]}" && pwd)
runs=${2:-3}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d /tmp/servoloop-plugin-compile.XXXXXX)
trap 'rm -rf "$work"' EXIT

cmake --install "$build_dir" --prefix "$work/prefix" >"$work/install.log"
mkdir -p "$work/project"
cp "$source_dir/bench/plugin_compile/fifty_line_controller.cpp" "$work/project/"
cat >"$work/project/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(fifty_line LANGUAGES CXX)
find_package(servoloop REQUIRED)
servoloop_add_plugin(fifty_line NO_PRECOMPILED_HEADERS SOURCES fifty_line_controller.cpp LINK servoloop::controller_manager servoloop::plugin)
CMAKE
cmake -S "$work/project" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log"
lines=$(c++ -std=c++20 -E $(sed -n 's/.*-isystem \([^ ]*\).*/-I\1/p' <(ninja -C "$work/build" -t commands | head -1) | head -1) \
  -I"$work/prefix/include" -I/usr/include/eigen3 "$work/project/fifty_line_controller.cpp" | wc -l)
echo "preprocessed: $lines lines"
for i in $(seq "$runs"); do
  ninja -C "$work/build" -t clean >/dev/null
  start=$(date +%s.%N)
  ninja -C "$work/build" >/dev/null
  end=$(date +%s.%N)
  awk -v i="$i" -v a="$start" -v b="$end" 'BEGIN { printf "build %d: %.2f s\n", i, b - a }'
done
