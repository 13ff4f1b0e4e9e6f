#!/usr/bin/env bash
# The two things a person does with a fresh clone; each sets everything up first.
#   ./hexlod.sh view   install what is missing, build, and open the viewer on the default terrain
#   ./hexlod.sh test   install what is missing, build, and run every test layer
set -euo pipefail
cd "$(dirname "$0")"

case "${1:-}" in
  view)
    scripts/setup.sh
    ./build.sh
    open_flag=()
    [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && open_flag=(--open)
    echo "hexlod: serving the viewer at http://127.0.0.1:5173/ (Ctrl-C stops it)"
    exec npx vite --config vite.config.js --port 5173 --strictPort "${open_flag[@]}"
    ;;
  test)
    scripts/setup.sh
    ./build.sh
    failed=()
    echo "== native tests (GoogleTest via CTest)"
    ctest --test-dir build/native --output-on-failure || failed+=(native)
    echo "== Node tests (loaders, WASM core, CLI)"
    node --test tests/node/*.test.js || failed+=(node)
    echo "== browser tests (headless Chromium)"
    node --test --test-concurrency=1 tests/browser/*.test.js || failed+=(browser)
    if [ ${#failed[@]} -gt 0 ]; then
      echo "hexlod: FAILED test layers: ${failed[*]}" >&2
      exit 1
    fi
    echo "hexlod: all test layers passed"
    ;;
  *)
    echo "usage: ./hexlod.sh view | test" >&2
    exit 2
    ;;
esac
