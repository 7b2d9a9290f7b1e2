#include "eval/report_html.h"
#include "eval/escape_html.h"
#include "report_viewer_js.h"
#include <fmt/core.h>

namespace bmfr {

namespace {

const char* kStyle =
    "body{font-family:'DejaVu Sans',Helvetica,Arial,sans-serif;margin:1.5em 2em;color:#222}"
    "h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ddd}"
    "table{border-collapse:collapse;margin:0.5em 0}"
    "td,th{border:1px solid #ccc;padding:3px 9px;text-align:right}"
    "td:first-child,th:first-child{text-align:left}"
    "table.meta td,table.meta th{text-align:left;vertical-align:top}"
    "td.wrap{max-width:40em;word-break:break-word;font-size:0.85em}"
    ".plots{display:grid;grid-template-columns:repeat(auto-fill,minmax(520px,1fr));gap:12px}"
    ".plots figure{margin:0}.plots svg{width:100%;height:auto}"
    "figcaption{font-size:0.85em;color:#555}"
    "p.notes{font-size:0.9em;max-width:60em;margin:0.3em 0}"
    "img{max-width:100%;image-rendering:pixelated}"
    "#viewer .controls{display:flex;flex-wrap:wrap;gap:6px 16px;align-items:center;margin:6px 0}"
    "#v-box{width:100%;overflow:hidden;background:#222}"
    "#v-canvas{display:block;image-rendering:pixelated;cursor:grab}"
    "#v-bar-box{font-size:0.85em}#v-bar{vertical-align:middle}"
    ".pictures figure{margin:0 0 1em 0}"
    ".pictures figure.tile{display:inline-block;vertical-align:top;margin-right:14px;"
    "max-width:32%}";

} // namespace

std::string reportHtml(const ReportContent& c) {
    std::string h = "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\">"
                    "<title>bmfr eval</title><style>";
    h += kStyle;
    h += "</style></head><body><h1>bmfr eval</h1>";
    h += "<p>" + c.heading + "</p>";
    h += "<p>RMSE, PSNR, SSIM, FLIP and the temporal errors are computed on tone-mapped frames, "
         "clamp(x<sup>1/2.2</sup>, 0, 1), as the BMFR paper scores; relMSE on linear radiance. "
         "Best value per column in bold; none for the temporal error, whose target is the "
         "reference's own value (notes under the table).</p>";
    h += c.tableHtml;
    h += "<h2>Per frame</h2><div class=\"plots\">";
    for (const ReportPlot& p : c.plots)
        h += "<figure>" + p.svg + "<figcaption><a href=\"" + escapeHtml(p.stem) +
             ".svg\">SVG</a> " + "<a href=\"" + escapeHtml(p.stem) +
             ".png\">PNG</a></figcaption></figure>";
    h += "</div>";

    h += "<h2>Viewer</h2><section id=\"viewer\"><div class=\"controls\">"
         "<label>frame <input type=\"range\" id=\"v-frame\" min=\"0\" value=\"0\"></label>"
         "<span id=\"v-frame-label\"></span><button id=\"v-play\">play</button>"
         "<label>A <select id=\"v-a\"></select></label>"
         "<label>B <select id=\"v-b\"></select></label>"
         "<label>view <select id=\"v-mode\"></select></label>"
         "<label>exposure <input type=\"range\" id=\"v-ev\" min=\"-6\" max=\"6\" step=\"0.5\" "
         "value=\"0\"></label><span id=\"v-ev-label\"></span>"
         "<label>error scale <input type=\"range\" id=\"v-vmax\" min=\"-3\" max=\"1\" "
         "step=\"0.1\"></label>"
         "<button id=\"v-zoom-out\">-</button><button id=\"v-zoom-in\">+</button>"
         "<button id=\"v-zoom-1\">1:1</button><button id=\"v-zoom-fit\">fit</button>"
         "<span id=\"v-zoom-label\"></span></div>"
         "<div id=\"v-box\"><canvas id=\"v-canvas\" width=\"64\" height=\"64\"></canvas></div>"
         "<div class=\"controls\"><span id=\"v-caption\"></span><span id=\"v-pixel\"></span>"
         "<a id=\"v-full\" href=\"#\"></a></div>"
         "<div id=\"v-bar-box\"><span id=\"v-bar-what\"></span>: "
         "<span id=\"v-bar-lo\"></span> <canvas id=\"v-bar\" width=\"256\" height=\"12\"></canvas>"
         " <span id=\"v-bar-mid\"></span> ... <span id=\"v-bar-hi\"></span></div>"
         "<p><small>Keys: space plays and pauses (at the sequence's frame rate, looping; the "
         "frame slider stops it); left/right step frames; f flips between A and B; a, b show "
         "one; s compares with a slider (click to move it); e cycles the error views; +/- zoom, "
         "or the wheel; drag to pan. Each error view opens where the 99th percentile of the best "
         "non-noisy method's error is full brightness; the error scale slider sets it. Pixels "
         "stay square at any zoom. Exposure acts on linear values: the "
         "frames are stored as clamp(x<sup>1/2.2</sup>) in 8 bits, and the viewer shows "
         "clamp((2<sup>EV</sup> x)<sup>1/2.2</sup>), so a negative EV cannot bring back what the "
         "display clipped; the EXR outputs hold the HDR values.</small></p></section>";
    h += "<script type=\"application/json\" id=\"viewer-data\">" + c.viewerJson + "</script>";

    if (!c.videos.empty() || !c.videoNote.empty()) {
        h += "<h2>Videos</h2><p>";
        for (const std::string& v : c.videos)
            h += "<a href=\"" + escapeHtml(v) + "\">" + escapeHtml(v) + "</a> ";
        h += escapeHtml(c.videoNote) + "</p>";
    }
    h += "<h2>Pictures</h2><div class=\"pictures\">";
    for (const ReportPicture& p : c.pictures)
        h += std::string(p.tile ? "<figure class=\"tile\">" : "<figure>") + "<figcaption>" +
             escapeHtml(p.title) + " (<a href=\"" + escapeHtml(p.file) + "\">" +
             escapeHtml(p.file) + "</a>)</figcaption><img alt=\"" + escapeHtml(p.title) +
             "\" src=\"data:image/png;base64," + p.png + "\"></figure>";
    h += "</div><h2>Run</h2>" + c.metadataHtml;
    h += "<script>";
    h += kReportViewerJs;
    h += "</script></body></html>\n";
    return h;
}

} // namespace bmfr
