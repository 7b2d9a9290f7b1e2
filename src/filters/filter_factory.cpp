#include <bmfr/denoiser.h>
#include <bmfr/error.h>
#include <bmfr/svgf.h>

namespace bmfr {

std::unique_ptr<Filter> makeFilter(const std::string& name, const Settings& bmfr,
                                   const SvgfSettings& svgf) {
    if (name == "bmfr") return std::make_unique<Denoiser>(bmfr);
    if (name == "svgf") return std::make_unique<SvgfDenoiser>(svgf);
    throw Error("unknown filter '" + name + "' (expected bmfr or svgf)");
}

} // namespace bmfr
