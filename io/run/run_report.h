// report.html: a run on one page, self-contained and offline (nothing fetched): summary.json's
// figures as tables (the run, notes and warnings, the mass ledger, materials, loads, water,
// timings, files), the film, and the maps and plots as pictures that zoom. Written with
// summary.json at the end of every run (also one that failed or was interrupted).
#pragma once

#include <string>
#include <vector>

namespace talus {

/// Writes DIR/report.html from DIR/summary.json and the pictures among `files` (paths relative
/// to DIR: maps/**.png, plots/*.png, animation.mp4 or .gif, embedded as data). Throws WriteError.
void writeRunReport(const std::string& dir, const std::vector<std::string>& files);

/// The page with %%TALUS_SUMMARY%% and %%TALUS_MEDIA%% where the two JSON blocks go
/// (io/run/report_page.html, compiled in).
const std::string& reportPageTemplate();

} // namespace talus
