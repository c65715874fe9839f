// `talus render` end to end: a short run of the default scene (coarse) with volume frames,
// rendered by Blender (Debian's 3.4) over its terrain; skipped where Blender is not installed.
// Also the one-line refusals: no frames, no Blender.
#include "io/common/input_error.h"
#include "io/output/render.h"
#include "io/run/run_driver.h"
#include "process_support.h"
#include "test_support.h"

#include <cairo.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

using namespace talus;
namespace fs = std::filesystem;

namespace {

/// Brightness (0..1) statistics of a PNG: mean of a square and standard deviation of the whole.
struct Picture {
  int width = 0, height = 0;
  std::vector<double> v;
  double mean(int x0, int y0, int size) const {
    double s = 0;
    for (int y = y0; y < y0 + size; ++y)
      for (int x = x0; x < x0 + size; ++x) s += v[size_t(y) * width + x];
    return s / (size * size);
  }
  double spread() const {
    double m = 0, q = 0;
    for (double b : v) m += b, q += b * b;
    m /= double(v.size());
    return std::sqrt(std::max(0.0, q / double(v.size()) - m * m));
  }
};

Picture readPng(const std::string& path) {
  Picture p;
  cairo_surface_t* img = cairo_image_surface_create_from_png(path.c_str());
  if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
    ADD_FAILURE() << "cannot read " << path;
    return p;
  }
  p.width = cairo_image_surface_get_width(img), p.height = cairo_image_surface_get_height(img);
  const int stride = cairo_image_surface_get_stride(img);
  const unsigned char* d = cairo_image_surface_get_data(img);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      uint32_t px;
      std::memcpy(&px, d + size_t(y) * stride + 4 * x, 4);
      p.v.push_back((((px >> 16) & 255) + ((px >> 8) & 255) + (px & 255)) / (3 * 255.0));
    }
  cairo_surface_destroy(img);
  return p;
}

bool haveBlender() {
  std::string out;
  return test::shell("command -v blender", out) == 0;
}

} // namespace

TEST(Render, TheDefaultSceneOverItsTerrain) {
  if (!haveBlender()) GTEST_SKIP() << "blender not installed (Debian package 'blender'): render skipped";
  const std::string dir = test::tempDir("render_default");
  SceneSetup scene = loadSceneString(defaultSceneText(), "default.toml",
                                     {"simulation.dx=8", "simulation.end_time=2", "output.frame_interval=1",
                                      "output.animation=false", "output.report=false"});
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(scene), opt).ok);
  RenderOptions o;
  o.dir = dir, o.width = 96, o.height = 54, o.samples = 4;
  int reported = 0;
  const RenderResult r = makeRender(o, [&](int done, int total) {
    reported = done;
    EXPECT_EQ(total, 3);
  });
  ASSERT_TRUE(r.problem.empty()) << r.problem;
  EXPECT_EQ(r.frames, 3);
  EXPECT_EQ(reported, 3);
  EXPECT_TRUE(fs::exists(dir + "/render/render.mp4"));
  for (int i = 0; i < 3; ++i) {
    const Picture p = readPng(dir + "/render/frame_0000" + std::to_string(i) + ".png");
    ASSERT_EQ(p.width, 96);
    ASSERT_EQ(p.height, 54);
    // Not blank: terrain and flow against the sky. The corner above the horizon is sky; the
    // framed flow at the centre differs from it by more than render noise (4 samples).
    EXPECT_GT(p.spread(), 0.03) << i;
    EXPECT_GT(std::abs(p.mean(40, 22, 16) - p.mean(0, 0, 8)), 0.05) << i;
  }
}

TEST(Render, RefusesAFolderWithoutFramesAndSaysWhenBlenderIsMissing) {
  const std::string dir = test::tempDir("render_refusals");
  RenderOptions o;
  o.dir = dir;
  try {
    makeRender(o);
    FAIL() << "no error for a folder without frames";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no volume frames"), std::string::npos) << e.what();
  }
  fs::create_directories(dir + "/frames");
  std::ofstream(dir + "/frames/volume_00000.vdb") << "x";
  o.blender = dir + "/no-such-blender";
  const RenderResult r = makeRender(o);
  EXPECT_NE(r.problem.find("apt-get install blender"), std::string::npos) << r.problem;
  EXPECT_EQ(r.frames, 0);
}
