// Every output file goes through here: written to a temporary file beside it, flushed and
// checked, then renamed over the target. A failure (a full disk, a missing folder, no
// permission) throws bmfr::Error with the path and the reason and leaves no partial file.
#pragma once
#include <string>

namespace bmfr {

void writeFileAtomically(const std::string& path, const std::string& bytes);
void writeFileAtomically(const std::string& path, const void* data, size_t size);

/// A temporary name beside `path`, unique to this process and call, for writers that produce
/// the file themselves ("<path>.<pid>-<n>.part").
std::string temporaryPathFor(const std::string& path);
/// Renames a finished temporary file over `path`; on failure removes it and throws bmfr::Error
/// with the rename's reason.
void commitTemporary(const std::string& temporary, const std::string& path);

} // namespace bmfr
