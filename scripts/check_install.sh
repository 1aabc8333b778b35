#!/usr/bin/env bash
# Checks that servoloop works as an installed package, the way a user who
# writes a controller out of tree uses it:
#   1. installs BUILD_DIR into a fresh temporary prefix (cmake --install);
#   2. configures and builds examples/custom_controller against that prefix
#      only (find_package(servoloop), Ninja), with its gtest;
#   3. checks `<prefix>/bin/servoloop control list-types --json`: the installed
#      plugins are found with no environment variable, the example's type is
#      found through SERVOLOOP_PLUGIN_PATH, and again after it is installed
#      into the package's plugin folder;
#   4. runs the example's gtest (plugin loader + test RobotHW + hand-computed efforts).
# Usage: scripts/check_install.sh BUILD_DIR   (BUILD_DIR fully built first)
# Exits non-zero with a message saying what failed. Set CHECK_INSTALL_KEEP=1
# to keep the temporary folder for inspection.
set -euo pipefail

check_name=check_install
# shellcheck source=lib/installed_package.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/installed_package.sh"

begin_check "$@"
example_source=$source_dir/examples/custom_controller
example_type=my_controllers/GravityCompensatedPD

# --- 1. install ---------------------------------------------------------------------
install_build_into_prefix
config=$(find "$prefix" -name servoloopConfig.cmake -print -quit)
[[ -n "$config" ]] || fail "the install has no servoloopConfig.cmake (find_package(servoloop) cannot work)"
# The installed headers are exactly the ones authors start from
# (tests/install/author_headers.txt) and the servoloop headers those include.
step "checking the installed headers against tests/install/author_headers.txt"
python3 - "$prefix/include" "$source_dir/tests/install/author_headers.txt" <<'PY' || fail "see above"
import os, re, sys
include_dir, list_file = sys.argv[1:]
entries = [line.strip() for line in open(list_file) if line.strip() and not line.startswith("#")]
installed = {os.path.relpath(os.path.join(folder, name), include_dir)
             for folder, _, names in os.walk(os.path.join(include_dir, "servoloop")) for name in names}
problems, needed, pending = [], set(), [(header, list_file) for header in entries]
while pending:
    header, included_by = pending.pop()
    if header in needed:
        continue
    needed.add(header)
    if header not in installed:
        problems.append(f"{header} (included by {os.path.basename(included_by)}) is not installed: "
                        "add it to its module's INSTALL_HEADERS")
        continue
    text = open(os.path.join(include_dir, header)).read()
    pending += [(match, header) for match in re.findall(r'#include "(servoloop/[^"]+)"', text)]
for header in sorted(installed - needed):
    problems.append(f"{header} is installed but no author header needs it: drop it from INSTALL_HEADERS, "
                    "or add it to tests/install/author_headers.txt if authors include it")
if problems:
    sys.exit("installed headers:\n  " + "\n  ".join(problems))
print(f"installed headers: {len(installed)}, exactly the {len(entries)} author headers and what they include")
PY
step "compiling the author headers together against the installed package alone"
{
  grep -v '^#' "$source_dir/tests/install/author_headers.txt" | sed -n 's|^\(servoloop/.*\)$|#include "\1"|p'
} >"$work/author_headers.cpp"
cxx=$(cache_value CMAKE_CXX_COMPILER)
if ! "${cxx:-c++}" -std=c++20 -fsyntax-only -I"$prefix/include" -I/usr/include/eigen3 \
    "$work/author_headers.cpp" >"$work/author_headers.log" 2>&1; then
  show_log "$work/author_headers.log"
  fail "the author headers do not compile against the installed package alone (see above)"
fi

# Every servoloop library the installed binaries and plugins load must come from
# the prefix itself (RUNPATH), not from the build folder.
check_runpath() {
  local binary=$1 line
  while IFS= read -r line; do
    [[ "$line" == *"not found"* ]] && fail "$binary: a library is not found: $line"
    if [[ "$line" == *libservoloop_* && "$line" != *"=> $prefix/"* ]]; then
      fail "$binary loads a servoloop library from outside the install: $line (check CMAKE_INSTALL_RPATH)"
    fi
  done < <(env -u LD_LIBRARY_PATH ldd "$binary")
}
check_runpath "$servoloop_exe"
shopt -s nullglob
installed_plugins=("$installed_plugin_dir"/*.so)
shopt -u nullglob
for plugin in "${installed_plugins[@]}"; do check_runpath "$plugin"; done
echo "installed: ${#installed_plugins[@]} plugin libraries in ${installed_plugin_dir#"$prefix"/}"

# --- 2. build the example against the prefix -----------------------------------------
build_example_against_prefix examples/custom_controller libmy_controllers.so -DMY_CONTROLLERS_BUILD_TESTS=ON

# --- 3. list-types -------------------------------------------------------------------
# list_types <label> <env...>: runs list-types --json with the given environment
# changes; the JSON goes to $work/<label>.json.
list_types() {
  local label=$1
  shift
  if ! env "$@" "$servoloop_exe" control list-types --json >"$work/$label.json" 2>"$work/$label.err"; then
    show_log "$work/$label.err"
    fail "servoloop control list-types --json ($label) failed"
  fi
}
# check_types <label> <example library or ""> : the installed plugins each
# provide a type; the example type comes from that library (or is absent).
check_types() {
  python3 - "$work/$1.json" "$1" "$2" "$example_type" "$build_dir" \
    "${installed_plugins[@]}" <<'PY'
import json, os, sys
path, label, example_library, example_type, build_dir, *installed = sys.argv[1:]
problems = []
try:
    types = json.load(open(path))
except ValueError as error:
    sys.exit(f"list-types ({label}) printed no valid JSON: {error}")
by_library = {}
for entry in types:
    by_library.setdefault(os.path.realpath(entry["library"]), []).append(entry["type"])
    if os.path.realpath(entry["library"]).startswith(build_dir + os.sep):
        problems.append(f"type {entry['type']} comes from the build folder: {entry['library']}")
for library in installed:
    if not by_library.get(os.path.realpath(library)):
        problems.append(f"installed plugin {os.path.basename(library)} provides no type "
                        f"(it failed to load: see the warnings above)")
found = [e for e in types if e["type"] == example_type]
if example_library:
    if not found:
        problems.append(f"{example_type} is not listed (expected from {example_library})")
    elif os.path.realpath(found[0]["library"]) != os.path.realpath(example_library):
        problems.append(f"{example_type} comes from {found[0]['library']}, expected {example_library}")
    elif found[0]["kind"] != "controller":
        problems.append(f"{example_type} has kind {found[0]['kind']}, expected controller")
elif found:
    problems.append(f"{example_type} is listed although nothing puts it on the path: {found[0]['library']}")
if problems:
    sys.exit(f"list-types ({label}):\n  " + "\n  ".join(problems))
print(f"list-types ({label}): {len(types)} types, " +
      (f"{example_type} from {example_library}"
       if example_library else f"{example_type} absent as expected"))
PY
}
step "servoloop control list-types --json, installed plugins only (no SERVOLOOP_PLUGIN_PATH)"
list_types no_path -u SERVOLOOP_PLUGIN_PATH
check_types no_path "" || { cat "$work/no_path.err" >&2; fail "see above"; }
step "servoloop control list-types --json with SERVOLOOP_PLUGIN_PATH=<example build folder>"
list_types plugin_path SERVOLOOP_PLUGIN_PATH="$example_build"
check_types plugin_path "$example_library" || { cat "$work/plugin_path.err" >&2; fail "see above"; }

# --- 4. the example's gtest ------------------------------------------------------------
step "running the example's gtest (plugin loader, test RobotHW, hand-computed efforts)"
if ! env -u SERVOLOOP_PLUGIN_PATH "$example_build/my_controllers_test" >"$work/gtest.log" 2>&1; then
  show_log "$work/gtest.log"
  fail "the example's gtest failed (see above)"
fi
grep -E '^\[  PASSED  \]' "$work/gtest.log" || fail "the example's gtest ran no test"

# --- 5. install the example next to the installed plugins --------------------------------
step "installing the example into the package's plugin folder"
if ! cmake --install "$example_build" >"$work/example-install.log" 2>&1; then
  show_log "$work/example-install.log"
  fail "cmake --install of the example failed"
fi
[[ -f "$installed_plugin_dir/libmy_controllers.so" ]] ||
  fail "the example did not install to \${SERVOLOOP_PLUGIN_DIR} ($installed_plugin_dir)"
list_types installed_example -u SERVOLOOP_PLUGIN_PATH
check_types installed_example "$installed_plugin_dir/libmy_controllers.so" ||
  { cat "$work/installed_example.err" >&2; fail "see above"; }

# --- 6a. an SDF world, read by the installed SDF reader module ----------------------------
step "the installed servoloop launches an SDF world (its SDF reader module loaded from the prefix)"
cat >"$work/box.world" <<'SDF'
<?xml version="1.0"?>
<sdf version="1.6"><world name="w">
  <include><uri>model://ground_plane</uri></include>
  <model name="box"><pose>0 0 0.5 0 0 0</pose><link name="link">
    <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
  </link></model>
</world></sdf>
SDF
if ! env -u SERVOLOOP_PLUGIN_PATH "$prefix/bin/servoloop" launch "$work/box.world" --duration 0.1 \
    >"$work/world.log" 2>&1; then
  show_log "$work/world.log"
  fail "the installed servoloop could not launch an SDF world"
fi
grep -q "libservoloop_sdf_reader" <(LD_DEBUG=files env -u SERVOLOOP_PLUGIN_PATH "$prefix/bin/servoloop" \
    launch "$work/box.world" --duration 0.01 2>&1) || fail "the SDF world was not read by the installed SDF reader"

# --- 6. the Python package ----------------------------------------------------------------
python_module=$(find "$prefix" -name '_servoloop*.so' -print -quit)
if [[ -n "$python_module" ]]; then
  python_root=$(dirname "$(dirname "$python_module")")
  step "the installed Python package runs a world (PYTHONPATH=$python_root, installed plugins only)"
  if ! env -u SERVOLOOP_PLUGIN_PATH PYTHONPATH="$python_root" /usr/bin/python3 - "$source_dir" >"$work/python.log" 2>&1 <<'PY'
import os, sys
import servoloop
launch = os.path.join(sys.argv[1], "robots", "one_dof", "one_dof_w_jnt_ctl.launch.yaml")
with servoloop.World(launch) as world:
    assert world.step(0.25) == 250, world.time
    assert world.joint_state()["name"] == ["joint1"]
print("World ran", world)
PY
  then
    show_log "$work/python.log"
    fail "the installed Python package did not run a world"
  fi
  step "the installed servoloop sweep runs a sweep with the installed Python package"
  cat >"$work/tiny.sweep.yaml" <<YAML
launch: $source_dir/robots/one_dof/one_dof_w_jnt_ctl.launch.yaml
duration: 0.2
vary: {/one_DOF_robot/joint1_position_controller/pid/p: [5.0, 10.0]}
measure: {q: {topic: /one_DOF_robot/joint_states, field: "position[0]", reduce: last}}
YAML
  if ! env -u SERVOLOOP_PLUGIN_PATH -u PYTHONPATH "$prefix/bin/servoloop" sweep "$work/tiny.sweep.yaml" \
      --out "$work/tiny-sweep" --jobs 1 >"$work/sweep.log" 2>&1; then
    show_log "$work/sweep.log"
    fail "the installed servoloop sweep failed"
  fi
  [[ $(wc -l <"$work/tiny-sweep/episodes.csv") -eq 3 ]] || fail "the installed sweep did not write its two rows"
fi

step "OK: servoloop installs, builds an out-of-tree controller and loads it"
