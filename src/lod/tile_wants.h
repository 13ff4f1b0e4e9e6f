// The tiles a field that arrives by tiles (field/sample_tiles.h) should fetch next: under every
// cell the data holds back (Refiner::starved), the tiles of the level its children need, most
// needed first by the cell's projected error (paper §5's screen-space error, in pixels).
// Collected again each time it is asked, so a tile no cell needs any more drops out: the
// caller's queue follows the view.
#pragma once

#include <cstdint>
#include <vector>

#include "field/heightfield.h"
#include "field/sparse_grid.h"
#include "mesh/embedding.h"
#include "mesh/hex_mesh.h"

namespace hexlod {

/// One tile to fetch. 16 bytes (the C ABI's hexlod_tile_want).
struct TileWant {
    int32_t level, tx, ty;
    float priority; // the largest projected error (pixels) of a cell that needs it
};

class TileWants {
public:
    /// At most this many wants, the most needed.
    static constexpr int32_t kMaxWants = 4096;

    /// The wants of the cells in `starved` (per cell record, Refiner::starved), most needed
    /// first; tiles already present are not wanted.
    const std::vector<TileWant>& collect(const HexMesh& mesh, const Heightfield& field, const std::vector<float>& starved);
    const std::vector<TileWant>& wants() const { return wants_; }
    /// The present tiles the drawn mesh stands on: under each cell of step s, those of the levels
    /// whose samples are s to s / 4 apart (a level coarser than s would not have let its parent
    /// split; the finer one below keeps its heights). Letting other tiles go changes heights
    /// where they were (vertices blend) and may let cells there merge. The coarsest level is
    /// always held, and not listed. Priority: 0. A pass over the live cells: for a cache near its cap, not for
    /// every frame.
    const std::vector<TileWant>& collectInUse(const HexMesh& mesh, const Heightfield& field);
    size_t memoryBytes() const;

private:
    // Empties the list and starts a new stamp; false for a field held whole.
    bool begin(const Heightfield& field);
    void want(const SampleTiles& tiles, int32_t level, int32_t tx, int32_t ty, float priority);

    std::vector<TileWant> wants_;
    // Per level and tile: the stamp of the collection that listed it, and where. Sparse: a world
    // field has millions of tiles, a view lists a few thousand.
    struct Listed {
        uint32_t stamp = 0;
        int32_t index = 0; // in wants_
    };
    std::vector<SparseGrid<Listed>> listed_;
    uint32_t now_ = 0;
};

} // namespace hexlod
