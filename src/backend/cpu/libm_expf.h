// std::exp of floats eight at a time with the C library's bits, for kernels whose reference
// calls it per element (Mara 2017's Gaussian tap weights): a scalar expf per tap cost stage 7 a
// seventh of its time.
#pragma once
#include "backend/cpu/simd.h"
#include <cmath>
#include <cstdint>
#include <cstring>

// glibc 2.28 on, x86-64, GCC: the expf below is its algorithm. Elsewhere callers keep std::exp.
#if BMFR_SIMD_F16C && defined(__GLIBC__) && (__GLIBC__ > 2 || __GLIBC_MINOR__ >= 28)
#define BMFR_LIBM_EXPF 1
#else
#define BMFR_LIBM_EXPF 0
#endif

namespace bmfr::cpu {

/// Whether libmExpf runs on the path kIsa: the paths with AVX2 and FMA, on whose processors
/// glibc's ifunc picks its FMA build of expf (the baseline path may run where it does not). A
/// glibc told otherwise (GLIBC_TUNABLES masking AVX2 or FMA) runs its plain build, whose bits
/// differ at about one float in a billion; Simd.LibmExpfGivesTheCLibrarysBits would show it.
template <Isa kIsa> constexpr bool kHasLibmExpf = bool(BMFR_LIBM_EXPF) && kIsa >= Isa::Avx2;

#if BMFR_LIBM_EXPF
namespace detail {
typedef double d4 __attribute__((vector_size(32)));
typedef uint64_t u64x4 __attribute__((vector_size(32)));

/// a b + c per lane, rounded once.
BMFR_SIMD_INLINE d4 fusedMulAdd(d4 a, d4 b, d4 c) {
    asm("vfmadd213pd %2, %1, %0" : "+v"(a) : "v"(b), "vm"(c));
    return a;
}

/// expf of four lanes, as glibc computes it (sysdeps/ieee754/flt-32/e_expf.c, Szabolcs Nagy's):
/// x 32 / ln 2 = k + r in double, 2^(k/32) from a table, 2^(r/32) a cubic.
BMFR_SIMD_INLINE simd::f4 expf4(simd::f4 x) {
    // 2^(i/32) as doubles, less i << 47 (k's whole part is added to the exponent field).
    static constexpr uint64_t kTable[32] = {
        0x3ff0000000000000, 0x3fefd9b0d3158574, 0x3fefb5586cf9890f, 0x3fef9301d0125b51,
        0x3fef72b83c7d517b, 0x3fef54873168b9aa, 0x3fef387a6e756238, 0x3fef1e9df51fdee1,
        0x3fef06fe0a31b715, 0x3feef1a7373aa9cb, 0x3feedea64c123422, 0x3feece086061892d,
        0x3feebfdad5362a27, 0x3feeb42b569d4f82, 0x3feeab07dd485429, 0x3feea47eb03a5585,
        0x3feea09e667f3bcd, 0x3fee9f75e8ec5f74, 0x3feea11473eb0187, 0x3feea589994cce13,
        0x3feeace5422aa0db, 0x3feeb737b0cdc5e5, 0x3feec49182a3f090, 0x3feed503b23e255d,
        0x3feee89f995ad3ad, 0x3feeff76f2fb5e47, 0x3fef199bdd85529c, 0x3fef3720dcef9069,
        0x3fef5818dcfba487, 0x3fef7c97337b9b5f, 0x3fefa4afa2a490da, 0x3fefd0765b6e4540,
    };
    constexpr double kInvLn2N = 0x1.71547652b82fep+0 * 32, kShift = 0x1.8p+52;
    constexpr double kC0 = 0x1.c6af84b912394p-5 / 32 / 32 / 32,
                     kC1 = 0x1.ebfce50fac4f3p-3 / 32 / 32, kC2 = 0x1.62e42ff0c52d6p-1 / 32;
    const d4 xd = __builtin_convertvector(x, d4);
    // glibc's FMA build fuses z = x 32 / ln 2 into both k + shift and r = z - k (its plain build
    // rounds z first): k, to nearest even, in the low bits of kd.
    d4 kd = fusedMulAdd(d4{} + kInvLn2N, xd, d4{} + kShift);
    u64x4 ki;
    std::memcpy(&ki, &kd, sizeof ki);
    kd -= kShift;
    const d4 r = fusedMulAdd(d4{} + kInvLn2N, xd, -kd);
    u64x4 t;
    for (int l = 0; l < 4; ++l) t[l] = kTable[ki[l] % 32] + (ki[l] << 47);
    d4 s;
    std::memcpy(&s, &t, sizeof s);
    const d4 z = fusedMulAdd(d4{} + kC0, r, d4{} + kC1);
    const d4 y = fusedMulAdd(z, r * r, fusedMulAdd(d4{} + kC2, r, d4{} + 1.0));
    return __builtin_convertvector(y * s, simd::f4);
}
} // namespace detail

/// std::exp of eight lanes x <= 0 with glibc's bits (checked against it at every float from 0
/// to -104, Simd.LibmExpfGivesTheCLibrarysBits), 0 below -103.97 as expf's; NaN lanes give a
/// NaN. Only on the paths where kHasLibmExpf. (From -103.97 to -103.28 glibc returns 2^-149,
/// which its polynomial rounds to as well.)
template <Isa kIsa> BMFR_SIMD_INLINE simd::f8 libmExpf(simd::f8 x) {
    static_assert(kHasLibmExpf<kIsa>);
    const simd::f4 lo = detail::expf4(__builtin_shufflevector(x, x, 0, 1, 2, 3)),
                   hi = detail::expf4(__builtin_shufflevector(x, x, 4, 5, 6, 7));
    const simd::f8 e = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
    return x < -0x1.9fe368p6f ? simd::f8{} : e;
}
#endif

/// std::exp(x[k]) for k < n into out, eight at a time where kHasLibmExpf (x and out then hold
/// n rounded up to eight floats).
template <Isa kIsa> BMFR_SIMD_INLINE void expfRun(const float* x, int n, float* out) {
#if BMFR_LIBM_EXPF
    if constexpr (kHasLibmExpf<kIsa>) {
        for (int k = 0; k < n; k += 8) simd::store8(out + k, libmExpf<kIsa>(simd::load8(x + k)));
        return;
    }
#endif
    for (int k = 0; k < n; ++k) out[k] = std::exp(x[k]);
}

/// expfRun on the active path, for the tests.
void expfOnActivePath(const float* x, int n, float* out);

} // namespace bmfr::cpu
