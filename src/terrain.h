// Terrain: one height field and everything the paper builds on it, wired once: the field
// (§4.7's input), the hexagon mesh (§4), the refiner with its criteria and caches (§5, §5.1,
// §6), the geomorph blends and the fan stream (§7). The C ABI (api/hexlod.h), the benchmark
// and the tests drive the core through this class instead of wiring the pieces by hand.
//
// Allocation happens when the terrain is created, when the mesh is (re)built, when a pool grows
// and when the pools are compacted after the mesh shrank by a sixteenth; a frame (setView,
// updateLod, syncStream) allocates nothing else.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "field/heightfield.h"
#include "lod/refiner.h"
#include "lod/tile_residency.h"
#include "lod/tile_wants.h"
#include "lod/view_criteria.h"
#include "mesh/hex_mesh.h"
#include "stream/fan_stream.h"
#include "stream/geomorph.h"

namespace hexlod {

/// Everything that is not the camera: the refinement (§5, §6), the blends and the stream (§7).
struct TerrainSettings {
    RefinerSettings lod;
    int32_t morphFrames = 0;                // geomorph blend length in LOD updates (0: off, at most Geomorph::kMaxFrames)
    IndexLayout layout = IndexLayout::Fans; // how the stream writes each cell's slot
    bool normals = true;                    // whether the stream keeps the vertex normals
    bool compactPools = true;               // give the pools' free records back when the mesh shrank by a sixteenth
};

class Terrain {
public:
    /// A terrain of width x height samples of `type`, uninitialised; null (and *error set)
    /// for a bad size or type or when memory is exhausted.
    static std::unique_ptr<Terrain> create(int32_t width, int32_t height, SampleType type, const char** error);

    /// A terrain whose samples arrive by tiles (field/sample_tiles.h): `levels` x (width,
    /// height, tileWidth, tileHeight), the full resolution first. Write and commit the coarsest
    /// level's tiles, then setScale, prepare and resetMesh as for any terrain.
    static std::unique_ptr<Terrain> createTiled(int32_t width, int32_t height, SampleType type, int32_t levels,
                                                const int32_t* dims, const char** error);
    /// A tiled terrain: where to write a tile's samples (SampleTiles::tileBuffer), then commit
    /// it; or let one go. The heights change at the end of the next syncStream (the vertices
    /// there blend to their new heights, the refiner tests the cells there again). False for
    /// a tile outside the levels, one not written or not held, or a terrain held whole.
    /// The terrain lets tiles go itself past its tile cap (lod/tile_residency.h); evictTile is
    /// for tests that take a tile away.
    void* tileBuffer(int32_t level, int32_t tx, int32_t ty);
    bool commitTile(int32_t level, int32_t tx, int32_t ty);
    bool evictTile(int32_t level, int32_t tx, int32_t ty);
    /// A tiled terrain: the bytes of samples its tiles past the coarsest level may hold; the
    /// next syncStream lets the least recently used ones go down to it. False for a terrain
    /// held whole or a cap that is not a number >= 0.
    bool setTileCap(double bytes);
    /// A tiled terrain: its voids filled with the lowest height (pits, for drawing them as holes)
    /// or from the surface around them (SampleTiles::setVoidsAsPits); the heights change at
    /// the next syncStream. False for a terrain held whole.
    bool setVoidsAsPits(bool pits);
    const TileResidency& residency() const { return residency_; }
    /// A tiled terrain: the height range of all its samples, as the file states it
    /// (Heightfield::declareHeightRange); with a mesh, every bound is packed anew. Returns null
    /// or what is wrong.
    const char* declareHeightRange(double low, double high);
    /// The tiles the view needs next, most needed first (lod/tile_wants.h); none for a
    /// terrain held whole or when every cell has the samples it needs.
    const std::vector<TileWant>& tileWants();
    /// The present tiles the drawn mesh stands on (TileWants::collectInUse). A pass over the
    /// live cells.
    const std::vector<TileWant>& tilesInUse();

    Heightfield& field() { return *field_; }
    const Heightfield& field() const { return *field_; }
    /// How samples become metres. With a mesh, the mesh is rebuilt from its base for the new
    /// scale (every position and cached bound depends on it; the settings are kept).
    /// Returns null, or what is wrong and the previous scale kept.
    const char* setScale(const HeightfieldScale& scale);
    /// After the samples were written: fills missing ones, computes the height range.
    const char* prepare() { return field_->prepare(); }

    /// (Re)creates the base mesh over the whole field (§4.7) and attaches the refiner, the
    /// blends and the stream to it. Returns null or what is wrong.
    const char* resetMesh(Embedding embedding);
    bool hasMesh() const { return hasMesh_; }
    /// Counts mesh rebuilds: state kept per mesh outside the terrain (a popping meter)
    /// compares it to know when to start again.
    uint32_t meshEpoch() const { return meshEpoch_; }

    /// Applies the settings: the only way to change them (the pieces are handed out read-only).
    /// The refiner compares them at its next update and re-tests every cell when one that
    /// decides a split changed; the layout and normals switches rewrite the stream only when
    /// they change.
    void configure(const TerrainSettings& settings);
    /// The settings in force, as the pieces hold them (configure() wrote them there).
    TerrainSettings settings() const {
        return {refiner_.settings(), morph_.frames(), stream_.layout(), stream_.normals(), compactPools_};
    }

    // One frame, in this order: the camera, one budgeted refinement step (§6), the stream (§7).
    void setView(const View& view) { refiner_.setView(view); }
    UpdateStats updateLod();
    /// Applies the frame's changes to the stream, then gives the pools' free records back when
    /// the mesh shrank by a sixteenth (compact()): memory held between frames is what the mesh
    /// needs, not what it needed a frame ago.
    void syncStream();
    /// The stream's dirty ranges since the last acknowledgeStream (FanStream::dirtyVertices;
    /// collecting them sorts them, hence not const).
    const std::vector<ElementRange>& dirtyVertexRanges() { return stream_.dirtyVertices(); }
    const std::vector<ElementRange>& dirtyIndexRanges() { return stream_.dirtyIndices(); }
    /// The renderer uploaded every dirty range of the stream: forget them.
    void acknowledgeStream() { stream_.acknowledge(); }
    /// Writes the stream's level-ordered view (FanStream::buildLevelView), for the diagnostic
    /// views of the page; the stream then hands it out.
    void buildLevelView(bool outline) { stream_.buildLevelView(mesh_, outline); }
    /// Renumbers the mesh densely and every consumer with it, giving the pools' free records
    /// back. syncStream does it (with compactPools) when the mesh shrank by a sixteenth; call it
    /// between frames only, after syncStream.
    void compact();
    /// Counts compactions: state kept per vertex number outside the terrain (a popping meter)
    /// renumbers itself with lastRenumbering() when this moved.
    uint32_t renumberings() const { return renumberings_; }
    /// Old -> new vertex numbers of the compaction at the end of this frame's syncStream
    /// (kNone: freed); kept until the next updateLod.
    const std::vector<int32_t>& lastRenumbering() const { return renumbering_; }
    /// The refiner converged and no merge waits for its vertices to fade out (§7), so the
    /// drawn surface will not change until the camera or a setting does.
    bool converged() const { return refiner_.lastUpdate().converged && refiner_.pendingMerges() == 0; }

    /// Records the mesh operations of every update (HexMesh::setOperationLog), for a benchmark
    /// that performs them again on a copy of the mesh; null: none.
    void setOperationLog(std::vector<MeshOperation>* log) { mesh_.setOperationLog(log); }
    /// Every cell is due at the next update (Refiner::restart): it is tested again from its
    /// cached bounds (§5.1). A converged mesh stays as it is.
    void retestEveryCell() { refiner_.restart(); }
    /// The uniform split, `rounds` times (Fig. 4), outside the refiner. Returns the splits.
    int64_t refineUniform(int32_t rounds);
    /// Height in metres (unscaled) of the surface as drawn now at (x, z) metres, blends
    /// included (drawn_surface.h); false where no drawn triangle covers the point.
    bool drawnHeightAt(double x, double z, float& height) const;
    /// Bytes of the mesh structures, the refiner's caches and the stream.
    size_t memoryBytes() const;

    /// The pieces, read-only: what changes them goes through the methods above, so that the
    /// pieces stay wired to each other and configure() stays the one way to set the settings.
    const HexMesh& mesh() const { return mesh_; }
    const Refiner& refiner() const { return refiner_; }
    const Geomorph& morph() const { return morph_; }
    const FanStream& stream() const { return stream_; }

    Terrain(const Terrain&) = delete; // the pieces point at each other
    Terrain& operator=(const Terrain&) = delete;

private:
    explicit Terrain(std::unique_ptr<Heightfield> field) : field_(std::move(field)) {}
    void attachMesh();
    void applyHeightChanges();

    std::unique_ptr<Heightfield> field_;
    HexMesh mesh_;
    bool hasMesh_ = false;
    uint32_t meshEpoch_ = 0;
    bool compactPools_ = true;
    uint32_t renumberings_ = 0;
    std::vector<int32_t> renumbering_;
    Geomorph morph_;
    Refiner refiner_;
    FanStream stream_;
    // A tiled terrain: the samples whose heights changed since the last sync, the tiles to
    // fetch, which tiles stay, and scratch lists of the vertices that move.
    SampleRect changedHeights_;
    TileWants wants_;
    TileResidency residency_;
    std::vector<int32_t> moving_, movingCells_;
    std::vector<float> movingHeights_;
    std::vector<uint8_t> movingMark_;
};

} // namespace hexlod
