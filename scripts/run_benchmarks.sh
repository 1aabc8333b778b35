#!/usr/bin/env bash
# Builds servoloop's benchmarks and runs them all; see docs/benchmarks.md.
#
#   scripts/run_benchmarks.sh [--quick]
#
# Environment:
#   BUILD_DIR        build folder (default: <repo>/build-bench), configured
#                    RelWithDebInfo with SERVOLOOP_BUILD_BENCHMARKS=ON
#   RESULTS_DIR      where the figures go (default: $BUILD_DIR/benchmark-results/<UTC date-time>)
#   JOBS             parallel build jobs (default 2)
#   SPAWNER_RUNS     spawner round trips to time (default 30)
#   LAUNCH_RUNS      `servoloop launch --duration 30` runs to time (default 3)
# --quick: fewer repetitions and shorter runs, to check that everything works.
#
# Every benchmark prints its figures and, at the end, ratios of medians taken
# in the same run (the machine may be shared; see docs/benchmarks.md).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-bench}"
JOBS="${JOBS:-2}"
SPAWNER_RUNS="${SPAWNER_RUNS:-30}"
LAUNCH_RUNS="${LAUNCH_RUNS:-3}"
QUICK=0
if [[ "${1:-}" == "--quick" ]]; then QUICK=1; fi
RESULTS_DIR="${RESULTS_DIR:-$BUILD_DIR/benchmark-results/$(date -u +%Y%m%dT%H%M%SZ)}"
mkdir -p "$RESULTS_DIR"
BIN="$BUILD_DIR/bin"

log() { echo "== $*" >&2; }

# --- machine and load ---------------------------------------------------------
machine_info() {
  echo "date (UTC): $(date -u '+%Y-%m-%d %H:%M:%S')"
  echo "git: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "nproc: $(nproc)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "load average (1/5/15 min): $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "kernel: $(uname -r)"
}

# --- build -------------------------------------------------------------------------
log "configuring $BUILD_DIR (RelWithDebInfo, benchmarks on)"
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSERVOLOOP_BUILD_BENCHMARKS=ON >"$RESULTS_DIR/configure.log"
targets=(servoloop_benchmarks)
# grep reads the whole list: grep -q would stop early, cut the pipe and, with
# pipefail, make the test fail even when the target is there.
if cmake --build "$BUILD_DIR" --target help | grep '^servoloop:' >/dev/null; then targets+=(servoloop); fi
log "building ${targets[*]} with -j$JOBS"
cmake --build "$BUILD_DIR" -j"$JOBS" --target "${targets[@]}" >"$RESULTS_DIR/build.log"

{ echo "[before]"; machine_info; } >"$RESULTS_DIR/machine.txt"

# --- 1 and 2: Google Benchmark executables -------------------------------------------------
if [[ $QUICK == 1 ]]; then
  manager_flags=(--benchmark_repetitions=3 --benchmark_min_time=0.01)
  loop_flags=(--benchmark_repetitions=3)
else
  manager_flags=()
  loop_flags=()
fi

log "1. controller manager cost per cycle"
"$BIN/servoloop_bench_controller_manager" "${manager_flags[@]}" --benchmark_color=false \
  --benchmark_out="$RESULTS_DIR/controller_manager.json" --benchmark_out_format=json \
  | tee "$RESULTS_DIR/controller_manager.txt"

log "2. whole loop vs raw Bullet"
"$BIN/servoloop_bench_loop_vs_bullet" "${loop_flags[@]}" --benchmark_color=false \
  --benchmark_out="$RESULTS_DIR/loop_vs_bullet.json" --benchmark_out_format=json \
  | tee "$RESULTS_DIR/loop_vs_bullet.txt"
[[ -x "$BIN/servoloop_bench_loop_vs_mujoco" ]] && { log "5. whole loop vs raw MuJoCo, raw Bullet vs raw MuJoCo"; "$BIN/servoloop_bench_loop_vs_mujoco" "${loop_flags[@]}" --benchmark_color=false --benchmark_out="$RESULTS_DIR/loop_vs_mujoco.json" --benchmark_out_format=json | tee "$RESULTS_DIR/loop_vs_mujoco.txt"; }

# --- 3: headless real-time factor of the seed run -------------------------------------------
duration=30
[[ $QUICK == 1 ]] && duration=3
log "3. seed real-time factor, in process"
"$BIN/servoloop_bench_seed_rtf" --duration "$duration" --repetitions 5 | tee "$RESULTS_DIR/seed_rtf_in_process.txt"

has_subcommand() { [[ -x "$BIN/servoloop" ]] && "$BIN/servoloop" "$1" --help >/dev/null 2>&1; }

median_of() { sort -g | awk '{v[NR]=$1} END {if (NR==0) {print "nan"; exit} m=(NR%2)?v[(NR+1)/2]:(v[NR/2]+v[NR/2+1])/2; print m}'; }

RUN_DIR="$(mktemp -d /tmp/servoloop-bench-run.XXXXXX)"
chmod 700 "$RUN_DIR"
export SERVOLOOP_RUN_DIR="$RUN_DIR"
NODE_PID=""
cleanup() {
  if [[ -n "$NODE_PID" ]]; then kill -INT "$NODE_PID" 2>/dev/null || true; wait "$NODE_PID" 2>/dev/null || true; fi
  rm -rf "$RUN_DIR"
}
trap cleanup EXIT

if has_subcommand launch; then
  log "3. seed real-time factor, servoloop launch --duration $duration --json ($LAUNCH_RUNS runs)"
  : >"$RESULTS_DIR/seed_rtf_launch.txt"
  for run in $(seq 1 "$LAUNCH_RUNS"); do
    start_ns=$(date +%s%N)
    (cd "$ROOT" && "$BIN/servoloop" launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml \
      --duration "$duration" --json) >"$RESULTS_DIR/seed_rtf_launch_$run.json" 2>"$RESULTS_DIR/seed_rtf_launch_$run.log"
    end_ns=$(date +%s%N)
    python3 - "$RESULTS_DIR/seed_rtf_launch_$run.json" "$duration" "$(( (end_ns - start_ns) / 1000 ))" \
      >>"$RESULTS_DIR/seed_rtf_launch.txt" <<'EOF'
import json, sys
summary = json.load(open(sys.argv[1]))
duration, process_us = float(sys.argv[2]), int(sys.argv[3])
print(f"loop RTF {summary['real_time_factor']:.1f} (sim {summary['sim_time']:.1f} s in {summary['wall_time']:.3f} s);"
      f" whole command {process_us / 1e6:.3f} s -> RTF incl. start-up {duration / (process_us / 1e6):.1f}")
EOF
  done
  cat "$RESULTS_DIR/seed_rtf_launch.txt"
  echo "median loop RTF: $(sed -E 's/^loop RTF ([0-9.]+).*/\1/' "$RESULTS_DIR/seed_rtf_launch.txt" | median_of)" \
    | tee -a "$RESULTS_DIR/seed_rtf_launch.txt"
else
  echo "servoloop launch is not built; see docs/benchmarks.md (TODO)" | tee "$RESULTS_DIR/seed_rtf_launch.txt"
fi

# --- 4: spawner round trip against a running node ------------------------------------------------
if has_subcommand launch && has_subcommand spawner && has_subcommand control; then
  log "4. spawner round trip ($SPAWNER_RUNS runs)"
  (cd "$ROOT" && exec "$BIN/servoloop" launch bench/launch/one_dof_idle.launch.yaml) \
    >"$RESULTS_DIR/spawner_node.log" 2>&1 &
  NODE_PID=$!
  for _ in $(seq 1 100); do
    [[ -S "$RUN_DIR/one_DOF_robot.sock" ]] && break
    sleep 0.1
  done
  ns=(-N /one_DOF_robot)
  controllers=(joint_state_controller joint1_position_controller)
  : >"$RESULTS_DIR/spawner_ms.txt"
  : >"$RESULTS_DIR/control_list_ms.txt"
  for _ in $(seq 1 "$SPAWNER_RUNS"); do
    start_ns=$(date +%s%N)
    "$BIN/servoloop" spawner "${ns[@]}" "${controllers[@]}" >/dev/null 2>>"$RESULTS_DIR/spawner.log"
    end_ns=$(date +%s%N)
    awk -v d=$((end_ns - start_ns)) 'BEGIN {printf "%.3f\n", d / 1e6}' >>"$RESULTS_DIR/spawner_ms.txt"
    # Reference: one request and its reply (process start-up, connect, list).
    start_ns=$(date +%s%N)
    "$BIN/servoloop" control list "${ns[@]}" >/dev/null 2>>"$RESULTS_DIR/spawner.log"
    end_ns=$(date +%s%N)
    awk -v d=$((end_ns - start_ns)) 'BEGIN {printf "%.3f\n", d / 1e6}' >>"$RESULTS_DIR/control_list_ms.txt"
    # Back to no controller (not timed).
    "$BIN/servoloop" control stop "${ns[@]}" "${controllers[@]}" >/dev/null 2>>"$RESULTS_DIR/spawner.log"
    "$BIN/servoloop" control unload "${ns[@]}" "${controllers[@]}" >/dev/null 2>>"$RESULTS_DIR/spawner.log"
  done
  {
    echo "spawner round trip (process start, connect, load 2, start 2 in one switch, exit):"
    echo "  median $(median_of <"$RESULTS_DIR/spawner_ms.txt") ms over $SPAWNER_RUNS runs" \
      "(min $(sort -g "$RESULTS_DIR/spawner_ms.txt" | head -1), max $(sort -g "$RESULTS_DIR/spawner_ms.txt" | tail -1)); target < 50 ms"
    echo "reference, servoloop control list (process start, connect, one request):"
    echo "  median $(median_of <"$RESULTS_DIR/control_list_ms.txt") ms"
  } | tee "$RESULTS_DIR/spawner.txt"
  kill -INT "$NODE_PID" 2>/dev/null || true
  wait "$NODE_PID" 2>/dev/null || true
  NODE_PID=""
else
  echo "servoloop launch/spawner/control are not built; see docs/benchmarks.md (TODO)" | tee "$RESULTS_DIR/spawner.txt"
fi

{ echo; echo "[after]"; machine_info; } >>"$RESULTS_DIR/machine.txt"
cat "$RESULTS_DIR/machine.txt"
log "figures in $RESULTS_DIR"
