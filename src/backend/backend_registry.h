// The backends' passes by filter: the one place that maps a Backend to its implementation.
// Each backend defines makePasses<S>() for the settings S of every filter it runs.
#pragma once
#include "filters/bmfr/bmfr_passes.h"
#include "filters/mara2017/mara_passes.h"
#include "filters/svgf/svgf_passes.h"
#include "filters/walr/walr_passes.h"
#include <memory>

namespace bmfr {

namespace reference {
template <class S> std::unique_ptr<PassesFor<S>> makePasses();
} // namespace reference
namespace cpu {
template <class S> std::unique_ptr<PassesFor<S>> makePasses();
} // namespace cpu
namespace cuda {
/// Made with `device` current; every call of the passes makes it current again.
template <class S> std::unique_ptr<PassesFor<S>> makePasses(int device);
} // namespace cuda

/// Throws bmfr::Error when `backend` cannot run here: not built into this library, no CUDA device
/// `cudaDevice`, or a BMFR_CPU_ISA this processor lacks.
void requireBackend(Backend backend, int cudaDevice = 0);

/// The passes of the filter with settings S on `backend` (on GPU `cudaDevice` for cuda). Throws
/// bmfr::Error when the backend is not built into this library or has no such device.
template <class S> std::unique_ptr<PassesFor<S>> makePasses(Backend backend, int cudaDevice = 0);

} // namespace bmfr
