// The verdict of the refinement criteria (paper §5, view_criteria.h) on one cell bound, and its
// margin: how far the camera may move before the verdict can change. Deferred re-testing
// (refiner.h) keeps a cell's verdict until the camera has used its margin up, so a margin
// must be a bound: the verdict holds for every view within it.
//
// A pure function of its inputs: the bound, the view and the thresholds of one update. The
// refiner (refiner.h) decides what to test and keeps the records; this file decides what a test
// says.
#pragma once

#include "lod/camera_odometers.h"
#include "lod/cell_bounds.h"
#include "lod/view_criteria.h"

namespace hexlod {

/// A margin no camera uses up (a verdict that does not depend on the view).
constexpr double kForever = 1e30;

/// How far the far plane may come closer before every cell is due (cells far away are often
/// near the far plane: a loose factor would leave their merge tests without margins).
constexpr double kFarShrink = 15.0 / 16.0;

/// A verdict of the criteria (§5) for one bound, and how far it holds.
struct CellVerdict {
    bool pass = true;
    double pixels = 0.0; // projected error (0 when culled; metres in view-independent mode)
    double margin = 0.0; // metres of view-space movement of the centre during which it cannot change
    Odometer odometer = Odometer::Travel; // what measures that movement
};

/// Everything a verdict depends on besides the cell, as it stands for one update.
struct VerdictContext {
    const View* view = nullptr;
    double planeNormX = 1.4142135623730951, planeNormY = 1.4142135623730951; // |(1, tanHalf)|: the side planes' normals
    Odometer moving = Odometer::Travel; // what a verdict that is not a cull by a side plane is measured by (CameraOdometers::moving)
    bool viewIndependent = false; // true: maxError metres everywhere; false: tau pixels on screen
    double tau = 1.0;             // pixels
    double maxError = 1.0;        // metres
    double verticalScale = 1.0;
    bool culling = true;          // frustum culling
    bool backfaceCulling = true;  // cone-of-normals culling (when slopes are given)
    double mergeNearest = 1e-9;   // metres: the smallest depth a merge test's bound uses
    bool farCoversData = false;   // the far plane culled no cell with samples in any view since farRef
    double farRef = 0.0;          // metres: the far plane when every cell was last made due
    EarthShape earth;             // the surface the cells are drawn on (earth_shape.h); flat: the plane
};

/// The cell a verdict is asked for: its footprint and cached bound (§5.1), its slopes (null or
/// unknown: no back-face test), and whether a failing verdict needs a margin (merge tests).
struct CellQuestion {
    Footprint footprint;
    CellError bound;
    const SlopeBox* slopes = nullptr;
    bool failMargin = false;
};

/// The verdict on `cell` and its margin (see cell_verdict.cpp for each case). dist: the
/// distance from the eye to the bound's sphere centre, rounded up (0 in view-independent
/// mode), which the margin's allowance for turning is charged at.
CellVerdict judgeCell(const VerdictContext& context, const CellQuestion& cell, double& dist);

/// Two verdicts in one record: the smaller margin, on the odometer both are measured by (any
/// plane's odometer runs behind the travel, so the travel bounds both otherwise).
void tighten(CellVerdict& into, const CellVerdict& other);

} // namespace hexlod
