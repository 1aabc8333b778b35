#!/usr/bin/env bash
# The ROS 1 bridge's figures (docs/benchmarks.md, "The ROS 1 bridge"): command
# latency from a ROS publisher to the node's bus (against the same commands
# over the node's socket), joint-state delivery at 50 Hz and 1 kHz, and the
# loop's statistics under the same client work without and with the bridge.
# Needs a build with the bridge (bash scripts/install_ros1.sh, then build) and
# runs roscore on a free port.
#   BUILD_DIR  build folder (default: build)
#   PIN=1      the loop thread alone on CPU 1 (the launch file's
#              realtime.cpu_affinity), everything else (the node's other
#              threads, ROS, the bridge, the harness) on CPU 0
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${PIN:-0}" = 1 ] && [ -z "${SERVOLOOP_BENCH_PINNED:-}" ]; then
  SERVOLOOP_BENCH_PINNED=1 exec taskset -c 0 bash "$0" "$@"
fi
build=${BUILD_DIR:-build}
bin="$build/bin"
[ -x "$bin/servoloop_ros1_bridge" ] || { echo "no ROS 1 bridge in $build: bash scripts/install_ros1.sh, then build" >&2; exit 1; }

# shellcheck source=scripts/ros1_session.sh
source scripts/ros1_session.sh
ns=/one_DOF_robot
start_roscore
launch_file=robots/one_dof/one_dof_w_jnt_ctl.launch.yaml
if [ -n "${SERVOLOOP_BENCH_PINNED:-}" ]; then
  # The seed's launch file with the loop thread on CPU 1 (paths made absolute).
  launch_file="$scratch/pinned.launch.yaml"
  sed -e "s|^  - urdf: |  - urdf: $PWD/robots/one_dof/|" -e "s|params: \[|params: [$PWD/robots/one_dof/|" \
    robots/one_dof/one_dof_w_jnt_ctl.launch.yaml > "$launch_file"
  printf 'realtime:\n  cpu_affinity: [1]\n' >> "$launch_file"
fi
start_background node.log "$bin/servoloop" launch "$launch_file" --rtf 1
until "$bin/servoloop" control list -N $ns 2>/dev/null | grep -q "joint1_position_controller.*running"; do sleep 0.2; done

stats() {  # the loop's compute time and the wake-up latency, p50/p99/max in us
  "$bin/servoloop" control stats -N $ns --json | /usr/bin/python3 -c '
import json, sys
s = json.load(sys.stdin)["loop"]
c = s["compute"]
print("cycles %d, overruns %d; compute p50 %.2f us, p99 %.2f us, max %.1f us" % (
    s["cycles"], s["overruns"], c["p50"] * 1e6, c["p99"] * 1e6, c["max"] * 1e6))'
}

# Two windows of the same client work, 10 s each at --rtf 1: commands at
# 100 Hz into the node and the 50 Hz joint states out of it; first over the
# node's socket (what `servoloop topic pub/echo` do), then from and to ROS
# through the bridge. The loop's statistics are taken over each window.
echo "== window 1: over the node's socket (no bridge)"
"$bin/servoloop" control stats -N $ns --reset > /dev/null 2>&1
"$bin/servoloop" topic echo $ns/joint_states > /dev/null 2>&1 & echo_pid=$!
"$bin/servoloop_bench_ros1_bridge" --mode ipc-latency --topic $ns/joint1_position_controller/command --count 1000 --rate 100
kill -INT $echo_pid; wait $echo_pid 2>/dev/null || true
echo "loop: $(stats)"

start_background bridge.log "$bin/servoloop" ros1-bridge -N $ns
until rostopic list 2>/dev/null | grep -q "$ns/joint_states"; do sleep 0.2; done
sleep 2
echo "== window 2: from and to ROS through the bridge"
"$bin/servoloop" control stats -N $ns --reset > /dev/null 2>&1
"$bin/servoloop_bench_ros1_bridge" --mode delivery --topic $ns/joint_states --period 0.02 --seconds 10 & delivery_pid=$!
"$bin/servoloop_bench_ros1_bridge" --mode ros-latency --topic $ns/joint1_position_controller/command --count 1000 --rate 100
wait $delivery_pid
echo "loop: $(stats)"

echo "== joint states at 1 kHz in ROS"
"$bin/servoloop" control switch -N $ns --stop joint_state_controller > /dev/null
"$bin/servoloop" control unload -N $ns joint_state_controller > /dev/null
"$bin/servoloop" param set -N $ns $ns/joint_state_controller/publish_rate 1000 > /dev/null
"$bin/servoloop" control load -N $ns joint_state_controller > /dev/null
"$bin/servoloop" control switch -N $ns --start joint_state_controller > /dev/null
sleep 1
"$bin/servoloop_bench_ros1_bridge" --mode delivery --topic $ns/joint_states --period 0.001 --seconds 10
echo "== (conditions: ${SERVOLOOP_BENCH_PINNED:+loop thread alone on CPU 1, the rest on CPU 0; }$(nproc --all) CPUs, $(uname -r), commit $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $(date -u +%F))"
