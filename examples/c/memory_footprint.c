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
    const int count = argc > 2 ? atoi(argv[2]) : 3;
    if (count < 1 || count > 3) {
        fprintf(stderr, "usage: memory_footprint [threads] [1 to 3 sizes]\n");
        return 2;
    }
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
    if (argc > 1) bmfrSetDeviceInt(device, "threads", atoi(argv[1]));
    bmfrCommitDevice(device);
    printf("| filter | preset |");
    for (int s = 0; s < count; ++s) printf(" %dx%d |", sizes[s][0], sizes[s][1]);
    printf("\n|---|---|%s\n", count == 1 ? "---|" : count == 2 ? "---|---|" : "---|---|---|");
    for (int f = 0; f < 4; ++f)
        for (int p = 0; p < 2; ++p) {
            BMFRFilter filter = bmfrNewFilter(device, filters[f]);
            bmfrSetFilterString(filter, "preset", presets[p]);
            bmfrCommitFilter(filter);
            printf("| %s | %s |", filters[f], presets[p]);
            for (int s = 0; s < count; ++s)
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
