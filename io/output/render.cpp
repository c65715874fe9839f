#include "io/output/render.h"

#include "io/common/input_error.h"
#include "io/common/json_text.h"
#include "io/common/program_path.h"
#include "io/common/raster_reader.h"
#include "io/output/vdb_frame_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace talus {

namespace {

/// The volume frames the options select, in order.
std::vector<std::string> selectFrames(const RenderOptions& o) {
  const fs::path dir = fs::path(o.dir) / "frames";
  std::vector<std::string> all;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string n = e.path().filename().string();
      if (n.rfind("volume_", 0) == 0 && e.path().extension() == ".vdb") all.push_back(e.path().string());
    }
  std::sort(all.begin(), all.end());
  if (all.empty())
    throw InputError(dir.string(), "no volume frames (frames/volume_*.vdb): run with [output] frame_interval > 0 and vdb = true (the default)");
  if (o.frame >= 0) {
    if (size_t(o.frame) >= all.size())
      throw InputError("--frame", "frame " + std::to_string(o.frame) + " does not exist: the run has " +
                                      std::to_string(all.size()) + " volume frames (0 .. " + std::to_string(all.size() - 1) + ")");
    return {all[size_t(o.frame)]};
  }
  std::vector<std::string> out;
  for (size_t i = 0; i < all.size(); i += size_t(std::max(1, o.every))) out.push_back(all[i]);
  return out;
}

/// A colour for a material by its name (snow white, ice pale blue, water blue, rock brown).
std::array<double, 3> colourOf(const std::string& name) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  auto has = [&](const char* k) { return n.find(k) != std::string::npos; };
  if (has("snow") || has("cover")) return {0.92, 0.94, 0.98};
  if (has("ice") || has("glacier")) return {0.62, 0.80, 0.95};
  if (has("water") || has("lake")) return {0.15, 0.35, 0.75};
  if (has("rock") || has("debris") || has("sediment") || has("soil") || has("mud")) return {0.45, 0.34, 0.24};
  return {0.7, 0.7, 0.7};
}

/// The ground of maps/ground_elevation.tif in [lo, hi] (world x, y) as float32 heights in the
/// local frame, at most 400 cells a side, into `heights`; the JSON describing them, or "" when
/// the run has no ground raster.
std::string writeTerrain(const std::string& runDir, const Vec3d& origin, const Vec3d& lo, const Vec3d& hi,
                         const std::string& heights) {
  const std::string path = (fs::path(runDir) / "maps" / "ground_elevation.tif").string();
  if (!fs::exists(path)) return "";
  const FloatRaster ground = readFloatRaster(path, "the ground raster");
  const RasterGrid& g = ground.grid;
  const std::vector<float>& z = ground.values;
  const double cell = std::max(g.cellSize, std::max(hi.x() - lo.x(), hi.y() - lo.y()) / 400);
  const int nx = int(std::floor((hi.x() - lo.x()) / cell)) + 1, ny = int(std::floor((hi.y() - lo.y()) / cell)) + 1;
  std::vector<float> out(size_t(nx) * size_t(ny), std::numeric_limits<float>::quiet_NaN());
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      int gc = 0, gr = 0;
      if (!g.locate(lo.x() + c * cell, lo.y() + r * cell, gc, gr)) continue;
      const float v = z[g.index(gc, gr)];
      if (v > -9000.f) out[size_t(r) * nx + c] = float(v - origin.z());
    }
  std::ofstream(heights, std::ios::binary).write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size() * sizeof(float)));
  std::ostringstream j;
  j.precision(10);
  j << "{\"heights\": " << jsonString(heights) << ", \"nx\": " << nx << ", \"ny\": " << ny << ", \"x0\": "
    << lo.x() - origin.x() << ", \"y0\": " << lo.y() - origin.y() << ", \"cell\": " << cell << "}";
  return j.str();
}

std::string vec(const Vec3d& v) {
  std::ostringstream s;
  s.precision(10);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

/// Where the camera looks from: south-south-west of the flow, 30 degrees up, far enough for
/// the flow's bounding sphere to fill the picture's height (35 mm lens on a 36 mm sensor).
Vec3d framingCamera(const Vec3d& target, double radius, double aspect) {
  const double halfV = std::atan(18.0 / 35.0 / aspect);
  const double dist = 0.8 * radius / std::tan(halfV); // a flat flow fills less than its bounding sphere
  const double az = 200 * M_PI / 180, el = 30 * M_PI / 180; // bearing from the target (clockwise from north)
  return target + dist * Vec3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
}

/// Runs Blender on the script and its JSON, logging to `log` and reporting frames; "" or why not.
std::string runBlender(const std::string& exe, const std::string& script, const std::string& config,
                       const std::string& log, const std::function<void(int, int)>& progress) {
  auto quote = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string cmd = quote(exe) + " -b --factory-startup -noaudio --python-exit-code 2 --python " + quote(script) +
                          " -- " + quote(config) + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "cannot start " + exe;
  std::ofstream out(log);
  std::array<char, 4096> line;
  std::string last;
  while (std::fgets(line.data(), int(line.size()), p)) {
    out << line.data();
    int done = 0, total = 0;
    if (std::sscanf(line.data(), "TALUS frame %d %d", &done, &total) == 2 && progress) progress(done, total);
    if (line[0] != '\n') last = line.data();
  }
  const int status = pclose(p);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (!last.empty() && last.back() == '\n') last.pop_back();
  return "blender failed (" + log + "): " + last;
}

/// render/render.mp4 from the PNG frames with ffmpeg; "" or why not.
std::string encode(const std::string& renderDir, int fps) {
  const std::string exe = findProgram("ffmpeg");
  if (exe.empty()) return "ffmpeg is not installed (apt-get install ffmpeg): no render.mp4";
  const std::string cmd = "'" + exe + "' -hide_banner -loglevel error -y -framerate " + std::to_string(fps) + " -i '" +
                          renderDir + "/frame_%05d.png' -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -threads 4 "
                          "-pix_fmt yuv420p '" + renderDir + "/render.mp4' 2>&1";
  return std::system(cmd.c_str()) == 0 ? "" : "ffmpeg could not encode render.mp4";
}

} // namespace

RenderResult makeRender(const RenderOptions& o, const std::function<void(int, int)>& progress) {
  if (!fs::is_directory(o.dir)) throw InputError(o.dir, "not a folder");
  const std::vector<std::string> frames = selectFrames(o);
  RenderResult res;
  const std::string exe = o.blender.empty() ? findProgram("blender") : o.blender;
  if (exe.empty() || access(exe.c_str(), X_OK) != 0) {
    res.problem = "blender is not installed: apt-get install blender (Debian's Blender 3.4 renders Talus's volumes)";
    return res;
  }
  // The flow's extent over the frames, and its materials.
  VolumeFrameInfo first = readVolumeFrameInfo(frames.front());
  Vec3d lo = Vec3d::Constant(INFINITY), hi = -lo;
  for (const std::string& f : frames) {
    const VolumeFrameInfo v = f == frames.front() ? first : readVolumeFrameInfo(f);
    if (!v.empty) lo = lo.cwiseMin(v.lo), hi = hi.cwiseMax(v.hi);
  }
  if (!(lo.x() <= hi.x())) throw InputError(o.dir + "/frames", "the selected volume frames hold no material");
  const Vec3d origin = first.localOrigin;
  const fs::path out = fs::path(o.dir) / "render";
  fs::create_directories(out);
  // The ground around the flow: its extent more on each side (what the camera sees around it).
  const Vec3d margin = Vec3d(hi.x() - lo.x(), hi.y() - lo.y(), 0);
  const std::string terrain = writeTerrain(o.dir, origin, lo - margin, hi + margin, fs::absolute(out / "terrain.f32").string());
  const Vec3d target = o.target ? Vec3d(*o.target - origin) : Vec3d(0.5 * (lo + hi) - origin);
  const Vec3d camera = o.camera ? Vec3d(*o.camera - origin)
                                : framingCamera(target, 0.5 * (hi - lo).norm(), double(o.width) / o.height);
  double rhoMax = 1;
  std::ostringstream mats;
  for (size_t m = 0; m < first.materials.size(); ++m) {
    const auto& [name, rho] = first.materials[m];
    rhoMax = std::max(rhoMax, rho);
    const auto c = colourOf(name);
    mats << (m ? ", " : "") << "[" << jsonString(name) << ", [" << c[0] << ", " << c[1] << ", " << c[2] << "]]";
  }
  std::ostringstream j;
  j.precision(10);
  j << "{\"origin\": " << vec(origin) << ", \"camera\": " << vec(camera) << ", \"target\": " << vec(target)
    << ", \"width\": " << o.width << ", \"height\": " << o.height << ", \"samples\": " << o.samples
    // Extinction 3 per metre in pure material of the densest kind: a metre of flow is opaque.
    << ", \"density_scale\": " << 3.0 / rhoMax << ", \"materials\": [" << mats.str() << "]";
  if (!terrain.empty()) j << ", \"terrain\": " << terrain;
  j << ", \"frames\": [";
  for (size_t i = 0; i < frames.size(); ++i) {
    char png[32];
    std::snprintf(png, sizeof png, "frame_%05zu.png", i);
    j << (i ? ", " : "") << "[" << jsonString(fs::absolute(frames[i]).string()) << ", "
      << jsonString(fs::absolute(out / png).string()) << "]";
    res.files.push_back("render/" + std::string(png));
  }
  j << "]}\n";
  std::ofstream(out / "scene.json") << j.str();
  std::ofstream(out / "talus_render.py") << renderBlenderScript();
  res.problem = runBlender(exe, (out / "talus_render.py").string(), (out / "scene.json").string(),
                           (out / "blender.log").string(), progress);
  if (!res.problem.empty()) return res;
  res.frames = int(frames.size());
  if (frames.size() > 1) {
    res.problem = encode(out.string(), o.fps);
    if (res.problem.empty()) res.files.push_back("render/render.mp4");
  }
  return res;
}

} // namespace talus
