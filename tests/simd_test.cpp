// The eight-wide helpers of the fast passes against plain index arithmetic.
#include "backend/cpu/bmfr/cpu_block_masks.h"
#include "backend/cpu/libm_expf.h"
#include "backend/cpu/simd.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>
#include <vector>

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

// Half planes: the integer conversions against the compiler's own _Float16 (libgcc's software
// conversion on this baseline build, the same rounding as F16C).
TEST(Simd, HalfLoadsAreExactForEveryFiniteHalf) {
    for (uint32_t bits = 0; bits < 65536; bits += 8) {
        uint16_t raw[8];
        _Float16 h[8];
        for (int l = 0; l < 8; ++l) raw[l] = uint16_t(bits + uint32_t(l));
        std::memcpy(h, raw, sizeof h);
        const f8 v = load8(h);
        for (int l = 0; l < 8; ++l) {
            const uint16_t b = raw[l];
            if ((b & 0x7c00) == 0x7c00) continue; // infinities and NaNs are never stored
            ASSERT_EQ(v[l], float(h[l])) << "half bits " << b;
        }
    }
}

TEST(Simd, HalfStoresRoundToNearestEvenAndSaturate) {
    std::vector<float> values = {0.0f,     -0.0f,         1.0f,   -1.0f,    65504.0f, 65519.0f,
                                 65520.0f, 1e9f,          -1e9f,  6.1e-5f,  6.0e-5f,  5.96e-8f,
                                 2.98e-8f, 2.9802322e-8f, 1e-30f, 0.33333f, 255.0f,   254.5f};
    // Ties: the midpoints between neighbouring halves in every binade, both signs.
    for (int e = -24; e < 16; ++e)
        for (int m : {1, 2, 3, 1023, 1024}) {
            const float step = std::ldexp(1.0f, e - 10);
            values.push_back(std::ldexp(1.0f, e) + (float(m) - 0.5f) * step);
        }
    uint32_t state = 12345;
    for (int i = 0; i < 200000; ++i) {
        state = state * 1664525u + 1013904223u;
        float f;
        const uint32_t bits = (state & 0x807fffffu) | (((state >> 23) % 48u + 100u) << 23);
        std::memcpy(&f, &bits, sizeof f);
        values.push_back(f);
    }
    while (values.size() % 8) values.push_back(0.5f);
    for (size_t i = 0; i < values.size(); i += 8) {
        _Float16 got[8];
        store8(got, load8(values.data() + i));
        for (int l = 0; l < 8; ++l) {
            const float x = std::clamp(values[i + size_t(l)], -65504.0f, 65504.0f);
            const _Float16 want = _Float16(x);
            uint16_t a, b;
            std::memcpy(&a, &got[l], 2), std::memcpy(&b, &want, 2);
            ASSERT_EQ(a, b) << "float " << values[i + size_t(l)];
        }
    }
}

#if BMFR_SIMD_F16C
// The F16C loads and stores (inline assembly, AVX2 and AVX-512 paths) give the bits of the
// integer conversions above, which are tested against _Float16.
BMFR_SIMD_TARGET_AVX2 [[gnu::noinline]] void roundTripF16c(const float* in, F16cHalf* half,
                                                           float* back) {
    store8(half, load8(in));
    store8(back, load8(static_cast<const F16cHalf*>(half)));
}

TEST(Simd, F16cHalvesMatchTheIntegerConversions) {
    if (bmfr::cpu::bestIsa() < bmfr::cpu::Isa::Avx2) GTEST_SKIP() << "this processor lacks F16C";
    uint32_t state = 777;
    for (int i = 0; i < 20000; ++i) {
        float in[8];
        for (float& f : in) {
            state = state * 1664525u + 1013904223u;
            const uint32_t bits = (state & 0x807fffffu) | (((state >> 23) % 50u + 98u) << 23);
            std::memcpy(&f, &bits, sizeof f);
        }
        in[0] = i == 0 ? 1e9f : in[0]; // saturates
        F16cHalf hw[8];
        _Float16 sw[8];
        float back[8];
        roundTripF16c(in, hw, back);
        store8(sw, load8(in));
        ASSERT_EQ(std::memcmp(hw, sw, sizeof hw), 0) << "float " << in[0] << " ...";
        const f8 soft = load8(sw);
        for (int l = 0; l < 8; ++l) ASSERT_EQ(back[l], soft[l]);
    }
}
#endif

TEST(Simd, MaskBucketsAreTheScalarOnes) {
    // The emitter mask's and firefly clamp's histogram buckets, eight at a time on the CPU,
    // against maskBucket: every half-octave edge and its neighbours, the ends of the range,
    // subnormals, zero, negatives, infinities and NaN.
    std::vector<float> v = {0.0f,       -0.0f,   -1.0f,       1e-45f,      1e-38f,
                            1.1e-38f,   5.9e-8f, 5.97e-8f,    6.0e-8f,     0.5f,
                            1.0f,       2048.0f, 4096.0f,     1e30f,       HUGE_VALF,
                            -HUGE_VALF, NAN,     0.70710677f, 0.70710678f, 0.7071068f};
    for (int b = -60; b <= 30; ++b) {
        const float edge = std::exp2(0.5f * float(b));
        v.push_back(edge);
        v.push_back(std::nextafter(edge, 0.0f));
        v.push_back(std::nextafter(edge, HUGE_VALF));
    }
    while (v.size() % 8) v.push_back(1.0f);
    for (size_t i = 0; i < v.size(); i += 8) {
        const i8 got = bmfr::cpu::maskBucket8(load8(v.data() + i));
        for (int l = 0; l < 8; ++l)
            EXPECT_EQ(got[l], bmfr::maskBucket(v[i + size_t(l)]))
                << "luminance " << v[i + size_t(l)];
    }
}

TEST(Simd, ExpWithinTwoUlpOfTheLibraryAndItsNonPositiveFormAlike) {
    // Eight points every 0.0137 over the range expf covers and past both ends.
    double worst = 0;
    for (float x = -90.0f; x < 90.0f; x += 0.0137f) {
        f8 v;
        for (int l = 0; l < 8; ++l) v[l] = x + 0.001f * float(l);
        const f8 e = exp8(v);
        for (int l = 0; l < 8; ++l) {
            const double ref = std::exp(double(v[l]));
            if (v[l] < kExpLow) {
                EXPECT_EQ(e[l], 0.0f) << v[l];
            } else if (v[l] > kExpHigh) {
                EXPECT_TRUE(std::isinf(e[l])) << v[l];
            } else {
                const double ulp = std::nextafter(float(ref), INFINITY) - float(ref);
                worst = std::max(worst, std::fabs(double(e[l]) - ref) / ulp);
            }
            if (v[l] <= 0.0f) {
                EXPECT_EQ(expNonPositive8(v)[l], e[l]) << v[l];
            }
        }
    }
    EXPECT_LE(worst, 2.0);
    f8 odd{};
    odd[0] = NAN, odd[1] = 0.0f, odd[2] = -0.0f, odd[3] = 1.0f;
    const f8 e = exp8(odd);
    EXPECT_TRUE(std::isnan(e[0]));
    EXPECT_EQ(e[1], 1.0f);
    EXPECT_EQ(e[2], 1.0f);
    EXPECT_NEAR(e[3], 2.7182817f, 1e-6f);
}

// deinterleave3's AVX-512 form (two loads, three permutes) reads the same eight records as the
// eight-lane shuffles of the other paths (the vector extensions run each form on any processor).
TEST(Simd, DeinterleaveOnEveryPathReadsEightRecords) {
    using bmfr::cpu::Isa;
    std::vector<float> packed(24); // exactly eight records: a read past them would show under ASan
    for (size_t k = 0; k < packed.size(); ++k) packed[k] = float(k) * 1.5f - 7.0f;
    f8 v[3][3];
    deinterleave3<Isa::Avx512>(packed.data(), v[0][0], v[0][1], v[0][2]);
    deinterleave3<Isa::Avx2>(packed.data(), v[1][0], v[1][1], v[1][2]);
    deinterleave3<Isa::Baseline>(packed.data(), v[2][0], v[2][1], v[2][2]);
    for (int path = 0; path < 3; ++path)
        for (int l = 0; l < 8; ++l)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(v[path][c][l], packed[size_t(3 * l + c)])
                    << "path " << path << ", lane " << l << ", channel " << c;
}

// Sixteen packed records (Mara 2017's runs of sixteen on the AVX-512 path) as three vectors, and
// the sixteen-lane mask helpers.
TEST(Simd, DeinterleaveSixteenRecordsAndSixteenLaneMasks) {
    // Exactly sixteen records: a read past them would show under ASan.
    std::vector<float> packed(48);
    for (size_t k = 0; k < packed.size(); ++k) packed[k] = float(k) * 1.5f - 7.0f;
    f32x16 v[3];
    deinterleave3x16(packed.data(), v[0], v[1], v[2]);
    for (int l = 0; l < 16; ++l)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(v[c][l], packed[size_t(3 * l + c)]) << "lane " << l << ", channel " << c;
    const i32x16 lanes = laneIndices<i32x16>();
    for (int l = 0; l < 16; ++l) EXPECT_EQ(lanes[l], l);
    for (int only = 0; only < 16; ++only) EXPECT_TRUE(anyLaneOf(lanes == only)) << only;
    EXPECT_FALSE(anyLaneOf(lanes == 16));
    EXPECT_FALSE(anyLaneOf(laneIndices<i8>() == 8));
    const f32x16 joined = joinLanes(f8{} + 1.0f, f8{} + 2.0f);
    for (int l = 0; l < 16; ++l) EXPECT_EQ(joined[l], l < 8 ? 1.0f : 2.0f);
}

// The helpers written once for eight and sixteen lanes give each lane the same bits at both
// widths (the sixteen-wide SVGF levels rely on it).
TEST(Simd, SixteenLanesAreTwoTimesEightLaneForLane) {
    for (float x = -100.0f; x < 100.0f; x += 0.37f) {
        f32x16 wide;
        for (int l = 0; l < 16; ++l) wide[l] = x + 0.011f * float(l) * (l % 2 ? -1.0f : 1.0f);
        f8 half[2];
        for (int h = 0; h < 2; ++h)
            for (int l = 0; l < 8; ++l) half[h][l] = wide[8 * h + l];
        const f32x16 colour[3] = {wide, wide * 0.5f, absOf(wide)};
        const f32x16 exp = expNonPositive(-absOf(wide)), lum = luminanceOf(colour);
        const f32x16 low = minOf(wide, splat<f32x16>(1.5f)),
                     high = maxOf(wide, splat<f32x16>(1.5f));
        for (int h = 0; h < 2; ++h) {
            const f8 c[3] = {half[h], half[h] * 0.5f, abs8(half[h])};
            const f8 e = expNonPositive8(-abs8(half[h])), y = luminance8(c);
            const f8 lo = min8(half[h], splat8(1.5f)), hi = max8(half[h], splat8(1.5f));
            for (int l = 0; l < 8; ++l) {
                EXPECT_EQ(exp[8 * h + l], e[l]) << wide[8 * h + l];
                EXPECT_EQ(lum[8 * h + l], y[l]) << wide[8 * h + l];
                EXPECT_EQ(low[8 * h + l], lo[l]);
                EXPECT_EQ(high[8 * h + l], hi[l]);
            }
        }
    }
    float out[16] = {};
    storeFirstLanes(out, splat<f32x16>(2.0f), 11);
    for (int l = 0; l < 16; ++l) EXPECT_EQ(out[l], l < 11 ? 2.0f : 0.0f) << l;
}

// expfOnActivePath gives std::exp's bits on every path: on every 61st float from -0 to -104
// (every one was checked once), at one whose result glibc's FMA build rounds the other way from
// its plain build (and from the correctly rounded value), and where expf is 0, 1 or NaN.
TEST(Simd, LibmExpfGivesTheCLibrarysBits) {
    using namespace bmfr::cpu;
    const Isa best = bestIsa();
    long differ[3] = {}, checked = 0;
    auto check = [&](std::vector<float>& x) {
        const int n = int(x.size());
        x.resize(size_t(n + 7) / 8 * 8, 0.0f); // expfOnActivePath reads whole groups of eight
        std::vector<float> out(x.size());
        for (int k = 0; k <= int(best); ++k) {
            setActiveIsa(Isa(k));
            expfOnActivePath(x.data(), n, out.data());
            setActiveIsa(best);
            for (int i = 0; i < n; ++i) {
                const float want = std::exp(x[size_t(i)]), got = out[size_t(i)];
                if (std::isnan(want) ? std::isnan(got) : std::memcmp(&want, &got, 4) == 0) continue;
                if (differ[k]++ < 3)
                    ADD_FAILURE() << isaName(Isa(k)) << ": expf(" << std::hexfloat << x[size_t(i)]
                                  << ") = " << want << ", not " << got;
            }
        }
        checked += n;
        x.clear();
    };
    std::vector<float> x;
    for (uint32_t u = 0x80000000u; u <= 0xc2d00000u; u += 61) {
        float v;
        std::memcpy(&v, &u, sizeof v);
        x.push_back(v);
        if (x.size() == size_t(1) << 20) check(x);
    }
    for (const float v : {-0x1.f8cbb2p+5f, -103.9f, -103.98f, -104.5f, -1e30f, -INFINITY, 0.0f})
        x.push_back(v);
    x.push_back(NAN);
    check(x);
    for (int k = 0; k <= int(best); ++k)
        EXPECT_EQ(differ[k], 0) << isaName(Isa(k)) << ", of " << checked;
}
