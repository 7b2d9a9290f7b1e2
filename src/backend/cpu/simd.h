// Eight-wide float vectors (GCC/Clang vector extensions) for the fast CPU passes.
// Portable source: the compiler lowers them to SSE, AVX2 or AVX-512 for each path (isa.h).
#pragma once
#include "backend/cpu/isa.h"
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace bmfr::simd {

typedef float f8 __attribute__((vector_size(32)));
typedef int32_t i8 __attribute__((vector_size(32)));
/// Sixteen lanes, for bodies that take one AVX-512 register per vector on that path (on this
/// project's Zen 4 machine, a sixteen-wide exponential and division ran 1.4x the eight-wide).
typedef float f32x16 __attribute__((vector_size(64)));
typedef int32_t i32x16 __attribute__((vector_size(64)));

/// A float vector's lane count and integer twin, for kernels written once for both widths.
template <class V> struct VectorTraits;
template <> struct VectorTraits<f8> {
    using Int = i8;
    static constexpr int kLanes = 8;
};
template <> struct VectorTraits<f32x16> {
    using Int = i32x16;
    static constexpr int kLanes = 16;
};
template <class V> using IntOf = typename VectorTraits<V>::Int;
template <class V> constexpr int kLanesOf = VectorTraits<V>::kLanes;

#define BMFR_SIMD_INLINE [[gnu::always_inline]] inline

// Hot kernels are compiled three times, for x86-64-v4 (AVX-512), x86-64-v3 (AVX2 + FMA + F16C)
// and the baseline, and called through the path isa.h chose at run time. Within one machine and
// path the code is fixed, so output bits are repeatable.
//
//   BMFR_SIMD_DISPATCH(void, rows, (const Args& a, long y0), (a, y0)) { ...body... }
//
// defines rows(a, y0), which calls the body compiled for the active path. The body is written
// once, as an always-inline function template (rowsBody<kIsa>) that each path's copy inlines;
// `kIsa` lets it choose what only some paths may execute (F16C, sixteen-wide vectors).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define BMFR_SIMD_TARGET_AVX512 [[gnu::target("arch=x86-64-v4")]]
#define BMFR_SIMD_TARGET_AVX2 [[gnu::target("arch=x86-64-v3")]]
#define BMFR_SIMD_F16C 1
#else
#define BMFR_SIMD_TARGET_AVX512
#define BMFR_SIMD_TARGET_AVX2
#define BMFR_SIMD_F16C 0
#endif
#if BMFR_SIMD_SINGLE_PATH
// One path, the baseline, for builds that check the source rather than its speed (the
// sanitizers: every path is this one source, so it indexes memory alike on each); isa.cpp
// then reports the baseline as the best path.
#define BMFR_SIMD_DISPATCH_WITH(Attr, BodyInline, Ret, name, Params, Args)                         \
    template <::bmfr::cpu::Isa kIsa> BodyInline Ret name##Body Params;                             \
    [[gnu::noinline]] Attr Ret name Params {                                                       \
        return name##Body<::bmfr::cpu::Isa::Baseline> Args;                                        \
    }                                                                                              \
    template <::bmfr::cpu::Isa kIsa> BodyInline Ret name##Body Params
#else
#define BMFR_SIMD_DISPATCH_WITH(Attr, BodyInline, Ret, name, Params, Args)                         \
    template <::bmfr::cpu::Isa kIsa> BodyInline Ret name##Body Params;                             \
    BMFR_SIMD_TARGET_AVX512 [[gnu::noinline]] Attr Ret name##Avx512 Params {                       \
        return name##Body<::bmfr::cpu::Isa::Avx512> Args;                                          \
    }                                                                                              \
    BMFR_SIMD_TARGET_AVX2 [[gnu::noinline]] Attr Ret name##Avx2 Params {                           \
        return name##Body<::bmfr::cpu::Isa::Avx2> Args;                                            \
    }                                                                                              \
    [[gnu::noinline]] Attr Ret name##Baseline Params {                                             \
        return name##Body<::bmfr::cpu::Isa::Baseline> Args;                                        \
    }                                                                                              \
    Ret name Params {                                                                              \
        switch (::bmfr::cpu::activeIsa()) {                                                        \
        case ::bmfr::cpu::Isa::Avx512:                                                             \
            return name##Avx512 Args;                                                              \
        case ::bmfr::cpu::Isa::Avx2:                                                               \
            return name##Avx2 Args;                                                                \
        default:                                                                                   \
            return name##Baseline Args;                                                            \
        }                                                                                          \
    }                                                                                              \
    template <::bmfr::cpu::Isa kIsa> BodyInline Ret name##Body Params
#endif
#define BMFR_SIMD_DISPATCH(Ret, name, Params, Args)                                                \
    BMFR_SIMD_DISPATCH_WITH(, BMFR_SIMD_INLINE, Ret, name, Params, Args)
// The same with every call in the body inlined too (GCC's flatten), so that header functions it
// calls, which are compiled for the baseline when left out of line, take the path's vectors.
#define BMFR_SIMD_DISPATCH_FLAT(Ret, name, Params, Args)                                           \
    BMFR_SIMD_DISPATCH_WITH(__attribute__((flatten)), inline, Ret, name, Params, Args)

template <class V> BMFR_SIMD_INLINE V loadVector(const float* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
template <class V> BMFR_SIMD_INLINE void storeVector(float* p, V v) {
    std::memcpy(p, &v, sizeof v);
}
BMFR_SIMD_INLINE f8 load8(const float* p) {
    return loadVector<f8>(p);
}
BMFR_SIMD_INLINE void store8(float* p, f8 v) {
    storeVector(p, v);
}
/// Half planes (history stored as 16-bit floats). As _Float16, for the baseline path: integer
/// arithmetic, since GCC 12 splits a vector conversion to _Float16 into one conversion per lane.
/// The AVX2 and AVX-512 paths store F16cHalf (below) instead.
typedef uint16_t u16x8 __attribute__((vector_size(16)));
typedef uint32_t u32x8 __attribute__((vector_size(32)));

/// Each lane clamped to [-65504, 65504], the finite halves (see roundToHalf, core/half.h).
template <class V> BMFR_SIMD_INLINE V saturateToHalf(V v) {
    V big{};
    for (int l = 0; l < kLanesOf<V>; ++l) big[l] = 65504.0f;
    return v > big ? big : (v < -big ? -big : v);
}
BMFR_SIMD_INLINE f8 saturateToHalf8(f8 v) {
    return saturateToHalf(v);
}

/// Eight halves as floats, exactly (normal, subnormal and zero halves; a half plane holds no
/// infinity or NaN).
BMFR_SIMD_INLINE f8 load8(const _Float16* p) {
    u16x8 h;
    std::memcpy(&h, p, sizeof h);
    const u32x8 w = __builtin_convertvector(h, u32x8);
    // The magnitude's bits land in a float's exponent and mantissa 112 binades too low; one
    // multiply rebiases normals and normalises subnormals alike.
    const f8 magnitude = f8((w & 0x7fffu) << 13) * 0x1p112f;
    return f8(u32x8(magnitude) | ((w & 0x8000u) << 16));
}
/// Stores roundToHalf (core/half.h) of each lane: saturated to the largest half, then rounded
/// to nearest, ties to even, as F16C and the C++ conversion do (tested bit for bit).
BMFR_SIMD_INLINE void store8(_Float16* p, f8 v) {
    u32x8 u = u32x8(saturateToHalf8(v));
    const u32x8 sign = u & 0x80000000u;
    u ^= sign;
    // Below 2^-14 the half is subnormal: adding 0.5 aligns its 10 bits at the bottom of the
    // float's mantissa, and the float addition rounds them to nearest even.
    f8 magic{};
    for (int l = 0; l < 8; ++l) magic[l] = 0.5f;
    const u32x8 small = u32x8(f8(u) + magic) - u32x8(magic);
    // Otherwise rebias the exponent and round the 13 dropped bits to nearest even.
    const u32x8 odd = (u >> 13) & 1u;
    const u32x8 normal = (u + (0xC8000000u + 0xfffu) + odd) >> 13;
    const u32x8 bits = (i8(u) < (113 << 23) ? small : normal) | (sign >> 16);
    const u16x8 h = __builtin_convertvector(bits, u16x8);
    std::memcpy(p, &h, sizeof h);
}
/// A half stored by F16C. A type of its own, so that only bodies compiled for a path that has
/// F16C (kIsa >= Isa::Avx2, with BMFR_SIMD_F16C) instantiate its loads and stores: inline
/// assembly, since a body shared by every path cannot call the F16C intrinsics.
struct F16cHalf {
    uint16_t bits;
};
typedef int16_t s16x8 __attribute__((vector_size(16)));
typedef int16_t s16x16 __attribute__((vector_size(32)));
template <class V> using HalvesOf = std::conditional_t<sizeof(V) == sizeof(f8), s16x8, s16x16>;
#if BMFR_SIMD_F16C
/// The lanes of V as halves, to floats: eight (the AVX2 and AVX-512 paths) or sixteen (the
/// AVX-512 path only).
template <class V> BMFR_SIMD_INLINE V loadHalves(const F16cHalf* p) {
    HalvesOf<V> h;
    std::memcpy(&h, p, sizeof h);
    V v;
    asm("vcvtph2ps %1, %0" : "=v"(v) : "vm"(h));
    return v;
}
/// The same as store8(_Float16*, f8), eight or sixteen lanes: saturate, then round to nearest
/// even (imm 4: MXCSR's rounding, which bmfr never changes from nearest even).
template <class V> BMFR_SIMD_INLINE void storeHalves(F16cHalf* p, V v) {
    v = saturateToHalf(v);
    HalvesOf<V> h;
    asm("vcvtps2ph $4, %1, %0" : "=vm"(h) : "v"(v));
    std::memcpy(p, &h, sizeof h);
}
BMFR_SIMD_INLINE f8 load8(const F16cHalf* p) {
    return loadHalves<f8>(p);
}
BMFR_SIMD_INLINE void store8(F16cHalf* p, f8 v) {
    storeHalves(p, v);
}
#endif
/// The half type a body compiled for `isa` stores.
template <cpu::Isa isa>
using HalfOf = std::conditional_t<BMFR_SIMD_F16C && isa >= cpu::Isa::Avx2, F16cHalf, _Float16>;

/// (1 - t) a + t b per lane, as bmfr::lerp.
BMFR_SIMD_INLINE f8 lerp8(f8 a, f8 b, f8 t) {
    return (1.0f - t) * a + t * b;
}

/// Lane masks (comparison results: -1 true, 0 false), reduced through shuffles.
BMFR_SIMD_INLINE bool allLanes(i8 m) {
    m &= __builtin_shuffle(m, i8{4, 5, 6, 7, 0, 1, 2, 3});
    m &= __builtin_shuffle(m, i8{2, 3, 0, 1, 6, 7, 4, 5});
    m &= __builtin_shuffle(m, i8{1, 0, 3, 2, 5, 4, 7, 6});
    return m[0] != 0;
}
BMFR_SIMD_INLINE bool anyLane(i8 m) {
    m |= __builtin_shuffle(m, i8{4, 5, 6, 7, 0, 1, 2, 3});
    m |= __builtin_shuffle(m, i8{2, 3, 0, 1, 6, 7, 4, 5});
    m |= __builtin_shuffle(m, i8{1, 0, 3, 2, 5, 4, 7, 6});
    return m[0] != 0;
}
/// Number of true lanes.
BMFR_SIMD_INLINE int countLanes(i8 m) {
    m += __builtin_shuffle(m, i8{4, 5, 6, 7, 0, 1, 2, 3});
    m += __builtin_shuffle(m, i8{2, 3, 0, 1, 6, 7, 4, 5});
    m += __builtin_shuffle(m, i8{1, 0, 3, 2, 5, 4, 7, 6});
    return -m[0];
}
/// Smallest lane.
BMFR_SIMD_INLINE int hminLanes(i8 v) {
    v = v < __builtin_shuffle(v, i8{4, 5, 6, 7, 0, 1, 2, 3})
            ? v
            : __builtin_shuffle(v, i8{4, 5, 6, 7, 0, 1, 2, 3});
    v = v < __builtin_shuffle(v, i8{2, 3, 0, 1, 6, 7, 4, 5})
            ? v
            : __builtin_shuffle(v, i8{2, 3, 0, 1, 6, 7, 4, 5});
    return v[0] < v[1] ? v[0] : v[1];
}
/// Lanes whose value is finite (x - x is NaN for NaN and Inf).
BMFR_SIMD_INLINE i8 finite8(f8 v) {
    return (v - v) == 0.0f;
}
/// Non-finite lanes of three channels replaced by 0 and counted (staged tails read as 0).
BMFR_SIMD_INLINE void finiteOrZero8(f8 v[3], int64_t& bad) {
    for (int c = 0; c < 3; ++c) {
        const i8 ok = finite8(v[c]);
        bad += countLanes(~ok);
        v[c] = ok ? v[c] : f8{};
    }
}
/// Lanes 0 .. n-1 true.
BMFR_SIMD_INLINE i8 firstLanes(int n) {
    const i8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    return lane < n;
}

typedef float f4 __attribute__((vector_size(16)));

/// Eight packed xyz records (24 floats) as x, y and z lanes, and back. Each 16-byte half of
/// the three registers m0, m1, m2 holds four records (records 0-3 low, 4-7 high) as
/// x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3, so a channel is two blends and one permute within
/// halves, none across them.
BMFR_SIMD_INLINE void deinterleave3(const float* p, f8& x, f8& y, f8& z) {
    auto halves = [p](int lo, int hi) {
        f4 a, b;
        std::memcpy(&a, p + 4 * lo, sizeof a);
        std::memcpy(&b, p + 4 * hi, sizeof b);
        return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7);
    };
    const f8 m0 = halves(0, 3), m1 = halves(1, 4), m2 = halves(2, 5);
    x = __builtin_shuffle(__builtin_shuffle(m0, m1, i8{0, 1, 10, 3, 4, 5, 14, 7}), m2,
                          i8{0, 9, 2, 3, 4, 13, 6, 7}); // x0 x3 x2 x1
    y = __builtin_shuffle(__builtin_shuffle(m0, m1, i8{8, 1, 2, 11, 12, 5, 6, 15}), m2,
                          i8{0, 1, 10, 3, 4, 5, 14, 7}); // y1 y0 y3 y2
    z = __builtin_shuffle(__builtin_shuffle(m0, m1, i8{0, 9, 2, 3, 4, 13, 6, 7}), m2,
                          i8{8, 1, 2, 11, 12, 5, 6, 15}); // z2 z1 z0 z3
    x = __builtin_shuffle(x, i8{0, 3, 2, 1, 4, 7, 6, 5});
    y = __builtin_shuffle(y, i8{1, 0, 3, 2, 5, 4, 7, 6});
    z = __builtin_shuffle(z, i8{2, 1, 0, 3, 6, 5, 4, 7});
}
/// deinterleave3 on the path kIsa: on AVX-512, two overlapping 64-byte loads and three
/// two-register permutes (the eight-lane form takes six half loads, three inserts, six blends and
/// three permutes). For taps, not for streaming rows: there the overlapping loads cost more.
template <cpu::Isa kIsa> BMFR_SIMD_INLINE void deinterleave3(const float* p, f8& x, f8& y, f8& z) {
    if constexpr (kIsa == cpu::Isa::Avx512) {
        f32x16 a, b; // floats 0 to 15 and 8 to 23
        std::memcpy(&a, p, sizeof a);
        std::memcpy(&b, p + 8, sizeof b);
        x = __builtin_shufflevector(a, b, 0, 3, 6, 9, 12, 15, 26, 29);
        y = __builtin_shufflevector(a, b, 1, 4, 7, 10, 13, 24, 27, 30);
        z = __builtin_shufflevector(a, b, 2, 5, 8, 11, 14, 25, 28, 31);
    } else {
        deinterleave3(p, x, y, z);
    }
}
BMFR_SIMD_INLINE void interleave3(f8 x, f8 y, f8 z, float* p) {
    x = __builtin_shuffle(x, i8{0, 3, 2, 1, 4, 7, 6, 5});
    y = __builtin_shuffle(y, i8{1, 0, 3, 2, 5, 4, 7, 6});
    z = __builtin_shuffle(z, i8{2, 1, 0, 3, 6, 5, 4, 7});
    const f8 m0 = __builtin_shuffle(__builtin_shuffle(x, y, i8{0, 9, 2, 3, 4, 13, 6, 7}), z,
                                    i8{0, 1, 10, 3, 4, 5, 14, 7});
    const f8 m1 = __builtin_shuffle(__builtin_shuffle(y, z, i8{0, 9, 2, 3, 4, 13, 6, 7}), x,
                                    i8{0, 1, 10, 3, 4, 5, 14, 7});
    const f8 m2 = __builtin_shuffle(__builtin_shuffle(z, x, i8{0, 9, 2, 3, 4, 13, 6, 7}), y,
                                    i8{0, 1, 10, 3, 4, 5, 14, 7});
    store8(p, __builtin_shuffle(m0, m1, i8{0, 1, 2, 3, 8, 9, 10, 11}));
    store8(p + 8, __builtin_shuffle(m2, m0, i8{0, 1, 2, 3, 12, 13, 14, 15}));
    store8(p + 16, __builtin_shuffle(m1, m2, i8{4, 5, 6, 7, 12, 13, 14, 15}));
}
/// The first n (1 to 8) packed xyz records; lanes n to 7 read as 0.
BMFR_SIMD_INLINE void loadXyz8(const float* p, int n, f8 out[3]) {
    if (n == 8) return deinterleave3(p, out[0], out[1], out[2]);
    float staged[24] = {};
    std::memcpy(staged, p, sizeof(float) * 3 * size_t(n));
    deinterleave3(staged, out[0], out[1], out[2]);
}
/// Sixteen packed xyz records (48 floats) as x, y and z lanes: three 64-byte loads and two
/// two-register permutes a channel (the AVX-512 path; elsewhere the permutes go through memory).
BMFR_SIMD_INLINE void deinterleave3x16(const float* p, f32x16& x, f32x16& y, f32x16& z) {
    f32x16 a, b, c; // floats 0 to 15, 16 to 31 and 32 to 47
    std::memcpy(&a, p, sizeof a);
    std::memcpy(&b, p + 16, sizeof b);
    std::memcpy(&c, p + 32, sizeof c);
    // Each channel's lanes from a and b first (the rest of the lanes are not used), then c's.
    const f32x16 xab = __builtin_shufflevector(a, b, 0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0,
                                               0, 0, 0),
                 yab = __builtin_shufflevector(a, b, 1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0,
                                               0, 0, 0),
                 zab = __builtin_shufflevector(a, b, 2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0,
                                               0, 0, 0);
    x = __builtin_shufflevector(xab, c, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29);
    y = __builtin_shufflevector(yab, c, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30);
    z = __builtin_shufflevector(zab, c, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31);
}
/// The sixteen lanes of lo then hi (float or integer).
template <class H> BMFR_SIMD_INLINE auto joinLanes(H lo, H hi) {
    return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
/// The lane indices 0, 1, ... of a mask type.
template <class M> BMFR_SIMD_INLINE M laneIndices() {
    M m;
    for (int l = 0; l < int(sizeof(M) / sizeof(int32_t)); ++l) m[l] = l;
    return m;
}
/// Lanes [h, h + 8) of v (float or integer), for h = 0 or (with sixteen lanes) 8.
template <class V> BMFR_SIMD_INLINE auto eightLanes(V v, int h) {
    if constexpr (sizeof(V) == 32)
        return v;
    else
        return h == 0 ? __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7)
                      : __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
}
/// Whether any lane of a mask of eight or sixteen lanes is true.
template <class M> BMFR_SIMD_INLINE bool anyLaneOf(M m) {
    if constexpr (sizeof(M) == sizeof(i8))
        return anyLane(m);
    else
        return anyLane(eightLanes(m, 0) | eightLanes(m, 8));
}
/// out[k] lane l = in[l] lane k: an 8x8 transpose in three rounds of two-vector shuffles.
BMFR_SIMD_INLINE void transpose8(const f8 in[8], f8 out[8]) {
    f8 a[8], b[8];
    for (int j = 0; j < 8; j += 2) {
        a[j] = __builtin_shuffle(in[j], in[j + 1], i8{0, 8, 2, 10, 4, 12, 6, 14});
        a[j + 1] = __builtin_shuffle(in[j], in[j + 1], i8{1, 9, 3, 11, 5, 13, 7, 15});
    }
    for (int j = 0; j < 8; j += 4)
        for (int k = 0; k < 2; ++k) {
            b[j + k] = __builtin_shuffle(a[j + k], a[j + k + 2], i8{0, 1, 8, 9, 4, 5, 12, 13});
            b[j + k + 2] =
                __builtin_shuffle(a[j + k], a[j + k + 2], i8{2, 3, 10, 11, 6, 7, 14, 15});
        }
    for (int k = 0; k < 4; ++k) {
        out[k] = __builtin_shuffle(b[k], b[k + 4], i8{0, 1, 2, 3, 8, 9, 10, 11});
        out[k + 4] = __builtin_shuffle(b[k], b[k + 4], i8{4, 5, 6, 7, 12, 13, 14, 15});
    }
}
/// The first n (1 to 8) packed xy records (motion vectors); lanes n to 7 read as 0.
BMFR_SIMD_INLINE void loadXy8(const float* p, int n, f8& x, f8& y) {
    f8 a, b;
    if (n == 8) {
        a = load8(p), b = load8(p + 8);
    } else {
        float staged[16] = {};
        std::memcpy(staged, p, sizeof(float) * 2 * size_t(n));
        a = load8(staged), b = load8(staged + 8);
    }
    x = __builtin_shuffle(a, b, i8{0, 2, 4, 6, 8, 10, 12, 14});
    y = __builtin_shuffle(a, b, i8{1, 3, 5, 7, 9, 11, 13, 15});
}
/// Stores the first n (1 to 8) lanes of x and y as packed xy records.
BMFR_SIMD_INLINE void storeXy8(float* p, int n, f8 x, f8 y) {
    float xy[16];
    for (int l = 0; l < 8; ++l) xy[2 * l] = x[l], xy[2 * l + 1] = y[l];
    std::memcpy(p, xy, sizeof(float) * 2 * size_t(n));
}
/// Stores the first n (1 to 8) records as packed xyz.
BMFR_SIMD_INLINE void storeXyz8(float* p, int n, const f8 v[3]) {
    if (n == 8) return interleave3(v[0], v[1], v[2], p);
    float staged[24];
    interleave3(v[0], v[1], v[2], staged);
    std::memcpy(p, staged, sizeof(float) * 3 * size_t(n));
}
/// Stores the first n (1 to 8) lanes to a float or half plane.
template <class T> BMFR_SIMD_INLINE void storeFirst(T* p, f8 v, int n) {
    if (n == 8) return store8(p, v);
    T staged[8];
    store8(staged, v);
    std::memcpy(p, staged, sizeof(T) * size_t(n));
}
/// The first n (1 to 8) lanes of a float or half plane; lanes n to 7 read as 0.
template <class T> BMFR_SIMD_INLINE f8 loadFirst(const T* p, int n) {
    if (n == 8) return load8(p);
    T staged[8] = {};
    std::memcpy(staged, p, sizeof(T) * size_t(n));
    return load8(staged);
}
/// The low byte of the first n (1 to 8) lanes, as n bytes.
BMFR_SIMD_INLINE void storeBytes(uint8_t* p, i8 v, int n) {
    typedef uint8_t u8x32 __attribute__((vector_size(32)));
    const u8x32 low =
        __builtin_shuffle(reinterpret_cast<const u8x32&>(v), u8x32{0, 4, 8, 12, 16, 20, 24, 28});
    if (n == 8) // the common case as one fixed-size store, not a variable-length copy
        std::memcpy(p, &low, 8);
    else
        std::memcpy(p, &low, size_t(n));
}
/// n (1 to 8) bytes as the first n lanes; lanes n to 7 read as 0.
BMFR_SIMD_INLINE i8 loadBytes(const uint8_t* p, int n) {
    typedef uint8_t bytes8 __attribute__((vector_size(8)));
    bytes8 b = {};
    if (n == 8) // the common case as one fixed-size load, not a variable-length copy
        std::memcpy(&b, p, 8);
    else
        std::memcpy(&b, p, size_t(n));
    return __builtin_convertvector(b, i8); // one zero-extending load (vpmovzxbd) on AVX2
}
/// base[index[l]] for each lane, of a float or half plane.
template <class T> BMFR_SIMD_INLINE f8 gather8(const T* base, i8 index) {
    T lanes[8];
    for (int l = 0; l < 8; ++l) lanes[l] = base[index[l]];
    return load8(lanes);
}
/// bmfr::luminance of a vector of colours, in its order of operations (bit for bit where
/// multiply-adds are not contracted).
template <class V> BMFR_SIMD_INLINE V luminanceOf(const V c[3]) {
    return (0.2126f * c[0] + 0.7152f * c[1]) + 0.0722f * c[2];
}
BMFR_SIMD_INLINE f8 luminance8(const f8 c[3]) {
    return luminanceOf(c);
}
/// Unnormalised YCoCg of bmfr::rgbToYCoCg for eight pixels, and back, with the same roundings.
BMFR_SIMD_INLINE void rgbToYCoCg8(const f8 c[3], f8 out[3]) {
    out[0] = (c[0] + 2.0f * c[1]) + c[2];
    out[1] = 2.0f * c[0] - 2.0f * c[2];
    out[2] = (2.0f * c[1] - c[0]) - c[2];
}
BMFR_SIMD_INLINE void yCoCgToRgb8(const f8 c[3], f8 out[3]) {
    out[0] = 0.25f * ((c[0] + c[1]) - c[2]);
    out[1] = 0.25f * (c[0] + c[2]);
    out[2] = 0.25f * ((c[0] - c[1]) - c[2]);
}

template <class V> BMFR_SIMD_INLINE V splat(float a) {
    // Lane by lane: GCC 12 builds an inlined f8{a, a, ...} from eight inserts in target clones,
    // where this loop becomes one broadcast.
    V v{};
    for (int l = 0; l < kLanesOf<V>; ++l) v[l] = a;
    return v;
}
BMFR_SIMD_INLINE f8 splat8(float a) {
    return splat<f8>(a);
}
/// Stores the first n (1 to the lane count) lanes.
template <class V> BMFR_SIMD_INLINE void storeFirstLanes(float* p, V v, int n) {
    if (n == kLanesOf<V>) {
        std::memcpy(p, &v, sizeof v);
        return;
    }
    float staged[kLanesOf<V>];
    std::memcpy(staged, &v, sizeof v);
    std::memcpy(p, staged, sizeof(float) * size_t(n));
}
/// |v| per lane (the sign bit cleared).
template <class V> BMFR_SIMD_INLINE V absOf(V v) {
    return V(IntOf<V>(v) & 0x7fffffff);
}
BMFR_SIMD_INLINE f8 abs8(f8 v) {
    return absOf(v);
}
template <class V> BMFR_SIMD_INLINE V minOf(V a, V b) {
    return b < a ? b : a;
}
template <class V> BMFR_SIMD_INLINE V maxOf(V a, V b) {
    return a < b ? b : a;
}
BMFR_SIMD_INLINE f8 min8(f8 a, f8 b) {
    return minOf(a, b);
}
BMFR_SIMD_INLINE f8 max8(f8 a, f8 b) {
    return maxOf(a, b);
}
/// log2(e), for exponentials taken as powers of two.
constexpr float kLog2E = 1.44269504088896341f;
/// The bounds of exp8 below: expf turns subnormal under the first; the second is Cephes'.
constexpr float kExpLow = -87.33654f, kExpHigh = 88.37626f;

/// e^x for kExpLow <= x <= kExpHigh (Cephes' expf: x = n ln 2 + r, a degree-6 polynomial in r,
/// then n added to the exponent); exp8 and expNonPositive handle the rest.
template <class V> BMFR_SIMD_INLINE V expInRange(V x) {
    using I = IntOf<V>;
    // n, x / ln 2 to the nearest integer, by adding 1.5 2^23 + 127: the sum's ulp is 1, and its
    // low mantissa bits hold n + 127, the exponent bits of 2^n, for the shift below. (Cephes
    // floors x / ln 2 + 1/2: the same n except within a rounding of a half.)
    constexpr float kShift = 12582912.0f + 127.0f;
    const V t = x * kLog2E + kShift;
    const V n = t - kShift;
    const V r = (x - n * 0.693359375f) - n * -2.12194440e-4f;
    V p = 1.9875691500e-4f * r + 1.3981999507e-3f;
    p = p * r + 8.3334519073e-3f;
    p = p * r + 4.1665795894e-2f;
    p = p * r + 1.6666665459e-1f;
    p = p * r + 5.0000001201e-1f;
    const V y = (p * (r * r) + r) + 1.0f;
    I bits;
    std::memcpy(&bits, &t, sizeof bits);
    bits <<= 23;
    V scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return y * scale;
}
/// e^x per lane, within 2 ulp of std::exp from kExpLow to kExpHigh; 0 below, +inf above (where
/// expf is subnormal, or finite up to 88.72), NaN stays NaN.
BMFR_SIMD_INLINE f8 exp8(f8 x) {
    const f8 lo = splat8(kExpLow), hi = splat8(kExpHigh);
    f8 e = expInRange(min8(max8(x, lo), hi));
    e = x < lo ? f8{} : e;
    e = x > hi ? splat8(__builtin_inff()) : e;
    return x == x ? e : x;
}
/// exp8 of lanes known to be <= 0 and not NaN (edge-stopping weights), without the checks
/// those lanes never need.
template <class V> BMFR_SIMD_INLINE V expNonPositive(V x) {
    const V lo = splat<V>(kExpLow);
    const V e = expInRange(maxOf(x, lo));
    return x < lo ? V{} : e;
}
BMFR_SIMD_INLINE f8 expNonPositive8(f8 x) {
    return expNonPositive(x);
}
/// maxOf as one vmaxps on the AVX2 and AVX-512 paths of GCC builds (b where a < b, else a: NaN
/// and signed zeros alike), where GCC 12 makes maxOf a compare and a blend; max(0, x) is
/// maxOn<kIsa>(V{}, x).
template <cpu::Isa kIsa, class V> BMFR_SIMD_INLINE V maxOn(V a, V b) {
    if constexpr (BMFR_SIMD_F16C && kIsa >= cpu::Isa::Avx2) {
        V r;
        asm("vmaxps %2, %1, %0" : "=v"(r) : "v"(b), "vm"(a));
        return r;
    } else {
        return maxOf(a, b);
    }
}
/// 2^u per lane of u[0 .. n) (n <= 8), in place, u[skip] left alone; u <= 0 (not NaN; -inf
/// included), clamped at -126, so that the result is at least 2^-126. 2^round(u) times a
/// polynomial of u - round(u) of degree kDegree: 5 (relative error below 2.4e-7 there) or 3
/// (below 7.5e-5, two multiply-adds fewer); each step taken for every vector in turn, so that
/// the n dependency chains interleave. Sixteen lanes (the AVX-512 path) round with vrndscaleps
/// and scale with vscalefps (inline assembly, as F16cHalf's): nine instructions at degree 5
/// where expNonPositive takes seventeen; eight lanes round by adding 1.5 2^23 + 127, whose low
/// mantissa bits are then 2^round(u)'s exponent bits (eleven).
template <int kDegree = 5, class V>
BMFR_SIMD_INLINE void exp2NonPositiveRows(V* u, int n, int skip) {
    static_assert(kDegree == 3 || kDegree == 5);
    constexpr bool kScalef = BMFR_SIMD_F16C && kLanesOf<V> == 16;
    constexpr float kShift = 12582912.0f + 127.0f;
    V rounded[8], p[8];
#pragma GCC unroll 8
    for (int t = 0; t < n; ++t) {
        if (t == skip) continue;
        if constexpr (kScalef) {
            u[t] = maxOn<cpu::Isa::Avx512>(u[t], splat<V>(-126.0f));
            asm("vrndscaleps $8, %1, %0" : "=v"(rounded[t]) : "v"(u[t])); // nearest even
            u[t] -= rounded[t];
        } else {
            u[t] = maxOf(u[t], splat<V>(-126.0f));
            rounded[t] = u[t] + kShift; // n + 127 in the low bits
            u[t] -= rounded[t] - kShift;
        }
    }
    // Relative minimax fits of 2^f on [-1/2, 1/2], lowest power first.
    static constexpr float c5[6] = {1.000000119f,    6.931469440e-1f, 2.402212024e-1f,
                                    5.550713092e-2f, 9.675540961e-3f, 1.327647129e-3f};
    static constexpr float c3[4] = {9.999281168e-1f, 6.932609677e-1f, 2.426107526e-1f,
                                    5.517140776e-2f};
    constexpr const float* c = kDegree == 5 ? c5 : c3;
#pragma GCC unroll 8
    for (int t = 0; t < n; ++t)
        if (t != skip) p[t] = c[kDegree] * u[t] + c[kDegree - 1];
#pragma GCC unroll 4
    for (int k = kDegree - 2; k >= 0; --k)
#pragma GCC unroll 8
        for (int t = 0; t < n; ++t)
            if (t != skip) p[t] = p[t] * u[t] + c[k];
#pragma GCC unroll 8
    for (int t = 0; t < n; ++t) {
        if (t == skip) continue;
        if constexpr (kScalef) {
            asm("vscalefps %2, %1, %0" : "=v"(u[t]) : "v"(p[t]), "v"(rounded[t]));
        } else {
            const V scale = V(IntOf<V>(rounded[t]) << 23);
            u[t] = p[t] * scale;
        }
    }
}

/// Sum of the eight lanes, as a fixed tree (repeatable).
BMFR_SIMD_INLINE float hsum8(f8 v) {
    return ((v[0] + v[4]) + (v[1] + v[5])) + ((v[2] + v[6]) + (v[3] + v[7]));
}
BMFR_SIMD_INLINE float hmin8(f8 v) {
    float m = v[0];
    for (int i = 1; i < 8; ++i) m = v[i] < m ? v[i] : m;
    return m;
}
BMFR_SIMD_INLINE float hmax8(f8 v) {
    float m = v[0];
    for (int i = 1; i < 8; ++i) m = m < v[i] ? v[i] : m;
    return m;
}
} // namespace bmfr::simd
