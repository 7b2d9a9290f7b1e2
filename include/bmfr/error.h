// Errors raised by the library: every failure says what was wrong and where.
#pragma once
#include <bmfr/api.h>
#include <stdexcept>
#include <string>
#include <utility>

namespace bmfr {

/// Thrown for invalid input (sizes, non-finite matrices, unreadable files...).
/// The message names the offending item (file, frame, buffer, pixel count).
class BMFR_API Error : public std::runtime_error {
  public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// A setting that cannot be applied, with its parts kept apart so that a front end can name the
/// setting its own way (the CLI as `--block-size 7 is outside [8, 64]`, Python as `block_size`).
class BMFR_API SettingError : public Error {
  public:
    SettingError(const std::string& what, std::string key, std::string value, std::string problem)
        : Error(what), key_(std::move(key)), value_(std::move(value)),
          problem_(std::move(problem)) {}
    const std::string& key() const { return key_; }         ///< the settings-table key
    const std::string& value() const { return value_; }     ///< the value as given or parsed
    const std::string& problem() const { return problem_; } ///< e.g. "is outside [8, 64]"

  private:
    std::string key_, value_, problem_;
};

} // namespace bmfr
