// Reads the real DEM fixtures in tests/fixtures (raw little-endian float32, row-major).
#pragma once

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "field/heightfield.h"
#include "terrain.h"

namespace hexlod::test {

struct Fixture {
    const char* name;
    int32_t width, height;
    float spacingX, spacingY;
    float minHeight, maxHeight; // from the fixture's .json sidecar
};

// The fixtures' sizes and ranges, as their .json sidecars give them.
inline const Fixture kVolcano{"volcano_maungawhau", 87, 61, 10.0f, 10.0f, 94.0f, 195.0f};
inline const Fixture kJacksboro{"jacksboro_fault", 403, 344, 74.4f, 92.6f, 236.0f, 1076.0f};
inline const Fixture kGrandCanyon{"grandcanyon_512", 512, 512, 61.7f, 61.7f, 479.0f, 2347.0f};

inline std::vector<float> readF32(const Fixture& f) {
    const std::string path = std::string(HEXLOD_FIXTURES) + "/" + f.name + ".f32";
    std::vector<float> data(size_t(f.width) * size_t(f.height));
    FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) return {};
    const size_t got = std::fread(data.data(), sizeof(float), data.size(), file);
    std::fclose(file);
    if (got != data.size()) return {};
    return data;
}

// A prepared f32 field holding a crop of the fixture (null if the file is unreadable).
inline std::unique_ptr<Heightfield> cropFixture(const Fixture& f, int32_t column, int32_t row, int32_t width, int32_t height) {
    const std::vector<float> data = readF32(f);
    if (data.empty()) return nullptr;
    auto field = Heightfield::create(width, height, SampleType::F32, nullptr);
    float* out = static_cast<float*>(field->samples());
    for (int32_t i = 0; i < height; ++i)
        for (int32_t j = 0; j < width; ++j) out[size_t(i) * width + j] = data[size_t(row + i) * f.width + column + j];
    HeightfieldScale scale;
    scale.spacingX = f.spacingX;
    scale.spacingY = f.spacingY;
    field->setScale(scale);
    field->prepare();
    return field;
}

// A prepared f32 height field holding the fixture's samples (null if the file is unreadable).
inline std::unique_ptr<Heightfield> loadFixture(const Fixture& f) { return cropFixture(f, 0, 0, f.width, f.height); }

// A terrain (the facade the C ABI drives) holding the fixture's prepared samples, no mesh yet
// (null if the file is unreadable).
inline std::unique_ptr<Terrain> loadTerrain(const Fixture& f) {
    const std::vector<float> data = readF32(f);
    if (data.empty()) return nullptr;
    auto terrain = Terrain::create(f.width, f.height, SampleType::F32, nullptr);
    std::copy(data.begin(), data.end(), static_cast<float*>(terrain->field().samples()));
    HeightfieldScale scale;
    scale.spacingX = f.spacingX;
    scale.spacingY = f.spacingY;
    terrain->setScale(scale);
    terrain->prepare();
    return terrain;
}

} // namespace hexlod::test
