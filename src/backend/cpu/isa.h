// Which instruction-set path the CPU backend's hot passes take. Each is compiled three times
// (baseline x86-64, AVX2 + FMA + F16C, AVX-512) and dispatched here at run time: by default the
// best the processor has; BMFR_CPU_ISA=baseline|avx2|avx512 in the environment, or
// setActiveIsa, picks a lower one (tests run every path the machine supports).
#pragma once
#include <string>
#include <vector>

namespace bmfr::cpu {

enum class Isa : int {
    Baseline = 0, ///< x86-64 (SSE2); also every non-x86 build
    Avx2 = 1,     ///< x86-64-v3: AVX2, FMA, F16C
    Avx512 = 2    ///< x86-64-v4: AVX-512 F, BW, CD, DQ, VL
};

/// "baseline", "avx2" or "avx512".
const char* isaName(Isa isa);
/// The best path this processor (and this build) supports.
Isa bestIsa();
/// The paths this processor supports, lowest first.
std::vector<Isa> supportedIsas();
/// The path the passes take now: bestIsa(), lowered by BMFR_CPU_ISA or setActiveIsa.
Isa activeIsa();
/// Makes the passes take `isa`. Throws bmfr::Error when the processor lacks it.
void setActiveIsa(Isa isa);
/// Parses "baseline", "avx2" or "avx512"; throws bmfr::Error naming the accepted values.
Isa parseIsa(const std::string& name);

} // namespace bmfr::cpu
