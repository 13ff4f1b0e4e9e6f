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

#include "field/heightfield_scale.h"
#include "field/sample_tiles.h"

namespace hexlod {

class Heightfield {
public:
    /// Allocates width*height samples (uninitialised). Returns null when the size is invalid
    /// or memory is exhausted; `error` then says which.
    static std::unique_ptr<Heightfield> create(int32_t width, int32_t height, SampleType type,
                                               const char** error);
    /// A field whose samples arrive by tiles (field/sample_tiles.h): `levels` x (width, height,
    /// tileWidth, tileHeight), the full resolution first, then ever coarser overviews. It holds
    /// no sample yet: the caller writes and commits the coarsest level's tiles before prepare().
    static std::unique_ptr<Heightfield> createTiled(int32_t width, int32_t height, SampleType type, int32_t levels,
                                                    const int32_t* dims, const char** error);
    /// The tiles of a tiled field, null for a field held whole.
    SampleTiles* tiles() { return tiles_.get(); }
    const SampleTiles* tiles() const { return tiles_.get(); }

    int32_t width() const { return width_; }
    int32_t height() const { return height_; }
    SampleType type() const { return type_; }
    /// The samples of a field held whole, row by row; null for a tiled field.
    void* samples() { return samples_.get(); }
    const void* samples() const { return samples_.get(); }
    size_t sampleCount() const { return size_t(width_) * size_t(height_); }
    /// Bytes of the samples held: all of them, or the tiles present.
    size_t byteSize() const { return tiles_ ? tiles_->sampleBytes() : sampleCount() * sampleBytes(type_); }

    /// Validates the scale and records it (spacings within [kMinSpacing, kMaxSpacing], a non-zero
    /// height scale and an offset within kMaxAbsHeight). Returns an error message or null.
    const char* setScale(const HeightfieldScale& scale);
    const HeightfieldScale& scale() const { return scale_; }

    /// Widens the height range to [low, high] metres (a tiled field, after prepare): what a file
    /// says of all its samples (GDAL's statistics), which the tiles present cannot show. The
    /// refinement packs its bounds in steps of the range (lod/packed_bounds.h): with the whole
    /// range known, the converged mesh is the one of the field loaded whole. False (nothing
    /// changed) for a range that is not finite or inverted.
    bool declareHeightRange(double low, double high);
    /// Grows the height range by what the tiles hold now (a tiled field, after tiles came).
    /// True when it grew.
    bool widenHeightRange();

    /// Call after the samples are written: replaces missing samples (nodata, NaN, inf) by the
    /// lowest valid height, so no spike or hole reaches the mesh, and finds min and max.
    /// Returns an error message (every sample missing, or heights beyond kMaxAbsHeight metres
    /// after the scale) or null; on error nothing changed.
    const char* prepare();
    size_t missingCount() const { return missingCount_; }
    float minHeight() const { return minHeight_; } // metres
    float maxHeight() const { return maxHeight_; } // metres

    /// Height in metres of sample (column j, row i); both must be inside the field. A tiled
    /// field answers from the finest level present there (sample_tiles.h).
    float heightAt(int32_t j, int32_t i) const {
        if (tiles_) return tiledHeightAt(j, i); // out of line: a field held whole inlines the rest
        const size_t k = size_t(i) * size_t(width_) + size_t(j);
        return float(rawAt(k) * scale_.heightScale + scale_.heightOffset);
    }
    /// Whether sample (j, i), inside the field, was no-data (its height is a fill): known for a
    /// tiled field (SampleTiles::missing); a field held whole is filled by the caller.
    bool sampleMissing(int32_t j, int32_t i) const { return tiles_ && tiledMissing(j, i); }
    /// Whether any sample was no-data so far (asked for every vertex the stream writes: inline).
    bool anyMissing() const { return tiles_ ? tiles_->missingCount() > 0 : missingCount_ > 0; }
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
    float tiledHeightAt(int32_t j, int32_t i) const;
    bool tiledMissing(int32_t j, int32_t i) const;
    void setRaw(size_t k, double raw);

    int32_t width_ = 0;
    int32_t height_ = 0;
    SampleType type_ = SampleType::F32;
    std::unique_ptr<uint8_t[]> samples_;
    std::unique_ptr<SampleTiles> tiles_;
    HeightfieldScale scale_;
    size_t missingCount_ = 0;
    float minHeight_ = 0.0f;
    float maxHeight_ = 0.0f;
};

} // namespace hexlod
