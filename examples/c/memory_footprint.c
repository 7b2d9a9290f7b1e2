/* Prints the host memory each filter takes at 720p, 1080p and 4K (bmfrGetFilterMemoryBytes),
 * with the faithful and the quality preset, as a Markdown table. Usage: memory_footprint [threads]
 */
#include <bmfr/bmfr.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char** argv) {
    const char* filters[] = {"bmfr", "svgf", "walr", "mara2017"};
    const char* presets[] = {"faithful", "quality"};
    const int sizes[][2] = {{1280, 720}, {1920, 1080}, {3840, 2160}};
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
    if (argc > 1) bmfrSetDeviceInt(device, "threads", atoi(argv[1]));
    bmfrCommitDevice(device);
    printf("| filter | preset | 1280x720 | 1920x1080 | 3840x2160 |\n|---|---|---|---|---|\n");
    for (int f = 0; f < 4; ++f)
        for (int p = 0; p < 2; ++p) {
            BMFRFilter filter = bmfrNewFilter(device, filters[f]);
            bmfrSetFilterString(filter, "preset", presets[p]);
            bmfrCommitFilter(filter);
            printf("| %s | %s |", filters[f], presets[p]);
            for (int s = 0; s < 3; ++s)
                printf(" %.1f MiB |",
                       bmfrGetFilterMemoryBytes(filter, sizes[s][0], sizes[s][1]) / 1048576.0);
            printf("\n");
            bmfrReleaseFilter(filter);
        }
    const char* message = NULL;
    const BMFRError error = bmfrGetDeviceError(device, &message);
    if (error != BMFR_ERROR_NONE) fprintf(stderr, "error: %s\n", message);
    bmfrReleaseDevice(device);
    return error == BMFR_ERROR_NONE ? 0 : 1;
}
