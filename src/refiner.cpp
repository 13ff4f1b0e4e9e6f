#include "refiner.h"

#include <algorithm>

namespace hexlod {

void Refiner::attach(HexMesh& mesh, const Heightfield& field) {
    mesh_ = &mesh;
    field_ = &field;
    pyramid_.build(field);
    mesh.setChangeLog(0, &changes_);
    changes_.clear();
    cache_.assign(cache_.size(), Cached{}); // every cached bound belongs to the old mesh
    currentTau_ = settings_.tau;
    last_ = {};
    pending_.clear(); // their vertices belong to the old mesh
    restart();
}

void Refiner::setView(const View& view) {
    const bool same = view.eye == view_.eye && view.forward == view_.forward && view.up == view_.up &&
                      view.tanHalfX == view_.tanHalfX && view.tanHalfY == view_.tanHalfY &&
                      view.pixelsPerTangent == view_.pixelsPerTangent && view.nearPlane == view_.nearPlane &&
                      view.farPlane == view_.farPlane;
    view_ = view;
    if (!same) markChanged();
}

size_t Refiner::memoryBytes() const {
    return cache_.capacity() * sizeof(Cached) + (changes_.capacity() + freedScratch_.capacity()) * sizeof(int32_t) +
           pending_.capacity() * sizeof(PendingMerge) + pyramid_.memoryBytes();
}

size_t Refiner::liveMemoryBytes() const {
    return size_t(mesh_ ? mesh_->liveCells() : 0) * sizeof(Cached) + pending_.size() * sizeof(PendingMerge) + pyramid_.memoryBytes();
}

void Refiner::noteChanges() {
    if (cache_.size() < size_t(mesh_->cellCapacity())) cache_.resize(size_t(mesh_->cellCapacity())); // grows geometrically
    for (int32_t c : changes_) cache_[size_t(c)].valid = 0;
    changes_.clear();
}

const CellError& Refiner::cachedError(int32_t c, uint8_t bit, CellError& slot, const CellShape& shape) {
    Cached& cached = cache_[size_t(c)];
    if (!(cached.valid & bit)) {
        slot = computeCellError(*field_, mesh_->embedding(), pyramid_, shape);
        cached.valid |= bit;
    }
    return slot;
}

bool Refiner::fails(const CellShape& shape, const CellError& e) const {
    if (settings_.viewIndependent) return ++tested_, e.error > settings_.maxError;
    return fails(footprintOf(*field_, mesh_->embedding(), shape), e);
}

bool Refiner::fails(const Footprint& f, const CellError& e, const SlopeBox* slopes) const {
    ++tested_;
    if (settings_.viewIndependent) return e.error > settings_.maxError;
    glm::dvec3 center;
    double radius;
    boundingSphere(f, e, settings_.verticalScale, center, radius);
    if (settings_.culling && outsideFrustum(view_, center, radius)) return false;
    if (settings_.backfaceCulling && slopes && backFacing(view_, center, radius, *slopes, settings_.verticalScale)) return false;
    const double tau = settings_.autoTau ? currentTau_ : settings_.tau;
    return projectedErrorPixels(view_, center, radius, double(e.error) * settings_.verticalScale) > tau;
}

bool Refiner::ownFails(int32_t c) {
    Cached& cached = cache_[size_t(c)];
    if (!(cached.valid & 1)) {
        const CellShape shape = shapeOfCell(*mesh_, c);
        cached.own = computeCellError(*field_, mesh_->embedding(), pyramid_, shape);
        cached.ownFootprint = footprintOf(*field_, mesh_->embedding(), shape);
        cached.ownSlopes = slopesUnder(*field_, mesh_->embedding(), cached.ownFootprint);
        cached.valid |= 1;
    }
    return fails(cached.ownFootprint, cached.own, &cached.ownSlopes);
}

bool Refiner::outOfBudget() {
    if (settings_.maxOperations > 0 && operations_ >= settings_.maxOperations) return true;
    // Reading the clock costs more than testing a cell: look at it every 32 visits.
    if (settings_.budgetMs > 0.0 && (visits_ & 31) == 0) {
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
        if (ms >= settings_.budgetMs) return true;
    }
    return false;
}

// One operation towards refining cell c: a split of it (or of what the balance rule needs
// first), or, for a semi-hexagon, the join that the split of the cell across it would make.
bool Refiner::refineStep(int32_t c) {
    const Hexagon& h = mesh_->cell(c);
    if (settings_.maxTriangles > 0 && mesh_->triangleCount() >= settings_.maxTriangles) return false;
    if (h.kind != CellKind::Semi) {
        if (!mesh_->canSplit(c)) return false;
        mesh_->applyStep(mesh_->firstStepToSplit(c));
        return true;
    }
    const int32_t across = h.opposite[wrapSlot(h.firstVisible + 3) - 1];
    if (across == kNone || mesh_->isLongEdge(across)) return mesh_->join(c);
    const int32_t other = hexIdx(across);
    if (!mesh_->canSplit(other)) return false;
    mesh_->applyStep(mesh_->firstStepToSplit(other));
    return true;
}

// A merge of c draws c's parent, and the outer halves of the joined hexagons in c's ring that
// it breaks: all of them must pass, or the next refine pass would split c again.
bool Refiner::mergeWanted(int32_t c) {
    const CellShape parent = parentShapeOfCell(*mesh_, c);
    if (fails(parent, cachedError(c, 2, cache_[size_t(c)].parent, parent))) return false;
    const Hexagon& h = mesh_->cell(c);
    const int32_t first = h.kind == CellKind::Full ? 1 : h.firstVisible;
    const int32_t edges = h.kind == CellKind::Full ? 6 : 3;
    for (int32_t i = 0; i < edges; ++i) {
        const int32_t o = h.opposite[wrapSlot(first + i) - 1];
        if (o == kNone) continue;
        const int32_t n = hexIdx(o);
        const Hexagon& ring = mesh_->cell(n);
        if (ring.kind != CellKind::Full || ring.splitCount != 0) continue; // a semi or a boundary cell: removed
        const int32_t k = mesh_->breakDiameterSlot(n);
        const bool facingFirstHalf = wrapSlot(edgeSlot(o) - k + 7) <= 3; // edge slots k, k+1, k+2
        const int32_t outerHalf = facingFirstHalf ? 1 : 0;
        CellShape outer;
        outer.kind = CellKind::Semi;
        outer.firstVisible = outerHalf == 0 ? k : wrapSlot(k + 3);
        outer.center = mesh_->cellCenter(n);
        outer.step = mesh_->cellStep(n);
        if (fails(outer, cachedError(n, uint8_t(4 << outerHalf), cache_[size_t(n)].half[outerHalf], outer))) return false;
    }
    return true;
}

// §7: "If a vertex v is to be removed, inverse blending is triggered by a merge [...], which
// [is] finished when the vertex has faded out." Without geomorphing the merge happens now.
bool Refiner::beginMerge(int32_t c) {
    if (!morph_ || !morph_->enabled()) return mesh_->merge(c);
    if (!mesh_->canMerge(c)) return false;
    PendingMerge merge{c, 0, {}};
    freedScratch_.clear();
    mesh_->verticesFreedByMerge(c, freedScratch_);
    for (int32_t v : freedScratch_) {
        merge.vertices[merge.count++] = v;
        morph_->blendOut(*mesh_, v);
    }
    pending_.push_back(merge);
    cache_[size_t(c)].pendingMerge = 1;
    return false; // nothing changed in the mesh yet
}

// Whether the merge would still free exactly the vertices that are fading out.
bool Refiner::stillFrees(const PendingMerge& merge) {
    if (!mesh_->canMerge(merge.cell)) return false;
    freedScratch_.clear();
    mesh_->verticesFreedByMerge(merge.cell, freedScratch_);
    return std::equal(freedScratch_.begin(), freedScratch_.end(), merge.vertices, merge.vertices + merge.count);
}

void Refiner::callOff(const PendingMerge& merge) {
    for (int32_t i = 0; i < merge.count; ++i)
        if (mesh_->isVertexLive(merge.vertices[i])) morph_->cancelBlendOut(*mesh_, merge.vertices[i]);
    cache_[size_t(merge.cell)].pendingMerge = 0;
}

void Refiner::advancePendingMerges() {
    size_t kept = 0;
    for (size_t i = 0; i < pending_.size(); ++i) {
        const PendingMerge merge = pending_[i];
        if (!stillFrees(merge) || !mergeWanted(merge.cell)) {
            callOff(merge); // the mesh changed around it, or the view wants the detail back
            continue;
        }
        bool faded = morph_ == nullptr || !morph_->enabled();
        if (!faded) {
            faded = true;
            for (int32_t k = 0; k < merge.count; ++k) {
                const StreamVertex& v = mesh_->streamVertex(merge.vertices[k]);
                if (!morph_->blendingOut(v)) morph_->blendOut(*mesh_, merge.vertices[k]); // reversed by a called-off merge
                faded = faded && morph_->fadedOut(v);
            }
        }
        if (!faded) {
            pending_[kept++] = merge;
            continue;
        }
        cache_[size_t(merge.cell)].pendingMerge = 0;
        mesh_->merge(merge.cell);
        ++operations_;
        ++operationsThisCycle_;
        noteChanges();
    }
    pending_.resize(kept);
}

void Refiner::adaptTau() {
    if (settings_.viewIndependent || !settings_.autoTau) {
        currentTau_ = settings_.tau;
        return;
    }
    const bool overCap = settings_.maxTriangles > 0 && mesh_->triangleCount() >= settings_.maxTriangles;
    const bool overTime = settings_.budgetMs > 0.0 && last_.milliseconds >= settings_.budgetMs && !last_.converged;
    if (overCap || overTime) currentTau_ = std::min(currentTau_ * 1.1, settings_.tau * 64.0);
    else if (last_.converged) currentTau_ = std::max(currentTau_ / 1.05, settings_.tau);
}

// Every update makes progress before a budget may stop it: an operation, or a few hundred
// cells tested (enough to get through a coarse mesh; the next update resumes after them).
bool Refiner::progressed() const { return operations_ > 0 || visits_ - visitsAtStart_ >= kMinVisits; }

int32_t Refiner::resumeCell() const {
    // The cell where the last update stopped, unless an outside call changed the mesh since.
    if (cursorCell_ != kNone && mesh_->isLive(cursorCell_) && mesh_->cell(cursorCell_).level == cursorLevel_) return cursorCell_;
    return mesh_->firstOfLevel(cursorLevel_);
}

void Refiner::restart() {
    for (const PendingMerge& merge : pending_) callOff(merge);
    pending_.clear();
    phase_ = Phase::Refine;
    cursorLevel_ = 0;
    cursorCell_ = kNone;
    operationsThisCycle_ = 0;
    cycleChanged_ = false;
    noteChanges();
}

// Walks the level lists from the cursor (ascending in the refine pass, descending in the
// coarsen pass), applying `step` to each cell; returns false when the budget stopped it, with
// the cursor on the cell to resume at.
template <typename Step>
bool Refiner::walkLevels(int32_t lastLevel, int32_t direction, Step&& step) {
    for (; cursorLevel_ * direction <= lastLevel * direction; cursorLevel_ += direction, cursorCell_ = kNone) {
        int32_t c = resumeCell();
        while (c != kNone) {
            ++visits_;
            if (progressed() && outOfBudget()) {
                cursorCell_ = c;
                return false;
            }
            int32_t next = mesh_->nextInLevel(c);
            if (step(c)) {
                ++operations_;
                ++operationsThisCycle_;
                noteChanges();
                // An operation may have moved or freed the next cell: start the level again.
                if (!mesh_->isLive(next) || mesh_->cell(next).level != cursorLevel_) next = mesh_->firstOfLevel(cursorLevel_);
                if (mesh_->isLive(c) && mesh_->cell(c).level == cursorLevel_) next = c; // not done with c yet
            }
            c = next;
        }
    }
    return true;
}

UpdateStats Refiner::update() {
    start_ = std::chrono::steady_clock::now();
    operations_ = 0;
    tested_ = 0;
    visitsAtStart_ = visits_;
    const OperationCounts before = mesh_->counts();
    bool converged = false;
    noteChanges();
    if (morph_) morph_->advance(); // one frame per update
    advancePendingMerges();
    // Consistent criteria converge in a few cycles; the cap only guarantees the update ends.
    for (int32_t cycle = 0; cycle < kMaxCyclesPerUpdate && !converged && !(progressed() && outOfBudget()); ++cycle) {
        if (phase_ == Phase::Refine) {
            // §6: levels in ascending order; cells a split creates land in finer lists and are
            // visited later in the same pass.
            if (!walkLevels(mesh_->maxLevel(), +1, [&](int32_t c) { return ownFails(c) && refineStep(c); })) break;
            phase_ = Phase::Coarsen;
            cursorLevel_ = mesh_->maxLevel();
            cursorCell_ = kNone;
        } else {
            // §6: levels in descending order; a cell is merged when what the merge makes passes.
            const bool done = walkLevels(2, -1, [&](int32_t c) {
                const Hexagon& h = mesh_->cell(c);
                return h.kind != CellKind::Semi && h.splitCount > 0 && !cache_[size_t(c)].pendingMerge && mergeWanted(c) &&
                       beginMerge(c);
            });
            if (!done) break;
            // A whole cycle without an operation: converged.
            const bool quiet = operationsThisCycle_ == 0 && !cycleChanged_;
            converged = quiet && pending_.empty();
            operationsThisCycle_ = 0;
            cycleChanged_ = false;
            phase_ = Phase::Refine;
            cursorLevel_ = 0;
            cursorCell_ = kNone;
            if (quiet) break; // only fades are left, and they need frames to pass
        }
    }
    last_.operations = operations_;
    last_.splits = int32_t(mesh_->counts().splits - before.splits);
    last_.merges = int32_t(mesh_->counts().merges - before.merges);
    last_.cellsTested = tested_;
    last_.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    last_.converged = converged;
    adaptTau();
    return last_;
}

} // namespace hexlod
