#!/usr/bin/env bash
# Soak: the seed robot on Bullet at real-time factor 1 for SOAK_SECONDS of
# simulated time (default 600, ten minutes), serving its socket, with a
# subscriber (`topic echo` of the joint states) and a publisher (`topic pub
# -r 50` of the position command) connected all the way. The node's resident
# memory, open files, threads and loop overruns are taken once the run has
# settled (SOAK_WARMUP_SECONDS of wall time, default 30) and again just before
# it ends; the run fails if open files or threads grew, if resident memory
# grew by more than SOAK_MAX_RSS_GROWTH_KB (default 2048), if the subscriber
# missed messages, or if the node did not end cleanly. Figures go to stdout;
# docs/reliability.md keeps a run's.
#   SERVOLOOP_EXE  the servoloop command (default build/bin/servoloop)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh python3
seconds=${SOAK_SECONDS:-600}
warmup=${SOAK_WARMUP_SECONDS:-30}
max_rss_growth_kb=${SOAK_MAX_RSS_GROWTH_KB:-2048}
exe=$(realpath "${SERVOLOOP_EXE:-build/bin/servoloop}")
work=$(mktemp -d /tmp/servoloop-soak.XXXXXX)
export SERVOLOOP_RUN_DIR="$work/run"
socket="$SERVOLOOP_RUN_DIR/one_DOF_robot.sock"
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$work"' EXIT

# One request on the node's socket; prints the reply line (empty if none).
ping() {
  python3 - "$socket" <<'PY' 2>/dev/null || true
import json, socket, sys
s = socket.socket(socket.AF_UNIX)
s.settimeout(5)
s.connect(sys.argv[1])
s.sendall(b'{"id": 1, "op": "ping"}\n')
data = b""
while b"\n" not in data:
    chunk = s.recv(4096)
    if not chunk:
        break
    data += chunk
print(data.split(b"\n")[0].decode())
PY
}
field() { python3 -c 'import json,sys; r=json.loads(sys.argv[1]); print(eval(sys.argv[2], {}, {"r": r}))' "$1" "$2"; }

# Resident memory (kB), open files, threads, loop cycles and overruns.
sample() {
  local reply
  reply=$(ping)
  echo "$(awk '/^VmRSS/ {print $2}' "/proc/$node/status") $(ls "/proc/$node/fd" | wc -l) \
$(ls "/proc/$node/task" | wc -l) $(field "$reply" 'r["loop"]["cycles"]') $(field "$reply" 'r["loop"]["overruns"]') \
$(field "$reply" 'r["sim_time"]')"
}

echo "== soak: $seconds s of simulated time at real-time factor 1 (Bullet), $(nproc) CPUs, $(uname -r)"
"$exe" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml --duration "$seconds" --rtf 1 --ipc --json \
  > "$work/summary.json" 2> "$work/node.err" &
node=$!
pids+=("$node")
for _ in $(seq 600); do [ -n "$(ping)" ] && break; sleep 0.1; done
[ -n "$(ping)" ] || { echo "the node did not start:" >&2; cat "$work/node.err" >&2; exit 1; }

"$exe" topic echo --json /one_DOF_robot/joint_states > "$work/echo.jsonl" 2> "$work/echo.err" &
pids+=($!)
"$exe" topic pub -r 50 /one_DOF_robot/joint1_position_controller/command std_msgs/Float64 1.0 \
  > /dev/null 2> "$work/pub.err" &
pids+=($!)

sleep "$warmup"
read -r rss0 fds0 threads0 cycles0 overruns0 sim0 <<< "$(sample)"
# The last sample a few simulated seconds before the end.
while true; do
  sim=$(field "$(ping)" 'r["sim_time"]')
  python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) - 3 else 1)" "$sim" "$seconds" && break
  sleep 2
done
read -r rss1 fds1 threads1 cycles1 overruns1 sim1 <<< "$(sample)"
wait "$node" || { echo "the node failed:" >&2; cat "$work/node.err" >&2; exit 1; }
messages=$(wc -l < "$work/echo.jsonl")
first=$(head -1 "$work/echo.jsonl" | python3 -c 'import json,sys; print(json.load(sys.stdin)["stamp"])')
last=$(tail -1 "$work/echo.jsonl" | python3 -c 'import json,sys; print(json.load(sys.stdin)["stamp"])')
expected=$(python3 -c "print(round(($last - $first) / 0.02) + 1)")
summary_overruns=$(python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(sum(r["loop"]["overruns"] for r in s["robots"]))' "$work/summary.json")
rtf=$(python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(round(s["real_time_factor"], 4))' "$work/summary.json")

printf '%-22s %14s %14s\n' "" "after ${warmup} s" "before the end"
printf '%-22s %14s %14s\n' "simulated time (s)" "$sim0" "$sim1"
printf '%-22s %14s %14s\n' "resident memory (kB)" "$rss0" "$rss1"
printf '%-22s %14s %14s\n' "open files" "$fds0" "$fds1"
printf '%-22s %14s %14s\n' "threads" "$threads0" "$threads1"
printf '%-22s %14s %14s\n' "loop cycles" "$cycles0" "$cycles1"
printf '%-22s %14s %14s\n' "overruns" "$overruns0" "$overruns1"
echo "whole run: real-time factor $rtf, $summary_overruns overruns; subscriber: $messages joint states from t = $first s to $last s ($expected expected at 50 Hz)"

status=0
[ "$fds1" -le "$fds0" ] || { echo "FAIL: open files grew" >&2; status=1; }
[ "$threads1" -le "$threads0" ] || { echo "FAIL: threads grew" >&2; status=1; }
[ $((rss1 - rss0)) -le "$max_rss_growth_kb" ] || { echo "FAIL: resident memory grew by $((rss1 - rss0)) kB" >&2; status=1; }
[ "$messages" -eq "$expected" ] || { echo "FAIL: the subscriber got $messages of $expected joint states" >&2; status=1; }
[ "$status" -eq 0 ] && echo "== soak: ok"
exit "$status"
