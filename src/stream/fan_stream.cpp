// The fan stream of paper §7, kept incrementally; see fan_stream.h for the layouts.
#include "stream/fan_stream.h"
#include "mesh/pool_growth.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hexlod {

void FanStream::attach(HexMesh& mesh) {
    mesh_ = &mesh;
    mesh.setChangeLog(1, &changedCells_);
    mesh.setVertexLog(&vertexLog_);
    mesh.setDeferVertexReuse(true);
    // Fixed point for the normal sums: a power of two as fine as 64 bits allow for faces as
    // large as the whole mesh (a sum over a dozen faces stays below 2^62).
    glm::dvec3 low(1e300), high(-1e300);
    for (int32_t v = 0; v < mesh.vertexCapacity(); ++v) {
        if (!mesh.isVertexLive(v)) continue;
        low = glm::min(low, glm::dvec3(mesh.vertexPosition(v)));
        high = glm::max(high, glm::dvec3(mesh.vertexPosition(v)));
    }
    const double extent = std::max(glm::length(high - low), 1.0);
    normalScale_ = std::ldexp(1.0, int(std::floor(std::log2(std::ldexp(1.0, 57) / (extent * extent)))));
    releaseArrays(); // a new mesh: nothing of the last one's peak stays allocated
    rewriteAll(mesh);
}

// Empties the per-record arrays and dirty state, giving their memory back, so that the rewrite
// that follows allocates them at the mesh's sizes (rewriteAll and sync size them).
void FanStream::releaseArrays() {
    releasePool(indices_);
    releasePool(normalSum_);
    releasePool(vertexNormals_);
    releasePool(cellPending_);
    releasePool(vertexPending_);
    releasePool(dirtyVertices_.marked);
    releasePool(dirtyIndices_.marked);
    releasePool(dirtyVertices_.list);
    releasePool(dirtyIndices_.list);
    touchedVertices_.clear();
}

void FanStream::setLayout(IndexLayout layout) {
    if (layout == layout_) return;
    layout_ = layout;
    if (mesh_) rewriteAll(*mesh_);
}

void FanStream::setNormals(bool on) {
    if (on == normals_) return;
    normals_ = on;
    if (!on) {
        // The point of turning them off: give the memory back (shrink_to_fit does nothing in
        // libstdc++ without exceptions).
        releasePool(normalSum_);
        releasePool(vertexNormals_);
        if (!keepsSlots()) releasePool(indices_); // the fans' last state was kept for the normals only
        return;
    }
    if (mesh_) rebuildNormals(*mesh_);
}

// Sums the face normals of every slot as it stands (what the renderer draws now); the next
// sync then moves the sums with the changes, as it always does.
void FanStream::rebuildNormals(HexMesh& mesh) {
    reserveLikePool(normalSum_, size_t(mesh.vertexCapacity()), mesh.vertexPoolRoom());
    normalSum_.assign(size_t(mesh.vertexCapacity()), glm::i64vec3(0));
    reserveLikePool(vertexNormals_, size_t(mesh.vertexCapacity()), mesh.vertexPoolRoom());
    vertexNormals_.assign(size_t(mesh.vertexCapacity()), PackedNormal{});
    if (vertexPending_.size() < normalSum_.size()) vertexPending_.resize(normalSum_.size(), false);
    if (layout_ == IndexLayout::Fans) { // from now on the fans' last state is kept (keepsSlots)
        reserveLikePool(indices_, mesh.fanTable().size(), mesh.cellPoolRoom() * size_t(kFanSlot));
        indices_.assign(mesh.fanTable().begin(), mesh.fanTable().end());
    }
    const size_t slots = indices_.size() / size_t(slotSize());
    for (size_t c = 0; c < slots; ++c) accumulate(mesh, indices_.data() + c * size_t(slotSize()), +1);
    finishNormals(mesh);
    touchedVertices_.clear();
    ++version_;
}

void FanStream::renumbered(HexMesh& mesh) {
    releaseArrays(); // the rewrite allocates them at the compacted sizes
    rewriteAll(mesh);
}

void FanStream::rewriteAll(HexMesh& mesh) {
    // As much room as the mesh's pools keep (a compaction leaves them one growth step).
    if (keepsSlots()) {
        indices_.reserve(mesh.cellPoolRoom() * size_t(slotSize()));
        indices_.assign(size_t(mesh.cellCapacity()) * size_t(slotSize()), kRestartIndex);
    } else {
        releasePool(indices_);
    }
    if (normals_) {
        normalSum_.reserve(mesh.vertexPoolRoom()), vertexNormals_.reserve(mesh.vertexPoolRoom());
        normalSum_.assign(size_t(mesh.vertexCapacity()), glm::i64vec3(0));
        vertexNormals_.assign(size_t(mesh.vertexCapacity()), PackedNormal{});
    }
    changedCells_.clear();
    for (int32_t c = 0; c < mesh.cellCapacity(); ++c) changedCells_.push_back(c);
    vertexLog_.clear();
    dirtyVertices_.markAll(mesh.vertexCapacity());
    dirtyIndices_.markAll(mesh.cellCapacity());
    Geomorph still; // no blends: the mesh is drawn as it is
    sync(mesh, still);
}

template <typename Visit>
void FanStream::forEachTriangle(const uint32_t* slot, Visit&& visit) const {
    if (layout_ == IndexLayout::Fans) {
        if (slot[0] == kRestartIndex) return;
        for (int32_t k = 1; k + 1 < kFanSlot && slot[k + 1] != kRestartIndex; ++k) visit(slot[0], slot[k], slot[k + 1]);
        return;
    }
    for (int32_t k = 0; k < kTriangleSlot && slot[k] != kRestartIndex; k += 3) visit(slot[k], slot[k + 1], slot[k + 2]);
}

void FanStream::markVertex(int32_t v) {
    if (vertexPending_[size_t(v)]) return;
    vertexPending_[size_t(v)] = true;
    touchedVertices_.push_back(v);
}

// Adds (sign +1) or removes (-1) the face normals of a slot's triangles to their vertices.
void FanStream::accumulate(const HexMesh& mesh, const uint32_t* slot, int64_t sign) {
    forEachTriangle(slot, [&](uint32_t a, uint32_t b, uint32_t c) {
        if (normals_) {
            const glm::dvec3 pa(mesh.vertexPosition(int32_t(a))), pb(mesh.vertexPosition(int32_t(b))),
                pc(mesh.vertexPosition(int32_t(c)));
            // Counter-clockwise seen from +y: the face normal points up. Its length is twice the
            // area, so larger faces weigh more.
            const glm::dvec3 n = glm::cross(pb - pa, pc - pa) * normalScale_;
            const glm::i64vec3 fixed(std::llround(n.x), std::llround(n.y), std::llround(n.z));
            for (uint32_t v : {a, b, c}) normalSum_[v] += fixed * sign;
        }
        for (uint32_t v : {a, b, c}) markVertex(int32_t(v)); // the upload needs them either way
    });
}

// Brings the kept slot of a cell (keepsSlots) in step with the mesh's fan.
void FanStream::writeSlot(const HexMesh& mesh, int32_t c) {
    if (!keepsSlots()) return;
    uint32_t* slot = indices_.data() + size_t(c) * size_t(slotSize());
    const uint32_t* fan = mesh.cellFan(c);
    if (layout_ == IndexLayout::Fans) {
        std::copy_n(fan, kFanSlot, slot); // a free cell's fan is all restarts
        return;
    }
    std::fill(slot, slot + slotSize(), kRestartIndex);
    if (!mesh.isLive(c)) return;
    const int32_t n = HexMesh::fanLength(mesh.cell(c));
    for (int32_t k = 1; k + 1 < n; ++k) {
        slot[3 * (k - 1)] = fan[0];
        slot[3 * (k - 1) + 1] = fan[k];
        slot[3 * (k - 1) + 2] = fan[k + 1];
    }
}

void FanStream::sync(HexMesh& mesh, Geomorph& morph) {
    // The pools may have grown: new slots start empty, new vertices with zero sums.
    const size_t cells = size_t(mesh.cellCapacity()), vertices = size_t(mesh.vertexCapacity());
    const size_t cellRoom = mesh.cellPoolRoom(), vertexRoom = mesh.vertexPoolRoom();
    if (keepsSlots() && indices_.size() < cells * size_t(slotSize())) {
        reserveLikePool(indices_, cells * size_t(slotSize()), cellRoom * size_t(slotSize()));
        indices_.resize(cells * size_t(slotSize()), kRestartIndex);
    }
    if (normals_ && normalSum_.size() < vertices) {
        reserveLikePool(normalSum_, vertices, vertexRoom);
        normalSum_.resize(vertices, glm::i64vec3(0));
    }
    if (normals_ && vertexNormals_.size() < vertices) {
        reserveLikePool(vertexNormals_, vertices, vertexRoom);
        vertexNormals_.resize(vertices, PackedNormal{});
    }
    if (vertexPending_.size() < vertices) {
        reserveLikePool(vertexPending_, vertices, vertexRoom);
        vertexPending_.resize(vertices, false);
    }
    if (cellPending_.size() < cells) {
        reserveLikePool(cellPending_, cells, cellRoom);
        cellPending_.resize(cells, false);
    }

    bool wrote = false;
    for (int32_t c : changedCells_) {
        if (cellPending_[size_t(c)]) continue;
        cellPending_[size_t(c)] = true;
        if (keepsSlots()) {
            const uint32_t* slot = indices_.data() + size_t(c) * size_t(slotSize());
            accumulate(mesh, slot, -1); // its old triangles: their vertices still hold their positions
            writeSlot(mesh, c);
            accumulate(mesh, slot, +1);
        } else {
            accumulate(mesh, mesh.cellFan(c), +1); // marks the vertices it draws
        }
        dirtyIndices_.mark(c);
        wrote = true;
    }
    for (int32_t c : changedCells_) cellPending_[size_t(c)] = false;
    changedCells_.clear();

    // New vertices blend in from their parent edges, in creation order (parents first). The log
    // holds v, a, b, across for a new vertex and ~v for a freed one (HexMesh::setVertexLog).
    for (size_t i = 0; i < vertexLog_.size();) {
        const int32_t v = vertexLog_[i];
        if (v < 0) {
            ++i;
            continue;
        }
        const VertexParents parents{vertexLog_[i + 1], vertexLog_[i + 2], vertexLog_[i + 3]};
        i += 4;
        // Parents outlive their children and freed slots wait for releaseFreedVertices, so the
        // logged parents of a vertex still live are the vertices they were.
        if (!mesh.isVertexLive(v)) continue;
        morph.blendIn(mesh, v, parents);
    }
    vertexLog_.clear();
    for (int32_t v : morph.changedVertices()) markVertex(v);
    morph.changedVertices().clear();

    finishNormals(mesh);
    wrote = wrote || !touchedVertices_.empty();
    touchedVertices_.clear();
    mesh.releaseFreedVertices(); // every slot that used them has been rewritten
    // A sync after a large change (a new mesh refined in one go) leaves its logs far larger than
    // frames need: that memory goes back (memory is counted at capacity).
    const size_t vertexListRoom = frameListRoom(size_t(mesh.liveVertices()));
    trimExcess(changedCells_, frameListRoom(size_t(mesh.liveCells())));
    trimExcess(vertexLog_, vertexListRoom);
    trimExcess(touchedVertices_, vertexListRoom);
    trimExcess(morph.changedVertices(), vertexListRoom);
    if (wrote) ++version_;
}

void FanStream::finishNormals(HexMesh& mesh) {
    for (int32_t v : touchedVertices_) {
        vertexPending_[size_t(v)] = false;
        dirtyVertices_.mark(v);
        if (!normals_ || !mesh.isVertexLive(v)) continue; // a freed vertex's sum is back to exactly zero
        const glm::dvec3 n(normalSum_[size_t(v)]);
        const double length = glm::length(n);
        int16_t* out = vertexNormals_[size_t(v)].xyz;
        if (length > 0.0) {
            for (int k = 0; k < 3; ++k) out[k] = int16_t(std::lround(n[k] / length * 32767.0));
        } else {
            out[0] = out[2] = 0, out[1] = 32767;
        }
        out[3] = mesh.vertexMissing(v) ? 32767 : 0; // the page's no-data holes (terrain.frag)
    }
}

void FanStream::DirtySet::mark(int32_t element) {
    const size_t block = size_t(element >> kBlockShift);
    if (block >= marked.size()) {
        marked.resize(block + 1, 0); // the pools grew
        // The list holds a block at most once: room for every block, no doubling past that.
        list.reserve(marked.capacity());
    }
    if (marked[block]) return;
    marked[block] = 1;
    list.push_back(int32_t(block));
}

void FanStream::DirtySet::markAll(int32_t elements) {
    clear();
    for (int32_t element = 0; element < elements; element += 1 << kBlockShift) mark(element);
}

void FanStream::DirtySet::clear() {
    for (int32_t block : list) marked[size_t(block)] = 0;
    list.clear();
}

void FanStream::DirtySet::collect(int32_t elements, std::vector<ElementRange>& out) {
    out.clear();
    std::sort(list.begin(), list.end());
    const int32_t blockSize = 1 << kBlockShift;
    for (int32_t block : list) {
        const int32_t first = block * blockSize;
        if (first >= elements) break;
        const int32_t end = std::min(first + blockSize, elements);
        if (!out.empty() && first - (out.back().first + out.back().count) <= kMergeGap * blockSize) {
            out.back().count = end - out.back().first;
        } else {
            out.push_back({first, end - first});
        }
    }
}

const std::vector<ElementRange>& FanStream::dirtyVertices() {
    dirtyVertices_.collect(mesh_ ? mesh_->vertexCapacity() : 0, vertexRanges_);
    return vertexRanges_;
}

const std::vector<ElementRange>& FanStream::dirtyIndices() {
    dirtyIndices_.collect(mesh_ ? mesh_->cellCapacity() : 0, indexRanges_);
    for (ElementRange& r : indexRanges_) r = {r.first * slotSize(), r.count * slotSize()};
    return indexRanges_;
}

void FanStream::acknowledge() {
    dirtyVertices_.clear();
    dirtyIndices_.clear();
}

void FanStream::buildLevelView(const HexMesh& mesh, bool outline) {
    levelIndices_.clear();
    levelOffsets_.clear();
    outline_.clear();
    if (!outline) releasePool(outline_); // its memory only while it is shown (not shrink_to_fit: see setNormals)
    for (int32_t level = 0; level <= mesh.maxLevel(); ++level) {
        levelOffsets_.push_back(int32_t(levelIndices_.size()));
        for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c)) {
            const Hexagon& h = mesh.cell(c);
            const uint32_t* fan = mesh.cellFan(c);
            levelIndices_.insert(levelIndices_.end(), fan, fan + HexMesh::fanLength(h));
            levelIndices_.push_back(kRestartIndex);
            if (!outline) continue;
            // Each cell edge once, from the cell with the lower index (or alone).
            for (int32_t slot = 1; slot <= 6; ++slot) {
                if (mesh.cornerVertex(c, slot) == kNone) continue;
                const int32_t o = h.opposite[slot - 1];
                if (o != kNone && hexIdx(o) < c) continue;
                const int32_t e = makeEdge(c, slot);
                outline_.push_back(uint32_t(mesh.edgeStart(e)));
                outline_.push_back(uint32_t(mesh.edgeEnd(e)));
            }
        }
    }
    levelOffsets_.push_back(int32_t(levelIndices_.size()));
}

size_t FanStream::memoryBytes() const {
    return indices_.capacity() * sizeof(uint32_t) + normalSum_.capacity() * sizeof(glm::i64vec3) +
           vertexNormals_.capacity() * sizeof(PackedNormal) +
           (changedCells_.capacity() + vertexLog_.capacity() + touchedVertices_.capacity()) * sizeof(int32_t) +
           (cellPending_.capacity() + vertexPending_.capacity()) / 8 + dirtyVertices_.marked.capacity() + dirtyIndices_.marked.capacity() +
           (dirtyVertices_.list.capacity() + dirtyIndices_.list.capacity()) * sizeof(int32_t) +
           (vertexRanges_.capacity() + indexRanges_.capacity()) * sizeof(ElementRange) +
           (levelIndices_.capacity() + outline_.capacity()) * sizeof(uint32_t) + levelOffsets_.capacity() * sizeof(int32_t);
}

size_t FanStream::liveMemoryBytes() const {
    if (!mesh_) return 0;
    return (keepsSlots() ? size_t(mesh_->liveCells()) * size_t(slotSize()) * sizeof(uint32_t) : 0) +
           (normals_ ? size_t(mesh_->liveVertices()) * (sizeof(glm::i64vec3) + sizeof(PackedNormal)) : 0);
}

} // namespace hexlod
