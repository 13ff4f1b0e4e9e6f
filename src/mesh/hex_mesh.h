// HexMesh: the hexagon mesh of "Hexagonal LOD for Interactive Terrain Rendering" (Sußner,
// Dachsbacher, Greiner, VMV 2005), §4: an abstraction layer of hexagons above the triangular
// 1-to-4 split, refined by split and join and coarsened by merge and break, free of hanging
// nodes after every single operation.
//
// Cells are records in one flat pool (indices, free list); vertices are entries in flat
// arrays (indices, free list), stored once and shared by every cell that uses them.
//
// A cell is a full hexagon (even level), an interior semi-hexagon (odd level: half of a
// hexagon, a trapezoid of four corners drawn as two triangles), or a boundary semi-hexagon
// (even level: half of a hexagon whose centre lies on the domain boundary, drawn as a
// three-triangle half fan around that centre, §4.2).
//
// Slots (§4.3): slot 0 is the centre, slots 1..6 the corners counter-clockwise with
// corner k in lattice direction kDirections[k-1] (CellCorners). A semi-hexagon keeps the slots
// of the whole hexagon it is half of: corners firstVisible .. firstVisible+3 (cyclically) are
// its own, the rest are kNone.
//
// A cell's vertices are stored once, as its triangle fan (§7), in a table of kCellFanSlot
// indices a cell that the renderer draws as it is (TRIANGLE_FAN with primitive restart):
//   full hexagon:          centre, six corners, corner 1 again, restart
//   boundary semi-hexagon: centre, corners firstVisible .. firstVisible+3, restart (§4.2)
//   interior semi-hexagon: its four corners from the fixed-rule corner, restart
//   free record:           restart
// so the slots are decoded from the fan (corners(), cornerVertex()), and an operation writes a
// cell's fan when it changes the cell (the record no longer holds a second copy of
// the vertices, 28 bytes a cell).
//
// Edge slot k (1..6) runs from corner k to corner k+1; a semi's long edge (its diameter, on the
// parent's edge) is stored in edge slot firstVisible+3 and runs from corner firstVisible+3 back
// to corner firstVisible. Directed edges are numbered e = 8*cell + slot.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/embedding.h"
#include "field/heightfield.h"
#include "mesh/lattice.h"
#include "mesh/stream_vertex.h"

namespace hexlod {

constexpr int32_t kNone = -1;
/// Columns and rows of lattice points stay under this: HexMesh::latticeAt recovers a point from
/// its float position exactly only there (a field's side is limited accordingly, kMaxTiledFieldSide).
constexpr int64_t kMaxLatticeReach = int64_t(1) << 22;

/// §4.3: the cell of a directed edge, and the next and previous edge around that cell (the
/// slot arithmetic wraps 6 to 1).
inline int32_t hexIdx(int32_t e) { return e / 8; }
inline int32_t nextEdge(int32_t e) { return (e / 8) * 8 + ((e - (e / 8) * 8) % 6) + 1; }
inline int32_t prevEdge(int32_t e) { return (e / 8) * 8 + ((e - (e / 8) * 8 + 4) % 6) + 1; }
inline int32_t edgeSlot(int32_t e) { return e - (e / 8) * 8; }
inline int32_t makeEdge(int32_t cell, int32_t slot) { return cell * 8 + slot; }
/// Slot arithmetic: maps any slot number >= 1 onto 1..6.
inline int32_t wrapSlot(int32_t slot) { return (slot - 1) % 6 + 1; }

enum class CellKind : uint8_t { Full = 0, Semi = 1, BoundarySemi = 2 };

/// §7: the parents of a vertex made by a split or a join, a and b the ends of the coarser edge
/// whose midpoint it was made at (the blend starts there), and across the third corner of the
/// coarser triangle on the side of that edge where the vertex lies in the ground plane (the
/// exact embedding moves vertices off their parent edge by up to half a sample; kNone when it
/// lies on the edge): the coarser surface under the vertex is in triangle (a, b, across). The
/// same triangle is there again when a merge or break removes the vertex.
struct VertexParents {
    int32_t a = kNone, b = kNone, across = kNone;
};
struct ParentPoints {
    LatticePoint a, b, across;
    bool hasAcross = false;
};

/// A cell's vertices by slot (§4.3): [0] the centre, [1..6] the corners; kNone if absent.
/// Decoded from the cell's fan (HexMesh::corners), changed, and written back (setCorners).
struct CellCorners {
    int32_t vertex[7] = {kNone, kNone, kNone, kNone, kNone, kNone, kNone};
};

/// Indices a cell's fan takes in the fan table: centre, six corners, corner 1 again, restart.
constexpr int32_t kCellFanSlot = 9;
/// WebGL2's fixed primitive-restart index; the fan table's filler (kNone as unsigned).
constexpr uint32_t kRestartIndex = 0xFFFFFFFFu;

struct Hexagon {
    int32_t opposite[6];   // opposite directed edge across edge slot k at [k-1]; kNone on the domain boundary or unused
    int32_t prev, next;    // §4.4: neighbours in the list of this level; next also chains free records
    uint8_t level;         // §4.4: even for full and boundary semi-hexagons, odd for semi-hexagons
    uint8_t splitCount;    // §4.6: splits of this record not yet undone by a merge
    CellKind kind;
    uint8_t firstVisible : 4;  // semi-hexagons: first own corner slot (1..6); 0 for full hexagons
    uint8_t fanFromSecond : 1; // interior semi-hexagons: the fan starts at corner firstVisible+1 (semiFanFromSecondCorner)
};
static_assert(sizeof(Hexagon) == 36, "the memory per drawn triangle counts the bytes of a cell");

/// One operation that a split needs first under the balance rule (§4.5), or the split itself.
struct SplitStep {
    enum Kind : uint8_t { Split, JoinPair, JoinBoundary } kind = Split;
    int32_t cell = kNone;  // the cell to split, or the semi-hexagon to join
    int32_t other = kNone; // JoinPair: the semi-hexagon across its long edge
};

/// One operation as a caller asked for it (HexMesh::setOperationLog), to perform it again on a
/// copy of the mesh in the same state (HexMesh::replay).
struct MeshOperation {
    enum Kind : uint8_t { Split, JoinPair, JoinBoundary, Merge, Break } kind = Split;
    int32_t cell = kNone;
    int32_t other = kNone; // JoinPair: the semi-hexagon across the long edge
};
static_assert(int(MeshOperation::Split) == int(SplitStep::Split) && int(MeshOperation::JoinPair) == int(SplitStep::JoinPair) &&
                  int(MeshOperation::JoinBoundary) == int(SplitStep::JoinBoundary),
              "applyStep logs a step's kind as it is");

/// Counts of the operations a call performed, for tests and the refinement loop.
struct OperationCounts {
    int64_t splits = 0, joins = 0, merges = 0, breaks = 0;
};

class HexMesh {
public:
    /// Sets up the base mesh over the field (§4.7, see hex_mesh_domain.cpp). Allocates the
    /// pools; `baseStep` 0 picks one from the field size. Returns an error message or null.
    const char* reset(const Heightfield& field, Embedding embedding, int32_t baseStep = 0);

    // --- The four operations (§4.1, §4.5, §4.6). Each returns false, changing nothing, when it
    // does not apply; otherwise the mesh is consistent when it returns.

    /// split: halves a full or boundary hexagon about its centre and fills the gap with
    /// semi-hexagons, joining those that share a long edge with a neighbour's. Splits first
    /// whatever the balance rule forces (§4.5). False at the finest level.
    bool split(int32_t cell);
    /// join: turns a semi-hexagon and the semi-hexagon across its long edge into one full
    /// hexagon (or, on the domain boundary, a semi-hexagon into a boundary hexagon).
    bool join(int32_t semi);
    /// merge: the inverse split of a cell whose split counter is positive; breaks neighbouring
    /// full hexagons with split counter 0 first. False (nothing changed) when impossible.
    bool merge(int32_t cell);
    /// break: the inverse join, allowed only where the result stays balanced.
    bool breakHexagon(int32_t cell);

    /// The first operation splitting `cell` needs (§4.5): the split itself when nothing is in
    /// the way, else a join or the split of a coarser cell that must come first. Each step
    /// needs nothing else first, so a caller can spend an operation budget one step at a time.
    SplitStep firstStepToSplit(int32_t cell) const;
    /// Performs one step from firstStepToSplit.
    void applyStep(const SplitStep& step);

    /// Records every cell an operation creates, changes or frees, into up to two logs (the
    /// refiner's caches and the fan stream); null: none. Slot 0 or 1.
    void setChangeLog(int32_t slot, std::vector<int32_t>* log) { changeLog_[slot] = log; }
    /// Records the operations that callers perform (applyStep, join, merge, breakHexagon; a
    /// split as the steps it took), in order, so that a benchmark can time them alone on a copy
    /// of the mesh (replay); null: none.
    void setOperationLog(std::vector<MeshOperation>* log) { operationLog_ = log; }
    /// Performs a logged operation again; on a copy of the mesh in the state the log began in,
    /// every cell gets the number it got there.
    void replay(const MeshOperation& operation);
    /// Records every vertex an operation creates, as v and its parents a, b, across
    /// (VertexParents; kNone for a base vertex), or frees, as ~v; in order; null: none.
    void setVertexLog(std::vector<int32_t>* log) { vertexLog_ = log; }
    /// While on, freed vertex slots are not reused until releaseFreedVertices(): a consumer of
    /// the logs can still read the positions of the vertices the old cells used.
    void setDeferVertexReuse(bool defer) { deferVertexReuse_ = defer; }
    void releaseFreedVertices();

    /// Whether the pools hold so many free records (after the mesh shrank) that compact() is
    /// worth its cost: a full rewrite of the stream and a full upload.
    bool wantsCompaction() const;
    /// Renumbers the live cells and vertices densely, keeping their order, and gives the free
    /// records' memory back (the pools never shrink otherwise). Writes old -> new numbers into
    /// cellMap and vertexMap (kNone for free records) for the consumers of per-record data,
    /// which must renumber theirs; the change logs are not renumbered (drain them first).
    /// Positions, blends, the hash and the triangles stay as they are.
    void compact(std::vector<int32_t>& cellMap, std::vector<int32_t>& vertexMap);

    /// For a hexagon made by a join: the corner slot k (1..3) where the joined long edge starts;
    /// the halves a break makes own corners k..k+3 and k+3..k+6.
    int32_t breakDiameterSlot(int32_t cell) const;

    /// Whether merge(cell) / breakHexagon(cell) would succeed, without changing anything.
    bool canMerge(int32_t cell) const;
    bool canBreak(int32_t cell) const;
    bool canSplit(int32_t cell) const;

    // --- Queries.
    const Hexagon& cell(int32_t c) const { return cells_[size_t(c)]; }
    bool isLive(int32_t c) const { return c >= 0 && size_t(c) < cells_.size() && cells_[size_t(c)].level != kFreeLevel; }
    int32_t cellCapacity() const { return int32_t(cells_.size()); }
    int32_t vertexCapacity() const { return int32_t(vertices_.size()); }
    /// The room the pools have (records allocated, used or not): per-record arrays of other
    /// parts reserve as much (reserveLikePool).
    size_t cellPoolRoom() const { return cells_.capacity(); }
    size_t vertexPoolRoom() const { return vertices_.capacity(); }
    /// Room for this many cell and vertex records at once, for a caller that knows how far a
    /// run of operations will grow the mesh (refineUniformly): the pools then grow in one step
    /// instead of many small ones, each a copy (pool_growth.h).
    void reserveRecords(size_t cells, size_t vertices);
    int32_t liveCells() const { return liveCells_; }
    int32_t liveVertices() const { return liveVertices_; }
    int32_t maxLevel() const { return maxLevel_; }
    int32_t baseStep() const { return baseStep_; }
    /// First cell of a level's list, and the next one after a cell (kNone at the end).
    int32_t firstOfLevel(int32_t level) const { return levelHead_[size_t(level)]; }
    int32_t nextInLevel(int32_t c) const { return cells_[size_t(c)].next; }
    /// A vertex's lattice point. Not stored (8 bytes a vertex): recovered from the
    /// position, which the embedding computed from it (see latticeAt).
    LatticePoint vertexLattice(int32_t v) const { return latticeAt(vertices_[size_t(v)].position); }
    /// The lattice point the embedding put at `position`: row r at z = r * spacingY and column j
    /// at x = j * spacingX (half a sample further east on a shifted odd row), each a double
    /// rounded to float, so rounding position / spacing gives r and j back exactly for
    /// |r|, |j| < 2^22 (float's relative error 2^-24 times 2^22 is below half a sample).
    LatticePoint latticeAt(const glm::vec3& position) const;
    const glm::vec3& vertexPosition(int32_t v) const { return vertices_[size_t(v)].position; }
    /// The vertex pool (free slots hold stale values), kStreamVertexWords floats a vertex with
    /// the position first: what the renderer uploads and the evaluator reads.
    const StreamVertex* vertexData() const { return vertices_.empty() ? nullptr : vertices_.data(); }
    /// The first position of the pool, with kStreamVertexWords floats between positions.
    const float* positionData() const { return vertices_.empty() ? nullptr : &vertices_[0].position.x; }
    /// The renderer's part of a vertex (normal and blend) is written by FanStream and Geomorph.
    StreamVertex& streamVertex(int32_t v) { return vertices_[size_t(v)]; }
    const StreamVertex& streamVertex(int32_t v) const { return vertices_[size_t(v)]; }
    /// §7's parents of a vertex (VertexParents) as lattice points; false for the base mesh's
    /// vertices. Not stored (12 bytes a vertex): a vertex is the midpoint of a coarser
    /// lattice edge, and its coordinates say which (their lowest set bit is the step s it was
    /// made at, their parity at s the edge's direction); `across` is one of twelve lattice
    /// offsets at step s, kept as a 4-bit code beside the vertex's live flag.
    bool parentPoints(int32_t v, ParentPoints& out) const;
    /// The parents as vertex indices, `slotOf(LatticePoint)` giving the live vertex at a lattice
    /// point or kNone; all kNone for a base vertex.
    template <typename SlotOf>
    VertexParents parentsBy(int32_t v, SlotOf&& slotOf) const {
        VertexParents found;
        ParentPoints points;
        if (!parentPoints(v, points)) return found;
        found.a = slotOf(points.a);
        found.b = slotOf(points.b);
        if (points.hasAcross) found.across = slotOf(points.across);
        return found;
    }
    /// The parents as vertex indices, found among the vertices of `cell` and of the cells across
    /// its edges, which hold the parents of every vertex merge(cell) frees (verticesFreedByMerge);
    /// kNone where not found there.
    VertexParents parentsAround(int32_t v, int32_t cell) const;
    /// Appends the vertices merge(cell) would free, forced breaks included. Call when
    /// canMerge(cell): the geomorph fades them out before the merge happens (§7).
    void verticesFreedByMerge(int32_t cell, std::vector<int32_t>& out) const;
    bool isVertexLive(int32_t v) const { return (vertexInfo_[size_t(v)] & kVertexLive) != 0; }
    /// Lattice step of a cell: the distance from its (possibly virtual) centre to its corners.
    int32_t cellStep(int32_t c) const;
    /// The cell's centre on the lattice (a semi-hexagon's lies on its long edge).
    LatticePoint cellCenter(int32_t c) const;
    /// Asks for a cell's record and fan ahead of their use (a hint; nothing changes).
    void prefetchCell(int32_t c) const {
        __builtin_prefetch(&cells_[size_t(c)]);
        __builtin_prefetch(fans_.data() + size_t(c) * kCellFanSlot);
    }
    const OperationCounts& counts() const { return counts_; }
    Embedding embedding() const { return embedding_; }
    /// Whether vertex v's height is a no-data fill (latticePointMissing).
    bool vertexMissing(int32_t v) const { return field_->anyMissing() && latticePointMissing(*field_, embedding_, vertexLattice(v)); }
    /// Number of triangles drawn: 6 per full hexagon, 3 per boundary, 2 per interior semi.
    int64_t triangleCount() const { return triangles_; }
    /// Bytes held by the mesh structures (pools at capacity, lists, free lists), the vertex
    /// pool's render data (StreamVertex) included.
    size_t memoryBytes() const;
    /// Of memoryBytes(), what live cells and vertices use (pools counted by use, not capacity).
    size_t liveMemoryBytes() const;
    /// Of memoryBytes(), the StreamVertex pool (what the renderer uploads).
    size_t vertexPoolBytes() const { return vertices_.capacity() * sizeof(StreamVertex); }
    /// The domain outline: lattice segments of the base mesh's boundary edges.
    const std::vector<std::pair<LatticePoint, LatticePoint>>& domainBoundary() const { return boundary_; }
    /// Twice the domain's area in lattice units (see latticeDoubleArea).
    int64_t domainDoubleArea() const { return domainDoubleArea_; }

    /// Appends the drawn triangles (vertex indices, counter-clockwise seen from +y): full
    /// hexagons as six triangles around the centre, boundary semi-hexagons as three, interior
    /// semi-hexagons as the two-triangle fan from their first own corner (a fixed rule).
    void appendTriangles(std::vector<uint32_t>& indices) const;

    /// The cell's triangle fan (§7): kCellFanSlot vertex indices, fanLength(c) of them used, the
    /// rest restarts (see the layout at the top). appendTriangles and the fan stream expand it.
    const uint32_t* cellFan(int32_t c) const { return fans_.data() + size_t(c) * kCellFanSlot; }
    /// 8 for a full hexagon, 5 for a boundary semi-hexagon, 4 for an interior one.
    static int32_t fanLength(const Hexagon& h) { return h.kind == CellKind::Full ? 8 : h.kind == CellKind::BoundarySemi ? 5 : 4; }
    /// Every cell's fan, kCellFanSlot indices a cell record (free ones all restarts): what the
    /// renderer draws in the fans layout.
    const std::vector<uint32_t>& fanTable() const { return fans_; }
    /// The cell's vertices by slot, decoded from its fan.
    CellCorners corners(int32_t c) const;
    /// The vertex in one slot of a cell (kNone if absent).
    int32_t cornerVertex(int32_t c, int32_t slot) const;

    /// Start and end vertex of a directed edge (a semi's long edge ends at its first corner).
    int32_t edgeStart(int32_t e) const { return cornerVertex(hexIdx(e), edgeSlot(e)); }
    int32_t edgeEnd(int32_t e) const;
    /// Whether the edge is the long edge of a semi-hexagon.
    bool isLongEdge(int32_t e) const;

    /// A hash of the mesh: every cell in level-list order with its kind, level, counter and
    /// the lattice points and positions of its vertices. Equal on native and WASM builds when
    /// the same operations ran.
    uint64_t hash() const;

    /// Checks every structural invariant (hex_mesh_invariants.cpp). Returns null when all
    /// hold, else a message naming the first violation. Costs O(n log n); for tests and debug.
    const char* checkInvariants() const;

    static constexpr uint8_t kFreeLevel = 0xFF;

private:
    friend class HexMeshInvariants;
    int32_t allocateCell();
    void freeCell(int32_t c);
    /// A new vertex at p, the midpoint of parents a and b; its `across` is whichever candidate
    /// lies on its side of a -> b in the ground plane (VertexParents). kNone parents: a base vertex.
    int32_t allocateVertex(LatticePoint p, int32_t a, int32_t b, int32_t across1, int32_t across2);
    int32_t acrossOf(int32_t v, int32_t a, int32_t b, int32_t candidate1, int32_t candidate2) const;
    static uint8_t acrossCode(LatticePoint p, LatticePoint across);
    /// The third corner of the semi-hexagon's fan triangle that holds its long edge.
    int32_t longEdgeFanCorner(int32_t semi) const;
    void freeVertex(int32_t v);
    void linkLevel(int32_t c);
    void unlinkLevel(int32_t c);
    void setLevel(int32_t c, int32_t level);
    void connect(int32_t e, int32_t f); // makes e and f opposite (either may be kNone)
    bool wouldStayBalancedAfterBreak(int32_t cell) const;
    void splitUnchecked(int32_t cell);
    void joinPair(int32_t keep, int32_t other);
    void joinBoundary(int32_t semi);
    void breakUnchecked(int32_t cell);
    int64_t cellTriangles(const Hexagon& h) const;
    /// Writes a cell's fan from its vertices by slot, after its kind and firstVisible are set
    /// (an interior semi-hexagon's fan corner follows the fixed rule of §7).
    void setCorners(int32_t c, const CellCorners& corners);
    /// §7's fixed rule for a semi-hexagon whose own corners start at slot `first`: whether its
    /// fan starts at the second corner (semiFanFromSecondCorner on their lattice points).
    bool semiFanFromSecond(const CellCorners& corners, int32_t first) const;
    const char* checkFan(int32_t c, const CellCorners& corners) const; // hex_mesh_invariants.cpp

    const Heightfield* field_ = nullptr;
    Embedding embedding_ = Embedding::Exact;
    int32_t baseStep_ = 1;
    int32_t maxLevel_ = 0;
    double columnsPerMetre_ = 1.0, rowsPerMetre_ = 1.0; // latticeAt

    std::vector<Hexagon> cells_;
    std::vector<uint32_t> fans_; // kCellFanSlot a cell record: the cells' vertices, as their fans
    int32_t freeCell_ = kNone;
    int32_t liveCells_ = 0;
    std::vector<int32_t> levelHead_, levelTail_;

    std::vector<StreamVertex> vertices_;
    // Per vertex: kVertexLive, and the code of its across parent (0: none, else 1 + an index of
    // acrossOffset in hex_mesh.cpp).
    static constexpr uint8_t kVertexLive = 0x80, kAcrossCode = 0x0F;
    std::vector<uint8_t> vertexInfo_;
    std::vector<int32_t> freeVertices_;
    std::vector<int32_t> freedVertices_; // freed while reuse is deferred
    bool deferVertexReuse_ = false;
    int32_t liveVertices_ = 0;

    std::vector<std::pair<LatticePoint, LatticePoint>> boundary_;
    int64_t domainDoubleArea_ = 0;
    int64_t triangles_ = 0;
    OperationCounts counts_;
    std::vector<int32_t>* changeLog_[2] = {nullptr, nullptr};
    std::vector<int32_t>* vertexLog_ = nullptr;
    std::vector<MeshOperation>* operationLog_ = nullptr;
    void logOperation(MeshOperation::Kind kind, int32_t cell, int32_t other = kNone) {
        if (operationLog_) operationLog_->push_back({kind, cell, other});
    }
    void logChange(int32_t c) {
        for (std::vector<int32_t>* log : changeLog_)
            if (log) log->push_back(c);
    }
};

} // namespace hexlod
