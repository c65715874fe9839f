// The run's film (io/output/animation.h): frame rasters that hold the flow's volume, a film with
// one picture per raster, `talus animate` with other choices, a film whose encoder fails once, and
// a run without FFmpeg.
#include "process_support.h"
#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <regex>

using namespace talus;
namespace fs = std::filesystem;

namespace {

/// Sum of a frame's values times the cell area (its volume for a thickness), and its time.
std::pair<double, double> frameVolume(const std::string& path) {
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!ds) return {NAN, NAN};
  double gt[6];
  ds->GetGeoTransform(gt);
  const int nx = ds->GetRasterXSize(), ny = ds->GetRasterYSize();
  std::vector<float> v(size_t(nx) * ny);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float32, 0, 0), CE_None);
  const double t = std::atof(ds->GetMetadataItem("TALUS_TIME_S"));
  GDALClose(ds);
  double sum = 0;
  for (float x : v)
    if (x > 0) sum += x;
  return {sum * gt[1] * gt[1], t};
}

const std::string kBinary = TALUS_BINARY;
// The default scene (rock onto a snow cover, on terrain: the film is on by default) for 1 s,
// a frame every 0.1 s.
const std::string kRun = " run --quiet --set simulation.end_time=1 --set output.animation.interval=0.1 --set output.h5=false"
                         " --set output.vdb=false --out ";

} // namespace

TEST(Animation, FramesHoldTheFlowsVolumeAndTheFilmHasAPictureForEach) {
  const std::string dir = test::tempDir("animation");
  std::string log;
  ASSERT_EQ(test::shell("\"" + kBinary + "\"" + kRun + dir + "/run", log), 0) << log;
  // Eleven frames, 0 to 1 s: the first at the start, then whenever a step passes a multiple of
  // the interval.
  for (int i = 0; i <= 10; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/run/animation/rasters/thickness_%05d.tif", i);
    const auto [volume, time] = frameVolume(dir + name);
    // The bilinear splat keeps every particle's volume on the map (the flow stays inside the
    // domain): the particles' 476 385 m3 (the rock release held to its geometric 85 352.8 m3,
    // match_volume, + 391 032 snow as seeded, `talus check`) within float sums over ~1e4 cells.
    EXPECT_NEAR(volume, 476384.8, 476384.8 * 1e-4) << name;
    EXPECT_NEAR(time, 0.1 * i, 0.02) << name;
  }
  EXPECT_FALSE(fs::exists(dir + "/run/animation/rasters/thickness_00011.tif"));
  if (test::shell("ffprobe -version", log) != 0) GTEST_SKIP() << "ffprobe is not installed (apt-get install ffmpeg)";
  ASSERT_EQ(test::shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,codec_name "
                  "-of csv=p=0 " + dir + "/run/animation.mp4", log), 0) << log;
  EXPECT_EQ(log, "h264,11\n");
  EXPECT_GT(fs::file_size(dir + "/run/animation.gif"), 1000u);
  EXPECT_FALSE(fs::exists(dir + "/run/animation/png")); // the drawn frames go once encoded
  std::ifstream summary(dir + "/run/summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), {});
  EXPECT_NE(text.find("\"animation\": \"animation.mp4\""), std::string::npos);
  // The run takes the colour scale's top from the frames it wrote (AnimationStyle::known);
  // `talus animate` reads it from every frame again: the same films, byte for byte.
  const std::string mp4 = test::slurp(dir + "/run/animation.mp4"), gif = test::slurp(dir + "/run/animation.gif");
  ASSERT_EQ(test::shell("\"" + kBinary + "\" animate " + dir + "/run", log), 0) << log;
  EXPECT_TRUE(test::slurp(dir + "/run/animation.mp4") == mp4);
  EXPECT_TRUE(test::slurp(dir + "/run/animation.gif") == gif);
}

TEST(Animation, TalusAnimateRemakesTheFilmWithOtherChoicesAndNamesWhatIsWrong) {
  const std::string dir = test::tempDir("animate_command");
  std::string log;
  ASSERT_EQ(test::shell("\"" + kBinary + "\"" + kRun + dir + "/run", log), 0) << log;
  if (test::shell("ffprobe -version", log) != 0) GTEST_SKIP() << "ffprobe is not installed (apt-get install ffmpeg)";
  ASSERT_EQ(test::shell("\"" + kBinary + "\" animate " + dir + "/run --quantity speed --fps 5 --width 320", log), 0) << log;
  ASSERT_EQ(test::shell("ffprobe -v error -select_streams v:0 -show_entries stream=width,r_frame_rate -of csv=p=0 " + dir +
                  "/run/animation.mp4", log), 0) << log;
  EXPECT_EQ(log, "320,5/1\n");
  // A folder without frames, and a window beside the frames: one line each, exit 2.
  EXPECT_EQ(test::shell("\"" + kBinary + "\" animate " + dir, log), 2);
  EXPECT_NE(log.find("talus: error: " + dir + "/animation/rasters: no thickness frames here"), std::string::npos) << log;
  EXPECT_EQ(test::shell("\"" + kBinary + "\" animate " + dir + "/run --window 0 0 10 10", log), 2);
  EXPECT_NE(log.find("--window: the window does not overlap the frames"), std::string::npos) << log;
}

TEST(Animation, WithoutFfmpegTheRunCompletesAndSaysWhereTheDrawnFramesAre) {
  const std::string dir = test::tempDir("animation_no_ffmpeg");
  std::string log;
  ASSERT_EQ(test::shell("PATH=/nonexistent \"" + kBinary + "\"" + kRun + dir + "/run", log), 0) << log;
  std::ifstream summary(dir + "/run/summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), {});
  EXPECT_NE(text.find("\"animation\": \"ffmpeg not found (apt-get install ffmpeg): the drawn frames are in animation/png/\""),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/run/animation/png/frame_00010.png"));
  EXPECT_FALSE(fs::exists(dir + "/run/animation.mp4"));
  EXPECT_EQ(test::shell("PATH=/nonexistent \"" + kBinary + "\" animate " + dir + "/run", log), 1);
  EXPECT_EQ(log, "talus: error: ffmpeg not found (apt-get install ffmpeg): the drawn frames are in animation/png/\n");
}

TEST(Animation, AFilmWhoseEncoderFailsOnceIsEncodedAgainAlone) {
  // An ffmpeg that fails its first call and is the real one after. The two films' encoders start
  // together, so the one that fails is either.
  const std::string dir = test::tempDir("animation_encoder_fails");
  std::string real;
  if (test::shell("command -v ffmpeg", real) != 0) GTEST_SKIP() << "ffmpeg is not installed (apt-get install ffmpeg)";
  real.erase(real.find_last_not_of('\n') + 1);
  fs::create_directories(dir + "/bin");
  std::ofstream(dir + "/bin/ffmpeg") << "#!/bin/sh\nif mkdir '" << dir << "/failed_once' 2>/dev/null; then echo a fault of the moment >&2; exit 1; fi\nexec '"
                                     << real << "' \"$@\"\n";
  fs::permissions(dir + "/bin/ffmpeg", fs::perms::owner_all);
  std::string log;
  ASSERT_EQ(test::shell("\"" + kBinary + "\"" + kRun + dir + "/run --set output.report=false", log), 0) << log;
  fs::remove(dir + "/run/animation.mp4");
  fs::remove(dir + "/run/animation.gif");
  ASSERT_EQ(test::shell("PATH=" + dir + "/bin:$PATH \"" + kBinary + "\" animate " + dir + "/run", log), 0) << log;
  EXPECT_TRUE(std::regex_search(log, std::regex("talus animate: ffmpeg failed making animation\\.(mp4|gif) \\(ffmpeg: a "
                                                "fault of the moment\\); encoded again alone\n")))
      << log;
  EXPECT_TRUE(fs::exists(dir + "/failed_once"));
  EXPECT_TRUE(fs::exists(dir + "/run/animation.gif"));
  if (test::shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 " +
                      dir + "/run/animation.mp4", log) != 0) GTEST_SKIP() << "ffprobe is not installed (apt-get install ffmpeg)";
  EXPECT_EQ(log, "11\n") << "a picture for each of the 11 frames (0 to 1 s every 0.1 s)";
}
