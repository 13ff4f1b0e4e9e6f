#!/usr/bin/env bash
# build_wasm_tests.sh: the native GoogleTest suite (tests/native/*_test.cpp + the core in src/),
# built with Emscripten 3.1.6 into build/wasm-tests/hexlod_tests.js (+ .wasm), so the same tests
# run under Node and tests/node/native_wasm_agreement.test.js can show the two builds agree:
#   node build/wasm-tests/hexlod_tests.js [--gtest_filter=...]
# Incremental: GoogleTest is compiled once (it is slow), and nothing is rebuilt when no input
# changed since the last successful build, so repeated ./build.sh runs stay fast.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

out=build/wasm-tests
out_js=$out/hexlod_tests.js
out_wasm=$out/hexlod_tests.wasm
gtest_root=/usr/src/googletest/googletest # Debian's libgtest-dev/googletest sources

for file in "$gtest_root/src/gtest-all.cc" "$gtest_root/src/gtest_main.cc" "$gtest_root/include/gtest/gtest.h"; do
  [ -f "$file" ] || { echo "build_wasm_tests.sh: $file is missing; install googletest (scripts/setup.sh)" >&2; exit 1; }
done
command -v em++ >/dev/null || { echo "build_wasm_tests.sh: em++ not found; install emscripten (scripts/setup.sh)" >&2; exit 1; }

mkdir -p "$out/include"
# emcc must see GLM and the GoogleTest headers but not the rest of /usr/include (glibc headers
# break the wasm libc), so both are linked into a private include directory, as build.sh does.
ln -sfn /usr/include/glm "$out/include/glm"
ln -sfn "$gtest_root/include/gtest" "$out/include/gtest" # the headers that match the sources compiled below
# The emitted loader is CommonJS, but the repository's package.json says "type": "module".
printf '{ "type": "commonjs" }\n' >"$out/package.json"

shopt -s nullglob
core_sources=(src/*.cpp src/{field,mesh,lod,stream,diagnostics,api}/*.cpp) # the core, as in build.sh and CMakeLists.txt
test_sources=(tests/native/*_test.cpp) # the suite is every *_test.cpp, as in CMakeLists.txt

# Debian's emscripten runs its JS optimiser with node; it needs Debian's acorn on NODE_PATH.
emxx() { NODE_PATH=/usr/share/nodejs em++ "$@"; }

# Code generation shared by GoogleTest, the tests and the core: the WASM module's core flags.
codegen_flags=(
  -std=c++17          # the core is written in C++17
  -O3                 # as the WASM module: the code under test is the code that ships
  -ffp-contract=off   # no fused multiply-add: the same split/merge decisions as native
  -fno-exceptions     # as the module and the native suite; GoogleTest then sets GTEST_HAS_EXCEPTIONS=0 itself
)
gtest_flags=(
  "${codegen_flags[@]}"
  "-I$out/include"    # GoogleTest's own headers (see the links above)
  "-I$gtest_root"     # gtest-all.cc includes its parts as "src/gtest-*.cc"
)
compile_flags=(
  "${codegen_flags[@]}"
  -Wall -Wextra       # the same warnings as the native build
  "-I$out/include"    # GLM and GoogleTest only (see the links above)
  -Isrc               # the core's headers, as CMake's hexlod_core include directory
  "-DHEXLOD_FIXTURES=\"$root/tests/fixtures\"" # absolute, as CMake defines it: read in place via NODERAWFS
)
link_flags=(
  -O3                           # optimise the linked module (wasm-opt) as the WASM module is
  -sENVIRONMENT=node            # a command-line program for Node only
  -sNODERAWFS=1                 # file I/O goes straight to the real file system: the fixtures are read in place
  -sEXIT_RUNTIME=1              # main's return value (failed tests -> 1) becomes node's exit code, stdout is flushed
  -sWASM_ASYNC_COMPILATION=0    # 3.1.6 would fetch() the .wasm by path, which Node's global fetch rejects
  -sALLOW_MEMORY_GROWTH=1       # tests load real fields of any size without reserving memory up front
  -sMAXIMUM_MEMORY=4GB          # the same ceiling as the WASM module
  -sTOTAL_STACK=8MB             # some room for recursion (3.1.6 knows TOTAL_STACK, not STACK_SIZE); default is 5MB
  -sSTACK_OVERFLOW_CHECK=2      # a stack overflow aborts (non-zero exit) instead of silently corrupting memory
)

emscripten_version=$(cat "$(dirname "$(readlink -f "$(command -v em++)")")/emscripten-version.txt" 2>/dev/null || echo unknown)

# GoogleTest: compiled only when its objects are missing or were built with other flags.
gtest_stamp="emscripten $emscripten_version; ${gtest_flags[*]}"
if [ ! -f "$out/gtest-all.o" ] || [ ! -f "$out/gtest_main.o" ] ||
   [ "$(cat "$out/gtest.stamp" 2>/dev/null)" != "$gtest_stamp" ]; then
  rm -f "$out/gtest.stamp"
  echo "compiling GoogleTest for WebAssembly (once)..."
  emxx "${gtest_flags[@]}" -c "$gtest_root/src/gtest-all.cc" -o "$out/gtest-all.o"
  emxx "${gtest_flags[@]}" -c "$gtest_root/src/gtest_main.cc" -o "$out/gtest_main.o"
  printf '%s\n' "$gtest_stamp" >"$out/gtest.stamp"
fi

# The suite: skipped when the last successful build used the same sources and flags and no input
# (sources, headers in src/ and tests/native/, this script, the GoogleTest objects) is newer.
# The stamp is removed before building, so a failed build is never taken as up to date. It holds
# the content of the sources, not their times: a source saved while the build ran is newer than
# nothing the build wrote, yet the build did not see it.
build_stamp=$(printf '%s\n' "emscripten $emscripten_version" "${compile_flags[*]}" "${link_flags[*]}" \
  "${core_sources[@]}" "${test_sources[@]}"
  find src tests/native scripts/build_wasm_tests.sh -type f -print0 | LC_ALL=C sort -z | xargs -0 sha256sum)
if [ -f "$out_js" ] && [ -f "$out_wasm" ] && [ "$(cat "$out/build.stamp" 2>/dev/null)" = "$build_stamp" ] &&
   [ -z "$(find "$out/gtest-all.o" "$out/gtest_main.o" -type f -newer "$out_js" -print | head -n 1)" ]; then
  echo "$out_js is up to date"
  exit 0
fi
rm -f "$out/build.stamp"
emxx "${compile_flags[@]}" "${link_flags[@]}" "${core_sources[@]}" "${test_sources[@]}" \
  "$out/gtest-all.o" "$out/gtest_main.o" -o "$out_js"
printf '%s\n' "$build_stamp" >"$out/build.stamp"
echo "built $out_js and hexlod_tests.wasm ($(stat -c %s "$out_wasm") bytes); run: node $out_js"
