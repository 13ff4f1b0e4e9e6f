// See update_floor.h.
#include "update_floor.h"

#include "bench_clock.h"

namespace hexlod::bench {

namespace {

// A cell's shape as one key (lattice coordinates stay within 2^24 for every field hexlod opens).
uint64_t shapeKey(const CellShape& s) {
    return (uint64_t(uint32_t(s.center.q) & 0xFFFFFF) << 40) | (uint64_t(uint32_t(s.center.r) & 0xFFFFFF) << 16) |
           (uint64_t(s.step & 0x3FF) << 6) | (uint64_t(s.kind) << 3) | uint64_t(s.firstVisible);
}

} // namespace

UpdateFloor::UpdateFloor(Terrain& terrain, const Heightfield& field, bool slopes)
    : terrain_(terrain), mesh_(terrain.mesh()), copy_(terrain.mesh()), field_(field), slopes_(slopes) {
    pyramid_.build(field);
    copy_.setChangeLog(0, &changed_);
    copy_.setChangeLog(1, nullptr);
    copy_.setVertexLog(nullptr);
    copy_.setOperationLog(nullptr);
    copy_.setDeferVertexReuse(false);
    copy_.releaseFreedVertices();
    for (int32_t c = 0; c < copy_.cellCapacity(); ++c)
        if (copy_.isLive(c)) remember(c);
    terrain_.setOperationLog(&operations_);
}

UpdateFloor::~UpdateFloor() { terrain_.setOperationLog(nullptr); }

bool UpdateFloor::remember(int32_t cell) {
    const CellShape shape = shapeOfCell(copy_, cell);
    if (!seen_.insert(shapeKey(shape)).second) return false;
    shapes_.push_back(shape);
    return true;
}

UpdateFloor::Frame UpdateFloor::frame(bool compacted) {
    Frame f;
    changed_.clear();
    if (diverged_) {
        operations_.clear();
        return f;
    }
    const auto start = std::chrono::steady_clock::now();
    for (const MeshOperation& op : operations_) copy_.replay(op);
    f.operationsMs = msSince(start);
    operations_.clear();
    // Unchecked steps on a copy that went its own way could break it: stop at the first frame
    // whose triangles differ (matchesMesh says so).
    diverged_ = copy_.triangleCount() != mesh_.triangleCount();
    // The new shapes among the cells the operations made or changed (not timed: bookkeeping).
    shapes_.clear();
    for (int32_t c : changed_)
        if (copy_.isLive(c)) remember(c);
    f.newShapes = int32_t(shapes_.size());
    const Embedding embedding = copy_.embedding();
    const auto boundsStart = std::chrono::steady_clock::now();
    float sink = 0.0f; // read into checksum_, so the bounds are computed
    for (const CellShape& shape : shapes_) {
        const CellError e = computeCellError(field_, embedding, pyramid_, shape);
        sink += e.error;
        if (slopes_) sink += slopesUnder(field_, embedding, footprintOf(field_, embedding, shape)).dxHigh;
    }
    f.boundsMs = msSince(boundsStart);
    checksum_ = sink;
    if (compacted) copy_.compact(cellMap_, vertexMap_);
    return f;
}

} // namespace hexlod::bench
