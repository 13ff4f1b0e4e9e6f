// The benchmark's clock: milliseconds of wall time since a point, as every figure is printed.
#pragma once

#include <chrono>

namespace hexlod::bench {

inline double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace hexlod::bench
