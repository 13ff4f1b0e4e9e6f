// checkInvariants(): everything that must hold after every single operation (paper §4, §6:
// "the mesh is valid at each step"). Used by the tests and by debug builds.
#include <cstdio>

#include "mesh/hex_mesh.h"

namespace hexlod {

namespace {

// Coarsest resolution at which p is a hexagon centre: where a cell centred on p is born.
int32_t birthResolution(LatticePoint p, int32_t baseStep) {
    int32_t k = 0;
    for (int32_t s = baseStep; s >= 1; s /= 2, ++k)
        if (isCenterAtStep(p, s)) return k;
    return -1;
}

// Whether lattice segment (a, b) lies on segment (p, q): collinear and inside.
bool onSegment(LatticePoint a, LatticePoint b, LatticePoint p, LatticePoint q) {
    auto inside = [&](LatticePoint x) {
        if (latticeDoubleArea(p, q, x) != 0) return false;
        const int64_t dq = q.q - p.q, dr = q.r - p.r;
        const int64_t t = (x.q - p.q) * dq + (x.r - p.r) * dr, len = dq * dq + dr * dr;
        return t >= 0 && t <= len;
    };
    return inside(a) && inside(b);
}

// A set of non-zero 64-bit keys with open addressing: the checks run after every operation in
// the tests, so they must be cheap.
class KeySet {
public:
    explicit KeySet(size_t expected) {
        size_t size = 16;
        shift_ = 60;
        while (size < expected * 2) size *= 2, --shift_;
        slots_.assign(size, 0);
    }
    /// Inserts key + 1 (so 0 can mark empty slots); false when it was already there.
    bool insert(uint64_t key) {
        for (size_t i = slotOf(key);; i = (i + 1) & (slots_.size() - 1)) {
            if (slots_[i] == key + 1) return false;
            if (slots_[i] == 0) {
                slots_[i] = key + 1;
                return true;
            }
        }
    }
    bool contains(uint64_t key) const {
        for (size_t i = slotOf(key);; i = (i + 1) & (slots_.size() - 1)) {
            if (slots_[i] == key + 1) return true;
            if (slots_[i] == 0) return false;
        }
    }

private:
    // Fibonacci hashing: the top bits of the product are the well-mixed ones.
    size_t slotOf(uint64_t key) const { return size_t((key * 0x9E3779B97F4A7C15ull) >> shift_); }
    std::vector<uint64_t> slots_;
    int shift_;
};

thread_local char message[256];

template <typename First, typename... Rest>
const char* failure(const char* format, First first, Rest... rest) {
    std::snprintf(message, sizeof(message), format, first, rest...);
    return message;
}
inline const char* failure(const char* text) { return text; }

} // namespace

// The fan table (hex_mesh.h): a live cell's fan is its fixed-rule fan, padded with restarts.
const char* HexMesh::checkFan(int32_t c, const CellCorners& corners) const {
    const Hexagon& h = cells_[size_t(c)];
    const uint32_t* fan = cellFan(c);
    for (int32_t i = fanLength(h); i < kCellFanSlot; ++i)
        if (fan[i] != kRestartIndex) return failure("cell %d: fan entry %d past its fan is not a restart", c, i);
    if (h.kind == CellKind::Full && fan[7] != fan[1]) return failure("hexagon %d: the fan does not close at its first corner", c);
    if (h.kind == CellKind::Semi) {
        if (h.fanFromSecond != semiFanFromSecond(corners, h.firstVisible))
            return failure("semi-hexagon %d: the fan does not start at the fixed rule's corner", c);
    } else if (h.fanFromSecond) {
        return failure("cell %d: fanFromSecond set on a whole or boundary cell", c);
    }
    return nullptr;
}

const char* HexMesh::checkInvariants() const {
    if (fans_.size() != cells_.size() * kCellFanSlot) return failure("the fan table has %zu entries for %zu cells", fans_.size(), cells_.size());
    // Pools and level lists (§4.4): every live cell is in the list of its level exactly once,
    // and live plus free records account for the whole pool.
    std::vector<uint8_t> listed(cells_.size(), 0);
    int32_t listedCount = 0;
    for (int32_t level = 0; level <= maxLevel_; ++level) {
        int32_t prev = kNone;
        for (int32_t c = levelHead_[size_t(level)]; c != kNone; c = cells_[size_t(c)].next) {
            if (!isLive(c)) return failure("free cell %d is in the list of level %d", c, level);
            if (listed[size_t(c)]++) return failure("cell %d is listed twice", c);
            if (cells_[size_t(c)].level != level) return failure("cell %d of level %d is in the list of level %d", c, cells_[size_t(c)].level, level);
            if (cells_[size_t(c)].prev != prev) return failure("cell %d has a broken prev link", c);
            prev = c;
            ++listedCount;
        }
        if (levelTail_[size_t(level)] != prev) return failure("level %d has a wrong tail", level);
    }
    if (listedCount != liveCells_) return failure("%d cells listed but %d live", listedCount, liveCells_);
    int32_t freeCount = 0;
    for (int32_t c = freeCell_; c != kNone; c = cells_[size_t(c)].next) {
        if (isLive(c)) return failure("live cell %d is on the free list", c);
        for (int32_t i = 0; i < kCellFanSlot; ++i)
            if (cellFan(c)[i] != kRestartIndex) return failure("free cell %d draws: its fan is not all restarts", c);
        if (++freeCount > int32_t(cells_.size())) return failure("the free list of cells loops");
    }
    if (freeCount + liveCells_ != int32_t(cells_.size())) return failure("cell accounting: %d free + %d live != %zu", freeCount, liveCells_, cells_.size());

    // Vertices: the live ones are exactly those the cells use, at distinct lattice points,
    // placed by the embedding.
    std::vector<uint8_t> used(vertices_.size(), 0);
    int64_t triangles = 0;
    for (int32_t c = 0; c < int32_t(cells_.size()); ++c) {
        if (!isLive(c)) continue;
        const Hexagon& h = cells_[size_t(c)];
        const bool even = h.level % 2 == 0;
        if ((h.kind == CellKind::Semi) == even) return failure("cell %d: kind %d has level %d of the wrong parity", c, int(h.kind), h.level);
        if (h.kind == CellKind::Semi && h.splitCount != 0) return failure("semi-hexagon %d has split counter %d", c, h.splitCount);
        if (h.kind == CellKind::Full && h.firstVisible != 0) return failure("full hexagon %d has firstVisible set", c);
        if (h.kind != CellKind::Full && (h.firstVisible < 1 || h.firstVisible > 6)) return failure("semi-hexagon %d has no firstVisible", c);
        const CellCorners hv = corners(c);
        if ((hv.vertex[0] != kNone) != (h.kind != CellKind::Semi)) return failure("cell %d: centre presence does not match its kind", c);
        if (const char* fault = checkFan(c, hv)) return fault;
        const int32_t step = cellStep(c);
        if (step < 1) return failure("cell %d of level %d is finer than the samples", c, h.level);
        for (int32_t slot = 0; slot <= 6; ++slot) {
            const bool own = slot == 0 ? h.kind != CellKind::Semi
                                       : h.kind == CellKind::Full || wrapSlot(slot - h.firstVisible + 6 + 1) <= 4;
            const int32_t v = hv.vertex[slot];
            if (!own) {
                if (v != kNone) return failure("cell %d: slot %d should be empty", c, slot);
                if (slot >= 1 && h.opposite[slot - 1] != kNone) return failure("cell %d: unused edge slot %d has a neighbour", c, slot);
                continue;
            }
            if (v < 0 || v >= int32_t(vertices_.size()) || !isVertexLive(v)) return failure("cell %d: slot %d holds dead vertex %d", c, slot, v);
            used[size_t(v)] = 1;
        }
        // Lattice geometry: corners at centre + step * direction; the centre is born at the
        // level the counters say (level - 2 * splits for whole cells, level + 1 for semis).
        const LatticePoint centre = cellCenter(c);
        for (int32_t slot = 1; slot <= 6; ++slot) {
            if (hv.vertex[slot] == kNone) continue;
            if (vertexLattice(hv.vertex[slot]) != latticeAdd(centre, kDirections[slot - 1], step))
                return failure("cell %d: corner %d is not at its lattice position", c, slot);
        }
        const int32_t born = 2 * birthResolution(centre, baseStep_);
        const int32_t expected = h.kind == CellKind::Semi ? h.level + 1 : h.level - 2 * h.splitCount;
        if (born < 0 || born != expected) return failure("cell %d: level %d and split counter %d do not match its centre (born at level %d)", c, h.level, h.splitCount, born);
        triangles += cellTriangles(h);
    }
    if (triangles != triangles_) return failure("triangle count %lld, tracked %lld", (long long)triangles, (long long)triangles_);
    KeySet points(vertices_.size());
    int32_t liveVertices = 0, freeVertices = 0;
    for (size_t v = 0; v < vertices_.size(); ++v) {
        if (!isVertexLive(int32_t(v))) { ++freeVertices; continue; }
        ++liveVertices;
        if (!used[v]) return failure("live vertex %zu is used by no cell", v);
        const LatticePoint point = vertexLattice(int32_t(v));
        if (!points.insert(latticeKey(point))) return failure("two live vertices share lattice point (%d, %d)", point.q, point.r);
        // The lattice point is recovered from the position: the round trip must be exact.
        if (vertices_[v].position != embedLatticePoint(*field_, embedding_, point)) return failure("vertex %zu is not where the embedding puts it", v);
    }
    if (liveVertices != liveVertices_ || freeVertices != int32_t(freeVertices_.size() + freedVertices_.size()))
        return failure("vertex accounting is off");
    // §7's blends start on the coarser surface under a vertex: its parents (derived from its
    // lattice point and across code) are live vertices, and it is the midpoint of a and b.
    for (size_t v = 0; v < vertices_.size(); ++v) {
        ParentPoints parents;
        if (!isVertexLive(int32_t(v)) || !parentPoints(int32_t(v), parents)) continue;
        if (!points.contains(latticeKey(parents.a)) || !points.contains(latticeKey(parents.b)))
            return failure("vertex %zu has a dead parent", v);
        if (latticeMidpoint(parents.a, parents.b) != vertexLattice(int32_t(v)))
            return failure("vertex %zu is not the midpoint of its parents", v);
        if (parents.hasAcross && !points.contains(latticeKey(parents.across)))
            return failure("vertex %zu has a dead across parent", v);
    }

    // Edges: neighbour symmetry, and the balance rule (§4.5): no short edge of a semi-hexagon
    // carries the long edge of another semi-hexagon (they would be two levels apart).
    for (int32_t c = 0; c < int32_t(cells_.size()); ++c) {
        if (!isLive(c)) continue;
        const Hexagon& h = cells_[size_t(c)];
        for (int32_t slot = 1; slot <= 6; ++slot) {
            const int32_t e = makeEdge(c, slot);
            const int32_t o = h.opposite[slot - 1];
            if (h.kind == CellKind::BoundarySemi && slot == wrapSlot(h.firstVisible + 3) && o != kNone)
                return failure("boundary semi-hexagon %d has a neighbour across the domain boundary", c);
            if (cornerVertex(c, slot) == kNone || o == kNone) continue;
            if (!isLive(hexIdx(o))) return failure("edge %d faces a free cell", e);
            if (cells_[size_t(hexIdx(o))].opposite[edgeSlot(o) - 1] != e) return failure("edge %d: neighbour symmetry broken", e);
            if (edgeStart(o) != edgeEnd(e) || edgeEnd(o) != edgeStart(e)) return failure("edge %d and its opposite do not share endpoints", e);
            if (h.kind == CellKind::Semi && !isLongEdge(e) && isLongEdge(o)) return failure("balance: semi-hexagon %d (level %d) carries a level-%d semi-hexagon's long edge", c, h.level, cells_[size_t(hexIdx(o))].level);
        }
    }

    // No hanging nodes: every directed triangle edge is used once, and an edge whose reverse
    // no triangle uses lies on the domain boundary. The triangles tile the domain: they all turn
    // counter-clockwise and their areas add up to the domain's.
    std::vector<uint32_t> tris;
    appendTriangles(tris);
    KeySet directed(tris.size());
    int64_t area = 0;
    for (size_t t = 0; t < tris.size(); t += 3) {
        const int64_t a = latticeDoubleArea(vertexLattice(int32_t(tris[t])), vertexLattice(int32_t(tris[t + 1])), vertexLattice(int32_t(tris[t + 2])));
        if (a <= 0) return failure("triangle %zu is degenerate or clockwise", t / 3);
        area += a;
        for (int k = 0; k < 3; ++k)
            if (!directed.insert((uint64_t(tris[t + k]) << 32) | tris[t + (k + 1) % 3])) return failure("a directed triangle edge is used twice");
    }
    if (area != domainDoubleArea_) return failure("triangles cover area %lld, the domain %lld", (long long)area, (long long)domainDoubleArea_);
    for (size_t t = 0; t < tris.size(); ++t) {
        const uint32_t u = tris[t], v = tris[t % 3 == 2 ? t - 2 : t + 1];
        if (directed.contains((uint64_t(v) << 32) | u)) continue;
        const LatticePoint a = vertexLattice(int32_t(u)), b = vertexLattice(int32_t(v));
        bool onBoundary = false;
        for (const auto& [p, q] : boundary_) onBoundary = onBoundary || onSegment(a, b, p, q);
        if (!onBoundary) return failure("hanging node: edge (%d,%d)-(%d,%d) is used by one triangle inside the domain", a.q, a.r, b.q, b.r);
    }
    return nullptr;
}

} // namespace hexlod
