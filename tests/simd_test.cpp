// The eight-wide helpers of the fast passes against plain index arithmetic.
#include "backend/cpu/simd.h"
#include <gtest/gtest.h>

using namespace bmfr::simd;

TEST(Simd, DeinterleaveAndInterleaveXyzRecords) {
    float packed[24];
    for (int i = 0; i < 24; ++i) packed[i] = float(100 + i);
    f8 xyz[3];
    deinterleave3(packed, xyz[0], xyz[1], xyz[2]);
    for (int l = 0; l < 8; ++l)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(xyz[c][l], packed[3 * l + c]) << "lane " << l;
    float back[24] = {};
    interleave3(xyz[0], xyz[1], xyz[2], back);
    for (int i = 0; i < 24; ++i) EXPECT_EQ(back[i], packed[i]) << "float " << i;
}

TEST(Simd, PartialLoadsAndStoresTouchOnlyTheirLanes) {
    float packed[24];
    for (int i = 0; i < 24; ++i) packed[i] = float(1 + i);
    for (int n = 1; n <= 8; ++n) {
        f8 xyz[3];
        loadXyz8(packed, n, xyz);
        for (int l = 0; l < 8; ++l)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(xyz[c][l], l < n ? packed[3 * l + c] : 0.0f);
        float out[24];
        for (float& v : out) v = -1.0f;
        storeXyz8(out, n, xyz);
        for (int i = 0; i < 24; ++i) EXPECT_EQ(out[i], i < 3 * n ? packed[i] : -1.0f);
    }
}

TEST(Simd, BytesRoundTripThroughLanes) {
    const uint8_t bytes[8] = {0, 1, 2, 15, 7, 8, 9, 255};
    for (int n = 1; n <= 8; ++n) {
        const i8 lanes = loadBytes(bytes, n);
        for (int l = 0; l < 8; ++l) EXPECT_EQ(lanes[l], l < n ? int(bytes[l]) : 0);
        uint8_t out[8] = {42, 42, 42, 42, 42, 42, 42, 42};
        storeBytes(out, lanes, n);
        for (int l = 0; l < 8; ++l) EXPECT_EQ(out[l], l < n ? bytes[l] : 42);
    }
}

TEST(Simd, SplatAndReductions) {
    const f8 v = splat8(2.5f);
    for (int l = 0; l < 8; ++l) EXPECT_EQ(v[l], 2.5f);
    const f8 w = {3, -1, 4, 1, -5, 9, 2, 6};
    EXPECT_EQ(hmin8(w), -5.0f);
    EXPECT_EQ(hmax8(w), 9.0f);
    EXPECT_EQ(hsum8(w), 19.0f);
    EXPECT_TRUE(allLanes(firstLanes(8)));
    EXPECT_FALSE(allLanes(firstLanes(7)));
    EXPECT_EQ(countLanes(firstLanes(5)), 5);
}
