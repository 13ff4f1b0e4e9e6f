// The compact form of the refinement data the cache keeps per cell (paper §5.1;
// bytes per triangle). A bound packs into 6 bytes and a slope box into 8, each rounded
// outwards, so what comes back out of the cache is still a bound: lows no higher, highs and
// errors no lower than what was computed.
//
// - Heights (a cell's lowest and highest point): 16-bit steps over the field's height range,
//   about 0.12 m on the Himalaya; the field's samples are all in that range.
// - The error: a half float (11 significant bits) of the error scaled so that the largest
//   possible error (the height range) stays well below half's largest finite value; small
//   errors keep their relative precision, which is what a pixel tolerance needs near the eye.
// - Slopes: half floats; a box with a slope past half's range is kept as unknown (never
//   back-facing), as is one that was unknown.
//
// Every conversion is integer or exact IEEE arithmetic, so native and WASM builds agree.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "lod/cell_bounds.h"
#include "lod/float_rounding.h"

namespace hexlod {

namespace half {

constexpr uint16_t kNaN = 0x7E00;
constexpr uint16_t kInfinity = 0x7C00;

/// Half-float bits of a finite float's magnitude, truncated towards zero; inexact tells whether
/// anything was cut off. Past the largest finite half: the largest finite half, inexact.
inline uint16_t magnitudeTowardZero(uint32_t absBits, bool& inexact) {
    if (absBits == 0) {
        inexact = false;
        return 0;
    }
    const int32_t e = int32_t(absBits >> 23) - 127;
    if (e > 15) {
        inexact = true;
        return 0x7BFF;
    }
    const uint32_t significand = (absBits & 0x7FFFFFu) | 0x800000u;
    if (e >= -14) { // a normal half: 10 of the 23 fraction bits stay
        inexact = (significand & 0x1FFFu) != 0;
        return uint16_t(uint32_t(e + 15) << 10 | ((significand >> 13) & 0x3FFu));
    }
    // A subnormal half counts units of 2^-24; the float is significand * 2^(e - 23).
    const int32_t shift = -(e + 1);
    if (shift >= 32) {
        inexact = true;
        return 0;
    }
    inexact = (significand & ((1u << shift) - 1u)) != 0;
    return uint16_t(significand >> shift);
}

/// The half nearest to a finite x on the side of `up` (towards +infinity) or down.
inline uint16_t rounded(float x, bool up) {
    uint32_t bits;
    std::memcpy(&bits, &x, sizeof(bits));
    const uint32_t negative = bits >> 31;
    bool inexact = false;
    uint16_t magnitude = magnitudeTowardZero(bits & 0x7FFFFFFFu, inexact);
    // Truncation moved towards zero; away from zero is the wanted side for a positive x rounded
    // up and a negative x rounded down. One step of the bits is one step of the value (the
    // largest finite half steps to infinity).
    if (inexact && (up != (negative != 0))) ++magnitude;
    return uint16_t(negative << 15 | magnitude);
}

inline float toFloat(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16, exponent = (h >> 10) & 0x1Fu, fraction = h & 0x3FFu;
    if (exponent == 0) {
        const float v = float(fraction) * 5.9604644775390625e-8f; // exact: an integer times 2^-24
        return sign ? -v : v;
    }
    const uint32_t bits = exponent == 31 ? (sign | 0x7F800000u | fraction << 13) : (sign | (exponent + 112u) << 23 | fraction << 13);
    float v;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
}

inline bool isFinite(uint16_t h) { return ((h >> 10) & 0x1Fu) != 0x1Fu; }

} // namespace half

/// A CellError in 6 bytes; error kNaN: not computed.
struct PackedBound {
    uint16_t low = 0, high = 0, error = half::kNaN;
};

/// A SlopeBox in 8 bytes of half floats; dxLow kNaN: unknown (never back-facing), and not
/// computed yet when dxHigh is kNotComputed too.
struct PackedSlopes {
    static constexpr uint16_t kNotComputed = 0;
    uint16_t dxLow = half::kNaN, dxHigh = half::kNaN, dzLow = half::kNaN, dzHigh = half::kNaN;
    static PackedSlopes notComputed() {
        PackedSlopes p;
        p.dxHigh = kNotComputed;
        return p;
    }
    bool computed() const { return !(dxLow == half::kNaN && dxHigh == kNotComputed); }
};

/// Packs and unpacks against one field's height range (set before use).
class BoundPacking {
public:
    void setHeightRange(float lowest, float highest) {
        lowest_ = double(lowest);
        const double range = double(highest) - double(lowest);
        step_ = range > 0.0 ? range / 65535.0 : 1.0;
        // The largest error (the range) scales to 32768, leaving half's top octave free.
        errorScale_ = range > 0.0 ? 32768.0 / range : 1.0;
    }

    static bool known(const PackedBound& b) { return b.error != half::kNaN; }

    PackedBound pack(const CellError& e) const {
        PackedBound p;
        p.low = heightCode(e.low, false);
        p.high = heightCode(e.high, true);
        p.error = half::rounded(roundedUp(double(e.error) * errorScale_), true);
        return p;
    }

    CellError unpack(const PackedBound& p) const {
        CellError e;
        e.low = decoded(p.low, false);
        e.high = decoded(p.high, true);
        e.error = roundedUp(double(half::toFloat(p.error)) / errorScale_);
        return e;
    }

    static PackedSlopes pack(const SlopeBox& s) {
        PackedSlopes p;
        if (!s.known()) return p;
        p.dxLow = half::rounded(s.dxLow, false), p.dxHigh = half::rounded(s.dxHigh, true);
        p.dzLow = half::rounded(s.dzLow, false), p.dzHigh = half::rounded(s.dzHigh, true);
        if (!half::isFinite(p.dxLow) || !half::isFinite(p.dxHigh) || !half::isFinite(p.dzLow) || !half::isFinite(p.dzHigh))
            return PackedSlopes{}; // steeper than half can say: unknown, never culled
        return p;
    }

    static SlopeBox unpack(const PackedSlopes& p) {
        SlopeBox s; // unknown
        if (p.dxLow == half::kNaN) return s;
        s.dxLow = half::toFloat(p.dxLow), s.dxHigh = half::toFloat(p.dxHigh);
        s.dzLow = half::toFloat(p.dzLow), s.dzHigh = half::toFloat(p.dzHigh);
        return s;
    }

private:
    double height(uint16_t code) const { return lowest_ + double(code) * step_; }

    // The decoded height of a code, as a float on the side of the bound.
    float decoded(uint16_t code, bool up) const { return up ? roundedUp(height(code)) : roundedDown(height(code)); }

    // The largest code whose decoded height is at or below h (up: the smallest at or above),
    // clamped to the range. Found from the nearest step and checked against the decoded floats,
    // so a bound never shrinks and a decoded height packs to itself.
    uint16_t heightCode(float h, bool up) const {
        const double t = (double(h) - lowest_) / step_;
        int32_t code = int32_t(std::fmax(0.0, std::fmin(65535.0, up ? std::ceil(t) : std::floor(t))));
        if (!up) {
            while (code < 65535 && decoded(uint16_t(code + 1), false) <= h) ++code;
            while (code > 0 && decoded(uint16_t(code), false) > h) --code;
        } else {
            while (code > 0 && decoded(uint16_t(code - 1), true) >= h) --code;
            while (code < 65535 && decoded(uint16_t(code), true) < h) ++code;
        }
        return uint16_t(code);
    }

    double lowest_ = 0.0, step_ = 1.0, errorScale_ = 1.0;
};

} // namespace hexlod
