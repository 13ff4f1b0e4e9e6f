// The merge side of the refinement loop (§6): what a merge test judges (the parent a merge
// draws and the halves of the ring hexagons it breaks, §4.6), how a merge happens and carries
// its bounds over (§5.1), at once or once its vertices have faded (§7, pending_merges.h), and
// the coarsening pass in descending level order. See refiner.h.
#include "lod/refiner.h"

#include <algorithm>

namespace hexlod {

// A merge of c draws c's parent, and the outer halves of the joined hexagons in c's ring that
// it breaks: all of them must pass, or the next refine pass would split c again. The parent
// first (parentVerdict), then the halves (halvesVerdict) of a merge that canMerge allows.
CellVerdict Refiner::parentVerdict(int32_t c, double& dist) {
    const CellShape parent = parentShapeOfCell(*mesh_, c);
    return judge(footprintOf(*field_, mesh_->embedding(), parent), parentBound(c, parent), nullptr, true, dist);
}

// The joined hexagons in c's ring that a merge of c breaks, each with the half it leaves.
int32_t Refiner::ringHalves(int32_t c, RingHalf out[6]) const {
    const Hexagon& h = mesh_->cell(c);
    const int32_t first = h.kind == CellKind::Full ? 1 : h.firstVisible;
    const int32_t edges = h.kind == CellKind::Full ? 6 : 3;
    int32_t count = 0;
    for (int32_t i = 0; i < edges; ++i) {
        const int32_t o = h.opposite[wrapSlot(first + i) - 1];
        if (o == kNone) continue;
        const int32_t n = hexIdx(o);
        const Hexagon& ring = mesh_->cell(n);
        if (ring.kind != CellKind::Full || ring.splitCount != 0) continue; // a semi or a boundary cell: removed
        const int32_t k = mesh_->breakDiameterSlot(n);
        const bool facingFirstHalf = wrapSlot(edgeSlot(o) - k + 7) <= 3; // edge slots k, k+1, k+2
        RingHalf& half = out[count++];
        half.ringCell = n;
        half.which = facingFirstHalf ? 1 : 0;
        half.shape.kind = CellKind::Semi;
        half.shape.firstVisible = half.which == 0 ? k : wrapSlot(k + 3);
        half.shape.center = mesh_->cellCenter(n);
        half.shape.step = mesh_->cellStep(n);
    }
    return count;
}

CellVerdict Refiner::halvesVerdict(int32_t c, CellVerdict all, double& dist) {
    RingHalf halves[6];
    const int32_t count = ringHalves(c, halves);
    for (int32_t i = 0; i < count; ++i) {
        const RingHalf& outer = halves[i];
        // As the cache gives it back (also once the half is a cell of its own): a tighter bound
        // here would merge what the next test splits again.
        if (!cache_.hasHalf(outer.ringCell, outer.which))
            cache_.setHalf(outer.ringCell, outer.which, computeCellError(*field_, mesh_->embedding(), pyramid_, outer.shape));
        double halfDist;
        const CellVerdict half = judge(footprintOf(*field_, mesh_->embedding(), outer.shape), cache_.half(outer.ringCell), nullptr, true, halfDist);
        if (!half.pass) {
            dist = halfDist;
            return half;
        }
        // One record for all: the smallest margin, checked with the largest distance (a turn
        // then moves and tilts each centre by at most the record's allowance; see testCell).
        tighten(all, half);
        dist = std::max(dist, halfDist);
    }
    return all;
}

// A merge turns the cell's record back into its parent (§4.6): the parent bound it cached is
// its own bound now (§5.1), and the half its merge test bounded in each broken ring hexagon is
// the own bound of the semi-hexagon that half becomes.
bool Refiner::mergeNow(int32_t c) {
    struct Kept {
        CellShape shape;
        PackedBound bound;
    } kept[7];
    int32_t count = 0;
    if (cache_.hasParent(c)) kept[count++] = {parentShapeOfCell(*mesh_, c), cache_.packedParent(c)};
    RingHalf halves[6];
    const int32_t ring = ringHalves(c, halves);
    for (int32_t i = 0; i < ring; ++i)
        if (cache_.hasHalf(halves[i].ringCell, halves[i].which)) kept[count++] = {halves[i].shape, cache_.packedHalf(halves[i].ringCell)};
    if (!mesh_->merge(c)) return false;
    // The cells the merge changed, from the mesh's log (fresh_ lists a cell once, and it may
    // be there from an earlier merge of this update); only when there is a bound to carry.
    if (count > 0) mergeChanged_.assign(changes_.begin(), changes_.end());
    noteChanges();
    if (count == 0) return true;
    for (int32_t r : mergeChanged_) {
        if (!mesh_->isLive(r)) continue;
        const CellShape shape = shapeOfCell(*mesh_, r);
        for (int32_t k = 0; k < count; ++k)
            if (sameShape(shape, kept[k].shape)) cache_.setPackedOwn(r, kept[k].bound);
    }
    return true;
}

// §7: "If a vertex v is to be removed, inverse blending is triggered by a merge [...], which
// [is] finished when the vertex has faded out." Without geomorphing the merge happens now.
bool Refiner::beginMerge(int32_t c) {
    if (!fades_ || !fades_->enabled()) return mergeNow(c);
    if (!mesh_->canMerge(c)) return false;
    pending_.begin(*mesh_, *fades_, c);
    state_[size_t(c)] |= kPending;
    return false; // nothing changed in the mesh yet
}

void Refiner::callOff(const PendingMerges::Merge& merge) {
    PendingMerges::cancelFades(*mesh_, *fades_, merge);
    if (merge.cell == kNone) return; // its record is gone (renumber)
    state_[size_t(merge.cell)] &= uint8_t(~(kPending | kCancel));
    // Due, and tested again in this update (retestChanged follows advancePendingMerges): an
    // update that called a merge off must not report converged before its cell's test.
    makeDueForRetest(merge.cell);
    queueFresh(merge.cell);
}

// The fading merges: called off when the mesh around them changed or their record's re-test
// found them no longer wanted (they are re-tested only when due, like every cell); merged
// once faded, each merge an operation of the budget.
void Refiner::advancePendingMerges() {
    pending_.keepIf([&](const PendingMerges::Merge& merge) {
        if (merge.cell == kNone || (state_[size_t(merge.cell)] & kCancel) || !pending_.stillFrees(*mesh_, merge)) {
            callOff(merge); // the mesh changed around it, or the view wants the detail back
            return false;
        }
        const bool faded = fades_ == nullptr || !fades_->enabled() || PendingMerges::fadedOut(*mesh_, *fades_, merge);
        if (!faded || (progressed() && outOfBudget())) return true;
        state_[size_t(merge.cell)] &= uint8_t(~(kPending | kCancel));
        if (mergeNow(merge.cell)) ++operations_;
        return false;
    });
}

// §6: merges in descending level order, each when what it makes passes. False when the
// budget stopped it.
bool Refiner::coarsen() {
    std::sort(mergeList_.begin(), mergeList_.end(), [&](int32_t a, int32_t b) {
        const int32_t la = mesh_->isLive(a) ? mesh_->cell(a).level : -1, lb = mesh_->isLive(b) ? mesh_->cell(b).level : -1;
        return la > lb || (la == lb && a < b);
    });
    mergeList_.erase(std::unique(mergeList_.begin(), mergeList_.end()), mergeList_.end());
    size_t k = 0;
    for (; k < mergeList_.size(); ++k) {
        if (progressed() && outOfBudget()) break;
        const int32_t c = mergeList_[k];
        if (!mesh_->isLive(c) || !(state_[size_t(c)] & kWanted)) continue; // changed since
        ++visits_;
        state_[size_t(c)] &= uint8_t(~kWanted);
        if (!mesh_->canMerge(c)) {
            state_[size_t(c)] |= kBlocked;
            continue;
        }
        if (beginMerge(c)) {
            ++operations_;
            retestChanged();
        }
    }
    const bool done = k == mergeList_.size();
    // What the budget left keeps kWanted and its place, for the next update's coarsening (the
    // sweep does not look for it: that was a read of every cell's state in every update).
    mergeList_.erase(mergeList_.begin(), mergeList_.begin() + ptrdiff_t(k));
    return done;
}

} // namespace hexlod
