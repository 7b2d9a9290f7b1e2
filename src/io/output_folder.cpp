#include "io/output_folder.h"
#include <bmfr/error.h>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

/// What the holder of a lock file wrote into it ("pid 1234: bmfr denoise ..."), or "". A
/// holder that has only just taken the lock gets up to 100 ms to write it.
std::string holderOf(int fd) {
    std::string s;
    for (int attempt = 0; attempt < 10 && s.empty(); ++attempt) {
        if (attempt) ::usleep(10000);
        char text[512] = {};
        const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
        s.assign(text, n > 0 ? size_t(n) : 0);
    }
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

} // namespace

OutputFolder::OutputFolder(const std::string& directory, const std::string& command,
                           const std::string& lockName)
    : directory_(directory), lockPath_((fs::path(directory) / lockName).string()) {
    std::error_code ec;
    fs::path start = fs::absolute(directory, ec).lexically_normal();
    if (!start.has_filename()) start = start.parent_path(); // "out/"
    for (fs::path p = start; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        made_.push_back(p.string());
        if (p == p.parent_path()) break;
    }
    fs::create_directories(directory, ec);
    if (ec || !fs::is_directory(directory)) {
        removeMadeFolders();
        throw Error("cannot make the output folder " + directory + ": " +
                    (ec ? ec.message() : std::string("a file of that name exists")));
    }
    try {
        lock(command);
    } catch (...) {
        removeMadeFolders();
        throw;
    }
}

void OutputFolder::lock(const std::string& command) {
    // The holder unlinks the lock file before it unlocks: a file locked after that is stale,
    // and the lock is taken again on the file now at the path.
    while (true) {
        fd_ = ::open(lockPath_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd_ < 0)
            throw Error("cannot lock the output folder " + directory_ + ": " +
                        std::strerror(errno));
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            const int err = errno;
            const std::string holder = holderOf(fd_);
            ::close(fd_);
            fd_ = -1;
            if (err == EWOULDBLOCK)
                throw Error("another run is writing to " + directory_ + " (" +
                            (holder.empty() ? "it has not said which" : holder) +
                            "); wait for it to finish or give another output folder");
            throw Error("cannot lock the output folder " + directory_ + ": " + std::strerror(err));
        }
        struct stat held {
        }, named{};
        if (::fstat(fd_, &held) == 0 && ::stat(lockPath_.c_str(), &named) == 0 &&
            held.st_ino == named.st_ino && held.st_dev == named.st_dev)
            break;
        ::close(fd_);
    }
    const std::string text = "pid " + std::to_string(::getpid()) + ": " + command + "\n";
    if (::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, text.data(), text.size(), 0) < 0) {
        // The lock holds without the note: only the message a second run prints is poorer.
    }
}

OutputFolder::~OutputFolder() {
    // Only its own lock file: a folder removed and made again during the run has another's.
    struct stat held {
    }, named{};
    if (::fstat(fd_, &held) == 0 && ::stat(lockPath_.c_str(), &named) == 0 &&
        held.st_ino == named.st_ino && held.st_dev == named.st_dev)
        ::unlink(lockPath_.c_str());
    ::close(fd_);
    removeMadeFolders();
}

void OutputFolder::removeMadeFolders() const {
    std::error_code ec;
    for (const std::string& dir : made_)
        if (fs::is_directory(dir, ec) && fs::is_empty(dir, ec)) fs::remove(dir, ec);
}

bool isEmptyOutputFolder(const std::string& directory) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(directory, ec))
        if (e.path().filename().string().rfind(kOutputLockFile, 0) != 0) return false;
    return true;
}

} // namespace bmfr
