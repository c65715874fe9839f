// report.html: a run or an ensemble on one page, self-contained and offline (nothing fetched).
// For a run: summary.json's figures as tables (the run, notes and warnings, the mass ledger,
// materials, loads, water, timings, files), the film, and the maps and plots as pictures that
// zoom. For an ensemble: the member table (sortable), the Morris screening, the probability and
// quantile maps and the run-out distribution. The page (io/output/report_page.html, compiled
// in) builds its tables from the JSON it is given with a small script, no library.
#pragma once

#include <string>
#include <vector>

namespace talus {

/// Writes DIR/report.html: `summaryJson` (a run's summary.json, or an ensemble's summary with
/// "kind": "ensemble") and the pictures among `files` (paths relative to DIR: maps/**.png,
/// plots/*.png, runout.png, animation.mp4 or .gif, embedded as data). Throws WriteError.
void writeReportPage(const std::string& dir, const std::string& summaryJson, const std::vector<std::string>& files);

/// The page with %%TALUS_SUMMARY%% and %%TALUS_MEDIA%% where the two JSON blocks go.
const std::string& reportPageTemplate();

} // namespace talus
