#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for a
# bounded time on a corpus seeded from the repository's own files. Any crash,
# uncaught exception, timeout, leak or sanitizer report fails the run, and the
# input that caused it is kept in the output folder.
#   FUZZ_SECONDS   seconds per target (default 30)
#   BUILD_DIR      build folder (default build-fuzz)
#   FUZZ_TARGETS   the targets to run, separated by spaces (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
bash scripts/install_deps.sh clang libclang-rt-14-dev
seconds=${FUZZ_SECONDS:-30}
build_dir=${BUILD_DIR:-build-fuzz}

CC=clang CXX=clang++ cmake -S . -B "$build_dir" -G Ninja -DSERVOLOOP_FUZZ=ON -DSERVOLOOP_BUILD_TESTS=OFF -DSERVOLOOP_ROS1_BRIDGE=OFF \
  -DSERVOLOOP_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build "$build_dir" --parallel 2 --target servoloop_fuzzers

work=$(mktemp -d /tmp/servoloop-fuzz.XXXXXX)
echo "== fuzzing ${seconds} s per target; corpora and any crashing inputs in $work"

# Seeds: the repository's own inputs of each family.
seed() {
  local name=$1
  shift
  mkdir -p "$work/$name/corpus" "$work/$name/artifacts"
  find "$@" -type f 2>/dev/null | while read -r file; do
    [ "$(stat -c %s "$file")" -le 65536 ] && cp "$file" "$work/$name/corpus/$(echo "$file" | tr '/' '_')"
  done
  return 0
}
seed urdf_fuzz $(find robots tests/assets -name '*.urdf')
seed xacro_fuzz $(find tests/assets -name '*.xacro')
seed params_yaml_fuzz $(find robots examples -name '*.yaml' ! -name '*.launch.yaml')
seed launch_yaml_fuzz $(find robots examples -name '*.launch.yaml')
seed roslaunch_fuzz $(find robots -name '*.launch')
mkdir -p "$work/ipc_request_fuzz/corpus" "$work/ipc_request_fuzz/artifacts"
printf '{"id": 1, "op": "ping"}' > "$work/ipc_request_fuzz/corpus/ping"
printf '{"id": 2, "op": "topic.pub", "topic": "/a/command", "msg": {"data": 1.0}}' > "$work/ipc_request_fuzz/corpus/pub"
mkdir -p "$work/message_json_fuzz/corpus" "$work/message_json_fuzz/artifacts"
printf 'data: 1.0' > "$work/message_json_fuzz/corpus/float"
printf '{name: [j1, j2], position: [0.1, 0.2], velocity: [], effort: []}' > "$work/message_json_fuzz/corpus/joint_state"
printf '[1, 2, 3]' > "$work/message_json_fuzz/corpus/array"
printf '{linear: {x: 0.5}, angular: {z: 1.0}}' > "$work/message_json_fuzz/corpus/twist"
printf '{joint_names: [a, b], points: [{positions: [1, 2], velocities: [0, 0], time_from_start: 1.5}]}' > "$work/message_json_fuzz/corpus/trajectory"

status=0
all_targets="urdf_fuzz xacro_fuzz params_yaml_fuzz launch_yaml_fuzz roslaunch_fuzz ipc_request_fuzz message_json_fuzz"
for target in ${FUZZ_TARGETS:-$all_targets}; do
  log="$work/$target/log.txt"
  if (cd "$work/$target" && "$root/$build_dir/fuzz/$target" corpus -max_total_time="$seconds" -timeout=10 \
        -rss_limit_mb=2048 -max_len=65536 -artifact_prefix=artifacts/ -print_final_stats=1) > "$log" 2>&1; then
    runs=$(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}')
    corpus=$(find "$work/$target/corpus" -type f | wc -l)
    echo "== $target: ok, ${runs:-?} inputs in ${seconds} s; corpus now $corpus inputs"
  else
    status=1
    echo "== $target: FAILED (see $log); the input:"
    ls "$work/$target/artifacts"
    grep -m5 -E 'ERROR|==[0-9]+==|terminate|SUMMARY' "$log" || true
  fi
done
exit $status
