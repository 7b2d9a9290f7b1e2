#include "core/closest_name.h"
#include <algorithm>
#include <cctype>

namespace bmfr {

namespace {

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

std::string folded(const std::string& s) {
    std::string r;
    for (const char c : s)
        if (c != '-' && c != '_') r += char(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

} // namespace

std::string closestName(const std::string& given, const std::vector<std::string>& known) {
    const std::string g = folded(given);
    std::string best;
    // A near miss: two edits, or one for names so short that two would reach anything.
    size_t bestDistance = g.size() <= 3 ? 2 : 3;
    for (const std::string& k : known)
        if (const size_t d = editDistance(g, folded(k)); d < bestDistance) {
            best = k;
            bestDistance = d;
        }
    return best;
}

std::string didYouMean(const std::string& given, const std::vector<std::string>& known,
                       const std::string& prefix) {
    const std::string best = closestName(given, known);
    return best.empty() ? std::string() : " (did you mean '" + prefix + best + "'?)";
}

} // namespace bmfr
