#!/usr/bin/env bash
# The two things a person does with a fresh clone; each sets up what it needs first.
#   ./hexlod.sh view   install what the page needs (Emscripten, GLM, Node, the npm packages),
#                      build only the page's WebAssembly module (build/wasm, skipped when up to
#                      date) and serve the viewer on its default terrain with Vite's dev server
#                      at http://127.0.0.1:$HEXLOD_PORT/ (default 5173); prints each step's time
#   ./hexlod.sh test   install everything, build everything (./build.sh: native, both
#                      WebAssembly modules, dist/, the WebAssembly test suite) and run every
#                      test layer
set -euo pipefail
cd "$(dirname "$0")"

# Seconds since $1 (an $EPOCHREALTIME), to a tenth.
since() {
  local now=${EPOCHREALTIME/,/.}
  awk -v start="${1/,/.}" -v now="$now" 'BEGIN { printf "%.1f", now - start }'
}

case "${1:-}" in
  view)
    port=${HEXLOD_PORT:-5173}
    [[ $port =~ ^[0-9]+$ ]] || { echo "hexlod: HEXLOD_PORT must be a port number, not '$port'" >&2; exit 2; }

    start=$EPOCHREALTIME
    scripts/setup.sh view
    echo "hexlod: [1/3] packages ready ($(since "$start") s)"

    start=$EPOCHREALTIME
    # Whether the module was built or found up to date: its modification time moved or not.
    wasm_time() { stat -c %y build/wasm/hexlod_core.wasm 2>/dev/null || true; }
    before=$(wasm_time)
    ./build.sh page
    [ "$(wasm_time)" = "$before" ] && state="up to date" || state=built
    echo "hexlod: [2/3] page core $state ($(since "$start") s)"

    open_flag=()
    [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && open_flag=(--open)
    echo "hexlod: [3/3] serving http://127.0.0.1:$port/ (Ctrl-C stops it)"
    exec npx vite --config vite.config.js --port "$port" --strictPort "${open_flag[@]}"
    ;;
  test)
    suite_start=$EPOCHREALTIME
    scripts/setup.sh
    ./build.sh
    layer_times=("setup and build $(since "$suite_start") s")
    failed=()
    # Each test's duration goes to a file of JSON lines beside the usual report; the slowest are
    # listed at the end (scripts/test_times.js).
    times_dir=$(mktemp -d)
    timing() { echo "--test-reporter=spec" "--test-reporter-destination=stdout" \
      "--test-reporter=./lib/test_time_reporter.js" "--test-reporter-destination=$times_dir/$1.jsonl"; }
    # The native tests and the Node tests run side by side: each keeps one core of two busy (CTest
    # runs one test at a time, node --test one file at a time on two cores), and the native ones
    # end well before the Node ones. The native output is kept and shown whole under its own
    # heading once both are done, so neither layer's lines are mixed into the other's.
    native_log=$(mktemp)
    layer_start=$EPOCHREALTIME
    ctest --test-dir build/native --output-on-failure >"$native_log" 2>&1 &
    native_pid=$!
    trap 'kill "$native_pid" 2>/dev/null || true; rm -rf "$native_log" "$times_dir"' EXIT
    echo "== Node tests (loaders, WASM core, CLI), the native tests running beside them"
    # shellcheck disable=SC2046
    node --test $(timing node) tests/node/*.test.js || failed+=(node)
    native_status=0
    wait "$native_pid" || native_status=$?
    echo "== native tests (GoogleTest via CTest)"
    cat "$native_log"
    layer_times+=("Node and native tests $(since "$layer_start") s")
    [ "$native_status" -eq 0 ] || failed+=(native)
    echo "== browser tests (headless Chromium)"
    layer_start=$EPOCHREALTIME
    # shellcheck disable=SC2046
    node --test --test-concurrency=1 $(timing browser) tests/browser/*.test.js || failed+=(browser)
    layer_times+=("browser tests $(since "$layer_start") s")
    echo "== times"
    printf '  %s\n' "${layer_times[@]}" "whole suite $(since "$suite_start") s"
    node scripts/test_times.js 5 "$times_dir"/*.jsonl
    rm -rf "$native_log" "$times_dir"
    trap - EXIT
    if [ ${#failed[@]} -gt 0 ]; then
      echo "hexlod: FAILED test layers: ${failed[*]}" >&2
      exit 1
    fi
    echo "hexlod: all test layers passed"
    ;;
  *)
    echo "usage: ./hexlod.sh view | test   (view serves on \$HEXLOD_PORT, default 5173)" >&2
    exit 2
    ;;
esac
