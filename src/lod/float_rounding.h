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

/// A non-negative float in 16 bits: its upper half (the bfloat16 format: the float's exponent,
/// 7 bits of mantissa), rounded up or down; for figures that need range more than precision
/// (packed_bounds.h's IEEE halves stop at 65,504: distances and margins reach millions of metres).
inline uint16_t halfBitsUp(float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof(bits));
    return uint16_t((bits >> 16) + ((bits & 0xFFFFu) != 0 ? 1u : 0u));
}
inline uint16_t halfBitsDown(float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof(bits));
    return uint16_t(bits >> 16);
}
inline float fromHalfBits(uint16_t half) {
    const uint32_t bits = uint32_t(half) << 16;
    float f;
    std::memcpy(&f, &bits, sizeof(f));
    return f;
}

} // namespace hexlod
