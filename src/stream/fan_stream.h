// FanStream: the index arrays the renderer uploads (paper §7), kept in step with the mesh
// incrementally. The vertex array is the mesh's own pool of StreamVertex, and the fans are the
// mesh's own fan table (vertex data and cell vertices exist once); this class writes the
// normals, tracks what changed, and keeps the triangle list when that layout is chosen.
//
// Every cell record owns a fixed slot of the index array, so an operation changes only the
// slots of the cells it changed:
//   Fans layout (9 indices a cell), drawn as TRIANGLE_FAN with primitive restart: the mesh's
//     fan table itself (HexMesh::fanTable, its layout in hex_mesh.h), nothing copied.
//   Triangles layout (18 indices a cell): the same triangles as an indexed list, padded with
//     restart indices (which end no triangle: WebGL2 always restarts at 0xFFFFFFFF); this
//     class writes it from the fans.
//
// Normals (§7, "averaged from the adjacent triangles of the current mesh") are sums of face
// normals kept per vertex in 64-bit fixed point: an operation subtracts the triangles of the
// slots it overwrites and adds the new ones, exactly, so incremental normals equal rebuilt ones
// bit for bit and never drift. That needs the old triangles' vertices to keep their positions
// until the sync, which HexMesh's deferred vertex reuse guarantees.
//
// What changed since the renderer last acknowledged is kept as dirty blocks, handed out as
// element ranges; the version moves whenever something was written.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>

#include "stream/geomorph.h"
#include "mesh/hex_mesh.h"

namespace hexlod {

enum class IndexLayout : int32_t { Fans = 0, Triangles = 1 };

/// A run of array elements [first, first + count) to upload.
struct ElementRange {
    int32_t first, count;
};

class FanStream {
public:
    static constexpr int32_t kFanSlot = kCellFanSlot;
    static constexpr int32_t kTriangleSlot = 18;

    /// Starts following `mesh` (until the next attach): sets its change logs and deferred vertex
    /// reuse, and writes every slot and normal afresh. Call after every mesh reset.
    void attach(HexMesh& mesh);
    /// Switches the layout; everything is rewritten.
    void setLayout(IndexLayout layout);
    IndexLayout layout() const { return layout_; }
    /// Whether the stream keeps the mesh's vertex normals (§7), on by default. Off, it keeps no
    /// normals (8 bytes a vertex) and no normal sums (24 bytes) and does no normal arithmetic;
    /// turned on, every normal is rebuilt exactly and marked dirty. The viewer turns them off
    /// while it lights the terrain from the field's own normals.
    void setNormals(bool on);
    bool normals() const { return normals_; }
    /// The vertex normals, one per vertex slot, 4 snorm16 (x, y, z, missing) each, averaged over the
    /// adjacent triangles; the renderer uploads them beside the vertex pool, with the same
    /// dirty ranges. Null while normals are off.
    const int16_t* normalData() const { return normals_ && !vertexNormals_.empty() ? vertexNormals_[0].xyz : nullptr; }
    const int16_t* normal(int32_t v) const { return vertexNormals_[size_t(v)].xyz; }
    int32_t slotSize() const { return layout_ == IndexLayout::Fans ? kFanSlot : kTriangleSlot; }

    /// The mesh renumbered its cells and vertices (HexMesh::compact): every slot and normal is
    /// written afresh into arrays sized for the compacted pools, and marked dirty.
    void renumbered(HexMesh& mesh);

    /// Applies what the mesh did since the last sync: rewrites the changed cells' slots and
    /// the normals they touch, starts the blend-in of new vertices, and marks all of it dirty.
    /// Allocates nothing unless the pools grew.
    void sync(HexMesh& mesh, Geomorph& morph);

    /// Moves vertices without changing the mesh (a tiled field's heights changed under them,
    /// field/sample_tiles.h): `move()` sets the new positions; `cells` are every live cell that
    /// draws a vertex that moves. Their normals follow exactly (the cells' triangles leave the
    /// sums before the move and come back after it) and their vertices are marked dirty. Call
    /// between frames, after a sync.
    template <typename Move>
    void moveVertices(HexMesh& mesh, const std::vector<int32_t>& cells, Move&& move) {
        for (int32_t c : cells) accumulate(mesh, keptSlot(mesh, c), -1);
        move();
        for (int32_t c : cells) accumulate(mesh, keptSlot(mesh, c), +1);
        finishNormals(mesh);
        touchedVertices_.clear();
        ++version_;
    }
    /// The index array to draw: the mesh's fan table, or the triangle list.
    const std::vector<uint32_t>& indices() const { return layout_ == IndexLayout::Fans ? mesh_->fanTable() : indices_; }
    /// Indices to draw: the slots of every cell record the pool has (free ones are restarts).
    int32_t indexCount() const { return mesh_ ? int32_t(indices().size()) : 0; }
    uint32_t version() const { return version_; }
    /// Dirty ranges since the last acknowledge(), in vertices and in indices.
    const std::vector<ElementRange>& dirtyVertices();
    const std::vector<ElementRange>& dirtyIndices();
    void acknowledge();

    // --- The level-ordered view, written on demand for the diagnostic views (colour by level,
    // hexagon outlines); the drawing path does not need it.
    /// Writes every cell's fan grouped by level (levelOffsets: first index of each level, plus
    /// the end), and, with outline, every cell edge once as a line pair.
    void buildLevelView(const HexMesh& mesh, bool outline);
    const std::vector<uint32_t>& levelIndices() const { return levelIndices_; }
    const std::vector<int32_t>& levelOffsets() const { return levelOffsets_; }
    const std::vector<uint32_t>& outline() const { return outline_; }

    size_t memoryBytes() const;
    /// Of memoryBytes(), what the mesh's live cells and vertices need: their index slots and
    /// normal sums (scratch lists and the diagnostic level view not counted).
    size_t liveMemoryBytes() const;

private:
    // Dirty blocks of 32 vertices (1.1 KB) or cells (1.1 KB of fan indices). Runs of dirty
    // blocks closer than kMergeGap blocks are uploaded as one range: a few clean bytes cost
    // less than another bufferSubData call.
    static constexpr int32_t kBlockShift = 5;
    static constexpr int32_t kMergeGap = 4;

    void rewriteAll(HexMesh& mesh);
    void writeSlot(const HexMesh& mesh, int32_t cell);
    /// Whether indices_ is kept: the triangle list, or in the fans layout with normals on, the
    /// fans as last synced (their old triangles' normals are subtracted when a cell changes).
    bool keepsSlots() const { return layout_ == IndexLayout::Triangles || normals_; }
    template <typename Visit>
    void forEachTriangle(const uint32_t* slot, Visit&& visit) const;
    void accumulate(const HexMesh& mesh, const uint32_t* slot, int64_t sign);
    void markVertex(int32_t v);
    // The slot whose triangles the normal sums hold: the kept one, or the mesh's fan.
    const uint32_t* keptSlot(const HexMesh& mesh, int32_t c) const {
        return keepsSlots() ? indices_.data() + size_t(c) * size_t(slotSize()) : mesh.cellFan(c);
    }
    void releaseArrays();
    void finishNormals(HexMesh& mesh);
    void rebuildNormals(HexMesh& mesh);
    struct DirtySet {
        std::vector<uint8_t> marked; // per block
        std::vector<int32_t> list;   // the marked blocks, in marking order
        void mark(int32_t element);
        void markAll(int32_t elements);
        void clear();
        void collect(int32_t elements, std::vector<ElementRange>& out); // sorts the list
    };

    IndexLayout layout_ = IndexLayout::Fans;
    bool normals_ = true;
    HexMesh* mesh_ = nullptr;
    std::vector<uint32_t> indices_; // see keepsSlots
    std::vector<glm::i64vec3> normalSum_; // per vertex, fixed point (see normalScale_)
    struct PackedNormal {
        int16_t xyz[4] = {0, 32767, 0, 0}; // snorm16 x, y, z and 1 where no-data; up until written
    };
    std::vector<PackedNormal> vertexNormals_; // per vertex slot while normals are on
    double normalScale_ = 1.0;            // fixed-point units per square metre of face normal
    std::vector<int32_t> changedCells_, vertexLog_;
    std::vector<bool> cellPending_, vertexPending_; // a bit per record (bytes per triangle)
    std::vector<int32_t> touchedVertices_;
    DirtySet dirtyVertices_, dirtyIndices_;
    std::vector<ElementRange> vertexRanges_, indexRanges_;
    uint32_t version_ = 0;

    std::vector<uint32_t> levelIndices_, outline_;
    std::vector<int32_t> levelOffsets_;
};

} // namespace hexlod
