#!/usr/bin/env bash
# build.sh: the one build entry point of hexlod.
#   ./build.sh          everything (./hexlod.sh test, npm run build): native, wasm, site, library, wasm-tests
#   ./build.sh native   only the native part (CMake + Ninja, into build/native): core, GoogleTest
#                       suite, benchmark
#   ./build.sh page     only the page's WebAssembly module, build/wasm: all that ./hexlod.sh view
#                       builds
#   ./build.sh wasm     both WebAssembly modules (Emscripten 3.1.6): build/wasm, the product the
#                       page loads, and build/wasm-diag, the same core with the diagnostics ABI,
#                       which Node (bin/, tests/node, benchmarks) loads
#   ./build.sh wasm-tests  the GoogleTest suite built to WebAssembly, run under Node (build/wasm-tests)
#   ./build.sh site     the static production site in dist/ (needs the WebAssembly module)
#   ./build.sh library  the package's browser library in library/ (import 'hexlod'; needs the module)
# A WebAssembly module is rebuilt only when its sources, flags or Emscripten changed (a content
# stamp in its folder); GoogleTest for WebAssembly likewise, and Ninja rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")"
target=${1:-all}

shopt -s nullglob
# The core: every .cpp in src/ and its section folders, as in CMakeLists.txt.
core_sources=(src/*.cpp src/{field,mesh,lod,stream,diagnostics,api}/*.cpp)

build_native() {
  # Compiler flags of the native build live in CMakeLists.txt, each with its reason.
  cmake -S . -B build/native -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  ninja -C build/native
}

emscripten_version() {
  cat "$(dirname "$(readlink -f "$(command -v em++)")")/emscripten-version.txt" 2>/dev/null || echo unknown
}

# One WebAssembly module: $1 the output folder, $2 the ABI headers whose functions it exports,
# then the sources. Skipped when its stamp says the same sources and flags built it.
build_wasm_module() {
  local out=$1 headers=$2
  shift 2
  mkdir -p "$out/include"
  # emcc must see GLM but not the rest of /usr/include (glibc headers break the wasm libc).
  ln -sfn /usr/include/glm "$out/include/glm"
  # Every function declared in the headers is exported, plus malloc/free for JS buffers.
  local exports
  exports=$(grep -ohE '\bhexlod_[a-z0-9_]+\(' $headers | tr -d '(' | sort -u | sed 's/^/_/' | paste -sd, -)
  local flags=(
    -std=c++17                      # the core is written in C++17
    -O3                             # the per-frame LOD update runs here: optimise for speed
    -ffp-contract=off               # no fused multiply-add: the same split/merge decisions as native
    -fno-exceptions                 # errors go by return value; smaller and faster code
    -Wall -Wextra                   # the same warnings as the native build
    "-I$out/include"                # GLM only (see the link above)
    -Isrc                           # the core names its headers from src/ (field/, mesh/, lod/, ...)
    -sMODULARIZE -sEXPORT_ES6       # an ES module factory, imported by the page, workers and Node
    -sEXPORT_NAME=createHexlodCore  # the factory's name
    -sENVIRONMENT=web,worker        # with node too, 3.1.6 emits __dirname into an ES module; Node passes wasmBinary instead
    -sALLOW_MEMORY_GROWTH=1         # fields of any size, without reserving memory up front
    -sMAXIMUM_MEMORY=4GB            # a 16385^2 16-bit field (512 MB) plus its mesh fits in a tab
    -sINITIAL_MEMORY=64MB           # small fields load without growing the memory at all
    -sFILESYSTEM=0                  # files arrive as bytes from JS: no virtual file system
    -sEXPORTED_FUNCTIONS="$exports,_malloc,_free"  # the C ABI is the whole boundary
    -sEXPORTED_RUNTIME_METHODS=UTF8ToString        # to read hexlod_last_error() messages
  )
  # Up to date when the last successful build had the same Emscripten, flags, source list, and
  # the same content of every file under src/ (any of them may be included). A content stamp,
  # not mtimes: git sets every file's mtime to when it wrote it (a clone, a checkout), and a
  # copy that keeps older mtimes (cp -p, rsync, tar) would look up to date when it is not.
  # Hashing src/ takes milliseconds. The stamp goes before the build, so a failed one has none.
  local stamp
  stamp=$(printf '%s\n' "emscripten $(emscripten_version)" "${flags[*]}" "$*"
          find src -type f -print0 | LC_ALL=C sort -z | xargs -0 sha256sum)
  if [ -f "$out/hexlod_core.mjs" ] && [ -f "$out/hexlod_core.wasm" ] &&
     [ "$(cat "$out/build.stamp" 2>/dev/null)" = "$stamp" ]; then
    echo "$out/hexlod_core.mjs and .wasm are up to date"
    return
  fi
  rm -f "$out/build.stamp"
  # Debian's emscripten runs its JS optimiser with node; it needs Debian's acorn on NODE_PATH.
  NODE_PATH=/usr/share/nodejs em++ "${flags[@]}" "$@" -o "$out/hexlod_core.mjs"
  printf '%s\n' "$stamp" >"$out/build.stamp"
  echo "built $out/hexlod_core.mjs and hexlod_core.wasm ($(stat -c %s "$out/hexlod_core.wasm") bytes)"
}

# The product (the page and dist/): the ABI of src/api/hexlod.h only, no diagnostics code.
build_page() {
  local product=()
  for source in "${core_sources[@]}"; do
    [ "$source" = src/api/hexlod_diagnostics_api.cpp ] || product+=("$source")
  done
  build_wasm_module build/wasm src/api/hexlod.h "${product[@]}"
}

build_wasm() {
  build_page
  # For Node (the CLI, its tests and benchmarks): the same core plus src/api/hexlod_diagnostics.h.
  build_wasm_module build/wasm-diag "src/api/hexlod.h src/api/hexlod_diagnostics.h" "${core_sources[@]}"
}

build_site() {
  # Relative asset URLs (vite.config.js base './'): dist/ works from any static host, at its
  # root or under a sub-path.
  npx vite build --config vite.config.js --logLevel warn
  echo "built the static site in dist/ ($(du -sh dist | cut -f1)): copy the folder to any static file server"
}

build_library() {
  # The package's browser library (vite.library.config.js): needs the page's WebAssembly module.
  npx vite build --config vite.library.config.js --logLevel error
  echo "built the browser library in library/ ($(du -sh library | cut -f1)): what import 'hexlod' loads"
}

case "$target" in
  native) build_native ;;
  page) build_page ;;
  wasm) build_wasm ;;
  site) build_site ;;
  library) build_library ;;
  wasm-tests) scripts/build_wasm_tests.sh ;;
  all) build_native; build_wasm; build_site; build_library; scripts/build_wasm_tests.sh ;;
  *) echo "usage: ./build.sh [native|page|wasm|site|library|wasm-tests|all]" >&2; exit 2 ;;
esac
