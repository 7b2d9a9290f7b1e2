// Intel Open Image Denoise as a peer method: its `RT` filter on colour, albedo and normal, one
// frame at a time, behind bmfr::Filter, so that `bmfr peer oidn` writes what `bmfr denoise`
// writes and `bmfr eval` scores it beside the filters. OIDN is single-frame: it keeps no history.
#pragma once
#include <bmfr/filter.h>
#include <memory>
#include <string>
#include <vector>

namespace bmfr::oidn {

struct PeerSettings {
    /// fast | balanced | high: OIDN's quality (OIDN_QUALITY_*); default high, OIDN's own.
    std::string quality = "high";
    /// none | fast | accurate, as Blender names them: none passes albedo and normal as noise
    /// free (cleanAux), fast passes them as possibly noisy, accurate denoises them first with
    /// filters of their own and then passes them as noise free. Default accurate, Blender's.
    std::string prefilter = "accurate";
    int threads = 0;                 ///< OIDN's worker threads, [0, 1024]; 0 = every core
    std::string library;             ///< libOpenImageDenoise.so.2; empty = libraryCandidates()
    bool colorIsDemodulated = false; ///< the sequence's colour is divided by albedo
};

std::vector<std::string> qualityNames();   ///< fast, balanced, high
std::vector<std::string> prefilterNames(); ///< none, fast, accurate

struct Peer {
    std::unique_ptr<Filter> filter;
    /// What runs, for reports: "OIDN 2.5.1, RT filter, CPU device (2 threads), quality high,
    /// prefilter accurate".
    std::string description;
    int threads = 0; ///< the worker threads OIDN's device runs
};

/// The peer, its OIDN device made and committed. Throws bmfr::Error when OIDN cannot be loaded
/// (saying how to install it), is older than 2.0, or refuses a setting or the device.
Peer makePeer(const PeerSettings& settings);

} // namespace bmfr::oidn
