// The packed refinement data of the cache (src/lod/packed_bounds.h): half floats rounded to
// the side asked for, and bounds that come back out of the cache still bounds, and tight.
#include "lod/packed_bounds.h"
#include "lod/refinement_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace hexlod;

namespace {

float fromBits(uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, sizeof(f));
    return f;
}

} // namespace

TEST(PackedBounds, EveryHalfComesBackExactlyAndEveryFloatLandsBetweenItsTwoNeighbouringHalves) {
    for (uint32_t h = 0; h <= 0xFFFFu; ++h) {
        if (!half::isFinite(uint16_t(h))) continue;
        const float x = half::toFloat(uint16_t(h));
        // -0 comes back as +0's bits or its own; both are zero.
        EXPECT_EQ(half::toFloat(half::rounded(x, true)), x) << std::hex << h;
        EXPECT_EQ(half::toFloat(half::rounded(x, false)), x) << std::hex << h;
    }
    std::mt19937 random(12);
    std::uniform_int_distribution<uint32_t> anyBits;
    int32_t checked = 0;
    for (int32_t k = 0; k < 2000000; ++k) {
        const float x = fromBits(anyBits(random));
        if (!std::isfinite(x)) continue;
        const float down = half::toFloat(half::rounded(x, false)), up = half::toFloat(half::rounded(x, true));
        ASSERT_LE(down, x) << x;
        ASSERT_GE(up, x) << x;
        if (std::abs(x) <= 65504.0f) {
            // Neighbours: nothing representable lies strictly between them and x.
            const uint16_t d = half::rounded(x, false), u = half::rounded(x, true);
            if (down != up) {
                const float next = half::toFloat(uint16_t(x > 0 ? d + 1 : d - 1)); // one step up from down
                ASSERT_EQ(next, up) << x << " down " << std::hex << d << " up " << u;
            }
        } else {
            ASSERT_TRUE(x > 0 ? std::isinf(up) : std::isinf(down)) << "past the range: infinity on the far side";
        }
        ++checked;
    }
    EXPECT_GT(checked, 1900000);
}

TEST(PackedBounds, ABoundComesBackNoTighterAndAtMostAStepLooser) {
    BoundPacking packing;
    for (auto [lowest, highest] : {std::pair{-10994.0f, 8848.0f}, std::pair{236.0f, 1076.0f}, std::pair{0.0f, 0.0f}, std::pair{5.0f, 5.5f}}) {
        packing.setHeightRange(lowest, highest);
        const double step = std::max(double(highest) - lowest, 0.0) / 65535.0;
        std::mt19937 random(7);
        std::uniform_real_distribution<float> height(lowest, highest);
        std::uniform_real_distribution<double> exponent(-20.0, std::log2(std::max(double(highest) - lowest, 1e-6)));
        for (int32_t k = 0; k < 200000; ++k) {
            CellError e;
            e.low = height(random), e.high = height(random);
            if (e.low > e.high) std::swap(e.low, e.high);
            // A flat field's cells have no error; others from a millionth of a metre to the range.
            e.error = k % 10 == 0 || highest == lowest ? 0.0f : float(std::exp2(exponent(random)));
            const PackedBound p = packing.pack(e);
            ASSERT_TRUE(BoundPacking::known(p));
            const CellError back = packing.unpack(p);
            ASSERT_LE(back.low, e.low);
            ASSERT_GE(back.high, e.high);
            ASSERT_GE(back.error, e.error);
            ASSERT_GE(back.low, e.low - step * 1.001 - 1e-3 * step);
            ASSERT_LE(back.high, e.high + step * 1.001 + 1e-3 * step);
            // A half's relative precision; below its normal range (errors under range * 2^-29) a
            // fixed step of range * 2^-39.
            const double range = double(highest) - lowest;
            ASSERT_LE(back.error, e.error * (1.0 + 1.0 / 1024.0) + range * std::exp2(-38.0)) << e.error;
            ASSERT_EQ(back.low, packing.unpack(packing.pack(back)).low) << "a bound that came back packs to itself";
        }
    }
    EXPECT_FALSE(BoundPacking::known(PackedBound{})) << "a new entry is unknown";
}

TEST(PackedBounds, ASlopeBoxComesBackNoSmallerOrUnknown) {
    SlopeBox unknown;
    EXPECT_FALSE(BoundPacking::unpack(BoundPacking::pack(unknown)).known());
    std::mt19937 random(3);
    std::uniform_real_distribution<double> exponent(-12.0, 12.0);
    std::uniform_int_distribution<int> sign(0, 1);
    auto slope = [&] { return float((sign(random) ? -1.0 : 1.0) * std::exp2(exponent(random))); };
    for (int32_t k = 0; k < 100000; ++k) {
        SlopeBox box;
        box.dxLow = slope(), box.dxHigh = slope(), box.dzLow = slope(), box.dzHigh = slope();
        if (box.dxLow > box.dxHigh) std::swap(box.dxLow, box.dxHigh);
        if (box.dzLow > box.dzHigh) std::swap(box.dzLow, box.dzHigh);
        const SlopeBox back = BoundPacking::unpack(BoundPacking::pack(box));
        ASSERT_TRUE(back.known());
        ASSERT_LE(back.dxLow, box.dxLow);
        ASSERT_GE(back.dxHigh, box.dxHigh);
        ASSERT_LE(back.dzLow, box.dzLow);
        ASSERT_GE(back.dzHigh, box.dzHigh);
    }
    SlopeBox cliff;
    cliff.dxLow = -1.0f, cliff.dxHigh = 1e6f, cliff.dzLow = 0.0f, cliff.dzHigh = 0.5f;
    EXPECT_FALSE(BoundPacking::unpack(BoundPacking::pack(cliff)).known()) << "steeper than a half can say: never culled";
}

// The refiner scans a cell's slopes only when a test needs them: an entry tells a box not
// computed yet from every packed box, the unknown ones included, and reads it as unknown.
TEST(PackedBounds, SlopesNotComputedYetDifferFromEveryPackedBox) {
    EXPECT_FALSE(PackedSlopes::notComputed().computed());
    EXPECT_FALSE(BoundPacking::unpack(PackedSlopes::notComputed()).known()) << "never culled before they are computed";
    EXPECT_TRUE(BoundPacking::pack(SlopeBox{}).computed()) << "unknown (a large cell) is an answer, not a question";
    SlopeBox flat;
    flat.dxLow = flat.dxHigh = flat.dzLow = flat.dzHigh = 0.0f;
    EXPECT_TRUE(BoundPacking::pack(flat).computed());
    std::mt19937 random(5);
    std::uniform_real_distribution<float> slope(-4.0f, 4.0f);
    for (int32_t k = 0; k < 10000; ++k) {
        SlopeBox box;
        box.dxLow = slope(random), box.dxHigh = box.dxLow + std::abs(slope(random));
        box.dzLow = slope(random), box.dzHigh = box.dzLow + std::abs(slope(random));
        ASSERT_TRUE(BoundPacking::pack(box).computed()) << k;
    }
}

// A joined hexagon's parent slot keeps one of its halves (RefinementCache::setHalf): the half
// comes back as the same bound cached as a parent does, and only for the half it was stored for.
TEST(PackedBounds, AHalfInTheParentSlotComesBackAsTheCacheGivesABoundAndOnlyForItsSide) {
    RefinementCache cache;
    cache.setHeightRange(-400.0f, 8848.0f);
    cache.grow(4, 4);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> height(-400.0f, 8848.0f), error(0.0f, 3000.0f);
    for (int32_t trial = 0; trial < 2000; ++trial) {
        const int32_t which = trial & 1;
        const float a = height(random), b = height(random);
        const CellError e{std::min(a, b), std::max(a, b), trial % 7 == 0 ? 0.0f : error(random)};
        cache.invalidate(2);
        EXPECT_FALSE(cache.hasHalf(2, 0) || cache.hasHalf(2, 1));
        cache.setHalf(2, which, e);
        ASSERT_TRUE(cache.hasHalf(2, which));
        ASSERT_FALSE(cache.hasHalf(2, 1 - which)) << "the other half is not the one stored";
        cache.setParent(3, e);
        const CellError back = cache.half(2), expected = cache.parent(3);
        ASSERT_EQ(back.low, expected.low);
        ASSERT_EQ(back.high, expected.high);
        ASSERT_EQ(back.error, expected.error) << "the side's bit must not reach the error";
        ASSERT_GE(back.error, 0.0f);
    }
}

// nextUp and nextDown (float_rounding.h) step by the bits as std::nextafter does, for every
// sign, zeros, subnormals, the largest finite floats and the infinities.
TEST(PackedBounds, NextUpAndNextDownAreStdNextafter) {
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> values = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                                 std::numeric_limits<float>::min(), std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                                 1.0f, -1.0f, inf, -inf};
    std::mt19937 random(11);
    for (int32_t k = 0; k < 100000; ++k) {
        const uint32_t bits = uint32_t(random());
        const float f = fromBits(bits);
        if (std::isfinite(f)) values.push_back(f);
    }
    for (float f : values) {
        if (f != inf) {
            const float up = nextUp(f), expected = std::nextafter(f, inf);
            ASSERT_EQ(std::memcmp(&up, &expected, sizeof(float)), 0) << f;
        }
        if (f != -inf) {
            const float down = nextDown(f), expected = std::nextafter(f, -inf);
            ASSERT_EQ(std::memcmp(&down, &expected, sizeof(float)), 0) << f;
        }
    }
}

// halfBitsUp and halfBitsDown (float_rounding.h) keep a non-negative float in 16 bits on the
// chosen side, within a relative 2^-7, and exactly when it fits.
TEST(PackedBounds, SixteenBitFloatsRoundToTheChosenSide) {
    std::mt19937 random(12);
    for (int32_t k = 0; k < 100000; ++k) {
        const float f = std::abs(fromBits(uint32_t(random())));
        if (!std::isnormal(f) || f > 1e38f) continue; // normal floats: a 16-bit subnormal's step is coarser
        const float up = fromHalfBits(halfBitsUp(f)), down = fromHalfBits(halfBitsDown(f));
        ASSERT_GE(up, f);
        ASSERT_LE(down, f);
        ASSERT_LE(double(up) - double(down), std::ldexp(double(f), -7)) << f;
        if (up == down) {
            ASSERT_EQ(up, f);
        }
    }
    for (float exact : {0.0f, 1.0f, 0.5f, 1536.0f, 65536.0f}) {
        EXPECT_EQ(fromHalfBits(halfBitsUp(exact)), exact);
        EXPECT_EQ(fromHalfBits(halfBitsDown(exact)), exact);
    }
}
