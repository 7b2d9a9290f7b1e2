// One writer per output folder: a run holds an exclusive lock on its output folder for its
// whole life, so that a second run into the same folder fails at once instead of interleaving
// its files with the first's; and a folder a run made is removed again if the run leaves it
// empty (a run that failed before its first output).
#pragma once
#include <string>
#include <vector>

namespace bmfr {

/// The lock file a run keeps in its output folder (it names the run that holds it). Writers
/// that share a folder by design (the parts of one render) each lock a file of their own whose
/// name starts with this.
inline constexpr const char* kOutputLockFile = ".bmfr-lock";

class OutputFolder {
  public:
    /// Creates `directory` (and missing parents) and locks it for `command` (as "bmfr denoise
    /// ..."). Throws bmfr::Error when another process holds it, naming that process, or when
    /// the folder cannot be made or locked; nothing is written then. `lockName` (a file name
    /// starting with kOutputLockFile) lets writers that share the folder lock apart.
    OutputFolder(const std::string& directory, const std::string& command,
                 const std::string& lockName = kOutputLockFile);
    /// Unlocks; removes the folders it made that are empty.
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;
    /// True when this run made the folder (so a failed run leaves no folder behind).
    bool madeHere() const { return !made_.empty(); }

  private:
    void lock(const std::string& command);
    void removeMadeFolders() const;
    std::string directory_, lockPath_;
    std::vector<std::string> made_; ///< the folders made here, deepest first
    int fd_ = -1;
};

/// True when `directory` holds nothing but (possibly) the lock files of OutputFolders.
bool isEmptyOutputFolder(const std::string& directory);

} // namespace bmfr
