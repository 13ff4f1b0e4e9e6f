// How a height field's raw samples become metres: their type and scale (field/heightfield.h
// holds them whole, field/sample_tiles.h by tiles).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hexlod {

enum class SampleType : int32_t { U8 = 1, U16 = 2, I16 = 3, F32 = 4 };

/// Bytes per sample of a type, 0 for an unknown type.
size_t sampleBytes(SampleType type);

/// Largest field held whole (samples per side): 65536² samples are 8 GB at 16 bits, already
/// twice what a 4 GB WASM memory can hold.
constexpr int32_t kMaxFieldSide = 65536;
/// Largest field that arrives by tiles (samples per side), whose memory follows the tiles held.
/// The 32-bit lattice (mesh/lattice.h: q, r and the doubled x = 2q + r) would allow 2^29; what
/// binds first is that a vertex's lattice point is recovered from its float position
/// (HexMesh::latticeAt), exactly while columns and rows stay under 2^22, and the lattice reaches
/// up to a quarter of the shorter side past the east edge (hex_mesh_domain.cpp). 2^21 keeps it
/// in, and holds a world DEM at 1″ (1,296,000 x 626,400).
constexpr int32_t kMaxTiledFieldSide = 1 << 21;
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
