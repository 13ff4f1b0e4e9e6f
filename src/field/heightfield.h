// The height field the paper's §4.7 maps hexagons onto (input to every later section).
// Heightfield: the user's samples at their native depth, plus what turns them into metres.
//
// The samples live in one buffer owned here. JS decodes a file straight into that buffer
// (hexlod_terrain_samples), so a 16-bit field stays 16-bit and is never copied in full.
// Column j runs east along +x, row i runs south along +z (row 0 is the north edge).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

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

class Heightfield {
public:
    /// Allocates width*height samples (uninitialised). Returns null when the size is invalid
    /// or memory is exhausted; `error` then says which.
    static std::unique_ptr<Heightfield> create(int32_t width, int32_t height, SampleType type,
                                               const char** error);

    int32_t width() const { return width_; }
    int32_t height() const { return height_; }
    SampleType type() const { return type_; }
    void* samples() { return samples_.get(); }
    const void* samples() const { return samples_.get(); }
    size_t sampleCount() const { return size_t(width_) * size_t(height_); }
    size_t byteSize() const { return sampleCount() * sampleBytes(type_); }

    /// Validates the scale and records it (spacings within [kMinSpacing, kMaxSpacing], a non-zero
    /// height scale and an offset within kMaxAbsHeight). Returns an error message or null.
    const char* setScale(const HeightfieldScale& scale);
    const HeightfieldScale& scale() const { return scale_; }

    /// Call after the samples are written: replaces missing samples (nodata, NaN, inf) by the
    /// lowest valid height, so no spike or hole reaches the mesh, and finds min and max.
    /// Returns an error message (every sample missing, or heights beyond kMaxAbsHeight metres
    /// after the scale) or null; on error nothing changed.
    const char* prepare();
    size_t missingCount() const { return missingCount_; }
    float minHeight() const { return minHeight_; } // metres
    float maxHeight() const { return maxHeight_; } // metres

    /// Height in metres of sample (column j, row i); both must be inside the field.
    float heightAt(int32_t j, int32_t i) const {
        const size_t k = size_t(i) * size_t(width_) + size_t(j);
        return float(rawAt(k) * scale_.heightScale + scale_.heightOffset);
    }
    /// Same, with the indices clamped to the field (lookups outside the rectangle).
    float heightClamped(int32_t j, int32_t i) const;
    /// Bilinear height in metres at a horizontal position in metres (x east, z south), clamped.
    float heightAtPosition(double xMetres, double zMetres) const;

private:
    Heightfield() = default;
    double rawAt(size_t k) const {
        switch (type_) {
            case SampleType::U8: return static_cast<const uint8_t*>(samples_.get())[k];
            case SampleType::U16: return reinterpret_cast<const uint16_t*>(samples_.get())[k];
            case SampleType::I16: return reinterpret_cast<const int16_t*>(samples_.get())[k];
            case SampleType::F32: return reinterpret_cast<const float*>(samples_.get())[k];
        }
        return 0.0;
    }
    bool isMissing(size_t k) const;
    void setRaw(size_t k, double raw);

    int32_t width_ = 0;
    int32_t height_ = 0;
    SampleType type_ = SampleType::F32;
    std::unique_ptr<uint8_t[]> samples_;
    HeightfieldScale scale_;
    size_t missingCount_ = 0;
    float minHeight_ = 0.0f;
    float maxHeight_ = 0.0f;
};

} // namespace hexlod
