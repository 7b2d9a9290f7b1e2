// Text for a POSIX shell: a word that needs no quoting stays as it is, any other goes in single
// quotes (a ' inside as '\''). For commands we start (ffmpeg) and command lines we report.
#pragma once
#include <string>

namespace bmfr {

inline std::string shellQuote(const std::string& s) {
    const bool plain =
        !s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789-_=.,:/+@%") == std::string::npos;
    if (plain) return s;
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

} // namespace bmfr
