#!/usr/bin/env bash
# The native tests under UndefinedBehaviorSanitizer (-fsanitize=undefined
# -fno-sanitize-recover=all: the first signed overflow or other undefined behaviour fails the
# test), in their own build folder, build/native-ubsan. By default the tests of the largest
# fields, whose indices are the likeliest to overflow: the world-sized field and the tiled ones;
# any arguments go to the test binary instead (e.g. --gtest_filter='*' for all).
#   scripts/ubsan.sh [gtest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build/native-ubsan -G Ninja -DCMAKE_BUILD_TYPE=Release -DHEXLOD_UBSAN=ON >/dev/null
ninja -C build/native-ubsan -j2 hexlod_tests   # two jobs: the machines here have two cores
if [ $# -eq 0 ]; then set -- --gtest_filter='WorldField.*:TiledField.*:Heightfield.*:Embedding.*'; fi
UBSAN_OPTIONS=print_stacktrace=1 build/native-ubsan/hexlod_tests "$@"
