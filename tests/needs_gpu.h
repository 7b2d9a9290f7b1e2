// The fixture of the tests that need a CUDA device: reported skipped, with the driver's reason,
// where there is none.
#pragma once
#include "backend/cuda/cuda_device.h"
#include <bmfr/error.h>
#include <gtest/gtest.h>

namespace bmfr::test {

struct NeedsGpu : ::testing::Test {
    void SetUp() override {
        try {
            cuda::requireDevice();
        } catch (const Error& e) {
            GTEST_SKIP() << e.what();
        }
    }
};

} // namespace bmfr::test
