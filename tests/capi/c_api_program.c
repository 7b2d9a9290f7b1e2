/* The C API from C (built with -std=c99 -pedantic -Wall -Wextra -Werror): a device and each of
 * the four filters denoise frames of a moving wall given as RGBA16F colour and albedo,
 * octahedral normals, view depth and motion in UV units with y up; errors arrive through the
 * callback with their codes. Prints "c api program passed" and exits 0 when every check holds. */
#include <bmfr/bmfr.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

enum { W = 48, H = 32, FRAMES = 4 };

static int failures = 0;
static int errorsSeen = 0;
static BMFRError lastCode = BMFR_ERROR_NONE;
static char lastMessage[512];

static void onError(void* user, BMFRError code, const char* message) {
    ++*(int*)user;
    lastCode = code;
    strncpy(lastMessage, message, sizeof lastMessage - 1);
}

static void check(int ok, const char* what) {
    if (!ok) {
        fprintf(stderr, "FAILED: %s (last error %d: %s)\n", what, (int)lastCode, lastMessage);
        ++failures;
    }
}

/* IEEE half bits of a float in [2^-14, 65504] (no rounding needed for this test's values). */
static unsigned short toHalf(float v) {
    int e;
    const float m = frexpf(v, &e); /* v = m 2^e, m in [0.5, 1) */
    return (unsigned short)(((e + 14) << 10) | (int)((m * 2.0f - 1.0f) * 1024.0f));
}

int main(void) {
    static unsigned short color[W * H * 4], albedo[W * H * 4], motion[W * H * 2];
    static float normal[W * H * 2], depth[W * H], output[W * H * 4];
    /* A camera at the origin looking down -z, row-major; NDC y grows downwards. */
    const float vp[16] = {1.2f, 0, 0, 0, 0, -1.6f, 0, 0, 0, 0, -1.002f, -0.2002f, 0, 0, -1, 0};
    const char* filters[4] = {"bmfr", "svgf", "walr", "mara2017"};
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
    bmfrSetDeviceErrorFunction(device, onError, &errorsSeen);
    bmfrSetDeviceInt(device, "threads", 2);
    bmfrCommitDevice(device);
    check(bmfrGetDeviceInt(device, "threads") == 2, "the device has 2 threads");
    check(bmfrGetDeviceInt(device, "type") == BMFR_DEVICE_TYPE_CPU, "the device is a CPU one");
    for (int f = 0; f < 4; ++f) {
        BMFRFilter filter = bmfrNewFilter(device, filters[f]);
        bmfrSetFilterInt(filter, "maxWidth", W);
        bmfrSetFilterInt(filter, "maxHeight", H);
        bmfrSetFilterFloat(filter, "motionScaleX", (float)W);
        bmfrSetFilterFloat(filter, "motionScaleY", (float)H);
        bmfrSetFilterBool(filter, "motionYUp", true);
        bmfrCommitFilter(filter);
        const size_t bytes = bmfrGetFilterMemoryBytes(filter, W, H);
        if (bytes == 0) { /* another allocator (a sanitizer's): the query says so, not a number */
            check(lastCode == BMFR_ERROR_INVALID_OPERATION, "the footprint query's error");
            bmfrGetDeviceError(device, NULL);
            errorsSeen = 0;
        } else {
            check(bytes > (size_t)W * H * 12, "a footprint");
        }
        for (int frame = 0; frame < FRAMES; ++frame) {
            for (int i = 0; i < W * H; ++i) {
                const float noise = (float)((i * 7919 + frame * 104729) % 17) / 17.0f;
                for (int c = 0; c < 3; ++c) {
                    color[4 * i + c] = toHalf(0.25f + 0.5f * noise);
                    albedo[4 * i + c] = toHalf(0.5f);
                }
                color[4 * i + 3] = albedo[4 * i + 3] = toHalf(1.0f);
                normal[2 * i] = normal[2 * i + 1] = 0.0f; /* (0, 0, 1): facing the camera */
                depth[i] = 2.0f;
                motion[2 * i] = toHalf(1.0f / W); /* the wall moves a pixel to the left a frame */
                motion[2 * i + 1] = 0;
            }
            bmfrSetFilterImage(filter, "color", color, BMFR_FORMAT_HALF4, W, H, 0, 0, 0);
            bmfrSetFilterImage(filter, "albedo", albedo, BMFR_FORMAT_HALF4, W, H, 0, 0, 0);
            bmfrSetFilterImage(filter, "normal", normal, BMFR_FORMAT_FLOAT2, W, H, 0, 0, 0);
            bmfrSetFilterImage(filter, "depth", depth, BMFR_FORMAT_FLOAT, W, H, 0, 0, 0);
            bmfrSetFilterImage(filter, "motion", motion, BMFR_FORMAT_HALF2, W, H, 0, 0, 0);
            bmfrSetFilterImage(filter, "output", output, BMFR_FORMAT_FLOAT4, W, H, 0, 0, 0);
            bmfrSetFilterMatrix(filter, "viewProjection", vp);
            bmfrSetFilterInt(filter, "frameIndex", frame);
            bmfrExecuteFilter(filter);
        }
        check(errorsSeen == 0, filters[f]);
        int finite = 1;
        for (int i = 0; i < W * H; ++i)
            for (int c = 0; c < 3; ++c)
                finite = finite && isfinite(output[4 * i + c]) && output[4 * i + c] > 0.05f;
        check(finite, "the output is finite and positive");
        bmfrReleaseFilter(filter);
    }
    /* Errors: through the callback, with their codes, and read once from the device. */
    BMFRFilter filter = bmfrNewFilter(device, "bmfr");
    bmfrExecuteFilter(filter);
    check(errorsSeen == 1 && lastCode == BMFR_ERROR_INVALID_OPERATION, "execute before commit");
    bmfrSetFilterImage(filter, "color", color, (BMFRFormat)5, W, H, 0, 0, 0);
    check(errorsSeen == 2 && lastCode == BMFR_ERROR_INVALID_ARGUMENT, "an unknown format");
    check(strstr(lastMessage, "unknown format 5") != NULL, "the message names the format");
    bmfrSetFilterFloat(filter, "noiseAmplitude", -1.0f);
    bmfrCommitFilter(filter);
    check(errorsSeen == 3 && strstr(lastMessage, "noise") != NULL, "a setting out of range");
    const char* message = NULL;
    check(bmfrGetDeviceError(device, &message) == BMFR_ERROR_INVALID_OPERATION,
          "the device keeps the first error");
    check(bmfrGetDeviceError(device, &message) == BMFR_ERROR_NONE && message == NULL,
          "and clears it when read");
    bmfrReleaseFilter(filter);
    bmfrReleaseDevice(device);
    if (failures) return 1;
    printf("c api program passed\n");
    return 0;
}
