// UpdateFloor: the least an update of the paper's refinement loop (§6) could cost for the
// operations a flight makes, measured by doing only that on a copy of the mesh.
//
// Per frame it performs again the mesh operations the refiner performed (HexMesh::replay,
// timed), then computes the bound (§5, with the slope box when back-face culling is on) of
// every cell those operations made whose shape no frame has bounded before (timed): a loop
// must know a new cell's bound before it can judge it, and no cache can hold a bound not yet
// computed. It judges nothing: no criteria, no margins, no queues. Anything an update does is
// on top of this floor.
#pragma once

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "field/heightfield.h"
#include "field/min_max_pyramid.h"
#include "lod/cell_bounds.h"
#include "mesh/hex_mesh.h"
#include "terrain.h"

namespace hexlod::bench {

class UpdateFloor {
public:
    /// Starts from the mesh as it is (its cells' bounds count as known) and logs its operations.
    UpdateFloor(Terrain& terrain, const Heightfield& field, bool slopes);
    ~UpdateFloor();
    UpdateFloor(const UpdateFloor&) = delete;
    UpdateFloor& operator=(const UpdateFloor&) = delete;

    struct Frame {
        double operationsMs = 0.0, boundsMs = 0.0;
        int32_t newShapes = 0;
    };
    /// After the refiner's update: the same operations and the new cells' bounds, timed.
    /// `compacted`: the terrain compacted its pools since the last frame (the copy does too,
    /// so that cell numbers stay the same).
    Frame frame(bool compacted);
    /// Whether the copy is the mesh (the same cells, in the same places): the floor timed the
    /// flight's own operations.
    bool matchesMesh() const { return !diverged_ && copy_.hash() == mesh_.hash() && copy_.liveCells() == mesh_.liveCells(); }

private:
    bool remember(int32_t cell); // true when the cell's shape is new
    volatile float checksum_ = 0.0f;
    bool diverged_ = false;

    Terrain& terrain_;
    const HexMesh& mesh_;
    HexMesh copy_;
    const Heightfield& field_;
    MinMaxPyramid pyramid_;
    bool slopes_;
    std::vector<MeshOperation> operations_;
    std::vector<int32_t> changed_, cellMap_, vertexMap_;
    std::vector<CellShape> shapes_;
    struct ShapeHash {
        size_t operator()(uint64_t key) const { return size_t(key * 0x9E3779B97F4A7C15ull >> 17); }
    };
    std::unordered_set<uint64_t, ShapeHash> seen_;
};

} // namespace hexlod::bench
