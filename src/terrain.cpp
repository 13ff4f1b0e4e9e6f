// The terrain facade: the wiring of paper §4 (mesh), §5-§6 (refiner) and §7 (blends, stream)
// in one place; see terrain.h.
#include "terrain.h"

#include <new>
#include <vector>

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
    // Now the stream has applied every change and the refiner is between updates.
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
    return mesh_.memoryBytes() + refiner_.memoryBytes() + stream_.memoryBytes() + renumbering_.capacity() * sizeof(int32_t);
}

} // namespace hexlod
