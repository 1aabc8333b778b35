#!/usr/bin/env bash
# Guards the binary interface plugins are built against.
#
# Compiles abi/plugin_abi.cpp (every plugin-facing header) with GCC's
# class-layout dump (-fdump-lang-class) and keeps, for every servoloop class,
# its size, alignment, bases and virtual table. That is what an already-built
# plugin relies on: a new virtual in a base class, a reordered or added member
# or a changed base makes old plugins call the wrong function or read the
# wrong memory. The result is compared with abi/plugin_abi_layout.txt, recorded
# together with kPluginApiVersion (plugin/include/servoloop/plugin/plugin_api.hpp):
#   - layout unchanged, same version: OK;
#   - layout changed, same version: FAIL: bump kPluginApiVersion (the loader then
#     refuses plugins built before the change) and record the new layout;
#   - version bumped: FAIL until the new layout is recorded.
#
# Usage: scripts/check_abi.sh              check
#        scripts/check_abi.sh --record     write abi/plugin_abi_layout.txt
#        scripts/check_abi.sh --self-test  check that adding a virtual to
#                                          ControllerBase is caught
# CXX selects the compiler (default c++). Exits non-zero with a message.
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$(pwd)
baseline=abi/plugin_abi_layout.txt
cxx=${CXX:-c++}

fail() { echo "check_abi: FAILED: $*" >&2; exit 1; }

api_version() {
  sed -n 's/^inline constexpr std::uint32_t kPluginApiVersion = \([0-9]*\);.*/\1/p' \
    plugin/include/servoloop/plugin/plugin_api.hpp
}

# layout OUT [EXTRA_INCLUDE_DIR]: the filtered class dump of abi/plugin_abi.cpp.
layout() {
  local out=$1 extra=${2:-} work
  work=$(mktemp -d /tmp/servoloop-abi.XXXXXX)
  local includes=()
  [[ -n "$extra" ]] && includes+=(-I"$extra")
  for module in core plugin realtime params description hardware_interface transmissions controller_manager \
                sim_common controllers/common controllers/pid; do
    includes+=(-I"$source_dir/$module/include")
  done
  if ! "$cxx" -std=c++20 -fsyntax-only -fdump-lang-class="$work/dump" "${includes[@]}" \
        -I/usr/include/eigen3 abi/plugin_abi.cpp 2>"$work/errors"; then
    cat "$work/errors" >&2
    rm -rf "$work"
    fail "abi/plugin_abi.cpp does not compile"
  fi
  # Keep the servoloop classes and vtables; drop the compiler's node addresses.
  awk '/^(Class|Vtable for) servoloop::/ {keep = 1}
       /^$/ {if (keep) print ""; keep = 0}
       keep {print}' "$work/dump" | sed -E 's/ \(0x0x[0-9a-f]+\)//g' >"$out"
  rm -rf "$work"
  [[ -s "$out" ]] || fail "the class dump holds no servoloop class"
}

check() {
  local current=$1 version recorded
  version=$(api_version)
  [[ -f "$baseline" ]] || fail "no $baseline; record it with scripts/check_abi.sh --record"
  recorded=$(sed -n '1s/^# kPluginApiVersion \([0-9]*\)$/\1/p' "$baseline")
  if ! diff -u <(tail -n +2 "$baseline") "$current" >"$current.diff"; then
    if [[ "$version" == "$recorded" ]]; then
      head -n 60 "$current.diff" >&2
      fail "the plugin-facing class layout changed (diff above, $(grep -c '^[-+][^-+]' "$current.diff") lines) but" \
           "kPluginApiVersion is still $version: plugins built before this change would break." \
           "Bump kPluginApiVersion in plugin/include/servoloop/plugin/plugin_api.hpp, then record the" \
           "new layout with scripts/check_abi.sh --record"
    fi
    fail "kPluginApiVersion is $version but $baseline was recorded for version $recorded;" \
         "record the new layout with scripts/check_abi.sh --record"
  fi
  [[ "$version" == "$recorded" ]] ||
    fail "kPluginApiVersion is $version but $baseline was recorded for version $recorded with the same" \
         "layout; record it again with scripts/check_abi.sh --record"
  echo "check_abi: OK: $(grep -c '^Class servoloop::' "$current") plugin-facing classes as recorded for plugin API version $version"
}

mode=${1:-check}
tmp=$(mktemp -d /tmp/servoloop-abi-check.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
case "$mode" in
  check)
    layout "$tmp/layout.txt"
    check "$tmp/layout.txt"
    ;;
  --record)
    layout "$tmp/layout.txt"
    { echo "# kPluginApiVersion $(api_version)"; cat "$tmp/layout.txt"; } >"$baseline"
    echo "check_abi: recorded $(grep -c '^Class servoloop::' "$tmp/layout.txt") classes for plugin API version $(api_version) in $baseline"
    ;;
  --self-test)
    # A copy of controller_base.hpp with one more virtual, found first on the
    # include path: the check must refuse it.
    mkdir -p "$tmp/include/servoloop/controller_manager"
    header=controller_manager/include/servoloop/controller_manager/controller_base.hpp
    sed 's|^  virtual void setSafeOutput() {}|  virtual void setSafeOutput() {}\n  virtual void addedByTheSelfTest() {}|' \
      "$header" >"$tmp/include/servoloop/controller_manager/controller_base.hpp"
    grep -q addedByTheSelfTest "$tmp/include/servoloop/controller_manager/controller_base.hpp" ||
      fail "self-test: could not add a virtual to a copy of $header"
    layout "$tmp/changed.txt" "$tmp/include"
    if (check "$tmp/changed.txt") >"$tmp/out" 2>&1; then
      cat "$tmp/out" >&2
      fail "self-test: a new virtual in ControllerBase was not caught"
    fi
    grep -q "addedByTheSelfTest" "$tmp/out" || { cat "$tmp/out" >&2; fail "self-test: the diff does not show the new virtual"; }
    grep -q "Bump kPluginApiVersion" "$tmp/out" || { cat "$tmp/out" >&2; fail "self-test: no advice to bump the version"; }
    echo "check_abi: self-test OK: a virtual added to ControllerBase is refused without a version bump"
    ;;
  *)
    fail "unknown argument '$mode' (use --record or --self-test, or nothing to check)"
    ;;
esac
