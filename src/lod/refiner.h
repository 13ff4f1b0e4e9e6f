// Refiner: the interruptible refinement loop of paper §6 over the hexagon mesh, driven by the
// conservative criteria of view_criteria.h (§5) or by a view-independent maximum error.
//
// One update (§6) sweeps the cells in index order and re-tests only the cells that are due
// (below), refines the failing ones largest projected error first (a failing semi-hexagon is
// joined by splitting the cell across its long edge; the balance rule's steps come first),
// then coarsens in descending level order (a cell is merged back when what the merge makes
// passes). Each step is one mesh operation, after which the mesh is consistent; the update
// stops when the time or operation budget is spent and the next update resumes.
//
// Deferred re-testing: each test leaves a margin per cell, the distance the cell's centre may
// move in view space (eye travel plus the turn and tilt of the view times the cell's distance) before
// the test's verdict can change; a compact record per cell (12 bytes, swept in index order)
// says when the camera has used it up. A cell culled by a side plane counts only the eye's
// movement towards that plane's inside (camera_odometers.h). The margins are bounds (see
// cell_verdict.h), so a mesh that passed stays within tau until its cells are due.
//
// The verdicts and their margins come from cell_verdict.h. With geomorphing (§7), a merge
// first fades out the vertices it will free (pending_merges.h) and happens in the update where
// they have faded; it is called off if the mesh or the view no longer allow it.
// Refinement data is cached per cell record (§5.1), recomputed only for cells an operation
// changed, and carried across a split (the split cell's bound is its parent's) and a merge.
//
// The class is implemented in parts: refiner.cpp (the update, the sweep and the test records,
// the tests, the refining steps), refiner_merges.cpp (merge tests, merges and the coarsening),
// refiner_budget.cpp (the time and operation budget, auto tau), refiner_renumber.cpp (after a
// compaction of the mesh) and refiner_achieved_error.cpp (the HUD's achieved error).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "lod/camera_odometers.h"
#include "lod/float_rounding.h"
#include "lod/cell_bounds.h"
#include "lod/cell_verdict.h"
#include "lod/earth_shape.h"
#include "lod/frame_clock.h"
#include "lod/pending_merges.h"
#include "lod/refinement_cache.h"
#include "lod/sweep_summaries.h"
#include "mesh/hex_mesh.h"
#include "field/min_max_pyramid.h"
#include "lod/view_criteria.h"

namespace hexlod {

struct RefinerSettings {
    bool viewIndependent = false; // true: maxError metres everywhere; false: tau pixels on screen
    double tau = 1.0;             // pixels
    double maxError = 1.0;        // metres
    double verticalScale = 1.0;
    double budgetMs = 0.0;        // <= 0: no time limit
    int32_t maxOperations = 0;    // <= 0: no limit
    int32_t maxTriangles = 0;     // <= 0: no cap (a cell failing under the cap waits, but a split that started finishes; the update still converges)
    bool autoTau = false;
    bool culling = true;          // frustum culling
    bool backfaceCulling = true;  // cone-of-normals culling (exact embedding, cells of up to 4096 samples)
    EarthShape earth;             // the surface drawn (earth_shape.h): the bound follows its curvature
};

struct UpdateStats {
    int32_t operations = 0; // refiner steps: splits, joins and merges it performed
    int32_t splits = 0, merges = 0; // mesh splits and merges, forced ones included
    int32_t cellsTested = 0; // criteria evaluations (§5) this update: a cell's own, parent or half bound against the view
    int32_t ownVerdictsKept = 0; // re-tests that kept the cell's own verdict and judged only its merge
    double milliseconds = 0.0;
    bool converged = false; // every due re-test passes and nothing is left to refine or merge (fades may run on)
};

class Refiner {
public:
    /// Attaches to a mesh over `field` (both outlive the refiner's use) and builds the
    /// min/max pyramid (one pass over the samples).
    void attach(HexMesh& mesh, const Heightfield& field);
    /// The fades that merges wait for (§7; their clock is the caller's, ticked once per
    /// update); null: merges happen at once.
    void setVertexFades(VertexFades* fades) { fades_ = fades; }

    RefinerSettings& settings() { return settings_; }
    const RefinerSettings& settings() const { return settings_; }
    const View& view() const { return view_; }
    /// Sets the camera. Eye travel and turn feed the margins; a different frustum shape or
    /// resolution (or near and far planes moved far) makes every cell due.
    void setView(const View& view);
    /// Every cell is due at the next update (after the mesh changed outside the refiner).
    void restart();
    /// Kept for callers that change settings; nothing to do: every update compares the
    /// settings and makes every cell due when one that matters changed.
    void markChanged() {}

    /// The mesh renumbered its cells and vertices (HexMesh::compact): per-cell records, caches,
    /// states, pending merges and queued cells follow them; the sweep resumes at the same cell.
    void renumber(const std::vector<int32_t>& cellMap, const std::vector<int32_t>& vertexMap);

    /// A tiled field's heights changed in `rect` (tiles came or went, field/sample_tiles.h): the
    /// pyramid there is measured again, and every cell whose bounds may read those samples
    /// forgets them and is tested again at the next update. A wider height range packs bounds
    /// in other steps (refinement_cache.h): then every cell forgets.
    void heightsChanged(const SampleRect& rect, bool rangeGrew);
    /// Per cell record of a tiled field: the projected error (pixels; metres in view-independent
    /// mode) of a cell whose heights come from an overview and whose test with the detail still
    /// to come (the detail that level's samples show) fails; 0 for every other cell. The tiles to fetch are where these are
    /// (lod/tile_wants.h). Empty for a field held whole.
    const std::vector<float>& starved() const { return starved_; }

    /// One update (see above). Returns its figures.
    UpdateStats update();
    const UpdateStats& lastUpdate() const { return last_; }
    double currentTau() const { return currentTau_; }
    /// Merges waiting for their vertices to fade out.
    int32_t pendingMerges() const { return pending_.size(); }
    size_t memoryBytes() const;
    /// Of memoryBytes(), what the live cells and pending merges use (pools counted by use, not capacity).
    size_t liveMemoryBytes() const;
    /// The achieved screen error (refiner_achieved_error.cpp): the largest projected error in
    /// pixels over the live cells in view whose bound is cached; -1 in view-independent mode.
    double achievedErrorPixels() const;

private:
    // When a cell is next due: once the camera has used up the margin rho (metres, rounded
    // down) on the record's odometer since the update `stamp`, for a centre at distance dist
    // (rounded up) at the test (CameraOdometers::used). rho < 0: due now.
    // ownRho: the part of rho that the cell's own test gave (a merge candidate's record holds
    // its own test and its merge test): when the merge test's margin runs out first, the
    // re-test keeps what is left of the own verdict and judges the merge only (testCell).
    // Both in 16 bits (float_rounding.h's halfBits), dist rounded up and ownRho down.
    struct TestRecord {
        uint32_t stamp : CameraOdometers::kStampBits;
        uint32_t odometer : 3; // an Odometer
        uint16_t dist16 = 0, ownRho16 = 0;
        float rho;
        TestRecord() : stamp(0), odometer(0), rho(-1.0f) {}
        float dist() const { return fromHalfBits(dist16); }
        float ownRho() const { return fromHalfBits(ownRho16); }
    };
    static_assert(sizeof(TestRecord) == 12, "the bytes per cell (docs/DESIGN.md) count a 12-byte record");
    enum State : uint8_t {
        kFailing = 1,  // its own test failed: waiting for a refining step
        kWanted = 2,   // its merge is wanted (not started yet)
        kBlocked = 4,  // a merge candidate that canMerge refused: tested again when a cell that can unblock it changes
        kPending = 8,  // a merge of this record is fading its vertices out
        kCancel = 16,  // the pending merge is no longer wanted
        kFresh = 32,   // in fresh_, not retested yet (an operation logs a cell more than once)
        kHalfFailed = 64, // its merge failed on a half of a ring cell: tested again when a ring cell changes
        kLooked = 128,    // in looked_: retestChanged has looked at it
    };
    struct Candidate {
        float pixels;
        int32_t cell;
    };
    // Heap order: largest projected error on top; ties by cell index (deterministic).
    static bool lowerPriority(const Candidate& a, const Candidate& b) {
        return a.pixels < b.pixels || (a.pixels == b.pixels && a.cell > b.cell);
    }

    // judgeCell (cell_verdict.h) in this update's context, counted in tested_.
    CellVerdict judge(const Footprint& f, const CellError& e, const SlopeBox* slopes, bool failMargin, double& dist);
    void refreshVerdictContext();
    // The cached bounds (§5.1), computed when not cached; as the cache gives them back.
    CellError parentBound(int32_t cell, const CellShape& parent);
    CellError ownBound(int32_t cell);
    SlopeBox ownSlopes(int32_t cell, const Footprint& footprint); // computed when a test first needs them
    void noteChanges(bool collect = true); // collect: queue the changed cells for retestChanged
    void queueFresh(int32_t cell);
    void retestChanged();
    // An own verdict that still holds at a re-test: what is left of its margin, for a centre
    // now at most dist away (CameraOdometers::renewed).
    struct HeldOwn {
        double margin, dist;
    };
    bool ownHolds(const TestRecord& record, HeldOwn& held) const;
    void testCell(int32_t cell, const HeldOwn* held = nullptr);
    bool retest(int32_t cell); // testCell keeping the own verdict when ownHolds; true when kept
    CellVerdict parentVerdict(int32_t cell, double& dist);
    CellVerdict halvesVerdict(int32_t cell, CellVerdict parent, double& dist);
    // A joined hexagon in a merge candidate's ring that its merge breaks, and the half it leaves.
    struct RingHalf {
        int32_t ringCell;
        int32_t which; // RefinementCache::hasHalf
        CellShape shape;
    };
    int32_t ringHalves(int32_t cell, RingHalf out[6]) const;
    void setRecord(int32_t cell, double margin, Odometer odometer, double dist, double ownMargin);
    void makeDue(int32_t cell); // tested at the next sweep (or by retestChanged)
    void makeDueForRetest(int32_t cell); // queued for retestChanged: its group's summary stays
    void renew(TestRecord& record) const;
    void invalidateAll();
    void checkSettings();
    bool canRefine(int32_t cell) const;
    // A tiled field: whether a cell's heights come from an overview, with that level's detail
    // (metres) under it, and whether its children would be finer than that level (held back).
    bool coarserData(const CellShape& shape, const Footprint& footprint, float& detail, bool& heldBack) const;
    bool refineStep(int32_t cell);   // one operation towards refining the cell; false if none
    bool beginMerge(int32_t cell);   // merges now, or starts fading out (then false)
    bool mergeNow(int32_t cell);     // the merge itself, its parent bound carried over (§5.1)
    void advancePendingMerges();     // completes faded merges, calls off the stale ones
    void callOff(const PendingMerges::Merge& merge);
    bool outOfBudget(double share = 1.0); // share: of the time and operation budgets
    bool sweep();
    bool drain();
    bool coarsen();
    // Every update makes progress before a budget may stop it: an operation, or a few hundred
    // cells tested (the next update resumes after them).
    bool progressed() const { return operations_ > 0 || visits_ - visitsAtStart_ >= kMinVisits; }
    void adaptTau();
    double tau() const { return settings_.autoTau ? currentTau_ : settings_.tau; }

    HexMesh* mesh_ = nullptr;
    const Heightfield* field_ = nullptr;
    MinMaxPyramid pyramid_;
    RefinerSettings settings_;
    View view_;
    double planeNormX_ = std::sqrt(2.0), planeNormY_ = std::sqrt(2.0); // |(1, tanHalf)|: the side planes' normals, per view
    RefinementCache cache_;
    std::vector<TestRecord> records_;
    SweepSummaries summaries_; // of records_, by groups the sweep may pass over
    std::vector<uint8_t> state_;
    std::vector<float> starved_; // see starved(); tiled fields only
    std::vector<int32_t> changes_, fresh_; // the mesh's change log; the changed cells to retest, each once
    std::vector<int32_t> looked_;          // the cells around the changes that retestChanged looked at
    std::vector<int32_t> mergeChanged_;    // mergeNow's copy of the log of one merge
    std::vector<int32_t> capChains_;       // failing cells whose split began under a triangle cap: it may finish (refineStep)
    std::vector<Candidate> heap_;     // failing cells, largest projected error on top
    std::vector<int32_t> mergeList_;  // cells whose merge is wanted (kept across updates when a budget stopped the coarsening)
    VertexFades* fades_ = nullptr;
    PendingMerges pending_; // merges waiting for their vertices to fade out (§7)
    double currentTau_ = 1.0;

    // How far the camera moved and turned, which the records' margins are measured by.
    CameraOdometers odometers_;
    bool haveView_ = false;
    double farRef_ = 0.0;                 // the far plane when every cell was last made due
    double mergeNearest_ = 1e-9;          // the smallest depth a merge test's bound uses (cell_verdict.h)
    bool farCoversData_ = false;           // the far plane culled no cell with samples in any view since farRef_
    double farthestData(const glm::dvec3& eye) const;
    // The settings the records were computed for.
    RefinerSettings checked_;
    double checkedTau_ = 0.0;
    bool settingsChecked_ = false;

    // Where the loop stands, kept across updates: the group of records the sweep goes on from.
    int32_t sweepCursor_ = 0;

    // Per-update state.
    double startMs_ = 0.0; // frameClockMs() when the update began
    int32_t operations_ = 0;
    int32_t unresolved_ = 0; // failing cells left this cycle that a step could still refine
    uint32_t visits_ = 0, visitsAtStart_ = 0;
    static constexpr uint32_t kMinVisits = 256;
    UpdateStats last_;
    int32_t tested_ = 0; // criteria evaluations this update
    VerdictContext verdictContext_; // what judge() passes on: the view and thresholds of this update
    int32_t ownKept_ = 0;        // re-tests this update that kept the own verdict
    static constexpr int32_t kMaxCyclesPerUpdate = 64;
    static constexpr double kRefineShare = 0.8;
};

} // namespace hexlod
