// SampleTiles: the samples of a height field that arrive by tiles, as a Cloud-Optimized GeoTIFF
// read by range requests gives them: the full resolution and its overviews (coarser levels),
// each cut into tiles, any tile present or not. It lets the core refine a field far larger than
// memory (paper §5's refinement, §4.7's field) while only the tiles the view needs are held.
//
// Heights are read from the finest level present: per region (one full-resolution tile, or a
// block of 2^k x 2^k of them when the field has more than kMaxRegions tiles), the finest level
// whose samples around the region are all present gives the heights there, bilinear between
// that level's samples (its sample k sits at full-resolution position (k + 0.5) * scale - 0.5).
// What is kept per tile is sparse (field/sparse_grid.h): it follows the tiles held, not the
// field's size. The coarsest level is always whole (the caller loads it first), so
// every height has an answer, and a region's answer changes only when a tile arrives or goes.
//
// The refiner (lod/refiner.h) does not split a cell finer than the level its heights come from
// (levelIn); it asks for the tiles it would need instead (lod/tile_wants.h).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "field/heightfield_scale.h"
#include "field/sparse_grid.h"

namespace hexlod {

/// A rectangle of full-resolution samples, inclusive; empty when j0 > j1.
struct SampleRect {
    int32_t j0 = 0, i0 = 0, j1 = -1, i1 = -1;
    bool empty() const { return j0 > j1 || i0 > i1; }
    void add(const SampleRect& r);
    bool intersects(const SampleRect& r) const { return !empty() && !r.empty() && j0 <= r.j1 && r.j0 <= j1 && i0 <= r.i1 && r.i0 <= i1; }
};

/// What a level keeps per tile.
struct TileState {
    int32_t slot = -1;    // its buffer in the slot pool, or -1
    uint8_t present = 0;  // committed
    float detail = 0.0f;  // metres, see SampleTiles::commit
};

/// A tile of a level.
struct TileId {
    int32_t level = -1, tx = 0, ty = 0;
};

/// One level of the pyramid: level 0 is the full resolution.
struct TileLevel {
    int32_t width = 0, height = 0;         // samples
    int32_t tileWidth = 0, tileHeight = 0; // samples
    int32_t tilesAcross = 0, tilesDown = 0;
    double scaleX = 1.0, scaleY = 1.0;     // full-resolution samples per sample of this level
    SparseGrid<TileState> tiles;           // per tile, held only around the tiles that came
    size_t tileCount() const { return size_t(tilesAcross) * size_t(tilesDown); }
};

class SampleTiles {
public:
    static constexpr int32_t kMaxLevels = 24;
    /// Most tiles a level may have: the sparse per-tile state's page table stays about 256 KB.
    /// A 2^21-sample side (kMaxTiledFieldSide) needs tiles of 256 samples a side or more.
    static constexpr int64_t kMaxTilesPerLevel = int64_t(1) << 26;
    /// Most regions (what keeps the level heights come from, 5 bytes each, for the whole field):
    /// a field with more full-resolution tiles groups them, 2 x 2, 4 x 4, ..., a region (20 MB
    /// at most; a world DEM at 1″ in 512² tiles has 3.1 million, one a region).
    static constexpr int64_t kMaxRegions = int64_t(1) << 22;

    /// levels x (width, height, tileWidth, tileHeight), finest first; each level coarser than
    /// the one before. Returns an error message or null.
    const char* init(int32_t width, int32_t height, SampleType type, int32_t levels, const int32_t* dims);
    void setScale(const HeightfieldScale& scale) { scale_ = scale; }

    int32_t levelCount() const { return int32_t(levels_.size()); }
    const TileLevel& level(int32_t l) const { return levels_[size_t(l)]; }
    int32_t coarsest() const { return levelCount() - 1; }

    /// Where the caller writes tile (level, tx, ty): tileWidth * tileHeight samples of the
    /// field's type, row by row (allocated once per slot, reused after an eviction). Null for a
    /// tile outside the level or when memory is exhausted.
    void* tileBuffer(int32_t level, int32_t tx, int32_t ty);
    /// The tile's samples were written: from now on they are present. Missing samples (nodata,
    /// NaN) take the fill value; the tile's detail (the largest half second difference of its
    /// heights, metres: how far its samples stand off the line through their neighbours, the
    /// scale of what the next finer level may add) is measured. `changed` grows by the
    /// samples whose heights changed. False when the tile has no buffer.
    bool commit(int32_t level, int32_t tx, int32_t ty, SampleRect& changed);
    /// The tile is gone (the cache dropped it); `changed` as for commit. Tiles of the coarsest
    /// level stay. False when the tile was not held.
    bool evict(int32_t level, int32_t tx, int32_t ty, SampleRect& changed);
    bool present(int32_t level, int32_t tx, int32_t ty) const;
    /// The tiles held: slot s holds tile heldTile(s) (level -1 when the slot is free), s in
    /// [0, slotCount()). Committed or not (present says).
    int32_t slotCount() const { return int32_t(slotOwner_.size()); }
    const TileId& heldTile(int32_t s) const { return slotOwner_[size_t(s)]; }
    /// Whether every tile of the coarsest level is present (the field can be drawn).
    bool coarsestComplete() const;

    /// The tiles present read again with the scale now set (its no-data value): their range
    /// and their missing samples. Tiles may come before the scale does; the field's first
    /// prepare calls this (later ones find nothing to do).
    void rescan();
    /// The lowest and highest raw sample of every tile committed so far (missing samples
    /// excluded; an eviction does not narrow it); false when no sample came yet.
    bool rawRange(double& low, double& high) const;
    /// Fills the missing samples from now on (the present tiles first): the coarsest level's by
    /// interpolation across each gap along rows and columns (`raw`, the lowest height, where
    /// a row and a column hold none), every finer tile's from the coarser surface present under
    /// it, so a void is filled alike at every level and across tiles. Their marks stay (missing).
    void setFillRaw(double raw);
    /// Fills the voids with the lowest height instead (pits), or back from the surface around
    /// them: a pit's walls make the refinement follow a void's edge to the data's resolution,
    /// which a void drawn as a hole wants. `changed` grows by the samples whose heights changed.
    void setVoidsAsPits(bool pits, SampleRect& changed);
    size_t missingCount() const { return missing_; }

    /// Height in metres at full-resolution sample (j, i), inside the field.
    float height(int32_t j, int32_t i) const {
        const size_t region = regionOf(j / regionWidth_, i / regionHeight_);
        if (regionLevel_[region] == 0) {
            const TileLevel& l = levels_[0];
            const int32_t tx = j / l.tileWidth, ty = i / l.tileHeight;
            const int32_t slot = l.tiles.get(tx, ty).slot;
            return toMetres(rawIn(slot, size_t(i - ty * l.tileHeight) * size_t(l.tileWidth) + size_t(j - tx * l.tileWidth)));
        }
        return blended(regionLevel_[region], j, i);
    }
    /// Whether full-resolution sample (j, i), inside the field, is no-data where its height comes
    /// from: at a coarser level, whether missing samples weigh half or more in its bilinear blend.
    /// The page draws such samples as holes when asked (terrain.frag).
    bool missing(int32_t j, int32_t i) const;
    /// Lowest and highest height in metres over the samples of `rect` (clamped to the field):
    /// a bound of the heights height() gives there.
    void range(const SampleRect& rect, float& low, float& high) const;
    /// The coarsest level that heights come from in `rect`, and the largest detail (metres) of
    /// the tiles they come from (0 where that level is the full resolution).
    int32_t levelIn(const SampleRect& rect, float& detail) const;
    /// The finest level that heights come from in `rect` (the coarsest for an empty one).
    int32_t finestLevelIn(const SampleRect& rect) const;
    /// The full-resolution samples a region side: heights come from one level over each region.
    int32_t regionWidth() const { return regionWidth_; }
    int32_t regionHeight() const { return regionHeight_; }
    /// The tiles of `level` whose samples cover `rect` (clamped to the level).
    void tilesCovering(int32_t level, const SampleRect& rect, int32_t& tx0, int32_t& ty0, int32_t& tx1, int32_t& ty1) const;

    /// Bytes of the tiles held (their slots), of one slot, and of the bookkeeping.
    size_t sampleBytes() const;
    size_t slotBytes() const { return slotBytes_; }
    size_t memoryBytes() const;

private:
    double rawIn(int32_t slot, size_t k) const;
    float toMetres(double raw) const { return float(raw * scale_.heightScale + scale_.heightOffset); }
    float blended(int32_t level, int32_t j, int32_t i) const;
    // Where full-resolution sample (j, i) falls among a coarser level's samples: the four
    // around it and its fractions between them.
    struct BlendCorners {
        int32_t u0, v0, u1, v1;
        double fu, fv;
    };
    BlendCorners blendCorners(const TileLevel& l, int32_t j, int32_t i) const;
    bool missingAtLevel(const TileLevel& l, int32_t u, int32_t v) const;
    double rawAtLevel(const TileLevel& l, int32_t u, int32_t v) const;
    // The lowest and highest raw sample of `level` over [u0, u1] x [v0, v1], tile by tile (held).
    void levelRawRange(int32_t level, int32_t u0, int32_t v0, int32_t u1, int32_t v1, double& low, double& high) const;
    bool missingRaw(double raw) const;
    // Sets the bits of the tile's missing samples (and counts them).
    void markMissing(int32_t level, int32_t tx, int32_t ty);
    // Writes rawAt(u, v) (the level's sample indices) into the tile's marked samples; false when it has none.
    template <typename ValueAt>
    bool writeFill(int32_t level, int32_t tx, int32_t ty, ValueAt&& rawAt);
    void fillTile(int32_t level, int32_t tx, int32_t ty, SampleRect& changed);
    void fillCoarsest(SampleRect& changed);
    void fillAll(SampleRect& changed);
    // The height (metres) under full-resolution sample (j, i) from the next coarser level held there.
    float coarserSurface(int32_t level, int32_t j, int32_t i) const;
    // Writes into out[] (same stride) the interpolation across each run of NaN in line[] of n values.
    static void interpolateGaps(const float* line, size_t stride, size_t n, float* out);
    // The coarsest level is interpolated whole up to this many samples (12 bytes each while it
    // is: 48 MB); past it (a COG without overviews) each of its voids takes the lowest height.
    static constexpr size_t kMaxInterpolatedSamples = size_t(1) << 22;
    void widenRange(int32_t level, int32_t tx, int32_t ty);
    float measureDetail(int32_t level, int32_t tx, int32_t ty) const;
    // The level-l samples (inclusive) whose bilinear blend reaches full-resolution rect r.
    void samplesFor(int32_t level, const SampleRect& r, int32_t& u0, int32_t& v0, int32_t& u1, int32_t& v1) const;
    size_t regionOf(int32_t rx, int32_t ry) const { return size_t(ry) * size_t(regionsAcross_) + size_t(rx); }
    SampleRect regionRect(int32_t rx, int32_t ry) const;
    SampleRect tileRect(int32_t level, int32_t tx, int32_t ty) const; // full-resolution samples it reaches
    // The regions `around` after a tile of `level` came (arrived) or went: a region's level can
    // only become that level, or, where it was that level, the next complete one coarser.
    void updateRegions(const SampleRect& around, int32_t level, bool arrived, SampleRect& changed);
    // Whether every tile of `level` whose samples reach `r` is present, and their largest detail.
    bool completeAt(int32_t level, const SampleRect& r, float& detail) const;

    int32_t width_ = 0, height_ = 0;
    SampleType type_ = SampleType::I16;
    size_t bytesPerSample_ = 2;
    HeightfieldScale scale_;
    std::vector<TileLevel> levels_;
    size_t slotBytes_ = 0;
    std::vector<std::unique_ptr<uint8_t[]>> slots_;
    std::vector<TileId> slotOwner_; // per slot: the tile in it
    std::vector<std::vector<uint8_t>> slotMissing_; // per slot: a bit per missing sample; empty when none is
    std::vector<int32_t> freeSlots_;
    int32_t heldSlots_ = 0;
    // Regions: the full-resolution tiles (or blocks of them, kMaxRegions).
    int32_t regionWidth_ = 1, regionHeight_ = 1, regionsAcross_ = 0, regionsDown_ = 0;
    std::vector<uint8_t> regionLevel_;   // the level heights come from
    std::vector<float> regionDetail_;    // metres: the detail of the tiles they come from (0 at level 0)
    bool hasFill_ = false;
    bool voidsAsPits_ = false;
    double fillRaw_ = 0.0;
    size_t missing_ = 0;
    bool hasRange_ = false;
    double rangeLow_ = 0.0, rangeHigh_ = 0.0;
};

} // namespace hexlod
