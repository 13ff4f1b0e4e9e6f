// hexlod_bench: native figures of the core on a raw float32 height field. It prints figures;
// it is not a test.
//
//   hexlod_bench FILE.f32 WIDTH HEIGHT [SPACING_X_M SPACING_Y_M]
//
// For both lattice embeddings (paper §4.7): the time to refine uniformly to the finest level,
// the triangles and the bytes per triangle of the mesh structures, the time to write the fan
// stream, and the error against the original samples (max and p99) at full refinement.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "error_evaluator.h"
#include "fan_stream.h"
#include "heightfield.h"
#include "hex_mesh.h"
#include "hex_mesh_refine.h"

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int fail(const char* what, const char* detail) {
    std::fprintf(stderr, "hexlod_bench: %s%s\n", what, detail ? detail : "");
    return 1;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 4 && argc != 6) {
        std::fprintf(stderr, "usage: hexlod_bench FILE.f32 WIDTH HEIGHT [SPACING_X_M SPACING_Y_M]\n");
        return 2;
    }
    const int32_t width = std::atoi(argv[2]), height = std::atoi(argv[3]);
    hexlod::HeightfieldScale scale;
    if (argc == 6) scale.spacingX = std::atof(argv[4]), scale.spacingY = std::atof(argv[5]);

    const char* error = nullptr;
    auto field = hexlod::Heightfield::create(width, height, hexlod::SampleType::F32, &error);
    if (!field) return fail(error, nullptr);
    FILE* file = std::fopen(argv[1], "rb");
    if (!file) return fail("cannot open ", argv[1]);
    const size_t got = std::fread(field->samples(), 4, field->sampleCount(), file);
    std::fclose(file);
    if (got != field->sampleCount()) return fail("too few samples in ", argv[1]);
    if ((error = field->setScale(scale)) || (error = field->prepare())) return fail(error, nullptr);
    std::printf("%s: %dx%d samples, spacing %.1f x %.1f m, heights %.1f .. %.1f m\n", argv[1], width, height,
                scale.spacingX, scale.spacingY, field->minHeight(), field->maxHeight());

    for (hexlod::Embedding embedding : {hexlod::Embedding::Shifted, hexlod::Embedding::Exact}) {
        const char* name = embedding == hexlod::Embedding::Shifted ? "shifted" : "exact";
        hexlod::HexMesh mesh;
        auto start = std::chrono::steady_clock::now();
        mesh.reset(*field, embedding);
        hexlod::refineUniformly(mesh, mesh.maxLevel() / 2);
        const double refineMs = msSince(start);
        hexlod::FanStream stream;
        start = std::chrono::steady_clock::now();
        hexlod::buildFanStream(mesh, 1.0f, stream);
        const double streamMs = msSince(start);
        std::vector<uint32_t> triangles;
        mesh.appendTriangles(triangles);
        const hexlod::ErrorStats stats = hexlod::evaluateMeshError(
            *field, stream.vertices.data(), size_t(stream.vertexCount), hexlod::kFloatsPerVertex, triangles.data(), triangles.size());
        if (stats.error) return fail(stats.error, nullptr);
        std::printf("  %-7s full refinement: %lld triangles (%lld splits) in %.0f ms; fan stream %.0f ms; "
                    "mesh structures %.1f B/triangle; error vs samples: max %.3f m, p99 %.3f m, mean %.4f m, uncovered %lld\n",
                    name, (long long)mesh.triangleCount(), (long long)mesh.counts().splits, refineMs, streamMs,
                    double(mesh.memoryBytes()) / double(mesh.triangleCount()), stats.maxError, stats.p99Error,
                    stats.meanError, (long long)stats.uncovered);
    }
    return 0;
}
