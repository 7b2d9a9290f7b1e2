#include "io/atomic_file.h"
#include <bmfr/error.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace bmfr {

std::string temporaryPathFor(const std::string& path) {
    return path + ".part";
}

void commitTemporary(const std::string& temporary, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        throw Error("cannot write " + path + ": " + ec.message());
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
        std::remove(tmp.c_str());
        throw Error("cannot write " + path + ": " + std::strerror(written ? errno : err));
    }
    commitTemporary(tmp, path);
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    writeFileAtomically(path, bytes.data(), bytes.size());
}

} // namespace bmfr
