// A double as the nearest float on a chosen side, for bounds that must not shrink when they
// are stored as floats.
#pragma once

#include <cstdint>
#include <cstring>

namespace hexlod {

/// The next float above a finite f (std::nextafter towards +infinity, by its bits: the library
/// call was 1.5 % of an update, from every bound computed and packed).
inline float nextUp(float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof(bits));
    if ((bits & 0x7FFFFFFFu) == 0) bits = 1; // either zero: the smallest positive subnormal
    else if (bits >> 31) --bits;             // negative: towards zero
    else ++bits;
    std::memcpy(&f, &bits, sizeof(f));
    return f;
}

/// The next float below a finite f.
inline float nextDown(float f) { return -nextUp(-f); }

inline float roundedDown(double x) {
    float f = float(x);
    if (double(f) > x) f = nextDown(f);
    return f;
}

inline float roundedUp(double x) {
    float f = float(x);
    if (double(f) < x) f = nextUp(f);
    return f;
}

} // namespace hexlod
