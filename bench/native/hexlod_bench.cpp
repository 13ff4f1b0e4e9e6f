// hexlod_bench: native figures of the core on a raw float32 height field. It prints figures;
// it is not a test.
//
//   hexlod_bench FILE.f32 WIDTH HEIGHT [SPACING_X_M SPACING_Y_M]
//   hexlod_bench FILE.f32 WIDTH HEIGHT SPACING_X_M SPACING_Y_M --flight CAMERAS.txt
//                [--tau PX] [--budget-ms MS] [--budget-ops N] [--viewport WxH] [--tan-half-fov T]
//                [--morph-frames N] [--start-converged] [--measure-error] [--no-backface] [--no-normals] [--floor]
//                [--viewer-planes] [--verbose]
//
// Without --flight: for both lattice embeddings (paper §4.7), the time to refine uniformly to
// the finest level, the triangles and bytes per triangle of the mesh structures, the time to
// write the fan stream, and the error against the original samples at full refinement.
// With --flight: replays a camera path (one line per frame: eye x y z, target x y z, metres)
// through the refiner (exact embedding) and the fan stream, as `hexlod bench` does in
// WebAssembly, and prints the per-frame update figures, for the WASM/native ratio.
// --start-converged refines for the first camera without a budget before the flight starts (as
// `hexlod bench` does). --measure-error bounds, after each frame's update, the largest screen
// error of the drawn mesh: the §5 bound of every live cell recomputed from the samples
// (independent of the refiner's caches), culled cells left out; frames within tau count.
// --floor also times, per frame, only what any update must do for the operations the refiner
// performed: the operations themselves on a copy of the mesh and the bounds of the new cells
// (update_floor.h), in ms per million triangles, beside the update's own figure.
// The near and far planes are those of `hexlod bench` (lib/cli_common.js); --viewer-planes
// uses the page's fly camera's instead (web/cameras/clip_planes.js).
#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <time.h>

#include <glm/geometric.hpp>

#include "bench_clock.h"
#include "update_floor.h"

#include "diagnostics/error_evaluator.h"
#include "stream/fan_stream.h"
#include "stream/geomorph.h"
#include "diagnostics/popping_meter.h"
#include "field/heightfield.h"
#include "mesh/hex_mesh.h"
#include "mesh/hex_mesh_refine.h"
#include "field/min_max_pyramid.h"
#include "lod/refiner.h"
#include "terrain.h"

namespace {

using hexlod::bench::msSince;

int fail(const char* what, const char* detail) {
    std::fprintf(stderr, "hexlod_bench: %s%s\n", what, detail ? detail : "");
    return 1;
}

// A terrain (the facade the C ABI drives) over a raw float32 field, prepared; null (after
// printing why) on failure.
std::unique_ptr<hexlod::Terrain> loadRawTerrain(const char* path, int32_t width, int32_t height,
                                                const hexlod::HeightfieldScale& scale) {
    const char* error = nullptr;
    auto terrain = hexlod::Terrain::create(width, height, hexlod::SampleType::F32, &error);
    if (!terrain) return fail(error, nullptr), nullptr;
    hexlod::Heightfield& field = terrain->field();
    FILE* file = std::fopen(path, "rb");
    if (!file) return fail("cannot open ", path), nullptr;
    const size_t got = std::fread(field.samples(), 4, field.sampleCount(), file);
    std::fclose(file);
    if (got != field.sampleCount()) return fail("too few samples in ", path), nullptr;
    if ((error = terrain->setScale(scale)) || (error = terrain->prepare())) return fail(error, nullptr), nullptr;
    return terrain;
}

// CPU time of this thread in milliseconds: on a shared machine, time slices lost to other
// processes do not count (wall-clock figures there vary tenfold for the same work).
double threadCpuMs() {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    return values[std::min(values.size() - 1, size_t(p * double(values.size() - 1) + 0.5))];
}

// The largest screen error (pixels) of the drawn mesh for a view: the conservative bound of
// view_criteria.h over every live cell, recomputed from the samples; cells outside the frustum
// or back-facing (as the settings cull them) do not count.
double drawnMeshErrorPx(const hexlod::HexMesh& mesh, const hexlod::Heightfield& field, const hexlod::MinMaxPyramid& pyramid,
                        const hexlod::View& view, const hexlod::RefinerSettings& s) {
    double worst = 0.0;
    for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
        if (!mesh.isLive(c)) continue;
        const hexlod::CellShape shape = hexlod::shapeOfCell(mesh, c);
        const hexlod::CellError e = hexlod::computeCellError(field, mesh.embedding(), pyramid, shape);
        const hexlod::Footprint f = hexlod::footprintOf(field, mesh.embedding(), shape);
        glm::dvec3 center;
        double radius;
        hexlod::boundingSphere(f, e, s.verticalScale, center, radius);
        if (s.culling && hexlod::outsideFrustum(view, center, radius)) continue;
        const double px = hexlod::projectedErrorPixels(view, center, radius, double(e.error) * s.verticalScale);
        if (px <= worst) continue;
        if (s.backfaceCulling && hexlod::backFaces(view, center, radius, hexlod::slopesUnder(field, mesh.embedding(), f), s.verticalScale).backFacing)
            continue;
        worst = px;
    }
    return worst;
}

// Replays a camera path; prints p50 / p95 of update and stream times and the mesh figures.
int flight(hexlod::Terrain& terrain, int argc, char** argv) {
    const hexlod::Heightfield& field = terrain.field();
    const char* path = nullptr;
    double tau = 1.0, budgetMs = 0.0, tanHalfFov = 0.57735026918962573, width = 1920, height = 1080;
    int32_t budgetOps = 0, morphFrames = 0;
    bool startConverged = false, measureError = false, backface = true, verbose = false, normals = true, measureFloor = false,
         viewerPlanes = false;
    for (int k = 6; k < argc; ++k) {
        const std::string flag = argv[k];
        if (flag == "--verbose" || flag == "--floor") {
            (flag == "--verbose" ? verbose : measureFloor) = true;
            continue;
        }
        if (flag == "--no-normals") { // as the viewer runs while it lights from the field's normals
            normals = false;
            continue;
        }
        if (flag == "--viewer-planes") {
            viewerPlanes = true;
            continue;
        }
        if (flag == "--start-converged" || flag == "--measure-error" || flag == "--no-backface") {
            (flag == "--start-converged" ? startConverged : flag == "--measure-error" ? measureError : backface) = flag != "--no-backface";
            continue;
        }
        const char* value = k + 1 < argc ? argv[k + 1] : nullptr;
        if (!value) return fail("missing value after ", argv[k]);
        ++k;
        if (flag == "--flight") path = value;
        else if (flag == "--tau") tau = std::atof(value);
        else if (flag == "--budget-ms") budgetMs = std::atof(value);
        else if (flag == "--budget-ops") budgetOps = std::atoi(value);
        else if (flag == "--morph-frames") morphFrames = std::atoi(value);
        else if (flag == "--tan-half-fov") tanHalfFov = std::atof(value);
        else if (flag == "--viewport") {
            if (std::sscanf(value, "%lfx%lf", &width, &height) != 2) return fail("bad --viewport ", value);
        } else return fail("unknown option ", argv[k - 1]);
    }
    if (!path) return fail("--flight needs a camera file", nullptr);
    FILE* file = std::fopen(path, "r");
    if (!file) return fail("cannot open ", path);
    std::vector<std::array<double, 6>> cameras;
    std::array<double, 6> c;
    while (std::fscanf(file, "%lf %lf %lf %lf %lf %lf", &c[0], &c[1], &c[2], &c[3], &c[4], &c[5]) == 6) cameras.push_back(c);
    std::fclose(file);
    if (cameras.empty()) return fail("no cameras in ", path);

    if (const char* error = terrain.resetMesh(hexlod::Embedding::Exact)) return fail(error, nullptr);
    const hexlod::HexMesh& mesh = terrain.mesh();
    const hexlod::Refiner& refiner = terrain.refiner();
    const hexlod::FanStream& stream = terrain.stream();
    const hexlod::Geomorph& morph = terrain.morph();
    hexlod::TerrainSettings settings = terrain.settings();
    settings.lod.tau = tau;
    settings.lod.backfaceCulling = backface;
    settings.normals = normals;
    terrain.configure(settings);
    // Near and far planes as `hexlod bench` sets them (lib/cli_common.js, cameraFor): far ten
    // times the farthest corner of the field's box.
    const double extentX = double(field.width() - 1) * field.scale().spacingX, extentZ = double(field.height() - 1) * field.scale().spacingY;
    // With --viewer-planes, the planes the page's fly camera sets (web/cameras/clip_planes.js):
    // near at 0.3 times the height above the ground, far just past the farthest corner.
    auto viewOf = [&](const std::array<double, 6>& cam, hexlod::View& view) {
        const glm::dvec3 eye(cam[0], cam[1], cam[2]), target(cam[3], cam[4], cam[5]);
        const double distance = glm::length(target - eye);
        double farthest = 0.0;
        for (double x : {0.0, extentX})
            for (double z : {0.0, extentZ})
                for (double y : {double(field.minHeight()), double(field.maxHeight())})
                    farthest = std::max(farthest, glm::length(glm::dvec3(x, y, z) - eye));
        if (viewerPlanes) {
            const bool inside = eye.x >= 0.0 && eye.z >= 0.0 && eye.x <= extentX && eye.z <= extentZ;
            const double clearance = eye.y - (inside ? double(field.heightAtPosition(eye.x, eye.z)) : double(field.maxHeight()));
            const double far = farthest * 1.05 + 1.0;
            const double near = std::max(far / 1e6, 0.3 * std::max(clearance, 0.0));
            return hexlod::makeView(eye, target, {0, 1, 0}, tanHalfFov, width / height, height, near, std::max(far, near * 10.0), view);
        }
        return hexlod::makeView(eye, target, {0, 1, 0}, tanHalfFov, width / height, height, std::max(0.1, distance / 1e4),
                                10.0 * std::max({farthest, distance, 1.0}), view);
    };
    if (startConverged) {
        hexlod::View view;
        if (!viewOf(cameras[0], view)) return fail("degenerate camera in ", path);
        terrain.setView(view);
        for (int32_t n = 0; n < 1000 && !terrain.updateLod().converged; ++n) {
        }
        terrain.syncStream(); // the start's stream is not the flight's cost
        if (verbose) {
            hexlod::MinMaxPyramid p;
            p.build(field);
            std::printf("start: %lld triangles, error %.3f px\n", (long long)mesh.triangleCount(), drawnMeshErrorPx(mesh, field, p, view, refiner.settings()));
        }
    }
    settings.lod.budgetMs = budgetMs;
    settings.lod.maxOperations = budgetOps;
    settings.morphFrames = morphFrames;
    terrain.configure(settings);
    hexlod::MinMaxPyramid pyramid;
    if (measureError) pyramid.build(field);
    hexlod::PoppingMeter popping;
    std::vector<double> updateMs, updateCpuMs, streamMs, triangles, splits, merges, jumps, tested, convergedMsPerMillion, screenError,
        liveBytes, capacityBytes, convergedCpuMsPerMillion, floorMsPerMillion, floorOperationsMsPerMillion, newShapes;
    std::unique_ptr<hexlod::bench::UpdateFloor> updateFloor;
    if (measureFloor) updateFloor = std::make_unique<hexlod::bench::UpdateFloor>(terrain, field, backface);
    for (const auto& cam : cameras) {
        const uint32_t renumberingsBefore = terrain.renumberings();
        hexlod::View view;
        if (!viewOf(cam, view)) return fail("degenerate camera in ", path);
        terrain.setView(view);
        const double cpuStart = threadCpuMs();
        const hexlod::UpdateStats stats = terrain.updateLod();
        const double cpuMs = threadCpuMs() - cpuStart;
        const auto start = std::chrono::steady_clock::now();
        terrain.syncStream();
        streamMs.push_back(msSince(start));
        if (updateFloor) {
            const hexlod::bench::UpdateFloor::Frame f = updateFloor->frame(terrain.renumberings() != renumberingsBefore);
            const double mtri = double(mesh.triangleCount()) / 1e6;
            floorMsPerMillion.push_back((f.operationsMs + f.boundsMs) / mtri);
            floorOperationsMsPerMillion.push_back(f.operationsMs / mtri);
            newShapes.push_back(f.newShapes);
        }
        popping.follow(terrain.meshEpoch(), terrain.renumberings(), terrain.lastRenumbering()); // a compaction renumbers vertices
        jumps.push_back(popping.measure(mesh, morph, view, 1.0).maxJumpPx);
        updateMs.push_back(stats.milliseconds);
        updateCpuMs.push_back(cpuMs);
        triangles.push_back(double(mesh.triangleCount()));
        splits.push_back(stats.splits);
        merges.push_back(stats.merges);
        tested.push_back(stats.cellsTested);
        if (verbose)
            std::printf("frame %zu: %.3f ms, %d tested, %d ops, %d splits, %d merges, %lld triangles, converged %d\n", updateMs.size(),
                        stats.milliseconds, stats.cellsTested, stats.operations, stats.splits, stats.merges,
                        (long long)mesh.triangleCount(), int(stats.converged));
        const double mtri = double(mesh.triangleCount()) / 1e6;
        if (stats.converged) convergedMsPerMillion.push_back(stats.milliseconds / mtri);
        if (stats.converged) convergedCpuMsPerMillion.push_back(cpuMs / mtri);
        if (measureError) screenError.push_back(drawnMeshErrorPx(mesh, field, pyramid, view, refiner.settings()));
        liveBytes.push_back(double(mesh.liveMemoryBytes() + refiner.liveMemoryBytes() + stream.liveMemoryBytes()) / mtri / 1e6);
        capacityBytes.push_back(double(mesh.memoryBytes() + refiner.memoryBytes() + stream.memoryBytes()) / mtri / 1e6);
    }
    const double p95 = percentile(updateMs, 0.95), tri50 = percentile(triangles, 0.5);
    std::printf("native flight: %zu frames, tau %.2f px, budget %.1f ms / %d ops, geomorph %d frames\n", cameras.size(), tau,
                budgetMs, budgetOps, morphFrames);
    std::printf("  update ms p50 %.3f p95 %.3f; stream ms p50 %.3f p95 %.3f\n", percentile(updateMs, 0.5), p95,
                percentile(streamMs, 0.5), percentile(streamMs, 0.95));
    // Thread CPU time: on a loaded machine a wall-clock p95 is mostly time slices given to others.
    std::printf("  update thread CPU ms p50 %.3f p95 %.3f\n", percentile(updateCpuMs, 0.5), percentile(updateCpuMs, 0.95));
    std::printf("  triangles min %.0f p50 %.0f max %.0f; splits p50 %.0f max %.0f; merges p50 %.0f max %.0f\n",
                percentile(triangles, 0.0), tri50, percentile(triangles, 1.0), percentile(splits, 0.5), percentile(splits, 1.0),
                percentile(merges, 0.5), percentile(merges, 1.0));
    std::printf("  popping: largest vertex jump %.3f px, p99 of frames %.3f px\n", percentile(jumps, 1.0), percentile(jumps, 0.99));
    std::printf("  p95 update per million triangles: %.3f ms; mesh + refiner + stream %.1f B/triangle\n", p95 / (tri50 / 1e6),
                double(mesh.memoryBytes() + refiner.memoryBytes() + stream.memoryBytes()) / double(mesh.triangleCount()));
    std::printf("  cells tested per frame p50 %.0f p95 %.0f max %.0f\n", percentile(tested, 0.5), percentile(tested, 0.95),
                percentile(tested, 1.0));
    std::printf("  converged after the update in %zu of %zu frames; their update ms per million triangles p50 %.3f p95 %.3f\n",
                convergedMsPerMillion.size(), cameras.size(), percentile(convergedMsPerMillion, 0.5),
                percentile(convergedMsPerMillion, 0.95));
    std::printf("  the same in thread CPU time: p50 %.3f p95 %.3f\n", percentile(convergedCpuMsPerMillion, 0.5),
                percentile(convergedCpuMsPerMillion, 0.95));
    if (updateFloor && !updateFloor->matchesMesh()) return fail("--floor: the copy of the mesh is not the mesh after the flight", nullptr);
    if (updateFloor)
        std::printf("  floor (the same operations and the bounds of new cells, nothing judged): ms per million triangles p50 %.3f "
                    "p95 %.3f; operations alone p50 %.3f p95 %.3f; new cells bounded per frame p50 %.0f\n",
                    percentile(floorMsPerMillion, 0.5), percentile(floorMsPerMillion, 0.95), percentile(floorOperationsMsPerMillion, 0.5),
                    percentile(floorOperationsMsPerMillion, 0.95), percentile(newShapes, 0.5));
    if (measureError) {
        size_t within = 0;
        for (double px : screenError) within += px <= tau * (1.0 + 1e-9) ? 1 : 0;
        std::printf("  screen error of the drawn mesh after the update: p50 %.3f p95 %.3f max %.3f px; within tau in %.1f %% of frames\n",
                    percentile(screenError, 0.5), percentile(screenError, 0.95), percentile(screenError, 1.0),
                    100.0 * double(within) / double(screenError.size()));
    }
    if (verbose)
        std::printf("  bytes at the end: mesh %zu (vertex pool %zu; %d of %d cells, %d of %d vertices live), refiner %zu, stream %zu; %lld triangles\n",
                    mesh.memoryBytes(), mesh.vertexPoolBytes(), mesh.liveCells(), mesh.cellCapacity(), mesh.liveVertices(),
                    mesh.vertexCapacity(), refiner.memoryBytes(), stream.memoryBytes(), (long long)mesh.triangleCount());
    std::printf("  bytes per drawn triangle (mesh + refiner + stream): live p50 %.1f max %.1f; at capacity p50 %.1f max %.1f\n",
                percentile(liveBytes, 0.5), percentile(liveBytes, 1.0), percentile(capacityBytes, 0.5), percentile(capacityBytes, 1.0));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc > 6 && std::string(argv[6]) == "--flight") {
        hexlod::HeightfieldScale scale;
        scale.spacingX = std::atof(argv[4]);
        scale.spacingY = std::atof(argv[5]);
        auto terrain = loadRawTerrain(argv[1], std::atoi(argv[2]), std::atoi(argv[3]), scale);
        return terrain ? flight(*terrain, argc, argv) : 1;
    }
    if (argc != 4 && argc != 6) {
        std::fprintf(stderr, "usage: hexlod_bench FILE.f32 WIDTH HEIGHT [SPACING_X_M SPACING_Y_M]\n");
        return 2;
    }
    const int32_t width = std::atoi(argv[2]), height = std::atoi(argv[3]);
    hexlod::HeightfieldScale scale;
    if (argc == 6) scale.spacingX = std::atof(argv[4]), scale.spacingY = std::atof(argv[5]);

    auto terrain = loadRawTerrain(argv[1], width, height, scale);
    if (!terrain) return 1;
    const hexlod::Heightfield* field = &terrain->field();
    std::printf("%s: %dx%d samples, spacing %.1f x %.1f m, heights %.1f .. %.1f m\n", argv[1], width, height,
                scale.spacingX, scale.spacingY, field->minHeight(), field->maxHeight());

    for (hexlod::Embedding embedding : {hexlod::Embedding::Shifted, hexlod::Embedding::Exact}) {
        const char* name = embedding == hexlod::Embedding::Shifted ? "shifted" : "exact";
        if (const char* error = terrain->resetMesh(embedding)) return fail(error, nullptr);
        const hexlod::HexMesh& mesh = terrain->mesh();
        auto start = std::chrono::steady_clock::now();
        terrain->refineUniform(mesh.maxLevel() / 2);
        const double refineMs = msSince(start);
        start = std::chrono::steady_clock::now();
        terrain->syncStream(); // the whole mesh is new to the stream: every slot is written
        const double streamMs = msSince(start);
        std::vector<uint32_t> triangles;
        mesh.appendTriangles(triangles);
        start = std::chrono::steady_clock::now();
        const hexlod::ErrorStats stats = hexlod::evaluateMeshError(
            *field, mesh.positionData(), size_t(mesh.vertexCapacity()), hexlod::kStreamVertexWords, triangles.data(), triangles.size());
        const double evaluateMs = msSince(start);
        if (stats.error) return fail(stats.error, nullptr);
        std::printf("  %-7s full refinement: %lld triangles (%lld splits) in %.0f ms; fan stream %.0f ms; "
                    "mesh structures %.1f B/triangle; error vs samples: max %.3f m, p99 %.3f m, mean %.4f m, uncovered %lld "
                    "(evaluated in %.0f ms)\n",
                    name, (long long)mesh.triangleCount(), (long long)mesh.counts().splits, refineMs, streamMs,
                    double(mesh.memoryBytes()) / double(mesh.triangleCount()), stats.maxError, stats.p99Error,
                    stats.meanError, (long long)stats.uncovered, evaluateMs);
    }
    return 0;
}
