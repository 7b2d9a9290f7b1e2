// Errors raised by the library: every failure says what was wrong and where.
#pragma once
#include <stdexcept>
#include <string>

namespace bmfr {

/// Thrown for invalid input (sizes, non-finite matrices, unreadable files...).
/// The message names the offending item (file, frame, buffer, pixel count).
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

} // namespace bmfr
