// How a height field's raw samples become metres: their type and scale (field/heightfield.h
// holds them whole, field/sample_tiles.h by tiles).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hexlod {

enum class SampleType : int32_t { U8 = 1, U16 = 2, I16 = 3, F32 = 4 };

/// Bytes per sample of a type, 0 for an unknown type.
size_t sampleBytes(SampleType type);

/// Largest field the core accepts (samples per side). 65536 keeps every index math in 32 bits
/// while allowing far more than a 4 GB WASM memory can hold.
constexpr int32_t kMaxFieldSide = 65536;
/// Sample spacing, metres: a micrometre (surface metrology) to 100,000 km (a coarse whole planet).
constexpr double kMinSpacing = 1e-6, kMaxSpacing = 1e8;
/// Largest height magnitude, metres after the scale (offset included): a thousand times the
/// Moon's distance, far past any real relief, and small enough that heights times the largest
/// vertical scale (1000) stay within the camera's coordinates (api/hexlod.h).
constexpr double kMaxAbsHeight = 1e9;

struct HeightfieldScale {
    double spacingX = 1.0;     // metres between columns
    double spacingY = 1.0;     // metres between rows
    double heightScale = 1.0;  // metres per raw unit
    double heightOffset = 0.0; // metres at raw 0
    bool hasNodata = false;    // whether nodataRaw marks missing samples (NaN always does for f32)
    double nodataRaw = 0.0;    // raw value of a missing sample
};

} // namespace hexlod
