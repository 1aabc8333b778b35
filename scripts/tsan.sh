#!/usr/bin/env bash
# Builds the concurrent parts of servoloop under ThreadSanitizer and runs
# their tests: the controller manager, the control loop, the PID's gains, the topic bus, the
# IPC server and client, the node and its world loop, the command-line clients against a live
# node, the browser view's server against a node, and the fault suite. Any data race or lock-order report fails the run.
#   BUILD_DIR   build folder (default build-tsan)
# The membarrier fence of the controller manager is invisible to TSan; under
# TSan both of its sides use the sequentially consistent fallback
# (controller_manager/src/asymmetric_fence.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
build_dir=${BUILD_DIR:-build-tsan}
tests=(controller_manager_test control_loop_test topic_bus_test ipc_test node_run_test node_ipc_test pid_test
       cli_client_test cli_live_node_test e2e_seed_interactive_test fault_test controllers_test
       e2e_trajectory_action_test world_test world_control_test view_server_test)
cmake -S . -B "$build_dir" -G Ninja -DSERVOLOOP_SANITIZE_THREAD=ON -DSERVOLOOP_BUILD_BENCHMARKS=OFF -DSERVOLOOP_ROS1_BRIDGE=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$build_dir" --parallel 2 --target "${tests[@]}"
pattern="^($(IFS='|'; echo "${tests[*]}"))\$"
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
ctest --test-dir "$build_dir" --output-on-failure --parallel 2 -R "$pattern"
# ctest cannot see a report from a child process that still exited 0; the
# sanitizer's exit code (66) fails that child's test, and this is a backstop.
if grep -rl "WARNING: ThreadSanitizer" "$build_dir/Testing/Temporary" 2>/dev/null; then
  echo "ThreadSanitizer reported a problem (see the logs above)" >&2
  exit 1
fi
