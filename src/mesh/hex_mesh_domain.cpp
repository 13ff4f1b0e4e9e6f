// Height-field domain set-up (paper §4.7): the base hexagons over a W x H field.
//
// The paper fits base hexagons into the rectangle and cuts the corners away. hexlod must
// cover the whole field, of any size, so it does the opposite:
// - The base step S is a power of two (see chooseBaseStep); resolution k has step S >> k and
//   the finest step is 1, where every sample is a vertex.
// - Row 0 (north) is a lattice line through base centres: the hexagons centred on it are cut in
//   half and kept as boundary semi-hexagons (§4.2). The south boundary is the first lattice
//   row R >= H-1 that is a multiple of S, likewise cut. Rows between H-1 and R lie past the
//   field (at most S-1 rows, and none when H = 2^n + 1).
// - East and west, every base hexagon whose extent overlaps the field's columns is kept whole,
//   so the jagged outline lies outside the rectangle.
// Height lookups outside the field are clamped (embedding.cpp), and what lies outside the
// rectangle is hidden at draw time. Boundary edges stay boundary edges under every split:
// a ring semi-hexagon on one becomes a boundary semi-hexagon around its midpoint (§4.2).
#include <unordered_map>

#include "mesh/hex_mesh.h"
#include "mesh/pool_growth.h"

namespace hexlod {

namespace {

// Largest power of two no more than an eighth of the shorter side (at least 1). The lattice
// reaches up to two base steps past the east and west edges, so a small step wastes little
// (at most a quarter of the shorter side on each side, and nothing view-dependent refinement
// looks at); a few dozen base hexagons are still only a few hundred triangles.
int32_t chooseBaseStep(int32_t width, int32_t height) {
    const int32_t limit = std::max(1, (std::min(width, height) - 1) / 8);
    int32_t step = 1;
    while (step * 2 <= limit) step *= 2;
    return step;
}

} // namespace

const char* HexMesh::reset(const Heightfield& field, Embedding embedding, int32_t baseStep) {
    if (baseStep == 0) baseStep = chooseBaseStep(field.width(), field.height());
    if (baseStep < 1 || (baseStep & (baseStep - 1)) != 0 || baseStep > (1 << 20))
        return "the base step must be a power of two";
    // The lattice reaches two base steps past the east edge and one past the south edge; latticeAt
    // recovers points from float positions exactly only under 2^22 columns and rows.
    if (int64_t(field.width()) + 2 * int64_t(baseStep) + 1 >= kMaxLatticeReach || int64_t(field.height()) + baseStep >= kMaxLatticeReach)
        return "the base step is too large for this field: the lattice would reach past 2^22 samples";
    field_ = &field;
    embedding_ = embedding;
    baseStep_ = baseStep;
    maxLevel_ = 0;
    columnsPerMetre_ = 1.0 / field.scale().spacingX;
    rowsPerMetre_ = 1.0 / field.scale().spacingY;
    for (int32_t s = baseStep; s > 1; s /= 2) maxLevel_ += 2;

    releasePool(cells_);
    releasePool(fans_);
    freeCell_ = kNone;
    liveCells_ = 0;
    levelHead_.assign(size_t(maxLevel_) + 1, kNone);
    levelTail_.assign(size_t(maxLevel_) + 1, kNone);
    releasePool(vertices_);
    releasePool(vertexInfo_);
    releasePool(freeVertices_);
    releasePool(freedVertices_);
    liveVertices_ = 0;
    boundary_.clear();
    domainDoubleArea_ = 0;
    triangles_ = 0;
    counts_ = {};

    const int32_t S = baseStep;
    const int32_t lastRow = ((field.height() - 1 + S - 1) / S) * S; // R: the south boundary row
    const int32_t centreRows = lastRow / S;
    std::unordered_map<uint64_t, int32_t> vertexAt; // set-up only: shares corners between cells
    auto vertexOf = [&](LatticePoint p) {
        auto [it, inserted] = vertexAt.try_emplace(latticeKey(p), kNone);
        if (inserted) it->second = allocateVertex(p, kNone, kNone, kNone, kNone);
        return it->second;
    };

    // Doubled horizontal lattice position X = 2q + r keeps the overlap test in integers: a
    // hexagon of step S spans X in [Xc - 2S, Xc + 2S]; the field's samples span [0, 2W - 1].
    const int32_t fieldX = 2 * field.width() - 1;
    for (int32_t b = 0; b <= centreRows; ++b) {
        const int32_t r = b * S;
        // Centres of row b: q = a*S with (a - b) divisible by 3.
        int32_t aFirst = (-2 * S - r) / (2 * S) - 3;
        aFirst += positiveMod3(b - aFirst);
        for (int32_t a = aFirst;; a += 3) {
            const int32_t centreX = 2 * a * S + r;
            if (centreX - 2 * S >= fieldX) break;
            if (centreX + 2 * S <= 0) continue;
            const LatticePoint centre{a * S, r};
            const int32_t c = allocateCell();
            Hexagon& h = cells_[size_t(c)];
            if (b == 0 || b == centreRows) {
                h.kind = CellKind::BoundarySemi; // the half inside the rows [0, R]
                h.firstVisible = uint8_t(b == 0 ? 4 : 1);
            }
            const int32_t first = h.kind == CellKind::Full ? 1 : h.firstVisible;
            const int32_t corners = h.kind == CellKind::Full ? 6 : 4;
            CellCorners vertices;
            vertices.vertex[0] = vertexOf(centre);
            for (int32_t i = 0; i < corners; ++i) {
                const int32_t k = wrapSlot(first + i);
                vertices.vertex[k] = vertexOf(latticeAdd(centre, kDirections[k - 1], S));
            }
            setCorners(c, vertices);
            linkLevel(c);
            triangles_ += cellTriangles(cells_[size_t(c)]);
        }
    }

    // Neighbours: an edge u->v is opposite the edge v->u of another cell; edges without one
    // form the domain boundary.
    std::unordered_map<uint64_t, int32_t> edgeFrom;
    auto edgeKey = [](int32_t u, int32_t v) { return (uint64_t(uint32_t(u)) << 32) | uint32_t(v); };
    auto forEachEdge = [&](auto&& visit) {
        for (int32_t c = 0; c < int32_t(cells_.size()); ++c) {
            const Hexagon& h = cells_[size_t(c)];
            const int32_t first = h.kind == CellKind::Full ? 1 : h.firstVisible;
            const int32_t edges = h.kind == CellKind::Full ? 6 : 4; // a semi's diameter included
            for (int32_t i = 0; i < edges; ++i) {
                const int32_t e = makeEdge(c, wrapSlot(first + i));
                visit(e, edgeStart(e), edgeEnd(e));
            }
        }
    };
    forEachEdge([&](int32_t e, int32_t u, int32_t v) { edgeFrom[edgeKey(u, v)] = e; });
    forEachEdge([&](int32_t e, int32_t u, int32_t v) {
        const auto it = edgeFrom.find(edgeKey(v, u));
        if (it != edgeFrom.end()) connect(e, it->second);
        else boundary_.emplace_back(vertexLattice(u), vertexLattice(v));
    });

    std::vector<uint32_t> triangles;
    appendTriangles(triangles);
    for (size_t t = 0; t < triangles.size(); t += 3) {
        domainDoubleArea_ += latticeDoubleArea(vertexLattice(int32_t(triangles[t])), vertexLattice(int32_t(triangles[t + 1])),
                                               vertexLattice(int32_t(triangles[t + 2])));
    }
    return nullptr;
}

} // namespace hexlod
