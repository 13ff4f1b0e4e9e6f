// Popping measured as the issue of §7's geomorphing defines it; see popping_meter.h.
#include "diagnostics/popping_meter.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace hexlod {

namespace {

// Screen position in pixels from the view centre; false behind the near plane.
bool project(const View& view, const glm::vec3& p, double verticalScale, double& x, double& y, bool& onScreen) {
    const glm::dvec3 rel = glm::dvec3(p.x, double(p.y) * verticalScale, p.z) - view.eye;
    const double depth = glm::dot(rel, view.forward);
    if (depth < view.nearPlane) return false;
    const double tx = glm::dot(rel, view.right) / depth, ty = glm::dot(rel, view.up) / depth;
    x = tx * view.pixelsPerTangent;
    y = ty * view.pixelsPerTangent;
    onScreen = std::abs(tx) <= view.tanHalfX && std::abs(ty) <= view.tanHalfY;
    return true;
}

} // namespace

bool PoppingMeter::sameVertex(const HexMesh& mesh, int32_t v) const {
    if (size_t(v) >= previous_.size() || !previous_[size_t(v)].live || !mesh.isVertexLive(v)) return false;
    // The same lattice point is the same ground position (the mesh derives one from the other),
    // and blends are vertical: comparing x and z is comparing lattice points, without deriving them.
    const glm::vec3& was = previous_[size_t(v)].drawn, & is = mesh.vertexPosition(v);
    return was.x == is.x && was.z == is.z;
}

VertexParents PoppingMeter::parentsOf(const HexMesh& mesh, int32_t v) const {
    const VertexParents parents = mesh.parentsBy(v, [&](LatticePoint p) {
        const auto it = slotAt_.find(latticeKey(p));
        return it == slotAt_.end() ? kNone : it->second;
    });
    if (parents.a == kNone || parents.b == kNone) return VertexParents{}; // never: parents are live
    return parents;
}

// Where the previous frame's surface was at a vertex that may be new.
glm::vec3 PoppingMeter::previousSurfaceAt(const HexMesh& mesh, const Geomorph& morph, int32_t v, int32_t depth) const {
    if (sameVertex(mesh, v)) return previous_[size_t(v)].drawn;
    const VertexParents parents = parentsOf(mesh, v);
    if (parents.a == kNone || depth > 40) return morph.displayed(mesh.streamVertex(v));
    return Geomorph::coarserSurface(mesh, v, parents, [&](int32_t u) { return previousSurfaceAt(mesh, morph, u, depth + 1); });
}

// Where this frame's surface is at a vertex slot of the previous frame that may be gone.
glm::vec3 PoppingMeter::currentSurfaceAt(const HexMesh& mesh, const Geomorph& morph, int32_t v, int32_t depth) const {
    if (sameVertex(mesh, v)) return morph.displayed(mesh.streamVertex(v));
    const Seen& seen = previous_[size_t(v)];
    if (seen.parent[0] == kNone || depth > 40) return seen.drawn;
    glm::vec3 p(0.0f);
    for (int k = 0; k < 3; ++k)
        if (seen.weight[k] != 0.0f) p += seen.weight[k] * currentSurfaceAt(mesh, morph, seen.parent[k], depth + 1);
    return p;
}

void PoppingMeter::follow(uint32_t meshEpoch, uint32_t renumberings, const std::vector<int32_t>& lastRenumbering) {
    if (meshEpoch != meshEpoch_) reset();
    else if (renumberings == renumberings_ + 1 && !lastRenumbering.empty()) renumber(lastRenumbering);
    else if (renumberings != renumberings_) reset();
    meshEpoch_ = meshEpoch;
    renumberings_ = renumberings;
}

void PoppingMeter::renumber(const std::vector<int32_t>& vertexMap) {
    auto renumbered = [&](int32_t v) { return v >= 0 && size_t(v) < vertexMap.size() ? vertexMap[size_t(v)] : kNone; };
    int32_t size = 0;
    for (int32_t to : vertexMap) size = std::max(size, to + 1);
    std::vector<Seen> moved(size_t(size), Seen{{}, glm::vec3(0.0f), {kNone, kNone, kNone}, {0.0f, 0.0f, 0.0f}, false});
    for (size_t v = 0; v < previous_.size(); ++v) {
        const int32_t to = renumbered(int32_t(v));
        if (to == kNone) continue;
        Seen seen = previous_[v];
        for (int32_t& parent : seen.parent) parent = renumbered(parent);
        moved[size_t(to)] = seen;
    }
    previous_.swap(moved);
    slotAt_.clear();
    for (size_t v = 0; v < previous_.size(); ++v)
        if (previous_[v].live) slotAt_[latticeKey(previous_[v].lattice)] = int32_t(v);
}

PoppingStats PoppingMeter::measure(const HexMesh& mesh, const Geomorph& morph, const View& view, double verticalScale) {
    PoppingStats stats;
    const int32_t slots = mesh.vertexCapacity();
    const bool first = previous_.empty();
    auto jump = [&](const glm::vec3& from, const glm::vec3& to, int32_t kind) {
        double x0, y0, x1, y1;
        bool on0, on1;
        if (!project(view, from, verticalScale, x0, y0, on0) || !project(view, to, verticalScale, x1, y1, on1)) return;
        if (!on0 && !on1) return;
        const double px = std::hypot(x1 - x0, y1 - y0);
        ++stats.measured;
        if (px > 0.5) ++stats.jumpsOverHalfPx;
        if (px <= stats.maxJumpPx) return;
        stats.maxJumpPx = px;
        stats.atX = x1, stats.atY = y1, stats.kind = kind;
        stats.atDepth = glm::dot(glm::dvec3(to.x, double(to.y) * verticalScale, to.z) - view.eye, view.forward);
    };
    // The lattice point -> slot map follows the mesh to this frame: the slots whose vertex
    // changed leave it, then the new ones enter (a point may move from one slot to another).
    for (int32_t v = 0; v < int32_t(previous_.size()); ++v) {
        const Seen& seen = previous_[size_t(v)];
        if (!seen.live || sameVertex(mesh, v)) continue;
        const auto it = slotAt_.find(latticeKey(seen.lattice));
        if (it != slotAt_.end() && it->second == v) slotAt_.erase(it);
    }
    for (int32_t v = 0; v < slots; ++v)
        if (mesh.isVertexLive(v) && !sameVertex(mesh, v)) slotAt_[latticeKey(mesh.vertexLattice(v))] = v;
    if (!first) {
        for (int32_t v = 0; v < slots; ++v) {
            const bool live = mesh.isVertexLive(v);
            const glm::vec3 now = live ? morph.displayed(mesh.streamVertex(v)) : glm::vec3(0.0f);
            if (sameVertex(mesh, v)) {
                jump(previous_[size_t(v)].drawn, now, 0);
                continue;
            }
            if (size_t(v) < previous_.size() && previous_[size_t(v)].live) // freed (or its slot reused)
                jump(previous_[size_t(v)].drawn, currentSurfaceAt(mesh, morph, v, 0), 2);
            if (live) jump(previousSurfaceAt(mesh, morph, v, 0), now, 1); // new
        }
    }
    previous_.resize(size_t(slots));
    for (int32_t v = 0; v < slots; ++v) {
        Seen& seen = previous_[size_t(v)];
        const bool kept = sameVertex(mesh, v);
        seen.live = mesh.isVertexLive(v);
        if (!seen.live) continue;
        seen.drawn = morph.displayed(mesh.streamVertex(v));
        if (kept) continue; // its parents and their weights do not change while it lives
        seen.lattice = mesh.vertexLattice(v);
        const VertexParents parents = parentsOf(mesh, v);
        seen.parent[0] = parents.a, seen.parent[1] = parents.b, seen.parent[2] = parents.across;
        if (parents.a != kNone) Geomorph::coarserWeights(mesh, v, parents, seen.weight);
    }
    return stats;
}

} // namespace hexlod
