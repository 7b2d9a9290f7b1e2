#include "backend/cpu/isa.h"
#include <atomic>
#include <bmfr/error.h>
#include <cstdlib>

namespace bmfr::cpu {

namespace {

Isa detect() {
#if BMFR_SIMD_SINGLE_PATH
    return Isa::Baseline; // the other paths are not compiled (simd.h)
#elif defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4")) return Isa::Avx512;
    if (__builtin_cpu_supports("x86-64-v3")) return Isa::Avx2;
#endif
    return Isa::Baseline;
}

/// The environment's choice, checked once: an unknown or unsupported name is an error the
/// first time a pass asks, not a silent fallback.
Isa initial() {
    const char* env = std::getenv("BMFR_CPU_ISA");
    if (!env || !*env) return detect();
    const Isa want = parseIsa(env);
    if (int(want) > int(detect()))
        throw Error(std::string("BMFR_CPU_ISA=") + env + ": this processor supports at most " +
                    isaName(detect()));
    return want;
}

std::atomic<int>& active() {
    static std::atomic<int> isa{int(initial())};
    return isa;
}

} // namespace

const char* isaName(Isa isa) {
    switch (isa) {
    case Isa::Avx512:
        return "avx512";
    case Isa::Avx2:
        return "avx2";
    default:
        return "baseline";
    }
}

Isa bestIsa() {
    static const Isa best = detect();
    return best;
}

std::vector<Isa> supportedIsas() {
    std::vector<Isa> out;
    for (int k = 0; k <= int(bestIsa()); ++k) out.push_back(Isa(k));
    return out;
}

Isa activeIsa() {
    return Isa(active().load(std::memory_order_relaxed));
}

void setActiveIsa(Isa isa) {
    if (int(isa) > int(bestIsa()))
        throw Error(std::string("CPU path ") + isaName(isa) + ": this processor supports at most " +
                    isaName(bestIsa()));
    active().store(int(isa), std::memory_order_relaxed);
}

Isa parseIsa(const std::string& name) {
    for (Isa isa : {Isa::Baseline, Isa::Avx2, Isa::Avx512})
        if (name == isaName(isa)) return isa;
    throw Error("unknown CPU path '" + name + "' (use baseline, avx2 or avx512)");
}

} // namespace bmfr::cpu
