// End to end: Blender (Debian's 3.4, when installed) imports a VDB frame as a volume object in
// background mode, finds its grids at the right world position, and renders a small PNG with
// Cycles (denoising off: Debian's Blender has no denoiser). Skipped when blender is absent.
#include "io/output/vdb_frame_writer.h"
#include "test_support.h"

#include <array>
#include <cairo.h>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>

using namespace talus;

namespace {

std::string runCommand(const std::string& cmd, int& status) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    status = -1;
    return out;
  }
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  status = pclose(p);
  return out;
}

const char* kScript = R"PY(import sys, bpy, mathutils
vdb, png = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
vol = bpy.data.volumes.new("talus")
vol.filepath = vdb
vol.grids.load()
names = [g.name for g in vol.grids]
print("TALUS grids:", ",".join(names))
if "density" not in names or "velocity" not in names:
    sys.exit(3)
obj = bpy.data.objects.new("talus", vol)
scene.collection.objects.link(obj)
mat = bpy.data.materials.new("talus_volume")
mat.use_nodes = True
nodes = mat.node_tree.nodes
nodes.clear()
out = nodes.new("ShaderNodeOutputMaterial")
pv = nodes.new("ShaderNodeVolumePrincipled")
pv.inputs["Density"].default_value = 0.01  # the density grid is in kg/m3
mat.node_tree.links.new(pv.outputs["Volume"], out.inputs["Volume"])
vol.materials.append(mat)
bpy.context.view_layer.update()
corners = [obj.matrix_world @ mathutils.Vector(c) for c in obj.bound_box]
centre = sum(corners, mathutils.Vector()) / 8
radius = max((c - centre).length for c in corners)
print("TALUS centre %.4f %.4f %.4f" % tuple(centre))
cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(cam)
cam.location = centre + mathutils.Vector((0.0, -3.0 * radius, 1.5 * radius))
cam.rotation_euler = (centre - cam.location).to_track_quat("-Z", "Y").to_euler()
scene.camera = cam
world = bpy.data.worlds.new("world")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
scene.world = world
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 8
scene.cycles.use_denoising = False
scene.render.resolution_x = 64
scene.render.resolution_y = 64
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = png
bpy.ops.render.render(write_still=True)
)PY";

/// Mean brightness (0..1) of a square of the image.
double meanBrightness(cairo_surface_t* img, int x0, int y0, int size) {
  const int stride = cairo_image_surface_get_stride(img);
  const unsigned char* d = cairo_image_surface_get_data(img);
  double sum = 0;
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x) {
      uint32_t p;
      std::memcpy(&p, d + size_t(y) * stride + 4 * x, 4);
      sum += (((p >> 16) & 255) + ((p >> 8) & 255) + (p & 255)) / (3 * 255.0);
    }
  return sum / (size * size);
}

} // namespace

TEST(OutputBlender, ImportsAVolumeFrameAndRendersIt) {
  int status = 0;
  runCommand("command -v blender >/dev/null 2>&1", status);
  if (status != 0) GTEST_SKIP() << "blender not installed (Debian package 'blender'): end-to-end render skipped";

  // A 0.6 m ball of rock away from the world origin (Blender keeps transforms in single
  // precision, so this test stays at modest coordinates; see docs/outputs.md).
  auto sim = test::makeSimulation(R"([simulation]
dx = 0.05
end_time = 1
[domain]
min = [100, 200, 50]
max = [101, 201, 51]
[[materials]]
name = "rock"
model = "elastic"
density = 2500
youngs_modulus = 1e7
[[bodies]]
material = "rock"
shape = "sphere"
center = [100.5, 200.5, 50.5]
radius = 0.3
)");
  const std::string dir = test::tempDir("blender");
  writeVolumeVdb(dir + "/volume_00000.vdb", *sim);
  std::ofstream(dir + "/render.py") << kScript;
  const std::string png = dir + "/render.png";
  const std::string out = runCommand("cd '" + dir + "' && blender -b --factory-startup -noaudio --python-exit-code 2 "
                                     "--python render.py -- volume_00000.vdb '" + png + "' 2>&1",
                                     status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("TALUS grids: density,fraction_rock,velocity"), std::string::npos) << out;
  // Blender placed the volume where it is in world coordinates. It bounds a volume by whole
  // OpenVDB leaves (8 voxels), so its box centre is the ball's to within half a leaf, 0.2 m.
  const size_t at = out.find("TALUS centre ");
  ASSERT_NE(at, std::string::npos) << out;
  double c[3];
  ASSERT_EQ(std::sscanf(out.c_str() + at, "TALUS centre %lf %lf %lf", &c[0], &c[1], &c[2]), 3);
  EXPECT_NEAR(c[0], 100.5, 0.2);
  EXPECT_NEAR(c[1], 200.5, 0.2);
  EXPECT_NEAR(c[2], 50.5, 0.2);

  cairo_surface_t* img = cairo_image_surface_create_from_png(png.c_str());
  ASSERT_EQ(cairo_surface_status(img), CAIRO_STATUS_SUCCESS) << out;
  EXPECT_EQ(cairo_image_surface_get_width(img), 64);
  // The ball absorbs the white sky behind it: the centre of the picture is clearly darker than
  // its corners (8 samples are noisy, hence a wide margin).
  const double centre = meanBrightness(img, 24, 24, 16), corner = meanBrightness(img, 0, 0, 8);
  EXPECT_LT(centre, 0.7 * corner) << "centre " << centre << ", corner " << corner;
  cairo_surface_destroy(img);
}
