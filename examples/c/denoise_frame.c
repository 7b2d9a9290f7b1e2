/* The C API in one file: a device, a BMFR filter, one synthetic 64x32 frame of a flat wall in
 * half-float colour and albedo, and the errors through a callback. Builds as C99. */
#include <bmfr/bmfr.h>
#include <stdio.h>

enum { W = 64, H = 32 };

static void onError(void* user, BMFRError code, const char* message) {
    (void)user;
    fprintf(stderr, "bmfr error %d: %s\n", (int)code, message);
}

int main(void) {
    static unsigned short color[W * H * 4], albedo[W * H * 4];
    static float normal[W * H * 3], position[W * H * 3], output[W * H * 3];
    /* A camera at the origin looking down -z (clip w = -z), row-major. */
    const float viewProjection[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -0.2f, 0, 0, -1, 0};
    for (int i = 0; i < W * H; ++i) {
        for (int c = 0; c < 4; ++c) {
            color[4 * i + c] = (unsigned short)(0x3800 + (i * 7919) % 13 * 64); /* about 0.5 */
            albedo[4 * i + c] = 0x3800; /* 0.5 in IEEE half */
        }
        normal[3 * i + 2] = 1.0f;
        position[3 * i + 0] = (float)(i % W) / W - 0.5f;
        position[3 * i + 1] = (float)(i / W) / H - 0.5f;
        position[3 * i + 2] = -2.0f;
    }
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_DEFAULT);
    bmfrSetDeviceErrorFunction(device, onError, NULL);
    bmfrCommitDevice(device);
    BMFRFilter filter = bmfrNewFilter(device, "bmfr");
    bmfrSetFilterImage(filter, "color", color, BMFR_FORMAT_HALF4, W, H, 0, 0, 0);
    bmfrSetFilterImage(filter, "albedo", albedo, BMFR_FORMAT_HALF4, W, H, 0, 0, 0);
    bmfrSetFilterImage(filter, "normal", normal, BMFR_FORMAT_FLOAT3, W, H, 0, 0, 0);
    bmfrSetFilterImage(filter, "position", position, BMFR_FORMAT_FLOAT3, W, H, 0, 0, 0);
    bmfrSetFilterImage(filter, "output", output, BMFR_FORMAT_FLOAT3, W, H, 0, 0, 0);
    bmfrSetFilterMatrix(filter, "viewProjection", viewProjection);
    bmfrCommitFilter(filter);
    bmfrExecuteFilter(filter);
    const char* message = NULL;
    const BMFRError error = bmfrGetDeviceError(device, &message);
    if (error == BMFR_ERROR_NONE) printf("denoised %dx%d: first pixel %.3f\n", W, H, output[0]);
    bmfrReleaseFilter(filter);
    bmfrReleaseDevice(device);
    return error == BMFR_ERROR_NONE ? 0 : 1;
}
