// PoppingMeter: how far the drawn surface jumps between consecutive frames, for the benchmark
// of paper §7's geomorphing. Every vertex slot is compared between the frame just drawn and the
// one before, projected with the current camera only, so that camera motion is no jump:
//   - a vertex drawn in both frames: from where it was drawn to where it is drawn now;
//   - a new vertex: from where the previous surface was at it (the coarser surface under it,
//     Geomorph::coarserSurface, as drawn in the previous frame) to where it is drawn now;
//   - a freed vertex: from where it was drawn to the coarser surface under it now (the surface
//     that replaced it).
// Jumps whose ends are both off screen or behind the near plane are not counted.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "stream/geomorph.h"
#include "mesh/hex_mesh.h"
#include "lod/view_criteria.h"

namespace hexlod {

struct PoppingStats {
    double maxJumpPx = 0.0;  // largest jump this frame, pixels
    int32_t jumpsOverHalfPx = 0;
    int32_t measured = 0;    // vertex jumps measured (on screen)
    // Where the largest jump was: screen position (pixels from the centre, y up), depth
    // (metres) and what the vertex did: 0 kept, 1 new, 2 freed.
    double atX = 0.0, atY = 0.0, atDepth = 0.0;
    int32_t kind = 0;
};

class PoppingMeter {
public:
    /// Compares the frame now drawn with the last measured one (nothing on the first call).
    PoppingStats measure(const HexMesh& mesh, const Geomorph& morph, const View& view, double verticalScale);
    void reset() {
        previous_.clear();
        slotAt_.clear();
    }
    /// Keeps the last frame comparable across what the terrain did since: a new mesh (its
    /// epoch moved) starts again; one compaction (Terrain::renumberings moved by one) renumbers
    /// the last frame's records with Terrain::lastRenumbering; anything else starts again.
    /// Call before measure().
    void follow(uint32_t meshEpoch, uint32_t renumberings, const std::vector<int32_t>& lastRenumbering);

private:
    struct Seen {
        LatticePoint lattice;
        glm::vec3 drawn;
        int32_t parent[3]; // a, b, across
        float weight[3];
        bool live;
    };
    bool sameVertex(const HexMesh& mesh, int32_t v) const;
    // A live vertex's parents (HexMesh::parentPoints) as this frame's slots.
    VertexParents parentsOf(const HexMesh& mesh, int32_t v) const;
    glm::vec3 previousSurfaceAt(const HexMesh& mesh, const Geomorph& morph, int32_t v, int32_t depth) const;
    glm::vec3 currentSurfaceAt(const HexMesh& mesh, const Geomorph& morph, int32_t v, int32_t depth) const;

    void renumber(const std::vector<int32_t>& vertexMap);

    std::vector<Seen> previous_;
    // The slot of every live vertex's lattice point (latticeKey), kept in step with the mesh:
    // the mesh stores no parents, the meter finds them by their lattice points.
    std::unordered_map<uint64_t, int32_t> slotAt_;
    uint32_t meshEpoch_ = 0, renumberings_ = 0; // of the last frame's terrain
};

} // namespace hexlod
