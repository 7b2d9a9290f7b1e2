// Marks what the bmfr library exports: with -DBUILD_SHARED_LIBS=ON only these symbols are
// visible outside libbmfr.so (everything else is built with hidden visibility).
#pragma once

#if defined(_WIN32)
#define BMFR_API
#elif defined(__GNUC__) || defined(__clang__)
#define BMFR_API __attribute__((visibility("default")))
#else
#define BMFR_API
#endif
