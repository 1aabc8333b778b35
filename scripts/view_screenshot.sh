#!/usr/bin/env bash
# A screenshot of the browser view (docs/view.md): runs
# `servoloop launch LAUNCH --view` with the arguments given after the PNG,
# opens the page in Debian's headless Chromium for SECONDS of the world
# (default 6), writes what it shows to PNG, then stops the world.
#   bash scripts/view_screenshot.sh LAUNCH OUT.png [SECONDS] [-- launch arguments...]
# Needs: a build (build/bin/servoloop) and chromium (apt install chromium).
set -euo pipefail
cd "$(dirname "$0")/.."
launch=$1
png=$(realpath -m "$2")
seconds=${3:-6}
shift 2
[ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
run_dir=$(mktemp -d)
log="$run_dir/launch.log"
SERVOLOOP_RUN_DIR="$run_dir" build/bin/servoloop launch "$launch" --view 127.0.0.1:0 "$@" > /dev/null 2> "$log" &
pid=$!
trap 'kill -INT $pid 2>/dev/null; wait $pid 2>/dev/null; rm -rf "$run_dir"' EXIT
url=""
for _ in $(seq 1 300); do
  url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$log" | head -1 || true)
  [ -n "$url" ] && break
  kill -0 $pid 2>/dev/null || { cat "$log" >&2; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { echo "the view did not start:" >&2; cat "$log" >&2; exit 1; }
chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
  --user-data-dir="$run_dir/chromium" --window-size=1280,800 --hide-scrollbars \
  --virtual-time-budget=$((seconds * 1000)) --screenshot="$png" "$url" 2> /dev/null
echo "wrote $png ($url)"
