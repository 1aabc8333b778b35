# Shared by scripts/check_install.sh and scripts/check_backend_example.sh: both
# install a servoloop build into a temporary prefix and build an example
# against that prefix only. Source it after setting check_name; then call
# begin_check, install_build_into_prefix and build_example_against_prefix.

fail() {
  echo "$check_name: FAILED: $*" >&2
  exit 1
}
step() { echo "== $check_name: $*"; }
# Prints the last lines of a log file to stderr (for a failed step).
show_log() { echo "--- last lines of $1:" >&2; tail -n 40 "$1" >&2; }

# begin_check ARGS... : checks the one BUILD_DIR argument and sets build_dir,
# source_dir, work (a temporary folder, removed on exit unless
# CHECK_INSTALL_KEEP=1), prefix and example_build.
begin_check() {
  [[ $# -eq 1 ]] || fail "usage: $0 BUILD_DIR (a configured and fully built servoloop build folder)"
  [[ -f "$1/CMakeCache.txt" ]] || fail "'$1' is not a CMake build folder (no CMakeCache.txt)"
  build_dir=$(cd "$1" && pwd)
  source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  work=$(mktemp -d "${TMPDIR:-/tmp}/servoloop-$check_name.XXXXXX")
  if [[ "${CHECK_INSTALL_KEEP:-0}" == 1 ]]; then
    echo "$check_name: keeping $work"
  else
    trap 'rm -rf "$work"' EXIT
  fi
  prefix=$work/prefix
  example_build=$work/example-build
}

cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$build_dir/CMakeCache.txt"; }

# install_build_into_prefix: cmake --install into $prefix; sets servoloop_exe
# and installed_plugin_dir.
install_build_into_prefix() {
  step "installing $build_dir into a temporary prefix"
  if ! cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" 2>&1; then
    show_log "$work/install.log"
    fail "cmake --install $build_dir failed; build it completely first (cmake --build $build_dir)"
  fi
  servoloop_exe=$prefix/bin/servoloop
  [[ -x "$servoloop_exe" ]] || fail "the install has no bin/servoloop"
  local libdir
  libdir=$(cache_value CMAKE_INSTALL_LIBDIR)
  installed_plugin_dir=$prefix/${libdir:-lib}/servoloop/plugins
}

# build_example_against_prefix NAME LIBRARY [CMAKE_ARGS...]: configures and
# builds $example_source (called NAME in messages) against $prefix only, with
# the build's type and sanitizer flags, into $example_build; sets
# example_library to $example_build/LIBRARY, which must exist.
build_example_against_prefix() {
  local name=$1 library=$2
  shift 2
  local cmake_args=(-G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "$@")
  local build_type
  build_type=$(cache_value CMAKE_BUILD_TYPE)
  [[ -n "$build_type" ]] && cmake_args+=(-DCMAKE_BUILD_TYPE="$build_type")
  # A sanitized servoloop can only be linked into sanitized programs: build the
  # example the same way.
  if [[ "$(cache_value SERVOLOOP_SANITIZE)" == ON ]]; then
    local sanitize="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
    cmake_args+=(-DCMAKE_CXX_FLAGS="$sanitize" -DCMAKE_EXE_LINKER_FLAGS="$sanitize"
                 -DCMAKE_MODULE_LINKER_FLAGS="$sanitize")
  fi
  step "configuring $name with find_package(servoloop) from the prefix"
  if ! cmake -S "$example_source" -B "$example_build" "${cmake_args[@]}" >"$work/configure.log" 2>&1; then
    show_log "$work/configure.log"
    fail "configuring the example against the installed package failed (see above)"
  fi
  local found_dir
  found_dir=$(sed -n 's/^servoloop_DIR:PATH=//p' "$example_build/CMakeCache.txt")
  [[ "$found_dir" == "$prefix"/* ]] || fail "the example found servoloop in '$found_dir', not in the install"
  step "building the example"
  if ! cmake --build "$example_build" --parallel 2 >"$work/build.log" 2>&1; then
    show_log "$work/build.log"
    fail "building the example against the installed package failed (see above)"
  fi
  example_library=$example_build/$library
  [[ -f "$example_library" ]] || fail "the example build made no $library"
}
