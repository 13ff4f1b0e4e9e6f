// A double as the nearest float on a chosen side, for bounds that must not shrink when they
// are stored as floats.
#pragma once

#include <cmath>
#include <limits>

namespace hexlod {

inline float roundedDown(double x) {
    float f = float(x);
    if (double(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}

inline float roundedUp(double x) {
    float f = float(x);
    if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

} // namespace hexlod
