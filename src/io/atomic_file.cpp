#include "io/atomic_file.h"
#include <atomic>
#include <bmfr/error.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace bmfr {

std::string temporaryPathFor(const std::string& path) {
    // Unique per process and per call: two writers of one path never share a temporary file.
    static std::atomic<unsigned long> counter{0};
    return path + "." + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".part";
}

void commitTemporary(const std::string& temporary, const std::string& path) {
    std::error_code renamed;
    std::filesystem::rename(temporary, path, renamed);
    if (renamed) {
        std::error_code ignored; // the rename's reason is the one to report
        std::filesystem::remove(temporary, ignored);
        throw Error("cannot write " + path + ": " + renamed.message());
    }
}

void writeFileAtomically(const std::string& path, const void* data, size_t size) {
    const std::string tmp = temporaryPathFor(path);
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw Error("cannot write " + path + ": " + std::strerror(errno));
    const bool written =
        std::fwrite(data, 1, size, f) == size && std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
    const int err = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) {
        const int reason = written ? errno : err; // before remove() can change errno
        std::remove(tmp.c_str());
        throw Error("cannot write " + path + ": " + std::strerror(reason));
    }
    commitTemporary(tmp, path);
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    writeFileAtomically(path, bytes.data(), bytes.size());
}

} // namespace bmfr
