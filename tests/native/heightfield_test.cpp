#include "field/heightfield.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fixture.h"

using namespace hexlod;

TEST(Heightfield, RejectsSizesTypesAndScalesItCannotHold) {
    const char* error = nullptr;
    EXPECT_EQ(Heightfield::create(1, 100, SampleType::U16, &error), nullptr);
    EXPECT_STREQ(error, "a height field needs at least 2x2 samples");
    EXPECT_EQ(Heightfield::create(70000, 2, SampleType::U16, &error), nullptr);
    EXPECT_NE(std::string(error).find("held whole is limited to 65536"), std::string::npos) << error;
    // A tiled field holds only its tiles: its limit is the lattice's (kMaxTiledFieldSide).
    auto tiledOf = [&](int32_t width, int32_t height) {
        const int32_t dims[8] = {width, height, 512, 512, (width + 4095) / 4096, (height + 4095) / 4096, 512, 512};
        return Heightfield::createTiled(width, height, SampleType::I16, 2, dims, &error);
    };
    EXPECT_NE(tiledOf(1296000, 626400), nullptr) << error;
    EXPECT_NE(tiledOf(kMaxTiledFieldSide, kMaxTiledFieldSide), nullptr) << error;
    EXPECT_EQ(tiledOf(kMaxTiledFieldSide + 1, 1000), nullptr);
    EXPECT_STREQ(error, "a tiled height field side is limited to 2097152 samples");
    const int32_t tinyTiles[8] = {100000, 100000, 8, 8, 100, 100, 8, 8};
    EXPECT_EQ(Heightfield::createTiled(100000, 100000, SampleType::I16, 2, tinyTiles, &error), nullptr);
    EXPECT_NE(std::string(error).find("larger tiles"), std::string::npos) << error;
    EXPECT_EQ(Heightfield::create(4, 4, SampleType(9), &error), nullptr);
    EXPECT_NE(std::string(error).find("unknown sample type"), std::string::npos);

    auto field = Heightfield::create(4, 4, SampleType::U16, &error);
    ASSERT_NE(field, nullptr);
    HeightfieldScale bad;
    bad.spacingX = 0.0;
    EXPECT_NE(field->setScale(bad), nullptr);
    bad.spacingX = 1.0;
    bad.heightScale = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(field->setScale(bad), nullptr);
}

TEST(Heightfield, SixteenBitSamplesBecomeMetresThroughScaleAndOffset) {
    auto field = Heightfield::create(3, 2, SampleType::U16, nullptr);
    uint16_t* raw = static_cast<uint16_t*>(field->samples());
    const uint16_t values[6] = {0, 100, 65535, 7, 8, 9};
    std::copy(values, values + 6, raw);
    HeightfieldScale scale;
    scale.heightScale = 0.5;
    scale.heightOffset = -10.0;
    ASSERT_EQ(field->setScale(scale), nullptr);
    ASSERT_EQ(field->prepare(), nullptr);
    EXPECT_FLOAT_EQ(field->heightAt(1, 0), 40.0f);
    EXPECT_FLOAT_EQ(field->minHeight(), -10.0f);
    EXPECT_FLOAT_EQ(field->maxHeight(), 65535 * 0.5f - 10.0f);
    EXPECT_EQ(field->byteSize(), 12u);
}

TEST(Heightfield, MissingSamplesAreFilledWithTheLowestValidHeightNotASpike) {
    auto field = Heightfield::create(3, 3, SampleType::I16, nullptr);
    int16_t* raw = static_cast<int16_t*>(field->samples());
    const int16_t values[9] = {500, -32768, 700, 600, 650, -32768, 800, 900, 550};
    std::copy(values, values + 9, raw);
    HeightfieldScale scale;
    scale.hasNodata = true;
    scale.nodataRaw = -32768;
    field->setScale(scale);
    ASSERT_EQ(field->prepare(), nullptr);
    EXPECT_EQ(field->missingCount(), 2u);
    EXPECT_FLOAT_EQ(field->heightAt(1, 0), 500.0f);
    EXPECT_FLOAT_EQ(field->heightAt(2, 1), 500.0f);
    EXPECT_FLOAT_EQ(field->minHeight(), 500.0f);
    EXPECT_FLOAT_EQ(field->maxHeight(), 900.0f);
}

TEST(Heightfield, NonFiniteFloatsAreMissingAndAllMissingIsAnError) {
    auto field = Heightfield::create(2, 2, SampleType::F32, nullptr);
    float* raw = static_cast<float*>(field->samples());
    raw[0] = std::numeric_limits<float>::quiet_NaN();
    raw[1] = 3.0f;
    raw[2] = std::numeric_limits<float>::infinity();
    raw[3] = 5.0f;
    ASSERT_EQ(field->prepare(), nullptr);
    EXPECT_EQ(field->missingCount(), 2u);
    EXPECT_FLOAT_EQ(field->heightAt(0, 0), 3.0f);
    for (int k = 0; k < 4; ++k) raw[k] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_STREQ(field->prepare(), "every sample is nodata");
}

TEST(Heightfield, BilinearLookupHitsSamplesExactlyAndClampsOutside) {
    auto field = test::loadFixture(test::kGrandCanyon);
    ASSERT_NE(field, nullptr) << "missing fixture grandcanyon_512.f32";
    const double sx = field->scale().spacingX, sy = field->scale().spacingY;
    EXPECT_FLOAT_EQ(field->heightAtPosition(10 * sx, 20 * sy), field->heightAt(10, 20));
    const float mid = field->heightAtPosition(10.5 * sx, 20 * sy);
    EXPECT_NEAR(mid, 0.5f * (field->heightAt(10, 20) + field->heightAt(11, 20)), 1e-3f);
    EXPECT_FLOAT_EQ(field->heightAtPosition(-1e6, -1e6), field->heightAt(0, 0));
    EXPECT_FLOAT_EQ(field->heightAtPosition(1e9, 1e9), field->heightAt(511, 511));
    EXPECT_FLOAT_EQ(field->heightClamped(-3, 600), field->heightAt(0, 511));
}

TEST(Heightfield, RealFixturesHaveTheRangeTheirSidecarsGive) {
    for (const test::Fixture* f : {&test::kVolcano, &test::kJacksboro, &test::kGrandCanyon}) {
        auto field = test::loadFixture(*f);
        ASSERT_NE(field, nullptr) << f->name;
        EXPECT_EQ(field->missingCount(), 0u) << f->name;
        EXPECT_NEAR(field->minHeight(), f->minHeight, 0.5f) << f->name;
        EXPECT_NEAR(field->maxHeight(), f->maxHeight, 0.5f) << f->name;
    }
}
