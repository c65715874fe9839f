#include "io/output/animation.h"

#include "io/common/geotiff_writer.h"
#include "io/common/input_error.h"
#include "io/common/program_path.h"
#include "io/common/raster_reader.h"
#include "io/common/write_error.h"
#include "io/output/map_quicklook.h"


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <spawn.h>
#include <sys/wait.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

extern char** environ;

namespace talus {

namespace fs = std::filesystem;

namespace {

constexpr float kNoData = -9999.f;

struct Frame {
  RasterGrid grid;
  std::vector<float> values;
  double time = 0;
};

std::string frameName(const char* quantity, int index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05d.tif", quantity, index);
  return name;
}

Frame readFrame(const std::string& path) {
  FloatRaster r = readFloatRaster(path, "this animation frame");
  Frame f;
  f.grid = r.grid;
  f.values = std::move(r.values);
  f.time = r.timeSeconds.empty() ? 0 : std::atof(r.timeSeconds.c_str());
  return f;
}

/// The part of a frame inside the world window (whole cells), or the frame itself.
Frame crop(Frame f, const std::optional<std::array<double, 4>>& w) {
  if (!w) return f;
  int c0 = 0, r0 = 0;
  Frame out = f;
  out.grid = windowOf(f.grid, (*w)[0], (*w)[1], (*w)[2], (*w)[3], c0, r0);
  if (out.grid.size() == 0) throw InputError("--window", "the window does not overlap the frames");
  out.values.assign(out.grid.size(), 0.f);
  for (int r = 0; r < out.grid.ny; ++r)
    for (int c = 0; c < out.grid.nx; ++c) out.values[out.grid.index(c, r)] = f.values[f.grid.index(c0 + c, r0 + r)];
  return out;
}

/// The ground under each cell of `grid` from maps/ground_elevation.tif (nearest cell), or none.
std::vector<float> groundOn(const std::string& dir, const RasterGrid& grid) {
  const std::string path = (fs::path(dir) / "maps" / "ground_elevation.tif").string();
  if (!fs::exists(path)) return {};
  const Frame g = readFrame(path);
  std::vector<float> z(grid.size(), std::numeric_limits<float>::quiet_NaN());
  for (int r = 0; r < grid.ny; ++r)
    for (int c = 0; c < grid.nx; ++c) {
      int gc = 0, gr = 0;
      if (g.grid.locate(grid.cellCentreX(c), grid.cellCentreY(r), gc, gr)) {
        const float v = g.values[g.grid.index(gc, gr)];
        if (v != kNoData) z[grid.index(c, r)] = v;
      }
    }
  return z;
}

/// ffmpeg encoding one film from raw frames written to its standard input.
struct Encoder {
  pid_t pid = -1;
  int fd = -1; ///< the pipe's writing end
  std::string out;
  std::string temporary() const { return out + ".tmp" + fs::path(out).extension().string(); }
};

/// Starts ffmpeg reading width x height BGRA frames from a pipe into `out`'s temporary name,
/// through `filter`; its messages go to `log`. pid -1 when it cannot start.
Encoder startEncoder(const std::string& exe, int width, int height, int fps, const std::string& filter,
                     const std::string& out, const std::string& log) {
  Encoder e;
  e.out = out;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return e;
  // Cairo's ARGB32 words in memory: B, G, R, A on a little-endian machine.
  const char* pixfmt = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? "bgra" : "argb";
  std::vector<std::string> args{exe, "-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", pixfmt,
                                "-s", std::to_string(width) + "x" + std::to_string(height), "-framerate",
                                std::to_string(fps), "-i", "pipe:0", "-vf", filter};
  // x264's bitstream depends on its thread count, which it takes from the CPUs it may use (one
  // under mpirun's binding): a fixed count makes the film the same file on every machine.
  if (fs::path(out).extension() == ".mp4")
    args.insert(args.end(), {"-c:v", "libx264", "-threads", "4", "-pix_fmt", "yuv420p", "-crf", "23", "-movflags",
                             "+faststart"});
  args.push_back(e.temporary());
  std::vector<char*> argv;
  for (auto& x : args) argv.push_back(x.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  const int rc = posix_spawn(&e.pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    e.pid = -1;
    return e;
  }
  e.fd = fds[1];
  return e;
}

/// Writes one frame; false (and the pipe closed) once ffmpeg has stopped reading.
bool feed(Encoder& e, const void* data, size_t n) {
  const char* p = static_cast<const char*>(data);
  while (e.fd >= 0 && n > 0) {
    const ssize_t w = ::write(e.fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) {
      ::close(e.fd);
      e.fd = -1;
      return false;
    }
    p += w, n -= size_t(w);
  }
  return e.fd >= 0;
}

/// Ends the input, waits for ffmpeg; renames its file into place when whole, else removes it.
bool finish(Encoder& e) {
  if (e.fd >= 0) ::close(e.fd), e.fd = -1;
  int status = 0;
  while (e.pid >= 0 && waitpid(e.pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::error_code ec;
  if (e.pid < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    fs::remove(e.temporary(), ec);
    return false;
  }
  fs::rename(e.temporary(), e.out, ec);
  if (ec) throw WriteError(e.out, ec.message());
  return true;
}

/// Ignores SIGPIPE while alive (a stopped encoder is reported by write's EPIPE instead).
struct IgnoreSigpipe {
  struct sigaction old{};
  IgnoreSigpipe() {
    struct sigaction ign{};
    ign.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ign, &old);
  }
  ~IgnoreSigpipe() { sigaction(SIGPIPE, &old, nullptr); }
};

/// " (ffmpeg: <the first line of `log`>)", or "" when ffmpeg said nothing there.
std::string firstLine(const std::string& log) {
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);
  return line.empty() ? "" : " (ffmpeg: " + line.substr(0, 200) + ")";
}

/// One film: its file name and its ffmpeg filter.
struct Film {
  std::string name, filter;
};

/// Draws the `n` pictures with `draw` (eight at a time, side by side) and feeds them raw to one
/// ffmpeg process per film, all at once (no PNG in between: encoding and decoding them was most
/// of the films' cost). Whether each film was made, in `films`' order.
std::vector<bool> encode(const std::string& exe, const std::string& dir, int fps, size_t n,
                         const std::function<MapImage(size_t)>& draw, const MapImage& first,
                         const std::vector<Film>& films, const std::string& log) {
  IgnoreSigpipe quiet;
  std::vector<Encoder> enc;
  for (const Film& f : films)
    enc.push_back(startEncoder(exe, first.width(), first.height(), fps, f.filter, (fs::path(dir) / f.name).string(), log));
  constexpr size_t kBatch = 8; // pictures drawn side by side, then written in order
  for (size_t b = 0; b < n; b += kBatch) {
    std::vector<MapImage> batch(std::min(kBatch, n - b));
    tbb::parallel_for(size_t(0), batch.size(), [&](size_t i) { batch[i] = b + i == 0 ? first : draw(b + i); });
    for (const MapImage& m : batch)
      for (Encoder& e : enc)
        if (m.width() == first.width() && m.height() == first.height()) feed(e, m.pixels(), m.bytes());
  }
  std::vector<bool> made;
  for (Encoder& e : enc) made.push_back(finish(e));
  return made;
}

/// The MP4 and the GIF, encoded side by side; a film whose encoder failed is encoded once more
/// alone (CI once saw a run's MP4 missing beside a busy test, and five reruns under load did not
/// see it again: a fault of the moment, such as a thread ffmpeg could not start, should not cost
/// the film; summary.json says which was encoded twice). The films made go to r.files, a
/// failure to r.problem.
void encodeFilms(const std::string& exe, const std::string& dir, const AnimationStyle& style, size_t n,
                 const std::function<MapImage(size_t)>& draw, AnimationResult& r) {
  const MapImage first = draw(0);
  const std::string log = (fs::path(dir) / "animation" / "ffmpeg.log").string();
  fs::remove(log);
  // H.264 wants even sizes; the GIF gets its own palette, at a page's width.
  const std::string size = style.width > 0 ? "scale=" + std::to_string(style.width / 2 * 2) + ":-2"
                                           : "pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white";
  const std::string gif = "scale=" + std::to_string(style.gifWidth) +
                          ":-1:flags=lanczos,split[a][b];[a]palettegen=max_colors=128[p];[b][p]paletteuse=dither=bayer";
  const std::vector<Film> films = {{"animation.mp4", size}, {"animation.gif", gif}};
  const std::vector<bool> made = encode(exe, dir, style.fps, n, draw, first, films, log);
  for (size_t k = 0; k < films.size(); ++k) {
    if (!made[k]) {
      r.retried += (r.retried.empty() ? "" : ", ") + films[k].name + firstLine(log);
      if (!encode(exe, dir, style.fps, n, draw, first, {films[k]}, log).front()) {
        r.problem = "ffmpeg failed making " + films[k].name + " (its messages: animation/ffmpeg.log); `talus animate` "
                    "makes it again from animation/rasters/";
        return;
      }
    }
    r.files.push_back(films[k].name);
  }
  fs::remove(log);
  fs::remove_all(fs::path(dir) / "animation" / "png"); // drawn by an earlier run without ffmpeg
}

} // namespace

std::vector<std::string> writeAnimationFrame(const std::string& dir, int index, double time, const RasterGrid& grid,
                                             const std::vector<float>& thickness, const std::vector<float>& speed) {
  const fs::path rasters = fs::path(dir) / "animation" / "rasters";
  std::error_code ec;
  fs::create_directories(rasters, ec);
  if (ec) throw WriteError(rasters.string(), ec.message());
  std::vector<std::string> files;
  const std::vector<float>* values[2] = {&thickness, &speed};
  const char* units[2] = {"m", "m/s"};
  for (int q = 0; q < 2; ++q) {
    // Zero where no flow (the quick-look shows the relief there); no data only where unknown.
    std::vector<float> v = *values[q];
    for (float& x : v)
      if (std::isnan(x)) x = kNoData;
    GeoTiffBand b;
    b.description = q == 0 ? "flow thickness (vertical)" : "speed (mass-weighted mean)";
    b.unit = units[q];
    b.nodata = kNoData;
    b.metadata = {{"TALUS_TIME_S", std::to_string(time)}, {"TALUS_QUANTITY", animationQuantities()[size_t(q)]}};
    const std::string name = frameName(animationQuantities()[size_t(q)], index);
    writeGeoTiff((rasters / name).string(), grid, v, b);
    files.push_back("animation/rasters/" + name);
  }
  return files;
}

AnimationResult makeAnimation(const std::string& dir, const AnimationStyle& style) {
  const auto& qs = animationQuantities();
  const int qi = int(std::find(qs.begin(), qs.end(), style.quantity) - qs.begin());
  if (qi == int(qs.size())) throw InputError("--quantity", "'" + style.quantity + "': choose thickness or speed");
  if (style.fps < 1 || style.fps > 120) throw InputError("--fps", "must be 1 to 120");
  std::vector<std::string> frames;
  const fs::path rasters = fs::path(dir) / "animation" / "rasters";
  for (int i = 0; fs::exists(rasters / frameName(qs[size_t(qi)], i)); ++i)
    frames.push_back((rasters / frameName(qs[size_t(qi)], i)).string());
  if (frames.empty())
    throw InputError(rasters.string(), std::string("no ") + qs[size_t(qi)] + " frames here: run the scene with [output] animation = true");
  // The colour scale is the film's: the largest value of any frame unless given. The run that
  // wrote the frames knows it; read again it is a pass over every frame.
  double top = style.scaleMax;
  if (!(top > 0)) {
    float m = 0;
    if (style.known && style.known->frames == frames.size() && !style.window) m = style.known->largest[size_t(qi)];
    else
      for (const auto& f : frames)
        for (float v : crop(readFrame(f), style.window).values)
          if (v != kNoData && std::isfinite(v)) m = std::max(m, v);
    top = chart::niceCeil(m > 0 ? m : 1);
  }
  const RasterGrid shown = crop(readFrame(frames[0]), style.window).grid;
  const std::vector<float> ground = groundOn(dir, shown);
  auto frame = [&](size_t i, QuicklookStyle& look) {
    Frame f = crop(readFrame(frames[i]), style.window);
    look.title = qi == 0 ? "Flow thickness (vertical)" : "Speed";
    char t[64];
    std::snprintf(t, sizeof t, "t = %.1f s", f.time);
    look.subtitle = t;
    look.unit = qi == 0 ? "m" : "m/s";
    look.ramp = qi == 0 ? chart::Ramp::Viridis : chart::Ramp::Plasma;
    look.scaleMax = top;
    return f;
  };
  AnimationResult r;
  r.frames = int(frames.size());
  const std::string exe = findProgram("ffmpeg");
  if (exe.empty()) {
    // The pictures, for whoever encodes them another way (frames drawn side by side).
    const fs::path png = fs::path(dir) / "animation" / "png";
    fs::remove_all(png);
    fs::create_directories(png);
    tbb::parallel_for(size_t(0), frames.size(), [&](size_t i) {
      QuicklookStyle look;
      const Frame f = frame(i, look);
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05zu.png", i);
      writeMapQuicklook((png / name).string(), f.grid, f.values, ground, look, kNoData);
    });
    r.problem = "ffmpeg not found (apt-get install ffmpeg): the drawn frames are in animation/png/";
    return r;
  }
  const ShadedRelief relief{hillshade(shown, ground)}, none; // the frames share the first's grid
  auto draw = [&](size_t i) {
    QuicklookStyle look;
    const Frame f = frame(i, look);
    // A frame of another size gets no relief (the film skips it anyway, encodeFilms).
    const bool same = f.grid.nx == shown.nx && f.grid.ny == shown.ny;
    return drawMapQuicklook(f.grid, f.values, same ? relief : none, look, kNoData);
  };
  encodeFilms(exe, dir, style, frames.size(), draw, r);
  return r;
}

} // namespace talus
