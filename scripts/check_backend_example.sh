#!/usr/bin/env bash
# Checks that a backend can be written out of tree against the installed
# servoloop, the way docs/writing_a_backend.md walks a user through it:
#   1. installs BUILD_DIR into a fresh temporary prefix (cmake --install) and
#      checks it has what a backend builds on: the servoloop::sim_common target
#      and the headers of sim_common, transmissions and hardware_interface;
#   2. configures and builds examples/custom_backend (the "first_order"
#      simulator) against that prefix only (find_package(servoloop)), with its gtest;
#   3. `<prefix>/bin/servoloop control list-types --json --kind robot_hw`:
#      the installed backends are listed, and first_order (kind robot_hw) only
#      when SERVOLOOP_PLUGIN_PATH names the example's build folder;
#   4. runs the example's gtest (plugin loader by type name, seed URDF, cycles
#      checked against the analytic solution);
#   5. `servoloop launch config/wheel.launch.yaml --backend first_order`: a
#      velocity controller drives the wheel; the recorded joint states follow
#      v(t) = v*·(1 − e^(−(t − t0)/τ)) (τ = 0.05 s, v* = 0.8 rad/s from t0 = 0.05 s);
#   6. installs the example into the package's plugin folder, checks that it
#      finds libservoloop_sim_common there on its own, and lists it with no
#      environment variable.
# Usage: scripts/check_backend_example.sh BUILD_DIR   (BUILD_DIR fully built first)
# Exits non-zero with a message saying what failed. Set CHECK_INSTALL_KEEP=1
# to keep the temporary folder for inspection.
set -euo pipefail

check_name=check_backend_example
# shellcheck source=lib/installed_package.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/installed_package.sh"

begin_check "$@"
example_source=$source_dir/examples/custom_backend
example_type=first_order

# --- 1. install -----------------------------------------------------------------------
install_build_into_prefix
targets_file=$(find "$prefix" -name servoloopTargets.cmake -print -quit)
[[ -n "$targets_file" ]] || fail "the install has no servoloopTargets.cmake (find_package(servoloop) cannot work)"
grep -q 'add_library(servoloop::sim_common ' "$targets_file" ||
  fail "$targets_file does not export servoloop::sim_common (sim_common/CMakeLists.txt must use servoloop_add_library)"
for header in sim_common/sim_robot_hw.hpp sim_common/physics_engine.hpp sim_common/sim_settings.hpp \
              sim_common/joint_command_limiter.hpp transmissions/robot_transmissions.hpp \
              transmissions/transmission_parser.hpp hardware_interface/simulated_robot_hw.hpp \
              hardware_interface/joint_limits_loader.hpp plugin/plugin_register.hpp \
              controller_manager/wall_clock_loop.hpp; do
  [[ -f "$prefix/include/servoloop/$header" ]] || fail "the install lacks the header include/servoloop/$header"
done

# --- 2. build the example against the prefix -------------------------------------------
build_example_against_prefix examples/custom_backend libmy_backends.so -DMY_BACKENDS_BUILD_TESTS=ON \
  -DMY_BACKENDS_SEED_URDF="$source_dir/robots/one_dof/minimal_robot_description.urdf"

# --- 3. list-types --kind robot_hw -------------------------------------------------------
# list_backends <label> <env...>: list-types --json --kind robot_hw with the
# given environment changes; the JSON goes to $work/<label>.json.
list_backends() {
  local label=$1
  shift
  if ! env "$@" "$servoloop_exe" control list-types --json --kind robot_hw >"$work/$label.json" \
       2>"$work/$label.err"; then
    show_log "$work/$label.err"
    fail "servoloop control list-types --json --kind robot_hw ($label) failed"
  fi
}
# check_backends <label> <example library or "">: only robot_hw types; the
# installed mock backend is there; first_order comes from that library (or is absent).
check_backends() {
  python3 - "$work/$1.json" "$1" "$2" "$example_type" <<'PY'
import json, os, sys
path, label, example_library, example_type = sys.argv[1:]
try:
    types = json.load(open(path))
except ValueError as error:
    sys.exit(f"list-types ({label}) printed no valid JSON: {error}")
problems = [f"{e['type']} has kind {e['kind']} although --kind robot_hw was asked"
            for e in types if e["kind"] != "robot_hw"]
if not any(e["type"] == "mock" for e in types):
    problems.append("the installed backend 'mock' is not listed")
found = [e for e in types if e["type"] == example_type]
if example_library:
    if not found:
        problems.append(f"{example_type} is not listed (expected from {example_library})")
    elif os.path.realpath(found[0]["library"]) != os.path.realpath(example_library):
        problems.append(f"{example_type} comes from {found[0]['library']}, expected {example_library}")
elif found:
    problems.append(f"{example_type} is listed although nothing puts it on the path: {found[0]['library']}")
if problems:
    sys.exit(f"list-types ({label}):\n  " + "\n  ".join(problems))
print(f"list-types ({label}): backends " + ", ".join(e["type"] for e in types))
PY
}
step "servoloop control list-types --json --kind robot_hw, installed plugins only"
list_backends no_path -u SERVOLOOP_PLUGIN_PATH
check_backends no_path "" || { cat "$work/no_path.err" >&2; fail "see above"; }
step "servoloop control list-types --json --kind robot_hw with SERVOLOOP_PLUGIN_PATH=<example build folder>"
list_backends plugin_path SERVOLOOP_PLUGIN_PATH="$example_build"
check_backends plugin_path "$example_library" || { cat "$work/plugin_path.err" >&2; fail "see above"; }

# --- 4. the example's gtest ---------------------------------------------------------------
step "running the example's gtest (plugin loader by type name, seed URDF, analytic cycles)"
if ! env -u SERVOLOOP_PLUGIN_PATH "$example_build/my_backends_test" >"$work/gtest.log" 2>&1; then
  show_log "$work/gtest.log"
  fail "the example's gtest failed (see above)"
fi
grep -E '^\[  PASSED  \]' "$work/gtest.log" || fail "the example's gtest ran no test"
! grep -qE '^\[  SKIPPED \]' "$work/gtest.log" || fail "the example's gtest skipped tests (see $work/gtest.log)"

# --- 5. servoloop launch --backend first_order ----------------------------------------------
step "servoloop launch config/wheel.launch.yaml --backend first_order --duration 0.3"
csv=$work/wheel_states.csv
if ! env SERVOLOOP_PLUGIN_PATH="$example_build" "$servoloop_exe" launch \
     "$example_source/config/wheel.launch.yaml" --backend first_order --duration 0.3 --json \
     --pub /wheel/wheel_velocity_controller/command:=0.8@0.05 \
     --record /wheel/joint_states="$csv" >"$work/launch.json" 2>"$work/launch.err"; then
  show_log "$work/launch.err"
  fail "servoloop launch with the first_order backend failed (see above)"
fi
# The command, published at t0 = 0.05 s, reaches the controller at the first
# update at t >= t0 (t0 itself: 0.05 s is a whole number of 1 ms cycles) and the
# backend at that cycle's write. A joint state stamped t is the state after the
# physics step ending at t: at rest until t0, then v(t) = v*·(1 − e^(−(t − t0)/τ)).
python3 - "$csv" <<'PY' || { show_log "$work/launch.err"; fail "the launched wheel did not follow the first-order response"; }
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
if len(rows) < 20:
    sys.exit(f"{sys.argv[1]}: only {len(rows)} joint states recorded (publish_rate 100 over 0.3 s gives 30)")
tau, target, t0 = 0.05, 0.8, 0.05
worst = 0.0
for row in rows:
    t, v = float(row["time"]), float(row["wheel.velocity"])
    expected = target * (1.0 - math.exp(-(t - t0) / tau)) if t > t0 else 0.0
    worst = max(worst, abs(v - expected))
    if abs(v - expected) > 1e-9:
        sys.exit(f"wheel.velocity at t = {t}: {v}, expected 0.8·(1 − e^(−(t − 0.05)/0.05)) = {expected}")
print(f"launch: {len(rows)} joint states from t = {rows[0]['time']} to {rows[-1]['time']} s, "
      f"largest deviation from the analytic response {worst:.1e} rad/s")
PY
python3 - "$work/launch.json" <<'PY' || fail "the launch summary does not show the wheel on first_order"
import json, sys
summary = json.load(open(sys.argv[1]))
backends = [(robot.get("namespace"), robot.get("backend")) for robot in summary.get("robots", [])]
if backends != [("/wheel", "first_order")]:
    sys.exit(f"launch summary: robots {backends}, expected [('/wheel', 'first_order')]")
PY

# --- 6. install the example next to the installed plugins -----------------------------------
step "installing the example into the package's plugin folder"
if ! cmake --install "$example_build" >"$work/example-install.log" 2>&1; then
  show_log "$work/example-install.log"
  fail "cmake --install of the example failed"
fi
[[ -f "$installed_plugin_dir/libmy_backends.so" ]] ||
  fail "the example did not install to \${SERVOLOOP_PLUGIN_DIR} ($installed_plugin_dir)"
# The servoloop executable does not load libservoloop_sim_common itself: the
# installed plugin must find it (in the prefix) through its own RUNPATH.
while IFS= read -r line; do
  [[ "$line" == *"not found"* ]] && fail "the installed libmy_backends.so: a library is not found: $line (INSTALL_RPATH)"
  if [[ "$line" == *libservoloop_* && "$line" != *"=> $prefix/"* ]]; then
    fail "the installed libmy_backends.so loads a servoloop library from outside the install: $line"
  fi
done < <(env -u LD_LIBRARY_PATH ldd "$installed_plugin_dir/libmy_backends.so")
list_backends installed_example -u SERVOLOOP_PLUGIN_PATH
check_backends installed_example "$installed_plugin_dir/libmy_backends.so" ||
  { cat "$work/installed_example.err" >&2; fail "see above"; }

step "OK: an out-of-tree backend builds against the installed servoloop, loads by type name and runs"
