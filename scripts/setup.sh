#!/usr/bin/env bash
# Installs what hexlod needs, and nothing when all is present.
#   scripts/setup.sh        everything: to build, run and test (./hexlod.sh test, ./build.sh)
#   scripts/setup.sh view   only what the page needs (./hexlod.sh view): Emscripten, GLM, Node
#                           and npm, the npm packages; no native toolchain, GoogleTest or Chromium
# On Debian (12) as root, or with sudo, missing apt packages are installed; elsewhere it says
# exactly what is missing and how to get it. npm packages come from the committed lockfile.
set -euo pipefail
cd "$(dirname "$0")/.."
profile=${1:-all}
case "$profile" in
  all|view) ;;
  *) echo "usage: scripts/setup.sh [all|view]" >&2; exit 2 ;;
esac

# Debian packages and what each is for.
apt_packages=(
  emscripten     # em++ 3.1.6: the WebAssembly build of the core
  libglm-dev     # GLM, the core's vector maths
)
if [ "$profile" = all ]; then
  apt_packages+=(
    cmake          # native build
    ninja-build    # native build
    g++            # native build
    libgtest-dev   # native unit tests
    chromium       # headless browser tests (driven by playwright-core)
  )
fi
command -v node >/dev/null && command -v npm >/dev/null || apt_packages+=(nodejs npm)

missing_apt() {
  local name
  for entry in "${apt_packages[@]}"; do
    name=${entry%% *}
    dpkg-query -W -f='${Status}' "$name" 2>/dev/null | grep -q 'install ok installed' || echo "$name"
  done
}

if command -v apt-get >/dev/null && command -v dpkg-query >/dev/null; then
  mapfile -t missing < <(missing_apt)
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing Debian packages: ${missing[*]}"
    if [ "$(id -u)" -eq 0 ]; then
      as_root=()
    elif command -v sudo >/dev/null; then
      as_root=(sudo)
    else
      echo "setup: missing Debian packages: ${missing[*]}" >&2
      echo "setup: run as root: apt-get update && apt-get install -y ${missing[*]}" >&2
      exit 1
    fi
    "${as_root[@]}" apt-get update -q
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
else
  # Not Debian: check the tools themselves and say what to get.
  problems=()
  tools=(em++ node npm)
  [ "$profile" = all ] && tools+=(cmake ninja g++)
  for tool in "${tools[@]}"; do
    command -v "$tool" >/dev/null || problems+=("$tool")
  done
  [ -f /usr/include/glm/glm.hpp ] || problems+=("GLM headers in /usr/include/glm")
  if [ "$profile" = all ]; then
    [ -f /usr/include/gtest/gtest.h ] || problems+=("GoogleTest headers in /usr/include/gtest")
    command -v chromium >/dev/null || [ -n "${CHROMIUM_PATH:-}" ] || problems+=("chromium (or set CHROMIUM_PATH)")
  fi
  if [ ${#problems[@]} -gt 0 ]; then
    echo "setup: this is not Debian, and these are missing: ${problems[*]}" >&2
    if [ "$profile" = all ]; then
      echo "setup: install Emscripten 3.1.x (em++), GLM, CMake, Ninja, a C++17 compiler, GoogleTest," >&2
      echo "setup: Node.js >= 18 with npm, and Chromium; then run this again." >&2
    else
      echo "setup: install Emscripten 3.1.x (em++), GLM and Node.js >= 18 with npm; then run this again." >&2
    fi
    exit 1
  fi
fi

node_major=$(node -p 'process.versions.node.split(".")[0]')
if [ "$node_major" -lt 18 ]; then
  echo "setup: Node.js $(node --version) is too old: hexlod needs Node.js 18 or newer" >&2
  exit 1
fi

# npm packages exactly as the lockfile pins them. After a successful `npm ci` the lockfile's
# sha256 is written into node_modules; the install is skipped while it matches. (Comparing
# mtimes of package-lock.json and node_modules/.package-lock.json misjudges fresh clones and
# checkouts, where git gives every file the time it wrote it.) npm ci empties node_modules
# first, so a failed install leaves no stamp behind.
lock_stamp=node_modules/.hexlod-lockfile.sha256
if command -v sha256sum >/dev/null; then
  lock_sha=$(sha256sum package-lock.json | cut -d' ' -f1)
else
  lock_sha=$(shasum -a 256 package-lock.json | cut -d' ' -f1) # macOS
fi
if [ "$(cat "$lock_stamp" 2>/dev/null)" != "$lock_sha" ]; then
  echo "setup: installing npm packages from package-lock.json"
  npm ci --no-audit --no-fund
  echo "$lock_sha" >"$lock_stamp"
fi
