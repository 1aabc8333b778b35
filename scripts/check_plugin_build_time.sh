#!/usr/bin/env bash
# How long a controller author waits after an edit: installs BUILD_DIR into a
# temporary prefix, builds a copy of examples/custom_controller against it as
# RelWithDebInfo (find_package(servoloop), Ninja), then touches the
# controller's source RUNS times and times the rebuild each time (recompile and
# relink of the plugin). Prints each time and the median, and fails when the
# median exceeds LIMIT_S seconds.
# Usage: scripts/check_plugin_build_time.sh BUILD_DIR [RUNS] [LIMIT_S]   (default 3 runs, 5 s)
set -euo pipefail

check_name=plugin_build_time
# shellcheck source=lib/installed_package.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/installed_package.sh"

runs=${2:-3}
limit_s=${3:-5}
begin_check "$1"
install_build_into_prefix

example_copy=$work/custom_controller
cp -r "$source_dir/examples/custom_controller" "$example_copy"
step "configuring the example (RelWithDebInfo) against the prefix"
if ! cmake -S "$example_copy" -B "$example_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$work/configure.log" 2>&1; then
  show_log "$work/configure.log"
  fail "configuring the example against the installed package failed (see above)"
fi
if ! ninja -C "$example_build" >"$work/build.log" 2>&1; then
  show_log "$work/build.log"
  fail "building the example failed (see above)"
fi

source_file=$example_copy/src/gravity_compensated_pd_controller.cpp
times=()
for i in $(seq "$runs"); do
  touch "$source_file"
  start=$(date +%s.%N)
  ninja -C "$example_build" >"$work/rebuild.log" 2>&1 || { show_log "$work/rebuild.log"; fail "the rebuild failed"; }
  end=$(date +%s.%N)
  grep -q "Linking" "$work/rebuild.log" || fail "touching the source did not relink the plugin"
  times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')")
  echo "rebuild $i: ${times[-1]} s"
done
median=$(printf '%s\n' "${times[@]}" | sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }')
echo "plugin rebuild (examples/custom_controller, RelWithDebInfo): median ${median} s of ${runs} (limit ${limit_s} s)"
if ! awk -v m="$median" -v l="$limit_s" 'BEGIN { exit !(m <= l) }'; then
  fail "the plugin's rebuild took ${median} s (median), over the ${limit_s} s limit"
fi
