#include "filters/svgf/svgf_passes.h"

namespace bmfr {

void SvgfBuffers::captureDebug(int cur) {
    const ImageF& last = filtered[outputLevel];
    if (historyLengthF.width != last.width || historyLengthF.height != last.height) {
        historyLengthF.resize(last.width, last.height, 1);
        acceptF.resize(last.width, last.height, 1);
        finalLevel.resize(last.width, last.height, 3);
    }
    for (long i = 0; i < last.pixelCount(); ++i) {
        historyLengthF.data()[i] = historyLength[cur].data()[i];
        acceptF.data()[i] = accept.data()[i];
        store3(finalLevel.data(), i, load3Stride4(last.data(), i));
    }
}

DebugBuffers SvgfBuffers::debug(int) const {
    return {view(integrated), view(finalLevel), view(historyLengthF), view(acceptF)};
}

} // namespace bmfr
