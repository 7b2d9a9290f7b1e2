// The reference backend's QR: solveHouseholder built for the CPU path isa.h allows (BMFR_CPU_ISA).
#pragma once
#include "backend/cpu/isa.h"
#include "filters/bmfr/householder_qr.h"

namespace bmfr::reference {

using HouseholderSolver = int (*)(float* columns, int featureCount, int rows, float* coeffs);

inline HouseholderSolver householderSolver() {
    return cpu::activeIsa() >= cpu::Isa::Avx2 ? solveHouseholderAvx2 : solveHouseholder;
}

} // namespace bmfr::reference
