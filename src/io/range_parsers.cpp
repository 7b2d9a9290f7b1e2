#include "io/range_parsers.h"
#include <bmfr/error.h>
#include <cstdio>
#include <fmt/core.h>

namespace bmfr {

void checkFrameRangeSyntax(const std::string& spec) {
    if (spec.empty()) return;
    const size_t colon = spec.find(':');
    if (colon == std::string::npos)
        throw Error("frame range expects A:B, A: or :B, got '" + spec + "'");
    const std::string a = spec.substr(0, colon), b = spec.substr(colon + 1);
    for (const std::string& s : {a, b})
        if (s.find_first_not_of("0123456789") != std::string::npos)
            throw Error("frame range: '" + s + "' is not a frame number");
    // Longer numbers than a frame count can be are left to the sequence's range check.
    if (!a.empty() && !b.empty() && a.size() <= 9 && b.size() <= 9 && std::stol(a) >= std::stol(b))
        throw Error("frame range " + spec +
                    " is empty: A:B runs frames A to B-1, so B must exceed A");
}

std::pair<int, int> parseFrameRange(const std::string& spec, int count) {
    checkFrameRangeSyntax(spec);
    if (spec.empty()) return {0, count};
    const size_t colon = spec.find(':');
    auto num = [&](const std::string& s, int dflt) {
        if (s.empty()) return dflt;
        if (s.size() > 9 || std::stol(s) > count)
            throw Error(fmt::format("frame range {}: the sequence has frames 0:{}", spec, count));
        return int(std::stol(s));
    };
    int a = num(spec.substr(0, colon), 0), b = num(spec.substr(colon + 1), count);
    if (a >= b || b > count)
        throw Error(fmt::format("frame range {}: the sequence has frames 0:{}", spec, count));
    return {a, b};
}

std::array<int, 4> parseCrop(const std::string& s) {
    std::array<long, 4> v{};
    char tail = 0;
    if (std::sscanf(s.c_str(), "%ld,%ld,%ld,%ld%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4)
        throw Error("--crop expects x,y,w,h, got '" + s + "'");
    std::array<int, 4> c{};
    for (size_t k = 0; k < 4; ++k) {
        if (v[k] < 0 || v[k] > 65536)
            throw Error("--crop " + s + ": each of x,y,w,h must be in [0, 65536]");
        c[k] = int(v[k]);
    }
    return c;
}

std::map<std::string, std::string> parseLayerMap(const std::vector<std::string>& items) {
    std::map<std::string, std::string> layers;
    for (const std::string& c : items) {
        const size_t eq = c.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == c.size())
            throw Error("--channel '" + c +
                        "': expected BUFFER=LAYER, as albedo=ViewLayer.DiffCol");
        layers[c.substr(0, eq)] = c.substr(eq + 1);
    }
    return layers;
}

} // namespace bmfr
