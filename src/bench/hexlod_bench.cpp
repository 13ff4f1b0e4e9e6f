// hexlod_bench: native timings of the core on a raw float32 height field, for comparison with
// the same steps in WebAssembly (`hexlod bench`). It prints figures; it is not a test.
//
//   hexlod_bench FILE.f32 WIDTH HEIGHT [SPACING_X_M SPACING_Y_M] [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "grid_mesh.h"
#include "heightfield.h"

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int usage() {
    std::fprintf(stderr, "usage: hexlod_bench FILE.f32 WIDTH HEIGHT [SPACING_X_M SPACING_Y_M] [REPEATS]\n");
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 4) return usage();
    const int32_t width = std::atoi(argv[2]), height = std::atoi(argv[3]);
    hexlod::HeightfieldScale scale;
    if (argc >= 6) scale.spacingX = std::atof(argv[4]), scale.spacingY = std::atof(argv[5]);
    const int repeats = argc >= 7 ? std::max(1, std::atoi(argv[6])) : 5;

    const char* error = nullptr;
    auto field = hexlod::Heightfield::create(width, height, hexlod::SampleType::F32, &error);
    if (!field) {
        std::fprintf(stderr, "hexlod_bench: %s\n", error);
        return 1;
    }
    FILE* file = std::fopen(argv[1], "rb");
    if (!file) {
        std::fprintf(stderr, "hexlod_bench: cannot open %s\n", argv[1]);
        return 1;
    }
    const size_t got = std::fread(field->samples(), 4, field->sampleCount(), file);
    std::fclose(file);
    if (got != field->sampleCount()) {
        std::fprintf(stderr, "hexlod_bench: %s holds %zu samples, expected %dx%d\n", argv[1], got, width, height);
        return 1;
    }
    if ((error = field->setScale(scale))) {
        std::fprintf(stderr, "hexlod_bench: %s\n", error);
        return 1;
    }

    auto start = std::chrono::steady_clock::now();
    if ((error = field->prepare())) {
        std::fprintf(stderr, "hexlod_bench: %s\n", error);
        return 1;
    }
    std::printf("field %dx%d, heights %.1f..%.1f m, prepare %.2f ms\n", width, height,
                field->minHeight(), field->maxHeight(), msSince(start));

    hexlod::GridMesh mesh;
    for (int32_t cells : {256, 512, 1024}) {
        double best = 1e30;
        for (int r = 0; r < repeats; ++r) {
            start = std::chrono::steady_clock::now();
            hexlod::buildGridMesh(*field, cells, 1.0f, mesh);
            best = std::min(best, msSince(start));
        }
        std::printf("grid mesh <= %d cells/side: %zu triangles, best of %d: %.2f ms\n", cells,
                    mesh.indices.size() / 3, repeats, best);
    }
    return 0;
}
