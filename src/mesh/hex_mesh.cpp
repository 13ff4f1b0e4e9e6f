// The hexagon mesh operations of Sußner, Dachsbacher, Greiner (VMV 2005): split and join
// (§4.1, Fig. 3), the balance rule (§4.5, Fig. 5), merge and break (§4.6, Fig. 6), on the
// record layout of §4.3 and the level lists of §4.4. See hex_mesh.h for the slot conventions.
//
// Ring cell numbering used throughout: splitting a cell of step s around centre c with corners
// P_k = c + s*d(k-1) gives new corners Q_k = c + (s/2)*d(k-1), and along each edge k
// (P_k -> P_k+1) a semi-hexagon R_k whose own corners, in its own slots, are
//   slot k+2: P_k+1,  slot k+3: Q_k+1,  slot k+4: Q_k,  slot k+5: P_k   (firstVisible = k+2)
// so its edges are: slot k+2 side (shared with R_k+1's slot k+5), slot k+3 inner (shared with
// the centre's edge k), slot k+4 side, slot k+5 long (on the parent's edge k). Along a domain
// boundary edge R_k becomes a boundary semi-hexagon around the edge's midpoint (§4.2).
#include "mesh/hex_mesh.h"
#include "mesh/pool_growth.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace hexlod {

namespace {

// The edge slots along which a cell is split into ring cells, and its own corner slots.
struct CellSlots {
    int32_t firstEdge, edgeCount, cornerCount;
};

CellSlots slotsOf(const Hexagon& h) {
    if (h.kind == CellKind::Full) return {1, 6, 6};
    return {h.firstVisible, 3, 4}; // semi-hexagons: three short edges, four corners
}

} // namespace

// --- Pools and level lists (§4.4) ---------------------------------------------------------

int32_t HexMesh::allocateCell() {
    int32_t c = freeCell_;
    if (c != kNone) {
        freeCell_ = cells_[size_t(c)].next;
    } else {
        c = int32_t(cells_.size());
        reserveForPool(cells_, cells_.size() + 1);
        reserveLikePool(fans_, (cells_.size() + 1) * kCellFanSlot, cells_.capacity() * kCellFanSlot);
        cells_.emplace_back();
        fans_.resize(cells_.size() * kCellFanSlot, kRestartIndex);
    }
    Hexagon& h = cells_[size_t(c)];
    std::fill(std::begin(h.opposite), std::end(h.opposite), kNone);
    h.prev = h.next = kNone;
    h.level = 0;
    h.splitCount = 0;
    h.kind = CellKind::Full;
    h.firstVisible = 0;
    h.fanFromSecond = 0;
    ++liveCells_;
    logChange(c);
    return c;
}

void HexMesh::freeCell(int32_t c) {
    Hexagon& h = cells_[size_t(c)];
    h.level = kFreeLevel;
    h.next = freeCell_;
    std::fill_n(fans_.begin() + ptrdiff_t(c) * kCellFanSlot, kCellFanSlot, kRestartIndex); // draws nothing
    h.prev = kNone;
    freeCell_ = c;
    --liveCells_;
    logChange(c);
}

void HexMesh::reserveRecords(size_t cells, size_t vertices) {
    if (cells > cells_.capacity()) cells_.reserve(cells), fans_.reserve(cells * kCellFanSlot);
    if (vertices > vertices_.capacity()) vertices_.reserve(vertices), vertexInfo_.reserve(vertices);
}

int32_t HexMesh::allocateVertex(LatticePoint p, int32_t a, int32_t b, int32_t across1, int32_t across2) {
    int32_t v;
    if (!freeVertices_.empty()) {
        v = freeVertices_.back();
        freeVertices_.pop_back();
    } else {
        v = int32_t(vertices_.size());
        const size_t size = vertices_.size() + 1;
        reserveForPool(vertices_, size), reserveForPool(vertexInfo_, size);
        vertices_.emplace_back();
        vertexInfo_.emplace_back();
    }
    StreamVertex& sv = vertices_[size_t(v)];
    sv.position = embedLatticePoint(*field_, embedding_, p);
    sv.morphFromHeight = sv.position.y;
    sv.morphKey = 0.0f;
    const int32_t across = a == kNone ? kNone : acrossOf(v, a, b, across1, across2);
    vertexInfo_[size_t(v)] = uint8_t(kVertexLive | (across == kNone ? 0 : acrossCode(p, vertexLattice(across))));
    ++liveVertices_;
    if (vertexLog_) vertexLog_->insert(vertexLog_->end(), {v, a, b, across});
    return v;
}

int32_t HexMesh::acrossOf(int32_t v, int32_t parentA, int32_t parentB, int32_t candidate1, int32_t candidate2) const {
    const glm::vec3 a = vertices_[size_t(parentA)].position, b = vertices_[size_t(parentB)].position;
    // Side of a ground-plane point relative to the edge a -> b, in double: exact for floats.
    auto side = [&](const glm::vec3& q) {
        const double cross = (double(b.x) - a.x) * (double(q.z) - a.z) - (double(b.z) - a.z) * (double(q.x) - a.x);
        return (cross > 0.0) - (cross < 0.0);
    };
    const int own = side(vertices_[size_t(v)].position);
    int32_t across = kNone;
    if (own != 0) {
        for (int32_t c : {candidate1, candidate2})
            if (c != kNone && side(vertices_[size_t(c)].position) == own) across = c;
    }
    return across;
}

// Where a vertex's across parent can be, in steps of the step s it was made at: after a split,
// the third corner of a coarser (step 2s) triangle on its parent edge (the second ring of
// offsets); after a join, a corner of the semi-hexagon whose long edge it halves (the first).
namespace {
// Offset k of the twelve (k < 6: kDirections[k]; then kDirections[k] + kDirections[k + 1]).
constexpr int32_t kAcrossOffsets = 12;
LatticePoint acrossOffset(int32_t k) {
    if (k < 6) return kDirections[k];
    return latticeAdd(kDirections[k - 6], kDirections[(k - 5) % 6], 1);
}

// The step a non-base vertex was made at: the lowest set bit of its coordinates.
int32_t madeAtStep(LatticePoint p) {
    const uint32_t bits = uint32_t(p.q) | uint32_t(p.r);
    return int32_t(bits & (~bits + 1u));
}
} // namespace

uint8_t HexMesh::acrossCode(LatticePoint p, LatticePoint across) {
    const int32_t s = madeAtStep(p);
    for (int32_t k = 0; k < kAcrossOffsets; ++k)
        if (latticeAdd(p, acrossOffset(k), s) == across) return uint8_t(k + 1);
    return 0; // never: checkInvariants finds the across parent missing
}

bool HexMesh::parentPoints(int32_t v, ParentPoints& out) const {
    const LatticePoint p = vertexLattice(v);
    const int32_t s = madeAtStep(p);
    if (s == 0 || s >= baseStep_) return false; // on the base lattice: a base vertex
    // p is the midpoint of a step-2s lattice edge p -+ s d: p/s is odd where d is.
    const bool qOdd = (p.q & s) != 0, rOdd = (p.r & s) != 0;
    const LatticePoint d = qOdd && rOdd ? LatticePoint{1, -1} : (qOdd ? LatticePoint{1, 0} : LatticePoint{0, 1});
    out.a = latticeAdd(p, d, -s);
    out.b = latticeAdd(p, d, s);
    const int32_t code = vertexInfo_[size_t(v)] & kAcrossCode;
    out.hasAcross = code != 0;
    out.across = out.hasAcross ? latticeAdd(p, acrossOffset(code - 1), s) : p;
    return true;
}

VertexParents HexMesh::parentsAround(int32_t v, int32_t c) const {
    const Hexagon& h = cells_[size_t(c)];
    return parentsBy(v, [&](LatticePoint p) {
        auto in = [&](int32_t cell) {
            const uint32_t* fan = cellFan(cell);
            for (int32_t i = 0; i < kCellFanSlot; ++i) {
                const int32_t u = int32_t(fan[i]);
                if (u != kNone && vertexLattice(u) == p) return u;
            }
            return kNone;
        };
        int32_t u = in(c);
        for (int32_t k = 0; k < 6 && u == kNone; ++k)
            if (h.opposite[k] != kNone) u = in(hexIdx(h.opposite[k]));
        return u;
    });
}

void HexMesh::freeVertex(int32_t v) {
    vertexInfo_[size_t(v)] = 0;
    (deferVertexReuse_ ? freedVertices_ : freeVertices_).push_back(v);
    --liveVertices_;
    if (vertexLog_) vertexLog_->push_back(~v);
}

void HexMesh::releaseFreedVertices() {
    freeVertices_.insert(freeVertices_.end(), freedVertices_.begin(), freedVertices_.end());
    freedVertices_.clear();
}

bool HexMesh::wantsCompaction() const {
    // A sixteenth of a large pool unused (memory is counted at capacity: with growth by a
    // thirty-second, a pool holds at most about a tenth more than it uses); small pools are not
    // worth a rewrite, and each compaction rewrites and uploads the whole stream.
    constexpr size_t kLargePool = 4096;
    const size_t cells = cells_.size(), vertices = vertices_.size();
    return (cells >= kLargePool && 16 * size_t(liveCells_) < 15 * cells) ||
           (vertices >= kLargePool && 16 * size_t(liveVertices_) < 15 * vertices);
}

void HexMesh::compact(std::vector<int32_t>& cellMap, std::vector<int32_t>& vertexMap) {
    releaseFreedVertices();
    cellMap.assign(cells_.size(), kNone);
    int32_t cells = 0;
    for (size_t c = 0; c < cells_.size(); ++c)
        if (cells_[c].level != kFreeLevel) cellMap[c] = cells++;
    vertexMap.assign(vertices_.size(), kNone);
    int32_t vertices = 0;
    for (size_t v = 0; v < vertices_.size(); ++v)
        if (vertexInfo_[v] & kVertexLive) vertexMap[v] = vertices++;
    // Every reference to a cell or a vertex, renumbered; records move down in place.
    for (size_t c = 0; c < cells_.size(); ++c) {
        if (cellMap[c] == kNone) continue;
        Hexagon& h = cells_[c];
        uint32_t* fan = fans_.data() + c * kCellFanSlot;
        for (int32_t i = 0; i < kCellFanSlot; ++i)
            if (fan[i] != kRestartIndex) fan[i] = uint32_t(vertexMap[fan[i]]);
        for (int32_t& o : h.opposite)
            if (o != kNone) o = makeEdge(cellMap[size_t(hexIdx(o))], edgeSlot(o));
        if (h.prev != kNone) h.prev = cellMap[size_t(h.prev)];
        if (h.next != kNone) h.next = cellMap[size_t(h.next)];
    }
    for (std::vector<int32_t>* ends : {&levelHead_, &levelTail_})
        for (int32_t& c : *ends)
            if (c != kNone) c = cellMap[size_t(c)];
    const size_t cellRoom = roomAfterCompaction(size_t(cells)), vertexRoom = roomAfterCompaction(size_t(vertices));
    renumberPool(cells_, cellMap, size_t(cells), cellRoom);
    renumberPool(fans_, cellMap, size_t(cells), cellRoom, kCellFanSlot);
    renumberPool(vertices_, vertexMap, size_t(vertices), vertexRoom);
    renumberPool(vertexInfo_, vertexMap, size_t(vertices), vertexRoom); // parents are lattice points: nothing to renumber
    freeCell_ = kNone;
    releasePool(freeVertices_);
    releasePool(freedVertices_);
}

void HexMesh::linkLevel(int32_t c) {
    Hexagon& h = cells_[size_t(c)];
    const size_t level = h.level;
    h.prev = levelTail_[level];
    h.next = kNone;
    if (h.prev != kNone) cells_[size_t(h.prev)].next = c;
    else levelHead_[level] = c;
    levelTail_[level] = c;
}

void HexMesh::unlinkLevel(int32_t c) {
    Hexagon& h = cells_[size_t(c)];
    const size_t level = h.level;
    if (h.prev != kNone) cells_[size_t(h.prev)].next = h.next;
    else levelHead_[level] = h.next;
    if (h.next != kNone) cells_[size_t(h.next)].prev = h.prev;
    else levelTail_[level] = h.prev;
    h.prev = h.next = kNone;
}

void HexMesh::setLevel(int32_t c, int32_t level) {
    logChange(c); // every operation changes the level of what it changes
    unlinkLevel(c);
    cells_[size_t(c)].level = uint8_t(level);
    linkLevel(c);
}

void HexMesh::connect(int32_t e, int32_t f) {
    if (e != kNone) cells_[size_t(hexIdx(e))].opposite[edgeSlot(e) - 1] = f;
    if (f != kNone) cells_[size_t(hexIdx(f))].opposite[edgeSlot(f) - 1] = e;
}

// --- Queries -------------------------------------------------------------------------------

namespace {
// Nearest integer of a value within a millionth of one (latticeAt): a truncation, one
// instruction, where std::lround is a library call (hot: every cell test asks for centres).
int32_t nearestInteger(double v) { return int32_t(v >= 0.0 ? v + 0.5 : v - 0.5); }
} // namespace

LatticePoint HexMesh::latticeAt(const glm::vec3& position) const {
    const int32_t r = nearestInteger(double(position.z) * rowsPerMetre_);
    double column = double(position.x) * columnsPerMetre_;
    if (embedding_ == Embedding::Shifted && (r & 1) != 0) column -= 0.5;
    return {nearestInteger(column) - floorDiv2(r), r};
}

int32_t HexMesh::cellStep(int32_t c) const {
    const int32_t level = cells_[size_t(c)].level;
    return baseStep_ >> ((level + 1) / 2); // a semi-hexagon is half of a hexagon one level up
}

LatticePoint HexMesh::cellCenter(int32_t c) const {
    const Hexagon& h = cells_[size_t(c)];
    if (h.kind != CellKind::Semi) return vertexLattice(int32_t(cellFan(c)[0]));
    return latticeMidpoint(vertexLattice(cornerVertex(c, h.firstVisible)), vertexLattice(cornerVertex(c, wrapSlot(h.firstVisible + 3))));
}

bool HexMesh::isLongEdge(int32_t e) const {
    const Hexagon& h = cells_[size_t(hexIdx(e))];
    return h.kind == CellKind::Semi && edgeSlot(e) == wrapSlot(h.firstVisible + 3);
}

int32_t HexMesh::edgeEnd(int32_t e) const {
    const Hexagon& h = cells_[size_t(hexIdx(e))];
    const int32_t slot = edgeSlot(e);
    if (h.kind != CellKind::Full && slot == wrapSlot(h.firstVisible + 3)) return cornerVertex(hexIdx(e), h.firstVisible);
    return cornerVertex(hexIdx(e), wrapSlot(slot + 1));
}

// The fan of a semi-hexagon lists its own corners a .. a+3 from corner a, or from a+1 when
// fanFromSecond: own corner i (slot a+i) sits at fan position i - fanFromSecond, cyclically.
int32_t HexMesh::cornerVertex(int32_t c, int32_t slot) const {
    const Hexagon& h = cells_[size_t(c)];
    const uint32_t* fan = cellFan(c);
    if (h.kind == CellKind::Full) return int32_t(fan[slot]);
    if (slot == 0) return h.kind == CellKind::BoundarySemi ? int32_t(fan[0]) : kNone;
    const int32_t own = (slot - h.firstVisible + 6) % 6;
    if (own > 3) return kNone;
    if (h.kind == CellKind::BoundarySemi) return int32_t(fan[1 + own]);
    return int32_t(fan[(own + 4 - h.fanFromSecond) % 4]);
}

CellCorners HexMesh::corners(int32_t c) const {
    CellCorners out;
    for (int32_t slot = 0; slot <= 6; ++slot) out.vertex[slot] = cornerVertex(c, slot);
    return out;
}

bool HexMesh::semiFanFromSecond(const CellCorners& corners, int32_t first) const {
    auto at = [&](int32_t slot) { return vertexLattice(corners.vertex[wrapSlot(slot)]); };
    return semiFanFromSecondCorner(embedding_, at(first), at(first + 1), at(first + 2), at(first + 3));
}

// Also sets fanFromSecond, which only an interior semi-hexagon's fan uses.
void HexMesh::setCorners(int32_t c, const CellCorners& corners) {
    Hexagon& h = cells_[size_t(c)];
    uint32_t* fan = fans_.data() + size_t(c) * kCellFanSlot;
    std::fill_n(fan, kCellFanSlot, kRestartIndex);
    const int32_t* v = corners.vertex;
    const int32_t a = h.firstVisible;
    h.fanFromSecond = 0;
    switch (h.kind) {
        case CellKind::Full:
            for (int32_t slot = 0; slot <= 6; ++slot) fan[slot] = uint32_t(v[slot]);
            fan[7] = uint32_t(v[1]); // the fan closes at its first corner
            break;
        case CellKind::BoundarySemi: // §4.2: three-triangle half fan around the centre
            fan[0] = uint32_t(v[0]);
            for (int32_t i = 0; i < 4; ++i) fan[1 + i] = uint32_t(v[wrapSlot(a + i)]);
            break;
        case CellKind::Semi: { // §7: the fixed rule for the "arbitrary corner"
            const int32_t start = semiFanFromSecond(corners, a) ? 1 : 0;
            h.fanFromSecond = uint8_t(start);
            for (int32_t i = 0; i < 4; ++i) fan[i] = uint32_t(v[wrapSlot(a + (start + i) % 4)]);
            break;
        }
    }
}

int64_t HexMesh::cellTriangles(const Hexagon& h) const {
    switch (h.kind) {
        case CellKind::Full: return 6;
        case CellKind::BoundarySemi: return 3;
        case CellKind::Semi: return 2;
    }
    return 0;
}

size_t HexMesh::memoryBytes() const {
    return cells_.capacity() * sizeof(Hexagon) + fans_.capacity() * sizeof(uint32_t) +
           vertices_.capacity() * sizeof(StreamVertex) + vertexInfo_.capacity() + (freeVertices_.capacity() + freedVertices_.capacity()) * sizeof(int32_t) +
           (levelHead_.capacity() + levelTail_.capacity()) * sizeof(int32_t);
}

size_t HexMesh::liveMemoryBytes() const {
    return size_t(liveCells_) * (sizeof(Hexagon) + kCellFanSlot * sizeof(uint32_t)) +
           size_t(liveVertices_) * (sizeof(StreamVertex) + 1) +
           (levelHead_.size() + levelTail_.size()) * sizeof(int32_t);
}

void HexMesh::appendTriangles(std::vector<uint32_t>& out) const {
    for (int32_t level = 0; level <= maxLevel_; ++level) {
        for (int32_t c = levelHead_[size_t(level)]; c != kNone; c = cells_[size_t(c)].next) {
            const uint32_t* fan = cellFan(c);
            const int32_t n = fanLength(cells_[size_t(c)]);
            for (int32_t k = 1; k + 1 < n; ++k) out.insert(out.end(), {fan[0], fan[k], fan[k + 1]});
        }
    }
}

uint64_t HexMesh::hash() const {
    // Cells are combined by addition, so the hash depends on the mesh, not on the order of the
    // level lists (which depends on the history of operations).
    uint64_t sum = 0;
    for (int32_t level = 0; level <= maxLevel_; ++level) {
        for (int32_t c = levelHead_[size_t(level)]; c != kNone; c = cells_[size_t(c)].next) {
            const Hexagon& cell = cells_[size_t(c)];
            uint64_t h = 1469598103934665603ull; // FNV-1a over the cell
            auto mix = [&](uint64_t value) {
                for (int byte = 0; byte < 8; ++byte, value >>= 8) h = (h ^ (value & 0xFF)) * 1099511628211ull;
            };
            mix(uint64_t(cell.level) | uint64_t(cell.kind) << 8 | uint64_t(cell.splitCount) << 16 | uint64_t(cell.firstVisible) << 24);
            const CellCorners corners = this->corners(c);
            for (int32_t slot = 0; slot <= 6; ++slot) {
                const int32_t v = corners.vertex[slot];
                if (v == kNone) continue;
                mix(latticeKey(vertexLattice(v)));
                const glm::vec3& p = vertices_[size_t(v)].position;
                uint32_t bits[3];
                std::memcpy(bits, &p, sizeof(bits));
                mix(uint64_t(bits[0]) << 32 | bits[1]);
                mix(bits[2]);
            }
            sum += h * 0x9E3779B97F4A7C15ull + (h >> 29);
        }
    }
    return sum;
}

// --- split (§4.1) and the balance rule (§4.5) ---------------------------------------------

bool HexMesh::canSplit(int32_t c) const {
    if (!isLive(c)) return false;
    const Hexagon& h = cells_[size_t(c)];
    return h.kind != CellKind::Semi && h.level < maxLevel_;
}

bool HexMesh::split(int32_t c) {
    if (!canSplit(c)) return false;
    for (;;) {
        const SplitStep step = firstStepToSplit(c);
        applyStep(step);
        if (step.kind == SplitStep::Split && step.cell == c) return true;
    }
}

// §4.5: after splitting c, its new semi-hexagons (level l+1) border c's neighbours. A
// neighbour semi-hexagon touching c with a short edge has level l-1: two levels apart, which
// the balance rule forbids (Fig. 5). It is joined first: with its partner across its long
// edge, or by splitting the whole cell across it, which in turn may need a step first.
SplitStep HexMesh::firstStepToSplit(int32_t c) const {
    const CellSlots slots = slotsOf(cells_[size_t(c)]);
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t o = cells_[size_t(c)].opposite[wrapSlot(slots.firstEdge + i) - 1];
        if (o == kNone || cells_[size_t(hexIdx(o))].kind != CellKind::Semi || isLongEdge(o)) continue;
        const int32_t n = hexIdx(o);
        const int32_t across = cells_[size_t(n)].opposite[wrapSlot(cells_[size_t(n)].firstVisible + 3) - 1];
        if (across == kNone) return {SplitStep::JoinBoundary, n, kNone};
        if (cells_[size_t(hexIdx(across))].kind == CellKind::Semi) return {SplitStep::JoinPair, n, hexIdx(across)};
        return firstStepToSplit(hexIdx(across));
    }
    return {SplitStep::Split, c, kNone};
}

void HexMesh::applyStep(const SplitStep& step) {
    logOperation(MeshOperation::Kind(step.kind), step.cell, step.other);
    switch (step.kind) {
        case SplitStep::Split: splitUnchecked(step.cell); break;
        case SplitStep::JoinPair: joinPair(step.cell, step.other); break;
        case SplitStep::JoinBoundary: joinBoundary(step.cell); break;
    }
}

void HexMesh::replay(const MeshOperation& operation) {
    switch (operation.kind) {
        case MeshOperation::Split: applyStep({SplitStep::Split, operation.cell, kNone}); break;
        case MeshOperation::JoinPair: applyStep({SplitStep::JoinPair, operation.cell, operation.other}); break;
        case MeshOperation::JoinBoundary: applyStep({SplitStep::JoinBoundary, operation.cell, kNone}); break;
        case MeshOperation::Merge: merge(operation.cell); break;
        case MeshOperation::Break: breakHexagon(operation.cell); break;
    }
}

void HexMesh::splitUnchecked(int32_t c) {
    const Hexagon h = cells_[size_t(c)]; // a copy: the pool may grow below
    const CellCorners hv = corners(c);
    const CellSlots slots = slotsOf(h);
    const int32_t level = h.level;
    const int32_t half = cellStep(c) / 2;
    const LatticePoint center = vertexLattice(hv.vertex[0]);

    int32_t newCorner[8], ring[8];
    std::fill(std::begin(ring), std::end(ring), kNone);
    for (int32_t i = 0; i < slots.cornerCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        // Across: the spoke's two triangles in the fan, towards corner k-1 and corner k+1.
        newCorner[k] = allocateVertex(latticeAdd(center, kDirections[k - 1], half), hv.vertex[0], hv.vertex[k],
                                      hv.vertex[wrapSlot(k + 5)], hv.vertex[wrapSlot(k + 1)]);
    }
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i), k1 = wrapSlot(k + 1);
        const int32_t r = allocateCell();
        Hexagon& R = cells_[size_t(r)];
        R.firstVisible = uint8_t(wrapSlot(k + 2));
        CellCorners rv;
        rv.vertex[wrapSlot(k + 2)] = hv.vertex[k1];
        rv.vertex[wrapSlot(k + 3)] = newCorner[k1];
        rv.vertex[wrapSlot(k + 4)] = newCorner[k];
        rv.vertex[wrapSlot(k + 5)] = hv.vertex[k];
        if (h.opposite[k - 1] == kNone) { // §4.2: on the domain boundary the semi keeps a centre
            R.kind = CellKind::BoundarySemi;
            R.level = uint8_t(level + 2);
        } else {
            R.kind = CellKind::Semi;
            R.level = uint8_t(level + 1);
        }
        ring[k] = r;
        if (R.kind == CellKind::BoundarySemi) { // allocateVertex does not touch the cell pool
            // Across: the fan triangle (centre, k, k+1); outside is no surface.
            rv.vertex[0] = allocateVertex(latticeMidpoint(vertexLattice(hv.vertex[k]), vertexLattice(hv.vertex[k1])),
                                          hv.vertex[k], hv.vertex[k1], hv.vertex[0], kNone);
        }
        setCorners(r, rv);
        linkLevel(r);
        triangles_ += cellTriangles(cells_[size_t(r)]);
    }
    CellCorners shrunk = hv;
    for (int32_t i = 0; i < slots.cornerCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        shrunk.vertex[k] = newCorner[k];
    }
    setCorners(c, shrunk);
    cells_[size_t(c)].splitCount = uint8_t(h.splitCount + 1);
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        const int32_t r = ring[k];
        connect(makeEdge(c, k), makeEdge(r, wrapSlot(k + 3)));       // inner edge
        connect(makeEdge(r, wrapSlot(k + 5)), h.opposite[k - 1]);     // long edge, on the old edge
        const int32_t next = ring[wrapSlot(k + 1)];                    // side edge to the next ring cell
        if (next != kNone) connect(makeEdge(r, wrapSlot(k + 2)), makeEdge(next, wrapSlot(k + 5)));
    }
    setLevel(c, level + 2);
    ++counts_.splits;
    // Fig. 3b: semi-hexagons that share a long edge with a neighbour's are joined.
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        const int32_t r = ring[k];
        if (cells_[size_t(r)].kind != CellKind::Semi) continue;
        const int32_t o = cells_[size_t(r)].opposite[wrapSlot(k + 5) - 1];
        if (o != kNone && isLongEdge(o)) joinPair(r, hexIdx(o));
    }
}

// --- join (§4.1, Fig. 3b) ------------------------------------------------------------------

bool HexMesh::join(int32_t s) {
    if (!isLive(s) || cells_[size_t(s)].kind != CellKind::Semi) return false;
    const int32_t o = cells_[size_t(s)].opposite[wrapSlot(cells_[size_t(s)].firstVisible + 3) - 1];
    if (o == kNone) {
        logOperation(MeshOperation::JoinBoundary, s);
        joinBoundary(s);
        return true;
    }
    if (!isLongEdge(o)) return false; // the cell across is whole: only its split can join s
    logOperation(MeshOperation::JoinPair, s, hexIdx(o));
    joinPair(s, hexIdx(o));
    return true;
}

int32_t HexMesh::longEdgeFanCorner(int32_t semi) const {
    // The fan (q0; q1, q2, q3) has triangles (q0, q1, q2) and (q0, q2, q3); the long edge joins
    // corners a and a+3, so its triangle's third corner is a+2 when fanning from a, else a+1.
    const Hexagon& h = cells_[size_t(semi)];
    return cornerVertex(semi, wrapSlot(h.firstVisible + (h.fanFromSecond ? 1 : 2)));
}

void HexMesh::joinPair(int32_t keep, int32_t other) {
    const Hexagon o = cells_[size_t(other)];
    const CellCorners ov = corners(other);
    CellCorners kv = corners(keep);
    const int32_t a = cells_[size_t(keep)].firstVisible;
    kv.vertex[0] = allocateVertex(cellCenter(keep), kv.vertex[a], kv.vertex[wrapSlot(a + 3)], // the midpoint of the shared long edge
                                  longEdgeFanCorner(keep), longEdgeFanCorner(other));
    kv.vertex[wrapSlot(a + 4)] = ov.vertex[wrapSlot(a + 4)];
    kv.vertex[wrapSlot(a + 5)] = ov.vertex[wrapSlot(a + 5)];
    Hexagon& k = cells_[size_t(keep)];
    k.kind = CellKind::Full;
    k.firstVisible = 0;
    setCorners(keep, kv);
    // The other half's three short edges become this hexagon's edges a+3 .. a+5.
    for (int32_t slot = a + 3; slot <= a + 5; ++slot) connect(makeEdge(keep, wrapSlot(slot)), o.opposite[wrapSlot(slot) - 1]);
    setLevel(keep, k.level + 1);
    unlinkLevel(other);
    freeCell(other);
    triangles_ += 2; // two semis (2 + 2 triangles) become one hexagon (6)
    ++counts_.joins;
}

void HexMesh::joinBoundary(int32_t s) {
    CellCorners sv = corners(s);
    const int32_t a = cells_[size_t(s)].firstVisible;
    sv.vertex[0] = allocateVertex(cellCenter(s), sv.vertex[a], sv.vertex[wrapSlot(a + 3)], // the midpoint of its long edge
                                  longEdgeFanCorner(s), kNone);
    cells_[size_t(s)].kind = CellKind::BoundarySemi;
    setCorners(s, sv);
    setLevel(s, cells_[size_t(s)].level + 1);
    triangles_ += 1;
    ++counts_.joins;
}

// --- break (§4.6, Fig. 6b) -----------------------------------------------------------------

bool HexMesh::wouldStayBalancedAfterBreak(int32_t c) const {
    // After the break every edge of c is a short edge of a semi-hexagon; none may carry the
    // long edge of a finer semi-hexagon (§4.5).
    const CellSlots slots = slotsOf(cells_[size_t(c)]);
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t o = cells_[size_t(c)].opposite[wrapSlot(slots.firstEdge + i) - 1];
        if (o != kNone && isLongEdge(o)) return false;
    }
    return true;
}

bool HexMesh::canBreak(int32_t c) const {
    if (!isLive(c)) return false;
    const Hexagon& h = cells_[size_t(c)];
    // Only a cell made by a join (level >= 2, never split since) can be broken apart again.
    if (h.kind == CellKind::Semi || h.splitCount != 0 || h.level < 2) return false;
    return wouldStayBalancedAfterBreak(c);
}

bool HexMesh::breakHexagon(int32_t c) {
    if (!canBreak(c)) return false;
    logOperation(MeshOperation::Break, c);
    breakUnchecked(c);
    return true;
}

int32_t HexMesh::breakDiameterSlot(int32_t c) const {
    // The hexagon was joined along its parent's edge: the one diameter whose two corners are
    // vertices of the parent resolution (step 2s).
    const int32_t parentStep = 2 * cellStep(c);
    for (int32_t k = 1; k <= 3; ++k) {
        const LatticePoint p = vertexLattice(cornerVertex(c, k));
        if (p.q % parentStep == 0 && p.r % parentStep == 0) return k;
    }
    return 1; // unreachable for a consistent mesh (checkInvariants verifies the lattice)
}

void HexMesh::breakUnchecked(int32_t c) {
    const Hexagon j = cells_[size_t(c)];
    const CellCorners jv = corners(c);
    if (j.kind == CellKind::BoundarySemi) { // back to a semi-hexagon whose long edge is the boundary
        freeVertex(jv.vertex[0]);
        CellCorners semi = jv;
        semi.vertex[0] = kNone;
        cells_[size_t(c)].kind = CellKind::Semi;
        setCorners(c, semi);
        setLevel(c, j.level - 1);
        triangles_ -= 1;
        ++counts_.breaks;
        return;
    }
    const int32_t k = breakDiameterSlot(c);
    const int32_t other = allocateCell();
    Hexagon& h2 = cells_[size_t(other)];
    h2.kind = CellKind::Semi;
    h2.firstVisible = uint8_t(wrapSlot(k + 3));
    h2.level = uint8_t(j.level - 1);
    CellCorners v2;
    for (int32_t slot = k + 3; slot <= k + 6; ++slot) v2.vertex[wrapSlot(slot)] = jv.vertex[wrapSlot(slot)];
    setCorners(other, v2);
    linkLevel(other);
    for (int32_t slot = k + 3; slot <= k + 5; ++slot) connect(makeEdge(other, wrapSlot(slot)), j.opposite[wrapSlot(slot) - 1]);

    Hexagon& h1 = cells_[size_t(c)];
    CellCorners v1 = jv;
    v1.vertex[0] = kNone;
    v1.vertex[wrapSlot(k + 4)] = kNone;
    v1.vertex[wrapSlot(k + 5)] = kNone;
    h1.opposite[wrapSlot(k + 4) - 1] = kNone;
    h1.opposite[wrapSlot(k + 5) - 1] = kNone;
    h1.kind = CellKind::Semi;
    h1.firstVisible = uint8_t(k);
    setCorners(c, v1);
    connect(makeEdge(c, wrapSlot(k + 3)), makeEdge(other, k)); // the two long edges
    freeVertex(jv.vertex[0]);
    setLevel(c, j.level - 1);
    triangles_ -= 2;
    ++counts_.breaks;
}

// --- merge (§4.6, Fig. 6a) -----------------------------------------------------------------

bool HexMesh::canMerge(int32_t c) const {
    if (!isLive(c)) return false;
    const Hexagon& h = cells_[size_t(c)];
    if (h.kind == CellKind::Semi || h.splitCount == 0) return false;
    const CellSlots slots = slotsOf(h);
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        const int32_t o = h.opposite[k - 1];
        if (o == kNone) return false;
        const Hexagon& n = cells_[size_t(hexIdx(o))];
        if (n.kind == CellKind::Semi) {
            // The ring semi-hexagon of c's last split, touching c with its inner edge.
            if (n.level + 1 != h.level || edgeSlot(o) != wrapSlot(n.firstVisible + 1)) return false;
        } else if (n.level != h.level || !canBreak(hexIdx(o))) {
            // A ring cell that was joined can be broken only while its split counter is 0.
            return false;
        }
    }
    return true;
}

void HexMesh::verticesFreedByMerge(int32_t c, std::vector<int32_t>& out) const {
    const Hexagon& h = cells_[size_t(c)];
    const CellSlots slots = slotsOf(h);
    for (int32_t i = 0; i < slots.edgeCount; ++i) { // the centres of the ring cells merge breaks first
        const int32_t n = hexIdx(h.opposite[wrapSlot(slots.firstEdge + i) - 1]);
        if (cells_[size_t(n)].kind != CellKind::Semi) out.push_back(int32_t(cellFan(n)[0]));
    }
    for (int32_t i = 0; i < slots.cornerCount; ++i) out.push_back(cornerVertex(c, wrapSlot(slots.firstEdge + i)));
}

bool HexMesh::merge(int32_t c) {
    if (!canMerge(c)) return false;
    logOperation(MeshOperation::Merge, c);
    const CellSlots slots = slotsOf(cells_[size_t(c)]);
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t n = hexIdx(cells_[size_t(c)].opposite[wrapSlot(slots.firstEdge + i) - 1]);
        if (cells_[size_t(n)].kind != CellKind::Semi) breakUnchecked(n);
    }
    const Hexagon h = cells_[size_t(c)];
    const CellCorners hv = corners(c);
    int32_t ring[8], outerCorner[8];
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        ring[k] = hexIdx(h.opposite[k - 1]);
        outerCorner[k] = cornerVertex(ring[k], wrapSlot(k + 5));
        outerCorner[wrapSlot(k + 1)] = cornerVertex(ring[k], wrapSlot(k + 2));
    }
    for (int32_t i = 0; i < slots.edgeCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        connect(makeEdge(c, k), cells_[size_t(ring[k])].opposite[wrapSlot(k + 5) - 1]);
        unlinkLevel(ring[k]);
        freeCell(ring[k]);
        triangles_ -= 2;
    }
    CellCorners merged = hv;
    for (int32_t i = 0; i < slots.cornerCount; ++i) {
        const int32_t k = wrapSlot(slots.firstEdge + i);
        freeVertex(hv.vertex[k]);
        merged.vertex[k] = outerCorner[k];
    }
    setCorners(c, merged);
    cells_[size_t(c)].splitCount = uint8_t(h.splitCount - 1);
    setLevel(c, h.level - 2);
    ++counts_.merges;
    return true;
}

} // namespace hexlod
