// The self-contained report.html of `bmfr eval`: score table, plots, viewer, pictures and the
// run's metadata in one file (images inline as data: URIs; full-size PNGs linked beside it).
#pragma once
#include <string>
#include <vector>

namespace bmfr {

struct ReportPicture {
    std::string title;
    std::string png;   ///< PNG bytes, base64
    std::string file;  ///< the same picture's file beside the report
    bool tile = false; ///< laid out side by side with its neighbours (heat maps)
};

struct ReportPlot {
    std::string svg;  ///< inline SVG
    std::string stem; ///< plot_KEY: .svg and .png beside the report
};

struct ReportContent {
    std::string heading;   ///< one sentence: reference, frames, shown frame
    std::string tableHtml; ///< the score table
    std::vector<ReportPlot> plots;
    std::string viewerJson; ///< the viewer's data (see report_viewer.js)
    std::vector<ReportPicture> pictures;
    std::vector<std::string> videos; ///< file names beside the report
    std::string videoNote;           ///< why there is no video, when one was asked for
    std::string metadataHtml;
};

std::string reportHtml(const ReportContent& c);

} // namespace bmfr
