// The comparison's scores as tables: Markdown, CSV (means and per frame), JSON and an HTML table,
// all keyed by metricList(); missing values are empty cells or JSON null. The Markdown and HTML
// tables bold the best value of each column, the lowest or highest, but none of the temporal
// error's (it counts the scene's motion: the reference's own value is its target); notes under
// them say what the rows the demo names (and OIDN's) are and how the temporal columns read. When
// any method's run recorded its time (report.json), a last column gives ms per frame and a note
// names the machine it was measured on.
#pragma once
#include "eval/comparison.h"
#include <string>

namespace bmfr {

/// The score table as Markdown (best per column in bold), then its notes as a short list.
std::string markdownTable(const ComparisonResult& r);
/// Writes table.md, table.csv, per_frame.csv and table.json into o.output; `json` receives the
/// JSON text.
void writeTables(const ComparisonResult& r, const ComparisonOptions& o, std::string& json);
/// The score table as HTML (names escaped, best per column in bold), then its notes.
std::string tableHtml(const ComparisonResult& r);

} // namespace bmfr
