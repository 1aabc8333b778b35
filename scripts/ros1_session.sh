# Sourced by the scripts that run ROS 1 next to servoloop (bench_ros1.sh,
# ros1_rviz_screenshot.sh): a private scratch folder, run directory and ROS
# home, a free port for roscore, PYTHONPATH for the generated message
# packages, and `start_background CMD...`, whose processes (and their
# sessions) are stopped when the script exits. Expects $bin (the build's bin/).
scratch=$(mktemp -d /tmp/servoloop-ros1.XXXXXX)
export SERVOLOOP_RUN_DIR="$scratch/run" ROS_HOME="$scratch/ros" ROS_LOG_DIR="$scratch/ros/log" ROS_HOSTNAME=localhost
mkdir -p "$SERVOLOOP_RUN_DIR" && chmod 700 "$SERVOLOOP_RUN_DIR"
ros_port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://localhost:$ros_port"
eval "$("$bin/servoloop" ros1-bridge --print-env)"
background_pids=()
stop_background() {
  for pid in "${background_pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  sleep 2
  for pid in "${background_pids[@]}"; do kill -KILL -- "-$pid" 2>/dev/null || kill -KILL "$pid" 2>/dev/null || true; done
  rm -rf "$scratch"
}
trap stop_background EXIT
# start_background LOG CMD...: runs CMD in its own session, output to $scratch/LOG.
start_background() {
  local log=$1
  shift
  setsid "$@" > "$scratch/$log" 2>&1 &
  background_pids+=($!)
}
# roscore on the free port, waited for.
start_roscore() {
  start_background roscore.log roscore -p "$ros_port"
  until rosparam get /rosdistro > /dev/null 2>&1; do sleep 0.2; done
}
