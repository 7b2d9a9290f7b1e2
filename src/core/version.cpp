#include <bmfr/version.h>

namespace bmfr {

const char* libraryVersion() {
    return BMFR_VERSION;
}

} // namespace bmfr
