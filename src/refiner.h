// Refiner: the interruptible refinement loop of paper §6 over the hexagon mesh, driven by the
// conservative criteria of view_criteria.h (§5) or by a view-independent maximum error.
//
// One update refines in ascending level order (every cell whose bound fails is split; a
// failing semi-hexagon is joined by splitting the cell across its long edge), then coarsens
// in descending level order (a cell is merged back when the cell the merge would make passes).
// Each step is one mesh operation, after which the mesh is consistent; the update stops when
// the time or operation budget is spent and the next update resumes where it stopped.
// With geomorphing (§7), a merge first fades out the vertices it will free and happens in the
// update where they have faded; it is called off if the mesh or the view no longer allow it.
// Refinement data is cached per cell record (§5.1) and recomputed only for cells an
// operation changed.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "cell_bounds.h"
#include "geomorph.h"
#include "hex_mesh.h"
#include "min_max_pyramid.h"
#include "view_criteria.h"

namespace hexlod {

struct RefinerSettings {
    bool viewIndependent = false; // true: maxError metres everywhere; false: tau pixels on screen
    double tau = 1.0;             // pixels
    double maxError = 1.0;        // metres
    double verticalScale = 1.0;
    double budgetMs = 0.0;        // <= 0: no time limit
    int32_t maxOperations = 0;    // <= 0: no limit
    int32_t maxTriangles = 0;     // <= 0: no cap
    bool autoTau = false;
    bool culling = true;          // frustum culling
    bool backfaceCulling = true;  // cone-of-normals culling (exact embedding, cells of up to 4096 samples)
};

struct UpdateStats {
    int32_t operations = 0; // refiner steps: splits, joins and merges it performed
    int32_t splits = 0, merges = 0; // mesh splits and merges, forced ones included
    int32_t cellsTested = 0; // criteria evaluations (§5) this update: a cell's own, parent or half bound against the view
    double milliseconds = 0.0;
    bool converged = false;
};

class Refiner {
public:
    /// Attaches to a mesh over `field` (both outlive the refiner's use) and builds the
    /// min/max pyramid (one pass over the samples).
    void attach(HexMesh& mesh, const Heightfield& field);
    /// The blends to drive (their clock ticks once per update); null: merges happen at once.
    void setGeomorph(Geomorph* morph) { morph_ = morph; }

    RefinerSettings& settings() { return settings_; }
    const RefinerSettings& settings() const { return settings_; }
    const View& view() const { return view_; }
    /// Sets the camera; a different one marks the cycle under way as changed (see markChanged).
    void setView(const View& view);
    /// Start the next update with a fresh cycle (after the mesh changed outside the refiner).
    void restart();
    /// The camera or a setting changed: the cycle under way cannot prove convergence, but the
    /// loop resumes where it stopped, so no region starves under a moving camera.
    void markChanged() { cycleChanged_ = true; }

    /// One update (see above). Returns its figures.
    UpdateStats update();
    const UpdateStats& lastUpdate() const { return last_; }
    double currentTau() const { return currentTau_; }
    /// Merges waiting for their vertices to fade out.
    int32_t pendingMerges() const { return int32_t(pending_.size()); }
    size_t memoryBytes() const;
    /// Of memoryBytes(), what the live cells and pending merges use (pools counted by use, not capacity).
    size_t liveMemoryBytes() const;
    /// The achieved screen error (refiner_achieved_error.cpp): the largest projected error in
    /// pixels over the live cells in view whose bound is cached; -1 in view-independent mode.
    double achievedErrorPixels() const;

private:
    enum class Phase { Refine, Coarsen };
    // §5.1: refinement data cached per cell record: its own, its parent's (what a merge
    // makes) and, for a joined hexagon, its two halves' (what a break makes).
    struct Cached {
        CellError own;
        Footprint ownFootprint; // kept with `own`: every update tests every cell against it
        SlopeBox ownSlopes;
        CellError parent, half[2];
        uint8_t valid = 0; // bits: 1 own, 2 parent, 4 first half, 8 second half
        uint8_t pendingMerge = 0; // a merge of this record is fading its vertices out
    };
    // A merge started under geomorphing: the vertices it frees, fading out (§7).
    struct PendingMerge {
        int32_t cell;
        int32_t count;
        int32_t vertices[12]; // six corners and up to six centres of the ring cells it breaks
    };

    bool fails(const CellShape& shape, const CellError& e) const;
    bool fails(const Footprint& f, const CellError& e, const SlopeBox* slopes = nullptr) const;
    const CellError& cachedError(int32_t cell, uint8_t bit, CellError& slot, const CellShape& shape);
    void noteChanges();
    bool refineStep(int32_t cell);   // one operation towards refining the cell; false if none
    bool mergeWanted(int32_t cell);  // the merge makes nothing that fails
    bool beginMerge(int32_t cell);   // merges now, or starts fading out (then false)
    void advancePendingMerges();     // completes faded merges, calls off the stale ones
    void callOff(const PendingMerge& merge);
    bool stillFrees(const PendingMerge& merge);
    bool ownFails(int32_t cell);
    bool outOfBudget();
    template <typename Step>
    bool walkLevels(int32_t lastLevel, int32_t direction, Step&& step);
    bool progressed() const;
    int32_t resumeCell() const;
    void adaptTau();

    HexMesh* mesh_ = nullptr;
    const Heightfield* field_ = nullptr;
    MinMaxPyramid pyramid_;
    RefinerSettings settings_;
    View view_;
    std::vector<Cached> cache_;
    std::vector<int32_t> changes_;
    Geomorph* morph_ = nullptr;
    std::vector<PendingMerge> pending_;
    std::vector<int32_t> freedScratch_;
    double currentTau_ = 1.0;

    // Where the loop stands, kept across updates.
    Phase phase_ = Phase::Refine;
    int32_t cursorLevel_ = 0;
    int32_t cursorCell_ = kNone;
    int32_t operationsThisCycle_ = 0;
    bool cycleChanged_ = false;

    // Per-update state.
    std::chrono::steady_clock::time_point start_;
    int32_t operations_ = 0;
    uint32_t visits_ = 0, visitsAtStart_ = 0;
    static constexpr uint32_t kMinVisits = 256;
    UpdateStats last_;
    mutable int32_t tested_ = 0; // criteria evaluations this update
    static constexpr int32_t kMaxCyclesPerUpdate = 256;
};

} // namespace hexlod
