#!/usr/bin/env bash
# The node as users run it, against two references, each pair measured in
# alternating rounds in one window (docs/benchmarks.md, "The node as users run it"):
#
#   1. wall clock: `servoloop launch` of the seed on the mock at 1 kHz on the
#      wall clock (--clock wall) next to `cyclictest` (Debian's rt-tests) at
#      the same 1 ms interval and the same scheduling: wake-up latency p50,
#      p99 and max of each, and servoloop's p99 ÷ cyclictest's. Also the
#      paced cycle's compute time against the free-running one.
#   2. simulation: `servoloop launch --duration` of the seed on bullet,
#      free-running, against raw Bullet stepping of the same robot
#      (servoloop_bench_loop_vs_bullet's loop/seed/raw_bullet): wall time per
#      physics step, node ÷ raw; each round takes the median of 5 node runs,
#      as the harness takes the median of its 5 repetitions. The node's fixed
#      start and end (starting the loop thread, handing over to it and back;
#      no per-step cost) is measured apart, with runs of one step.
#
#   3. whole processes: the same `servoloop launch` against a raw program
#      (servoloop_bench_loop_vs_bullet --raw-process STEPS: loads the seed,
#      builds its Bullet world with its collision shapes, steps it under the
#      position law written out, exits), start to exit, in PAIRS pairs of
#      alternating order; wall and CPU ratios, median of the pairs.
#
#   scripts/bench_node.sh [--quick]
#
# Environment: BUILD_DIR (default <repo>/build), ROUNDS (default 5),
# SECONDS_PER_RUN (default 10: wall seconds of each wall-clock run),
# SIM_SECONDS (default 300: simulated seconds of each bullet run, about half a
# second of wall time, so the fixed start and end weigh little), PRIORITY
# (SCHED_FIFO priority for both in part 1; default 0: the normal scheduler),
# PARTS (default "1 2 3": which parts to run), PAIRS (part 3; default 2·ROUNDS+1).
# Needs python3; part 1 needs cyclictest (apt install rt-tests) and is
# skipped without it.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
BIN="$BUILD_DIR/bin"
ROUNDS="${ROUNDS:-5}"
SECONDS_PER_RUN="${SECONDS_PER_RUN:-10}"
SIM_SECONDS="${SIM_SECONDS:-300}"
PRIORITY="${PRIORITY:-0}"
PARTS="${PARTS:-1 2 3}"
if [[ "${1:-}" == "--quick" ]]; then ROUNDS=2; SECONDS_PER_RUN=2; SIM_SECONDS=5; fi
PAIRS="${PAIRS:-$((2 * ROUNDS + 1))}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
export SERVOLOOP_RUN_DIR="$WORK/run"
mkdir -m 700 "$SERVOLOOP_RUN_DIR"

echo "date (UTC): $(date -u '+%Y-%m-%d %H:%M:%S'); git $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo ?)"
echo "nproc $(nproc); load $(cut -d' ' -f1-3 /proc/loadavg); kernel $(uname -r); cpu:$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
echo "rounds $ROUNDS; wall-clock runs ${SECONDS_PER_RUN} s; bullet runs ${SIM_SECONDS} s simulated; priority $PRIORITY"

# --- 1. wall clock against cyclictest -------------------------------------------
SEED="$ROOT/robots/one_dof"
cat >"$WORK/wall.launch.yaml" <<EOF
world: {backend: mock, time_step: 0.001, clock: wall}
controller_manager: {update_rate: 1000}
$( [[ "$PRIORITY" -gt 0 ]] && echo "realtime: {priority: $PRIORITY, lock_memory: true}" )
robots:
  - urdf: $SEED/minimal_robot_description_w_jnt_ctl.urdf
    model: one_DOF_robot
    params: [$SEED/control_config/one_dof_ctl_params.yaml]
    controllers: [joint_state_controller, joint1_position_controller]
EOF

if [[ " $PARTS " != *" 1 "* ]]; then
  echo "(part 1 not run: PARTS=$PARTS)"
elif command -v cyclictest >/dev/null; then
  echo
  echo "== 1. wake-up latency at 1 kHz: servoloop launch --clock wall (mock) vs cyclictest"
  loops=$((SECONDS_PER_RUN * 1000))
  for round in $(seq "$ROUNDS"); do
    cyclictest -q -m --default-system -t 1 -i 1000 -l "$loops" -p "$PRIORITY" -h 10000 >"$WORK/cyclictest_$round.txt" 2>&1 || true
    "$BIN/servoloop" launch "$WORK/wall.launch.yaml" --duration "$SECONDS_PER_RUN" --json \
      --pub /one_DOF_robot/joint1_position_controller/command:=1.0 >"$WORK/servoloop_$round.json" 2>"$WORK/servoloop_$round.log"
  done
  # Free-running compute time of the same cycle (the mock stepped without sleeping).
  "$BIN/servoloop" launch "$SEED/one_dof_w_jnt_ctl.launch.yaml" --backend mock --duration 30 --json \
    --pub /one_DOF_robot/joint1_position_controller/command:=1.0 >"$WORK/free.json" 2>/dev/null
  python3 - "$WORK" "$ROUNDS" <<'PY'
import json, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])

def cyclictest_figures(path):
    counts, overflow, max_us = {}, 0, None
    for line in open(path):
        if line.startswith("# Max Latencies:"):
            max_us = float(line.split()[3])
        elif line.startswith("# Histogram Overflows:"):
            overflow = int(line.split()[3])
        elif line[:1].isdigit():
            us, count = line.split()[:2]
            counts[int(us)] = int(count)
    total = sum(counts.values()) + overflow
    def percentile(q):
        rank, seen = q * total, 0
        for us in sorted(counts):
            seen += counts[us]
            if seen >= rank:
                return us + 0.5  # the bucket's middle: 1 us buckets
        return max_us
    return percentile(0.5), percentile(0.99), max_us

rows = []
for r in range(1, rounds + 1):
    c50, c99, cmax = cyclictest_figures(f"{work}/cyclictest_{r}.txt")
    loop = json.load(open(f"{work}/servoloop_{r}.json"))["robots"][0]["loop"]
    w = loop["wakeup_latency"]
    rows.append((c50, c99, cmax, w["p50"] * 1e6, w["p99"] * 1e6, w["max"] * 1e6, loop["compute"]["p50"] * 1e6,
                 loop["overruns"], loop["cycles"]))
    print(f"  round {r}: cyclictest p50 {c50:7.1f} p99 {c99:7.1f} max {cmax:8.1f} us | servoloop p50 {rows[-1][3]:7.1f} "
          f"p99 {rows[-1][4]:7.1f} max {rows[-1][5]:8.1f} us, {loop['overruns']} overruns in {loop['cycles']} cycles")
med = lambda i: statistics.median(row[i] for row in rows)
print(f"  median: cyclictest p50 {med(0):.1f} p99 {med(1):.1f} max {med(2):.1f} us; "
      f"servoloop p50 {med(3):.1f} p99 {med(4):.1f} max {med(5):.1f} us")
ratios = [row[4] / row[1] for row in rows]
print(f"  servoloop p99 / cyclictest p99: median {statistics.median(ratios):.2f} "
      f"(rounds: {', '.join(f'{x:.2f}' for x in ratios)}); target <= 1.2")
free = json.load(open(f"{work}/free.json"))["robots"][0]["loop"]["compute"]
print(f"  cycle compute p50: paced on the wall clock {med(6):.2f} us, free-running {free['p50'] * 1e6:.2f} us "
      f"(ratio {med(6) / (free['p50'] * 1e6):.2f})")
PY
else
  echo "== 1. skipped: no cyclictest (apt install rt-tests)"
fi

# --- 2. the node against raw Bullet -------------------------------------------------
if [[ " $PARTS " == *" 2 "* ]]; then
echo
echo "== 2. seed on bullet, free-running: servoloop launch --duration $SIM_SECONDS vs raw Bullet stepping"
for round in $(seq "$ROUNDS"); do
  "$BIN/servoloop_bench_loop_vs_bullet" --benchmark_filter='loop/seed/raw_bullet' --benchmark_repetitions=5 \
    >"$WORK/raw_$round.txt" 2>/dev/null
  # As many node runs as the harness has repetitions; each side's median counts.
  for rep in 1 2 3 4 5; do
    (cd "$ROOT" && "$BIN/servoloop" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml --duration "$SIM_SECONDS" \
      --rtf 0 --json --pub /one_DOF_robot/joint1_position_controller/command:=1.0) >"$WORK/node_${round}_$rep.json" 2>/dev/null
    (cd "$ROOT" && "$BIN/servoloop" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml --duration 0.001 \
      --rtf 0 --json) >"$WORK/fixed_${round}_$rep.json" 2>/dev/null
  done
done
python3 - "$WORK" "$ROUNDS" <<'PY'
import json, re, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
rows = []
for r in range(1, rounds + 1):
    raw = None
    for line in open(f"{work}/raw_{r}.txt"):
        m = re.match(r"\s*loop/seed/raw_bullet\s+([0-9.]+) ns wall", line)  # the harness's median
        if m:
            raw = float(m.group(1))
    runs = [json.load(open(f"{work}/node_{r}_{rep}.json")) for rep in range(1, 6)]
    # what the user waits for, start to end; and the loop thread's own time
    node_ns = statistics.median(s["wall_time"] / s["cycles"] * 1e9 for s in runs)
    loop_ns = statistics.median(s["robots"][0]["loop"]["wall_time"] / s["robots"][0]["loop"]["cycles"] * 1e9 for s in runs)
    rtf = statistics.median(s["real_time_factor"] for s in runs)
    fixed_ms = statistics.median(json.load(open(f"{work}/fixed_{r}_{rep}.json"))["wall_time"] * 1e3 for rep in range(1, 6))
    rows.append((raw, node_ns, loop_ns))
    print(f"  round {r}: raw bullet {raw:7.1f} ns/step | node {node_ns:7.1f} ns/step (loop thread {loop_ns:7.1f}), "
          f"real-time factor {rtf:.0f}; a one-step run {fixed_ms:.2f} ms   (medians of 5 runs each)")
ratios = [n / raw for raw, n, _ in rows]
loop_ratios = [l / raw for raw, _, l in rows]
print(f"  node / raw bullet: median {statistics.median(ratios):.3f} (rounds: {', '.join(f'{x:.3f}' for x in ratios)}); "
      f"loop thread / raw bullet: median {statistics.median(loop_ratios):.3f}; target <= 1.10")
PY
fi

# --- 3. whole processes: the node against the raw program ------------------------------
if [[ " $PARTS " == *" 3 "* ]]; then
  echo
  echo "== 3. seed on bullet, whole processes: servoloop launch --duration $SIM_SECONDS vs the raw program, in pairs"
  PYTHONPATH="$ROOT/bench/report" python3 - "$BIN" "$ROOT" "$SIM_SECONDS" "$PAIRS" <<'PY'
import statistics, sys
from process_timing import paired
bin_dir, root, sim_seconds, pairs = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
steps = str(round(float(sim_seconds) / 0.001))
node = [f"{bin_dir}/servoloop", "launch", "robots/one_dof/one_dof_w_jnt_ctl.launch.yaml", "--duration", sim_seconds,
        "--rtf", "0", "--pub", "/one_DOF_robot/joint1_position_controller/command:=1.0"]
raw = [f"{bin_dir}/servoloop_bench_loop_vs_bullet", "--raw-process", steps]
wall_ratios, cpu_ratios, node_walls, raw_walls = paired(node, raw, pairs, root)
print(f"  raw program {statistics.median(raw_walls) * 1e3:.0f} ms, node {statistics.median(node_walls) * 1e3:.0f} ms "
      f"(medians of {pairs}; {steps} steps)")
print(f"  node / raw, wall: median {statistics.median(wall_ratios):.3f} (pairs {min(wall_ratios):.3f}-{max(wall_ratios):.3f}); "
      f"CPU: median {statistics.median(cpu_ratios):.3f}; target <= 1.05")
PY
fi
