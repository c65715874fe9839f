#include "tools/work_precision.h"

#include "engine/types.h"
#include "engine/simulation.h"
#include "io/scene/scene.h"
#include "tools/benchmark.h"
#include "tools/validation_cases.h"
#include "tools/work_precision_cases.h"
#include "tools/work_precision_plot.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tbb/global_control.h>
#include <tbb/info.h>

namespace talus {

namespace {

using namespace validation;
using work_precision::Case;
using work_precision::Point;
using work_precision::cases;
using work_precision::fmt;


std::string runDouble(const std::string& binary, const std::string& name, double cells, const std::string& shared,
                      Point& out) {
  std::string cmd = "\"" + binary + "\" work-precision --single " + name + " --cells " + fmt("%g", cells);
  if (!shared.empty()) cmd += " --shared \"" + shared + "\"";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "cannot run " + binary;
  char line[256] = {0};
  const bool got = std::fgets(line, sizeof line, p) != nullptr;
  pclose(p);
  if (!got) return "no output from " + binary;
  std::istringstream in(line);
  in >> out.error >> out.wall >> out.particles >> out.steps;
  out.cells = cells;
  return in ? "" : std::string("unreadable output: ") + line;
}

/// 1. Each case refined at fixed particles per cell and CFL; its points, per case, in `series`.
std::vector<std::vector<Point>> refinementSection(std::ostringstream& md, const std::vector<Case>& all,
                                                  const WorkPrecisionOptions& opt) {
  md << "## Error against resolution and cost\n\n"
     << "Each case is refined at 8 particles per cell and CFL 0.4. The observed order is "
     << "log2(e_coarse / e_fine) between successive levels.\n\n"
     << "![error against wall time](" << std::filesystem::path(opt.image).filename().string() << ")\n\n";
  std::vector<std::string> names;
  std::vector<std::vector<Point>> series;
  for (const Case& c : all) {
    std::fprintf(stderr, "work-precision: %s\n", c.name.c_str());
    md << "### " << c.name << ": " << c.what << "\n\nError: " << c.errorMeaning << ". Resolution: " << c.cellsMeaning
       << ".\n\n| resolution | particles | steps | wall (s) | error | observed order | figures |\n|---|---|---|---|---|---|---|\n";
    std::vector<Point> pts;
    for (double cells : opt.quick ? c.quickLevels : c.levels) {
      const Point p = c.run({cells, 8, 0.4});
      const std::string order =
          pts.empty() || !(p.error > 0) || !(pts.back().error > 0)
              ? "–"
              : fmt("%.2f", std::log(pts.back().error / p.error) / std::log(cells / pts.back().cells));
      md << "| " << cells << " | " << p.particles << " | " << p.steps << " | " << fmt("%.2f", p.wall) << " | "
         << fmt("%.3g", p.error) << " | " << order << " | " << p.detail << " |\n";
      pts.push_back(p);
      std::fprintf(stderr, "  %g cells: error %.3g, %.2f s %s\n", cells, p.error, p.wall, p.detail.c_str());
    }
    md << "\n";
    names.push_back(c.name);
    series.push_back(pts);
  }
  work_precision::plot(opt.image, names, series);
  return series;
}

/// What the refinement shows, and the resolution a user needs (text kept true by hand).
void readingSection(std::ostringstream& md) {
  md << "## Reading these results\n"
       "\n"
       "- **Elastic bar**: first-order convergence of the period. The fixed end is a wall at a node, so the\n"
       "  bar's effective length is known only to O(dx); the first mode itself is resolved far better.\n"
       "- **Sliding block**: first order. Loaded suddenly, the undamped elastic block rings (normal force\n"
       "  0..2 N, a 0.025 s period) and the 0.05 s samples alias the ringing into a start-up offset that\n"
       "  does not fall with dx; an error counted from 5 cells even grew as that start moved earlier.\n"
       "  Ramped over 0.2 s and measured beyond a fixed 0.1 m, the displacement converges; the fitted\n"
       "  acceleration is within 0.04 % at every level.\n"
       "- **Dam break**: the front speed converges to within 3 % of Martin & Moyce's; the position leads\n"
       "  Koshizuka & Oka by up to 22 % at every resolution (the experiments' late start). The wall\n"
       "  pressure needs water at c ≥ 40 times the front speed. The particles in the wall cell put the\n"
       "  impact peak within 15 % of Buchner's at H/dx = 10 and 20, but the wall's own load (the\n"
       "  momentum it removes, the error above) has no impact peak and a plateau 27–30 % short:\n"
       "  the goal is not met by the force (docs/convergence.md).\n"
       "- **Granular collapses**: the continuous deposit's far end converges where the front does not\n"
       "  fragment (a = 5, 10: two finest levels within 3 %), to Lajeunesse's law rather than Lube's\n"
       "  for tall columns; low columns (a = 0.5, 2) need about 32 cells across their length before\n"
       "  their run-out holds. The measure, the laws, the final heights, AFLIP, F-bar and the floor:\n"
       "  docs/convergence.md.\n"
       "- **Particles per cell and CFL**: at the resolutions above, neither moves the error much, except\n"
       "  the ramped sliding block's CFL (0.41 / 0.63 / 0.84 % at CFL 0.2 / 0.4 / 0.6: its time error is\n"
       "  as large as its spatial one); cost is linear in particles per cell and inversely proportional\n"
       "  to CFL.\n"
       "- **Float against double**: the same errors at similar cost, except where a thin front decides:\n"
       "  the a = 5 collapse (0.3 % against 2.5 % at 12 cells: last-bit differences change where its\n"
       "  front breaks, well inside its resolution scatter) and the dam break's front speed at 20\n"
       "  cells (2.8 % against 1.1 %: the sheet's tip is a few particles, and the speed's fit over\n"
       "  2 ≤ Z ≤ 8 follows them). Single precision with a local origin loses nothing else.\n"
       "\n"
       "## The resolution a user needs\n"
       "\n"
       "From the runs above and the study in docs/convergence.md (section 4), in cells across the\n"
       "released thickness (a collapse: across its length):\n"
       "\n"
       "| quantity | 10 % | 5 % |\n"
       "|---|---|---|\n"
       "| run-out of a thin snow flow with samosAT | 0.4 cells | 0.4 cells |\n"
       "| peak flow height of that flow | 1 cell | 1.6 cells |\n"
       "| run-out of a plastic collapse | 16 cells (a = 2, 5, 10, to the nearer law) | 12–16 cells for "
       "a = 5 and 10; 32 for a = 0.5 and 2 (below that a lower bound) |\n"
       "| dam-break front speed | 10 cells across the column | 20 cells |\n"
       "\n"
       "Cost of the basal and flow laws per particle-step: docs/throughput.md.\n"
       "\n";

}

/// 2. Particles per cell and CFL at one resolution.
void particlesPerCellSection(std::ostringstream& md, const std::vector<Case>& all, const WorkPrecisionOptions& opt) {
  md << "## Particles per cell and CFL\n\nSliding block at 4 cells across the block and elastic bar at 32 cells "
     << "along it (quick mode: 2 and 16).\n\n| case | particles/cell | CFL | particles | steps | wall (s) | error |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const Case& c : all) {
    if (c.name != "sliding_block" && c.name != "elastic_bar") continue;
    const double cells = c.name == "sliding_block" ? (opt.quick ? 2 : 4) : (opt.quick ? 16 : 32);
    for (const auto& [ppc, cfl] : std::vector<std::pair<int, double>>{{1, 0.4}, {8, 0.4}, {27, 0.4}, {8, 0.2}, {8, 0.6}}) {
      if (opt.quick && ppc == 27) continue;
      const Point p = c.run({cells, ppc, cfl});
      md << "| " << c.name << " | " << ppc << " | " << cfl << " | " << p.particles << " | " << p.steps << " | "
         << fmt("%.2f", p.wall) << " | " << fmt("%.3g", p.error) << " |\n";
    }
  }
  md << "\n";

}

/// 3. Float against double, at each case's second level (`series` from the refinement).
void precisionSection(std::ostringstream& md, const std::vector<Case>& all, const WorkPrecisionOptions& opt,
                      const std::vector<std::vector<Point>>& series) {
  md << "## Single against double precision\n\n";
  if (opt.doubleBinary.empty()) {
    md << "Not measured in this run: give `--double path/to/talus` built with `-DTALUS_DOUBLE=ON`.\n\n";
  } else {
    md << "The same cases with `-DTALUS_DOUBLE=ON` (particle and grid data in double; constitutive math is "
       << "double in both).\n\n| case | resolution | float error | double error | float wall (s) | double wall (s) |\n"
       << "|---|---|---|---|---|---|\n";
    for (size_t i = 0; i < all.size(); ++i) {
      const Point& f = series[i][std::min<size_t>(1, series[i].size() - 1)];
      Point d;
      const std::string err = runDouble(opt.doubleBinary, all[i].name, f.cells, opt.sharedDir, d);
      if (!err.empty()) {
        md << "| " << all[i].name << " | " << f.cells << " | " << fmt("%.3g", f.error) << " | " << err << " | | |\n";
        continue;
      }
      md << "| " << all[i].name << " | " << f.cells << " | " << fmt("%.3g", f.error) << " | " << fmt("%.3g", d.error)
         << " | " << fmt("%.2f", f.wall) << " | " << fmt("%.2f", d.wall) << " |\n";
    }
    md << "\n";
  }

}

/// 4. Throughput of every benchmark case.
void throughputSection(std::ostringstream& md, const WorkPrecisionOptions& opt) {
  md << "## Throughput\n\n`talus bench`: particle-steps per second per core, time per phase, memory. On this\n"
        "shared 2-vCPU VM the 2-thread figures scatter between runs, more than the 1-thread ones (the\n"
        "same build measured 91-98 % efficiency for the 250 000-particle cases with `talus bench`\n"
        "alone).\n\n"
     << "| case | threads | particles | p-steps/s per core | efficiency | bin | P2G | grid | G2P | bytes/particle | KB/block |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  BenchOptions bo;
  bo.cases = benchmarkCaseNames();
  bo.steps = opt.quick ? 5 : 30;
  bo.threads = {1, 2};
  for (const BenchResult& r : measureBenchmarks(bo, false))
    md << "| " << r.name << " | " << r.threads << " | " << r.particles << " | "
       << fmt("%.2e", r.particleStepsPerSecond / r.threads) << " | "
       << (r.efficiency > 0 ? fmt("%.0f %%", 100 * r.efficiency) : std::string("–")) << " | "
       << fmt("%.0f %%", 100 * r.binShare) << " | " << fmt("%.0f %%", 100 * r.p2gShare) << " | "
       << fmt("%.0f %%", 100 * r.gridShare) << " | " << fmt("%.0f %%", 100 * r.g2pShare) << " | "
       << fmt("%.0f", r.bytesPerParticle) << " | " << fmt("%.1f", r.bytesPerBlock / 1024) << " |\n";
  md << "\n";

}

/// 5. How cost grows with particles and with the domain.
void costSection(std::ostringstream& md, const WorkPrecisionOptions& opt, int threads) {
  md << "## How cost grows\n\nElastic slab (the `elastic` benchmark), " << threads << " threads. Against "
     << "particle count at a fixed domain:\n\n| particles | time per step (ms) | ns per particle-step | blocks |\n"
     << "|---|---|---|---|\n";
  for (double scale : opt.quick ? std::vector<double>{0.125, 0.25} : std::vector<double>{0.125, 0.25, 0.5, 1.0}) {
    const BenchResult r = measureScaling(scale, 1, opt.quick ? 5 : 20);
    md << "| " << r.particles << " | " << fmt("%.2f", 1e3 * r.secondsPerStep) << " | "
       << fmt("%.0f", 1e9 * r.secondsPerStep / double(r.particles)) << " | " << r.blocks << " |\n";
  }
  md << "\nAgainst domain size at a fixed particle count (the sparse grid should make this flat):\n\n"
     << "| domain volume (relative) | time per step (ms) | grid blocks | grid memory (MB) | dense box (MB) |\n"
     << "|---|---|---|---|---|\n";
  for (double d : opt.quick ? std::vector<double>{1, 4} : std::vector<double>{1, 4, 16, 64}) {
    const BenchResult r = measureScaling(opt.quick ? 0.125 : 0.25, d, opt.quick ? 5 : 20);
    // A dense box would hold one 16-byte node per cell of the domain: 1.4 x 0.9 x 0.8 m at dx.
    const double dx = 0.02 / std::cbrt(opt.quick ? 0.125 : 0.25);
    const double dense = 1.4 * 0.9 * 0.8 * d * d * d / (dx * dx * dx) * sizeof(Vec4) / 1e6;
    md << "| " << d * d * d << " | " << fmt("%.2f", 1e3 * r.secondsPerStep) << " | " << r.blocks << " | "
       << fmt("%.2f", r.bytesPerBlock * double(r.blocks) / 1e6) << " | " << fmt("%.2f", dense) << " |\n";
  }
  md << "\n";

}

/// 6. A thin layer on large terrain: grid memory of the sparse grid against a dense box.
void sparseSection(std::ostringstream& md, const WorkPrecisionOptions& opt) {
  md << "## Sparse against dense grid memory\n\nA one-cell-thick layer (dx = 5 m, one particle per cell) "
     << "over a square of side s at the middle height of a 1 km tall domain of the same footprint:\n\n"
     << "| layer side (m) | particles | active blocks | grid memory (MB) | dense box of the domain (MB) |\n"
     << "|---|---|---|---|---|\n";
  for (double side : opt.quick ? std::vector<double>{500} : std::vector<double>{500, 1000, 2000}) {
    SceneSetup s = loadSceneString(validation::thinLayerScene(side, side, 1000), "sparse-layer");
    Simulation sim(s.settings, std::move(s.groups));
    sim.step();
    const double dense = side / 5 * side / 5 * 1000 / 5 * sizeof(Vec4) / 1e6;
    md << "| " << side << " | " << sim.particleCount() << " | " << sim.grid().blockCount() << " | "
       << fmt("%.1f", double(sim.gridBytes()) / 1e6) << " | " << fmt("%.0f", dense) << " |\n";
  }
  md << "\n";

}

} // namespace

int runSingleCase(const std::string& caseName, const Resolution& res, const std::string& shared, bool printScene) {
  for (const Case& c : cases(shared))
    if (c.name == caseName) {
      if (printScene) {
        if (!c.scene) {
          std::fprintf(stderr, "talus: --scene: case '%s' is not one scene file\n", caseName.c_str());
          return 2;
        }
        std::fputs(c.scene(res).c_str(), stdout);
        return 0;
      }
      const Point p = c.run(res);
      std::printf("%.9g %.6g %zu %llu %s\n", p.error, p.wall, p.particles, p.steps, p.detail.c_str());
      return 0;
    }
  std::fprintf(stderr, "talus: unknown case '%s'\n", caseName.c_str());
  return 2;
}

int runWorkPrecision(const WorkPrecisionOptions& opt) {
  const auto started = std::chrono::steady_clock::now();
  for (const std::string& f : {opt.markdown, opt.image}) {
    const auto dir = std::filesystem::path(f).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
  }
  std::ostringstream md;
  const int threads = int(tbb::info::default_concurrency());
  const std::vector<Case> all = cases(opt.sharedDir);
  md << "# Performance: speed against accuracy\n\n"
     << "Regenerated by `talus work-precision` (`tools/work_precision.cpp`); every figure below was measured "
     << "by that command on the machine it ran on (" << threads << " hardware threads"
     << (opt.quick ? ", quick mode: fewer and coarser runs" : "") << "). Wall times are for the whole run of each "
     << "case at " << threads << " threads, in single precision unless stated. Where the time goes per "
     << "phase, and the measured speed-ups: docs/throughput.md.\n\n";

  const std::vector<std::vector<Point>> series = refinementSection(md, all, opt);
  readingSection(md);
  particlesPerCellSection(md, all, opt);
  precisionSection(md, all, opt, series);
  throughputSection(md, opt);
  costSection(md, opt, threads);
  sparseSection(md, opt);

  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  md << "---\nGenerated " << date << " in " << fmt("%.0f", total) << " s.\n";
  std::ofstream out(opt.markdown);
  out << md.str();
  if (!out) throw std::runtime_error("cannot write " + opt.markdown);
  std::fprintf(stderr, "work-precision: wrote %s and %s in %.0f s\n", opt.markdown.c_str(), opt.image.c_str(), total);
  return 0;
}

} // namespace talus
