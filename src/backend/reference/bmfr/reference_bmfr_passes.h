// The reference BMFR with the history planes that halfHistory rounds stored as Half, as the CUDA
// backend stores them: for the test that the shared kernels give the same bits from either
// storage (the reference backend itself keeps floats).
#pragma once
#include "filters/bmfr/bmfr_passes.h"
#include <memory>

namespace bmfr::reference {

/// Needs halfHistory on; allocate throws otherwise.
std::unique_ptr<BmfrPasses> makeBmfrPassesStoringHalves();

} // namespace bmfr::reference
