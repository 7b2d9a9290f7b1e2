// Where filters run and what they share: the backend and one pool of worker threads. Filters
// made from one Device share its threads, so an engine with several views or a tool with several
// filters does not oversubscribe the cores; each filter keeps its own history and buffers.
#pragma once
#include <bmfr/api.h>
#include <bmfr/filter.h>
#include <bmfr/temporal_settings.h>
#include <memory>
#include <string>

namespace bmfr {

class BMFR_API Device {
  public:
    /// `threads`: worker threads, 0 = all cores. `cudaDevice`: Backend::Cuda's GPU, numbered as
    /// cudaSetDevice numbers them (0 for the other backends); the library makes it current only
    /// while it works and then restores the caller's. Throws bmfr::Error when `backend` is not
    /// built into this library or has no such device.
    explicit Device(Backend backend = Backend::Cpu, int threads = 0, int cudaDevice = 0);
    ~Device();
    /// Copies share the threads and the reservation.
    Device(const Device&);
    Device& operator=(const Device&);

    Backend backend() const;
    int threadCount() const;
    int cudaDevice() const;
    /// Makes filter `name` ("bmfr", "svgf", ...) on this device, with its defaults overridden
    /// by `values` (as bmfr::makeFilter; the backend and threads are the device's, so giving
    /// either is an error). Filters of one device run one at a time: not thread-safe together.
    std::unique_ptr<Filter> makeFilter(const std::string& name,
                                       const SettingValues& values = {}) const;
    /// Filters made from now on size their buffers for maxWidth x maxHeight frames when made, so
    /// that on the host backends their first frame of that size, with packed RGB buffers, allocates
    /// nothing (RGBA or padded rows are copied into buffers made on first use; the cuda backend
    /// may allocate again). reserve(0, 0) drops the reservation. Throws bmfr::Error for a size
    /// below 1 otherwise.
    void reserve(int maxWidth, int maxHeight);
    /// The reserved size, 0 x 0 when none.
    int reservedWidth() const;
    int reservedHeight() const;

    struct State; ///< the library's: the threads and the reservation

  private:
    std::shared_ptr<State> state_;
    friend struct DeviceAccess;
};

} // namespace bmfr
