#!/usr/bin/env bash
# Installs the Debian 12 packages servoloop builds and tests against.
# Safe to run again: apt-get skips what is already installed. Extra package
# names given as arguments are installed too (scripts/fuzz.sh adds clang).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libbullet-dev libbullet-extras-dev
  liburdfdom-dev liburdfdom-headers-dev libtinyxml2-dev
  libyaml-cpp-dev libeigen3-dev nlohmann-json3-dev libcli11-dev
  libspdlog-dev libfmt-dev
  libwebsocketpp-dev libasio-dev libjs-three
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  libmujoco-dev libpng-dev gnuplot-nox libassimp-dev libsdformat-dev
  python3-dev pybind11-dev python3-numpy python3-yaml python3-distributed
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "servoloop: installing ${missing[*]}" >&2
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
