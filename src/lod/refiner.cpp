// The refinement loop of "Hexagonal LOD for Interactive Terrain Rendering" (Sußner,
// Dachsbacher, Greiner, VMV 2005), §6, with the criteria of §5 (view_criteria.h) and the
// cached refinement data of §5.1. See refiner.h for the order of work and the margins.
#include "lod/refiner.h"
#include "lod/float_rounding.h"
#include "mesh/pool_growth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace hexlod {

void Refiner::attach(HexMesh& mesh, const Heightfield& field) {
    mesh_ = &mesh;
    field_ = &field;
    pyramid_.build(field);
    mesh.setChangeLog(0, &changes_);
    changes_.clear();
    // Every cached bound, record and state belongs to the old mesh; noteChanges grows them again.
    cache_.clear();
    cache_.setHeightRange(field.minHeight(), field.maxHeight());
    releasePool(records_);
    releasePool(state_);
    releasePool(starved_);
    summaries_.release();
    currentTau_ = settings_.tau;
    last_ = {};
    pending_.clear(); // their vertices belong to the old mesh
    // A depth far below any sample spacing: merge tests bound the error at the sphere's
    // nearest depth, this close to the eye at the closest.
    mergeNearest_ = 1e-3 * std::min(field.scale().spacingX, field.scale().spacingY);
    restart();
}

// The farthest point of the field's box (its samples' columns, rows and height range) from the
// eye. Every cell that can fail a test has samples under it, so its bounding box, and its
// sphere, holds a point of that box: a far plane at least this far culls no such cell. A hair
// more covers the rounding of spheres and distances.
double Refiner::farthestData(const glm::dvec3& eye) const {
    const double x1 = double(field_->width() - 1) * field_->scale().spacingX, z1 = double(field_->height() - 1) * field_->scale().spacingY;
    const double scale = settings_.verticalScale;
    const double low = double(field_->minHeight()) * scale, high = double(field_->maxHeight()) * scale;
    double farthest = 0.0;
    if (!settings_.earth.flat()) {
        // On the curved Earth: the far side of the sphere holding the field's drawn image.
        const glm::dvec3 center(0.5 * x1, 0.5 * (low + high), 0.5 * z1);
        const double radius = 0.5 * glm::length(glm::dvec3(x1, high - low, z1));
        const CurvedCell field = curvedCell(settings_.earth, center, radius, 0.5 * std::hypot(x1, z1), low, high);
        farthest = glm::length(field.center - eye) + field.radius;
    } else {
        for (double x : {0.0, x1})
            for (double y : {low, high})
                for (double z : {0.0, z1}) farthest = std::max(farthest, glm::length(glm::dvec3(x, y, z) - eye));
    }
    return farthest * (1.0 + 1e-6) + 1e-3;
}

void Refiner::setView(const View& view) {
    if (haveView_) odometers_.move(view_, view);
    const bool sameShapeOfView = haveView_ && view.tanHalfX == view_.tanHalfX && view.tanHalfY == view_.tanHalfY &&
                                 view.pixelsPerTangent == view_.pixelsPerTangent;
    // Margins of failing merge tests assume a far plane that culls no cell with samples in any
    // view since (one beyond the field: the page's and the command line's are) or, else, far
    // >= kFarShrink * farRef_ (cell_verdict.cpp). Without the first, a camera flying towards the middle
    // of the field would make every cell due each time far shrank by a sixteenth. They do not
    // depend on the near plane (cell_verdict.cpp).
    const bool farCovers = field_ && view.farPlane >= farthestData(view.eye);
    const bool planesMoved = !farCovers && (farCoversData_ || view.farPlane < kFarShrink * farRef_);
    farCoversData_ = farCovers;
    view_ = view;
    planeNormX_ = std::sqrt(1.0 + view.tanHalfX * view.tanHalfX);
    planeNormY_ = std::sqrt(1.0 + view.tanHalfY * view.tanHalfY);
    haveView_ = true;
    if (!sameShapeOfView || planesMoved) invalidateAll();
}

size_t Refiner::memoryBytes() const {
    return cache_.memoryBytes() + records_.capacity() * sizeof(TestRecord) + state_.capacity() + summaries_.memoryBytes() +
           CameraOdometers::memoryBytes() +
           (changes_.capacity() + fresh_.capacity() + looked_.capacity() + mergeList_.capacity() + mergeChanged_.capacity() +
            capChains_.capacity()) *
               sizeof(int32_t) +
           heap_.capacity() * sizeof(Candidate) + pending_.memoryBytes() + pyramid_.memoryBytes();
}

size_t Refiner::liveMemoryBytes() const {
    const size_t cells = size_t(mesh_ ? mesh_->liveCells() : 0);
    return cells * (sizeof(RefinementCache::Entry) + sizeof(TestRecord) + 1) + size_t(double(cells) * SweepSummaries::bytesPerRecord() + 0.5) +
           pending_.liveMemoryBytes() + pyramid_.memoryBytes() + CameraOdometers::memoryBytes();
}

void Refiner::invalidateAll() {
    for (TestRecord& r : records_) r.rho = -1.0f;
    summaries_.readAll();
    farRef_ = view_.farPlane;
}

// The settings that the verdicts depend on; a change makes every cell due.
void Refiner::checkSettings() {
    const RefinerSettings& s = settings_;
    const bool same = settingsChecked_ && s.viewIndependent == checked_.viewIndependent && tau() == checkedTau_ &&
                      s.maxError == checked_.maxError && s.verticalScale == checked_.verticalScale &&
                      s.culling == checked_.culling && s.backfaceCulling == checked_.backfaceCulling && s.earth == checked_.earth;
    if (!same) invalidateAll();
    checked_ = s;
    checkedTau_ = tau();
    settingsChecked_ = true;
}

void Refiner::noteChanges(bool collect) {
    const size_t capacity = size_t(mesh_->cellCapacity());
    if (cache_.size() < capacity) { // grows with the pool
        const size_t room = mesh_->cellPoolRoom();
        cache_.grow(capacity, room);
        reserveLikePool(records_, capacity, room), reserveLikePool(state_, capacity, room);
        records_.resize(capacity);
        state_.resize(capacity, 0);
        if (field_->tiles()) reserveLikePool(starved_, capacity, room), starved_.resize(capacity, 0.0f);
        summaries_.resize(capacity, room);
    }
    if (!starved_.empty())
        for (int32_t c : changes_) starved_[size_t(c)] = 0.0f; // a tiled field's: tested again
    for (int32_t c : changes_) {
        cache_.invalidate(c);
        if (collect) makeDueForRetest(c);
        else makeDue(c);
        state_[size_t(c)] &= uint8_t(kPending | kCancel | kFresh | kLooked); // a pending merge is checked by stillFrees
        if (collect) queueFresh(c);
    }
    changes_.clear();
}

// Queues a cell for retestChanged, once however often it changed.
void Refiner::queueFresh(int32_t c) {
    uint8_t& state = state_[size_t(c)];
    if (state & kFresh) return;
    state |= kFresh;
    fresh_.push_back(c);
}

// Tests the cells the last operations created or changed (they are due), and the blocked
// merge candidates that the change may have unblocked. A merge is blocked by a ring cell that
// cannot be broken (HexMesh::canMerge): one that is not a plain joined hexagon of the same
// level, a neighbour, which changes with the operation that unblocks it; or one that a finer
// semi-hexagon rests its long edge on, two cells away, which changes when that semi-hexagon
// is joined or merged away. A merge test does not depend on the view to find that out, so
// blocked cells culled by a side plane may keep that plane's long margin.
void Refiner::retestChanged() {
    // Each cell around the changes is looked at once (the changed cells are neighbours of
    // each other, and the mesh does not change during this).
    auto firstLook = [&](int32_t n) {
        uint8_t& state = state_[size_t(n)];
        if (state & kLooked) return false;
        state |= kLooked;
        looked_.push_back(n);
        return true;
    };
    auto retestIfUnblocked = [&](int32_t n) {
        if ((state_[size_t(n)] & kBlocked) && firstLook(n) && mesh_->isLive(n) && mesh_->canMerge(n)) testCell(n);
    };
    // A neighbour whose merge test failed on a half of a ring cell: when c is that ring cell
    // (or now one, or no longer), the merge may pass. Its own verdict still holds. (A wanted
    // merge is checked by canMerge before it starts, and the halves it makes are tested.)
    auto retestMergeOf = [&](int32_t n) {
        if ((state_[size_t(n)] & kHalfFailed) && firstLook(n) && mesh_->isLive(n) && records_[size_t(n)].rho >= 0.0f) retest(n);
    };
    for (size_t k = 0; k < fresh_.size(); ++k) {
        const int32_t c = fresh_[k];
        state_[size_t(c)] &= uint8_t(~kFresh);
        if (!mesh_->isLive(c)) continue;
        if (records_[size_t(c)].rho < 0.0f) testCell(c);
        for (int32_t o : mesh_->cell(c).opposite) {
            if (o == kNone) continue;
            const int32_t n = hexIdx(o);
            retestIfUnblocked(n);
            retestMergeOf(n);
            const Hexagon& ring = mesh_->cell(n);
            if (ring.kind != CellKind::Full || ring.splitCount != 0) continue; // not a ring cell a merge breaks
            for (int32_t across : ring.opposite)
                if (across != kNone && hexIdx(across) != c) retestIfUnblocked(hexIdx(across));
        }
    }
    fresh_.clear();
    for (int32_t n : looked_) state_[size_t(n)] &= uint8_t(~kLooked);
    looked_.clear();
}

CellError Refiner::parentBound(int32_t c, const CellShape& parent) {
    if (!cache_.hasParent(c)) cache_.setParent(c, computeCellError(*field_, mesh_->embedding(), pyramid_, parent));
    return cache_.parent(c);
}

CellError Refiner::ownBound(int32_t c) {
    if (!cache_.hasOwn(c)) cache_.setOwn(c, computeCellError(*field_, mesh_->embedding(), pyramid_, shapeOfCell(*mesh_, c)));
    return cache_.own(c);
}

SlopeBox Refiner::ownSlopes(int32_t c, const Footprint& footprint) {
    if (!cache_.hasOwnSlopes(c)) cache_.setOwnSlopes(c, slopesUnder(*field_, mesh_->embedding(), footprint));
    return cache_.ownSlopes(c);
}


namespace {
// A margin as a record keeps it (CameraOdometers::storedMargin; kForever as the largest float).
float recordMargin(double margin) {
    return margin >= kForever ? std::numeric_limits<float>::max() : CameraOdometers::storedMargin(std::max(0.0, margin));
}
} // namespace

// ownMargin: of margin, the own test's (on the same odometer, which runs at least as fast as
// the own test's own odometer: tighten()).
void Refiner::setRecord(int32_t c, double margin, Odometer odometer, double dist, double ownMargin) {
    TestRecord& r = records_[size_t(c)];
    r.stamp = odometers_.stamp();
    r.odometer = uint32_t(odometer);
    r.dist16 = halfBitsUp(roundedUp(dist));
    r.rho = recordMargin(margin);
    r.ownRho16 = halfBitsDown(recordMargin(ownMargin));
    summaries_.set(c, odometer, r.dist(), r.rho);
}

void Refiner::makeDue(int32_t c) {
    records_[size_t(c)].rho = -1.0f;
    summaries_.madeDue(c);
}

// Due, and queued for retestChanged, which runs before the update ends and tests it (or
// finds it free): its test sets the record, which the group's summary takes in (set), or
// fails and makes it due for the sweep (makeDue). So its group's summary still bounds every
// record the sweep must find, and the group is not read again for it. (When every changed
// cell had its group read, the operations of a frame on the Grand Canyon at 50 m a frame,
// some 380 changed cells, had 86 % of all groups read in every sweep.)
void Refiner::makeDueForRetest(int32_t c) { records_[size_t(c)].rho = -1.0f; }

// Re-stamps a record that is not due before its stamp gets too old (CameraOdometers::renewed).
void Refiner::renew(TestRecord& r) const {
    const CameraOdometers::Renewed renewed = odometers_.renewed(r.stamp, Odometer(r.odometer), r.dist(), r.rho);
    const CameraOdometers::Renewed own = odometers_.renewed(r.stamp, Odometer(r.odometer), r.dist(), r.ownRho());
    r.dist16 = halfBitsUp(renewed.dist), r.rho = renewed.rho;
    r.ownRho16 = halfBitsDown(own.rho);
    r.stamp = odometers_.stamp();
}

// Whether a due record's own verdict still holds (its own margin is not used up; the record
// was not made due by a change), and how much of it is left.
bool Refiner::ownHolds(const TestRecord& r, HeldOwn& held) const {
    if (!(r.rho >= 0.0f) || r.ownRho16 == 0) return false;
    const CameraOdometers::Renewed own = odometers_.renewed(r.stamp, Odometer(r.odometer), r.dist(), r.ownRho());
    if (!(own.rho > 0.0f)) return false;
    // A margin kept as forever comes back as the largest 16-bit float (about 3.4e38), still
    // above kForever, which is what testCell and setRecord read as forever.
    held = {double(own.rho), double(own.dist)};
    return true;
}

// Tests a cell again, keeping its own verdict when that still holds. True when it was kept.
bool Refiner::retest(int32_t c) {
    HeldOwn held;
    const bool kept = ownHolds(records_[size_t(c)], held);
    testCell(c, kept ? &held : nullptr);
    return kept;
}

CellVerdict Refiner::judge(const Footprint& f, const CellError& e, const SlopeBox* slopes, bool failMargin, double& dist) {
    ++tested_;
    return judgeCell(verdictContext_, {f, e, slopes, failMargin}, dist);
}

// The view and thresholds the verdicts of this update are made for: none changes during it.
void Refiner::refreshVerdictContext() {
    VerdictContext& v = verdictContext_;
    v.view = &view_;
    v.planeNormX = planeNormX_, v.planeNormY = planeNormY_;
    v.moving = odometers_.moving();
    v.viewIndependent = settings_.viewIndependent;
    v.tau = tau();
    v.maxError = settings_.maxError;
    v.verticalScale = settings_.verticalScale;
    v.culling = settings_.culling;
    v.backfaceCulling = settings_.backfaceCulling;
    v.mergeNearest = mergeNearest_;
    v.farCoversData = farCoversData_;
    v.farRef = farRef_;
    v.earth = settings_.earth;
}

// Whether a step could refine the cell: false at the finest level (the split cannot happen,
// whatever the view), or for a semi-hexagon across from a cell at the finest level.
bool Refiner::canRefine(int32_t c) const {
    const Hexagon& h = mesh_->cell(c);
    if (h.kind != CellKind::Semi) return mesh_->canSplit(c);
    const int32_t across = h.opposite[wrapSlot(h.firstVisible + 3) - 1];
    if (across == kNone || mesh_->isLongEdge(across)) return true;
    return mesh_->canSplit(hexIdx(across));
}

bool Refiner::coarserData(const CellShape& shape, const Footprint& f, float& detail, bool& heldBack) const {
    const SampleTiles& tiles = *field_->tiles();
    const int32_t level = tiles.levelIn(samplesUnder(*field_, f), detail);
    if (level == 0) return false;
    const TileLevel& l = tiles.level(level);
    // Its children's vertices are step / 2 samples apart: finer than the level's samples.
    heldBack = 0.5 * shape.step < std::max(l.scaleX, l.scaleY) * (1.0 - 1e-9);
    return true;
}

// Tests a cell's own bound and, for a merge candidate, its merge; sets its record and state.
void Refiner::testCell(int32_t c, const HeldOwn* held) {
    double dist;
    CellVerdict own;
    // A tiled field: the verdict with the detail still to come is made with the own one.
    const bool tiled = field_->tiles() != nullptr;
    bool coarse = false, heldBack = false;
    CellVerdict withDetail;
    double detailDist = 0.0;
    if (tiled) held = nullptr;
    if (held) {
        // Its own verdict holds for what is left of its margin: a pass (or a failure at the
        // finest level, which is a pass with no margin limit to the rest of this test).
        own.margin = held->margin;
        own.odometer = Odometer(records_[size_t(c)].odometer);
        dist = held->dist;
    } else {
        const Footprint footprint = footprintOf(*field_, mesh_->embedding(), shapeOfCell(*mesh_, c));
        const CellError bound = ownBound(c);
        // The slopes only when the error fails (§5's cone of normals can only rescue a failing
        // cell; a passing one keeps its error margin): a scan of its samples, computed when first needed.
        SlopeBox slopes = cache_.ownSlopes(c);
        own = judge(footprint, bound, &slopes, false, dist);
        if (!own.pass && settings_.backfaceCulling && !cache_.hasOwnSlopes(c)) {
            slopes = ownSlopes(c, footprint);
            if (slopes.known()) own = judge(footprint, bound, &slopes, false, dist);
        }
        float detail = 0.0f;
        if (tiled && coarserData(shapeOfCell(*mesh_, c), footprint, detail, heldBack)) {
            // Its heights come from an overview: the finer samples may add the detail that
            // level shows. When that could fail the cell, it asks for them; when its children
            // would be finer than the overview, it waits for them instead of splitting.
            coarse = true;
            CellError wider = bound;
            wider.error += detail;
            wider.low -= detail, wider.high += detail;
            withDetail = judge(footprint, wider, &slopes, true, detailDist);
        }
        // (One that fails as it is and may split needs nothing more: its children are tested.)
        const bool starved = coarse && !withDetail.pass && (own.pass || heldBack);
        if (tiled) starved_[size_t(c)] = starved ? float(std::max(withDetail.pixels, 1e-6)) : 0.0f;
    }
    uint8_t& state = state_[size_t(c)];
    state &= uint8_t(kPending | kCancel | kFresh | kLooked);
    if (!own.pass && canRefine(c) && !heldBack) {
        state |= kFailing;
        makeDue(c);
        heap_.push_back({float(own.pixels), c});
        std::push_heap(heap_.begin(), heap_.end(), lowerPriority);
        if (state & kPending) state |= kCancel;
        return;
    }
    CellVerdict record = own;
    if (!own.pass) record.margin = kForever; // failing at the finest level: nothing to do, whatever the view
    if (coarse) {
        // Tested again when the verdict with the detail to come may change (or when tiles come:
        // heightsChanged), so the tiles asked for follow the view.
        if (own.pass) tighten(record, withDetail);
        else record = withDetail; // held back
        dist = std::max(dist, detailDist);
    }
    const double ownMargin = record.margin;
    const Hexagon& h = mesh_->cell(c);
    if (h.kind != CellKind::Semi && h.splitCount > 0) {
        // The parent's test before the structural check when its bound is cached: most merge
        // tests fail there, and canMerge reads up to 36 cells around c. A parent bound not
        // cached yet is a scan of its samples: a blocked merge is not worth it.
        const bool pending = state & kPending;
        bool blocked = !pending && !cache_.hasParent(c) && !mesh_->canMerge(c);
        double mergeDist = 0.0;
        CellVerdict merge;
        if (!blocked) {
            merge = parentVerdict(c, mergeDist);
            blocked = merge.pass && !pending && !mesh_->canMerge(c);
            if (merge.pass && !blocked) {
                merge = halvesVerdict(c, merge, mergeDist);
                if (!merge.pass) state |= kHalfFailed;
            }
        }
        if (blocked) {
            state |= kBlocked;
        } else {
            if (merge.pass) {
                if (state & kPending) {
                    // still wanted: it completes once faded
                } else {
                    state |= kWanted;
                    mergeList_.push_back(c);
                }
            } else if (state & kPending) {
                state |= kCancel;
            }
            // One record for both tests: the smaller margin, checked with the larger distance.
            // Not due means (movement on the record's odometer) + (turn, plus kTiltWeight tilt
            // when steady) * (D + travel) < rho for D >= every tested centre's distance at the
            // test: each centre moved less than rho <= its margin, and the up vector tilted by
            // less than tiltAllowed(rho, D) <= tiltAllowed(margin, its distance), as judgeCell()
            // assumed. tighten keeps the odometer that charges the most: a plane's only when
            // every verdict is a cull by that plane.
            tighten(record, merge);
            dist = std::max(dist, mergeDist);
        }
    }
    setRecord(c, record.margin, record.odometer, dist, ownMargin);
}

// One operation towards refining cell c: a split of it (or of what the balance rule needs
// first), or, for a semi-hexagon, the join that the split of the cell across it would make.
// A split keeps the split cell's record as the centre child (§4.1), so the bound it had is its
// parent's now (§5.1: refinement data kept per centre vertex across levels).
// Under a triangle cap, no split starts while the cap is reached, but one that started (a step
// the balance rule needed first was taken) finishes: otherwise a merge that frees triangles
// below the cap is undone by the balance step of a cell that then waits at the cap, and the
// merge is wanted again (under geomorphing, one split and one merge of the same cell every
// update, never converged).
bool Refiner::refineStep(int32_t c) {
    const Hexagon& h = mesh_->cell(c);
    const auto chain = std::find(capChains_.begin(), capChains_.end(), c);
    const bool started = chain != capChains_.end();
    if (settings_.maxTriangles > 0 && mesh_->triangleCount() >= settings_.maxTriangles && !started) return false;
    SplitStep step;
    int32_t target = c; // the cell whose split refines c
    if (h.kind != CellKind::Semi) {
        if (!mesh_->canSplit(c)) return false;
        step = mesh_->firstStepToSplit(c);
    } else {
        const int32_t across = h.opposite[wrapSlot(h.firstVisible + 3) - 1];
        if (across == kNone || mesh_->isLongEdge(across)) {
            if (!mesh_->join(c)) return false;
            if (started) capChains_.erase(chain);
            noteChanges();
            return true;
        }
        target = hexIdx(across);
        if (!mesh_->canSplit(target)) return false;
        step = mesh_->firstStepToSplit(target);
    }
    const bool last = step.kind == SplitStep::Split && step.cell == target; // c's own step: the chain ends
    if (started && last) capChains_.erase(chain);
    else if (!started && !last && settings_.maxTriangles > 0) capChains_.push_back(c);
    PackedBound kept;
    CellShape keptShape;
    const bool keep = step.kind == SplitStep::Split && cache_.hasOwn(step.cell);
    if (keep) {
        kept = cache_.packedOwn(step.cell);
        keptShape = shapeOfCell(*mesh_, step.cell);
    }
    mesh_->applyStep(step);
    noteChanges();
    if (keep && mesh_->isLive(step.cell) && sameShape(parentShapeOfCell(*mesh_, step.cell), keptShape))
        cache_.setPackedParent(step.cell, kept);
    return true;
}

void Refiner::restart() {
    for (const PendingMerges::Merge& merge : pending_.merges()) callOff(merge);
    pending_.clear();
    capChains_.clear();
    sweepCursor_ = 0;
    noteChanges(false);
    fresh_.clear();
    heap_.clear();
    mergeList_.clear();
    std::fill(state_.begin(), state_.end(), uint8_t(0));
    invalidateAll();
}

// Tests the due cells in index order (the check of each compact record first), queueing
// failing cells and wanted merges. One sweep is a full circle over the records, starting where
// the last one stopped; with a time budget it takes at most half of it, so that refining gets
// the rest. False when the budget stopped it (the cursor keeps the place).
//
// The records go by in groups, each passed over when its summary says that none of its
// records can be due (sweep_summaries.h), else read, its due cells found and its summary made
// again. The due cells of a few groups are then tested, each a few places ahead of its test
// asking for the cell's records (a due cell is a few in a hundred, so each test began with
// cache misses on the cell, its fan, its bound and its centre vertex).
bool Refiner::sweep() {
    constexpr int32_t kGroup = SweepSummaries::kGroup, kChunk = 4, kAhead = 4;
    const int32_t end = int32_t(records_.size()), groups = summaries_.groups();
    const double halfBudget = 0.5 * settings_.budgetMs;
    const int32_t first = sweepCursor_ < groups ? sweepCursor_ : 0;
    auto groupAt = [&](int32_t k) { return first + k < groups ? first + k : first + k - groups; };
    int32_t due[kChunk * kGroup];
    SweepSummaries::Maker maker;
    for (int32_t chunk = 0; chunk < groups; chunk += kChunk) {
        if (chunk > 0 && settings_.budgetMs > 0.0 && progressed()) {
            const double ms = frameClockMs() - startMs_;
            if (ms >= halfBudget) {
                sweepCursor_ = groupAt(chunk);
                return false;
            }
        }
        int32_t count = 0;
        for (int32_t k = chunk; k < std::min(groups, chunk + kChunk); ++k) {
            const int32_t g = groupAt(k);
            if (summaries_.canSkip(g, odometers_)) continue;
            maker.start();
            for (int32_t c = g * kGroup; c < std::min(end, (g + 1) * kGroup); ++c) {
                TestRecord& r = records_[size_t(c)];
                const CameraOdometers::Reading reading = odometers_.read(r.stamp, Odometer(r.odometer), r.dist());
                if (reading.used > r.rho) { // CameraOdometers::usedUp (rho < 0: due)
                    due[count++] = c;
                    continue;
                }
                const uint32_t age = odometers_.age(r.stamp);
                maker.add(Odometer(r.odometer), r.rho, r.dist(), age, reading);
                if (age >= CameraOdometers::kHistory / 2) renew(r);
            }
            maker.finish(summaries_, g, odometers_); // the due cells' tests below add their records to it
        }
        for (int32_t i = 0; i < count; ++i) {
            if (i + kAhead < count) {
                mesh_->prefetchCell(due[i + kAhead]);
                cache_.prefetch(due[i + kAhead]);
            }
            const int32_t c = due[i];
            if (!mesh_->isLive(c)) {
                // A free record: parked until an operation reuses it (noteChanges makes it due),
                // so later sweeps do not read the cell pool for it.
                records_[size_t(c)].rho = std::numeric_limits<float>::max();
                continue;
            }
            ++visits_;
            ownKept_ += retest(c) ? 1 : 0;
        }
    }
    sweepCursor_ = first;
    return true;
}

// Refines the failing cells, largest projected error first (as ROAM's split queue does),
// testing what each operation made. False when kRefineShare of the budget is spent: merges
// get the rest, or a fast camera would only ever add triangles.
bool Refiner::drain() {
    while (!heap_.empty()) {
        if (progressed() && outOfBudget(kRefineShare)) return false;
        std::pop_heap(heap_.begin(), heap_.end(), lowerPriority);
        const int32_t c = heap_.back().cell;
        const float pixels = heap_.back().pixels;
        heap_.pop_back();
        if (!mesh_->isLive(c) || !(state_[size_t(c)] & kFailing)) { // stale: changed and re-tested since
            if (!capChains_.empty()) capChains_.erase(std::remove(capChains_.begin(), capChains_.end(), c), capChains_.end());
            continue;
        }
        ++visits_;
        if (!refineStep(c)) {
            // Held back by the triangle cap: it waits (due again at the next update).
            continue;
        }
        ++operations_;
        retestChanged();
        if (mesh_->isLive(c) && (state_[size_t(c)] & kFailing) && records_[size_t(c)].rho < 0.0f) {
            // Not done with c yet (the step was one the balance rule needed first). A second
            // entry for c does no harm: an entry whose cell no longer fails is skipped.
            heap_.push_back({pixels, c});
            std::push_heap(heap_.begin(), heap_.end(), lowerPriority);
        }
    }
    return true;
}

UpdateStats Refiner::update() {
    startMs_ = frameClockMs();
    operations_ = 0;
    tested_ = 0;
    ownKept_ = 0;
    visitsAtStart_ = visits_;
    const OperationCounts before = mesh_->counts();
    bool converged = false;
    noteChanges(false); // changed outside an operation of ours: their records are due
    checkSettings();
    if (odometers_.beginUpdate()) invalidateAll(); // stamps wrapped: no record can be read back
    heap_.clear(); // (merges a budget left wait in mergeList_)
    refreshVerdictContext();
    // One sweep tests what is due; then the work it queued, and what that work makes, until
    // none is left. Converged: the sweep went full circle within this update and every
    // failing test was resolved (refined) and every wanted merge started; fades under way and
    // cells held back by the triangle cap do not count.
    const bool swept = sweep(); // when the budget stopped it, the work it found still goes first
    for (int32_t round = 0; round < kMaxCyclesPerUpdate; ++round) {
        advancePendingMerges();
        retestChanged();
        const bool drained = drain(); // stops at kRefineShare of the budget: merges get the rest
        if (!coarsen() || !drained) break;
        retestChanged();
        if (heap_.empty() && mergeList_.empty()) {
            converged = swept;
            break;
        }
    }
    heap_.clear();
    // Work lists that a large update (the first refinement of a mesh, a jump) grew give it back.
    const size_t room = frameListRoom(size_t(mesh_->liveCells()));
    trimExcess(heap_, room);
    trimExcess(mergeList_, room);
    trimExcess(fresh_, room);
    trimExcess(looked_, room);
    trimExcess(changes_, room);
    last_.operations = operations_;
    last_.splits = int32_t(mesh_->counts().splits - before.splits);
    last_.merges = int32_t(mesh_->counts().merges - before.merges);
    last_.cellsTested = tested_;
    last_.ownVerdictsKept = ownKept_;
    last_.milliseconds = frameClockMs() - startMs_;
    last_.converged = converged;
    adaptTau();
    return last_;
}

} // namespace hexlod
