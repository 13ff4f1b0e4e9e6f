// The terrain facade: the wiring of paper §4 (mesh), §5-§6 (refiner) and §7 (blends, stream)
// in one place; see terrain.h.
#include "terrain.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <vector>

#include "mesh/embedding.h"

#include "mesh/hex_mesh_refine.h"
#include "mesh/pool_growth.h"
#include "stream/drawn_surface.h"

namespace hexlod {

std::unique_ptr<Terrain> Terrain::create(int32_t width, int32_t height, SampleType type, const char** error) {
    auto field = Heightfield::create(width, height, type, error);
    if (!field) return nullptr;
    std::unique_ptr<Terrain> terrain(new (std::nothrow) Terrain(std::move(field)));
    if (!terrain && error) *error = "out of memory for the terrain";
    return terrain;
}

std::unique_ptr<Terrain> Terrain::createTiled(int32_t width, int32_t height, SampleType type, int32_t levels, const int32_t* dims,
                                              const char** error) {
    auto field = Heightfield::createTiled(width, height, type, levels, dims, error);
    if (!field) return nullptr;
    std::unique_ptr<Terrain> terrain(new (std::nothrow) Terrain(std::move(field)));
    if (!terrain && error) *error = "out of memory for the terrain";
    return terrain;
}

void* Terrain::tileBuffer(int32_t level, int32_t tx, int32_t ty) {
    return field_->tiles() ? field_->tiles()->tileBuffer(level, tx, ty) : nullptr;
}

bool Terrain::commitTile(int32_t level, int32_t tx, int32_t ty) {
    SampleTiles* tiles = field_->tiles();
    if (!tiles || !tiles->commit(level, tx, ty, changedHeights_)) return false;
    residency_.arrived(*tiles, level, tx, ty);
    return true;
}

bool Terrain::evictTile(int32_t level, int32_t tx, int32_t ty) {
    return field_->tiles() && field_->tiles()->evict(level, tx, ty, changedHeights_);
}

bool Terrain::setTileCap(double bytes) {
    if (!field_->tiles() || !(bytes >= 0.0)) return false;
    residency_.setCapBytes(bytes);
    return true;
}

bool Terrain::setVoidsAsPits(bool pits) {
    if (!field_->tiles()) return false;
    field_->tiles()->setVoidsAsPits(pits, changedHeights_);
    return true;
}

const char* Terrain::declareHeightRange(double low, double high) {
    if (!field_->tiles()) return "the terrain holds its samples whole: its height range is known";
    if (!field_->declareHeightRange(low, high)) return "the height range must be finite, low <= high, within 1e9 m";
    if (hasMesh_) refiner_.heightsChanged({0, 0, field_->width() - 1, field_->height() - 1}, true);
    return nullptr;
}

const std::vector<TileWant>& Terrain::tileWants() { return wants_.collect(mesh_, *field_, refiner_.starved()); }

const std::vector<TileWant>& Terrain::tilesInUse() { return wants_.collectInUse(mesh_, *field_); }

// The heights under some vertices changed (tiles came or went): each moves to its new height,
// blending from where it is drawn (§7's geomorph, as a split's new vertex does), and the cells
// whose bounds read those samples are tested again.
void Terrain::applyHeightChanges() {
    if (changedHeights_.empty()) return;
    const SampleRect rect = changedHeights_;
    changedHeights_ = {};
    const bool grew = field_->widenHeightRange();
    if (!hasMesh_) return;
    const double sx = field_->scale().spacingX, sy = field_->scale().spacingY;
    const int32_t vertices = mesh_.vertexCapacity();
    if (int32_t(movingMark_.size()) < vertices) movingMark_.resize(size_t(vertices), 0);
    moving_.clear(), movingHeights_.clear(), movingCells_.clear();
    for (int32_t v = 0; v < vertices; ++v) {
        if (!mesh_.isVertexLive(v)) continue;
        const glm::vec3& p = mesh_.vertexPosition(v);
        // A shifted odd row's vertex averages the samples on either side: one sample around.
        // Lattice points past the field read its edge samples (embedding.h): clamped.
        const int32_t j = std::clamp(int32_t(std::floor(p.x / sx)), 0, field_->width() - 1);
        const int32_t i = std::clamp(int32_t(std::lround(p.z / sy)), 0, field_->height() - 1);
        if (j + 1 < rect.j0 || j - 1 > rect.j1 || i < rect.i0 || i > rect.i1) continue;
        const float y = embedLatticePoint(*field_, mesh_.embedding(), mesh_.vertexLattice(v)).y;
        if (y == p.y) continue;
        moving_.push_back(v), movingHeights_.push_back(y);
        movingMark_[size_t(v)] = 1;
    }
    if (!moving_.empty()) {
        for (int32_t c = 0; c < mesh_.cellCapacity(); ++c) {
            if (!mesh_.isLive(c)) continue;
            const uint32_t* fan = mesh_.cellFan(c);
            for (int32_t k = 0; k < kCellFanSlot && fan[k] != kRestartIndex; ++k)
                if (movingMark_[fan[k]]) {
                    movingCells_.push_back(c);
                    break;
                }
        }
        stream_.moveVertices(mesh_, movingCells_, [&] {
            for (size_t k = 0; k < moving_.size(); ++k) {
                StreamVertex& sv = mesh_.streamVertex(moving_[k]);
                const float shown = morph_.displayed(sv).y;
                sv.position.y = movingHeights_[k];
                morph_.blendToNewHeight(mesh_, moving_[k], shown);
            }
        });
        for (int32_t v : moving_) movingMark_[size_t(v)] = 0;
    }
    refiner_.heightsChanged(rect, grew);
}

const char* Terrain::setScale(const HeightfieldScale& scale) {
    const HeightfieldScale previous = field_->scale();
    if (const char* error = field_->setScale(scale)) return error;
    if (!hasMesh_) return nullptr;
    if (const char* error = field_->prepare()) {
        field_->setScale(previous); // prepare changed nothing: the terrain stays as it was
        return error;
    }
    if (const char* error = mesh_.reset(*field_, mesh_.embedding(), mesh_.baseStep())) return error;
    attachMesh();
    return nullptr;
}

const char* Terrain::resetMesh(Embedding embedding) {
    if (const char* error = mesh_.reset(*field_, embedding)) return error;
    hasMesh_ = true;
    attachMesh();
    return nullptr;
}

void Terrain::attachMesh() {
    // Every consumer starts from the base mesh; the blend clock starts again.
    refiner_.attach(mesh_, *field_);
    refiner_.setVertexFades(&morph_);
    morph_.resetClock();
    morph_.changedVertices().clear();
    stream_.attach(mesh_);
    ++meshEpoch_;
}

void Terrain::configure(const TerrainSettings& settings) {
    refiner_.settings() = settings.lod;
    morph_.setFrames(settings.morphFrames);
    stream_.setLayout(settings.layout);
    stream_.setNormals(settings.normals);
    compactPools_ = settings.compactPools;
}

UpdateStats Terrain::updateLod() {
    if (!renumbering_.empty()) releasePool(renumbering_);
    morph_.advance(); // the blends' clock (§7): one frame per update, before the merges look at it
    return refiner_.update();
}

void Terrain::syncStream() {
    stream_.sync(mesh_, morph_);
    // Now the stream has applied every change and the refiner is between updates: the tiles
    // past the cap go (their heights fall back like any change), then the heights change.
    if (SampleTiles* tiles = field_->tiles()) {
        residency_.tick();
        if (hasMesh_ && residency_.overCap(*tiles)) residency_.keepWithinCap(*tiles, tilesInUse(), changedHeights_);
    }
    applyHeightChanges();
    if (compactPools_ && mesh_.wantsCompaction()) compact();
}

void Terrain::compact() {
    std::vector<int32_t> cellMap; // a rare event: the mesh shrank by a sixteenth
    mesh_.compact(cellMap, renumbering_);
    refiner_.renumber(cellMap, renumbering_);
    morph_.changedVertices().clear(); // the stream's rewrite uploads every vertex
    stream_.renumbered(mesh_);
    ++renumberings_;
}

int64_t Terrain::refineUniform(int32_t rounds) {
    const int64_t splits = refineUniformly(mesh_, rounds);
    refiner_.restart();
    return splits;
}

bool Terrain::drawnHeightAt(double x, double z, float& height) const {
    return hasMesh_ && hexlod::drawnHeightAt(*field_, mesh_, stream_, morph_, x, z, height);
}

size_t Terrain::memoryBytes() const {
    return mesh_.memoryBytes() + refiner_.memoryBytes() + stream_.memoryBytes() + renumbering_.capacity() * sizeof(int32_t) +
           wants_.memoryBytes() + residency_.memoryBytes() + (moving_.capacity() + movingHeights_.capacity() + movingCells_.capacity()) * 4 + movingMark_.capacity();
}

} // namespace hexlod
