#include <bmfr/error.h>
#include <bmfr/features.h>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace bmfr {

std::vector<Feature> defaultFeatures() {
    return parseFeatures("1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,p.y^2,p.z^2");
}

namespace {

std::string trim(const std::string& s) {
    size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

} // namespace

namespace {

/// Token names of the built-in sources, shared by parsing and formatting.
struct NamedSource {
    const char* name;
    FeatureSource source;
    bool scaled;
};
constexpr NamedSource kNamedSources[] = {
    {"1", FeatureSource::One, false},        {"n.x", FeatureSource::NormalX, false},
    {"n.y", FeatureSource::NormalY, false},  {"n.z", FeatureSource::NormalZ, false},
    {"p.x", FeatureSource::PositionX, true}, {"p.y", FeatureSource::PositionY, true},
    {"p.z", FeatureSource::PositionZ, true},
};

} // namespace

std::vector<Feature> parseFeatures(const std::string& list) {
    std::vector<Feature> out;
    std::stringstream ss(list);
    std::string token;
    while (std::getline(ss, token, ',')) {
        token = trim(token);
        Feature f;
        std::string name = token;
        size_t caret = token.find('^');
        if (caret != std::string::npos) {
            name = token.substr(0, caret);
            std::string e = token.substr(caret + 1);
            char* end = nullptr;
            f.exponent = std::strtof(e.c_str(), &end);
            if (e.empty() || *end != '\0' || !(f.exponent > 0.0f && f.exponent <= 8.0f))
                throw Error("feature '" + token + "': exponent must be a number in (0, 8]");
        }
        bool known = false;
        for (const NamedSource& n : kNamedSources)
            if (name == n.name) f.source = n.source, f.scaled = n.scaled, known = true;
        if (!known && name.rfind("extra", 0) == 0 && name.size() > 5 &&
            name.find_first_not_of("0123456789", 5) == std::string::npos) {
            f.source = FeatureSource::Extra;
            f.extraIndex = std::atoi(name.c_str() + 5);
            if (f.extraIndex > 15) throw Error("feature '" + token + "': extra index above 15");
            known = true;
        }
        if (!known)
            throw Error("unknown feature '" + token +
                        "' (expected 1, n.x, n.y, n.z, p.x, p.y, p.z or extraK, optionally ^E)");
        if (f.source == FeatureSource::One && f.exponent != 1.0f)
            throw Error("feature '" + token + "': the constant takes no exponent");
        out.push_back(f);
    }
    if (out.empty()) throw Error("empty feature list");
    return out;
}

std::string formatFeatures(const std::vector<Feature>& features) {
    std::string s;
    for (const Feature& f : features) {
        if (!s.empty()) s += ',';
        if (f.source == FeatureSource::Extra) {
            s += "extra";
            s += std::to_string(f.extraIndex);
        }
        for (const NamedSource& n : kNamedSources)
            if (n.source == f.source) s += n.name;
        if (f.exponent != 1.0f) {
            std::ostringstream e;
            e << f.exponent;
            s += '^';
            s += e.str();
        }
    }
    return s;
}

} // namespace bmfr
