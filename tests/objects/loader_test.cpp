// SPDX-License-Identifier: MIT
// Model loaders: every shared model loads; broken files fail with one line
// naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/model.h"
#include "test_util.h"

namespace ts = terrasprite;
namespace fs = std::filesystem;

namespace {

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Loading `path` throws InputError whose message names the file.
void expect_input_error(const std::string& path, const ts::ModelOptions& o = {}) {
  try {
    ts::load_model(path, o);
    ADD_FAILURE() << path << " loaded";
  } catch (const ts::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fs::path(path).filename().string()), std::string::npos)
        << e.what();
  }
}

}  // namespace

TEST(ModelLoader, ObjTriangleToWorldConventions) {
  tstest::TempDir dir;
  // A y-up triangle 2 units tall: becomes z-up, base on z = 0, 5 m tall.
  write(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 2 0\nf 1 2 3\n");
  ts::ModelOptions o;
  o.height_m = 5.0;
  const ts::Model m = ts::load_model(dir / "t.obj", o);
  ASSERT_EQ(m.triangles(), 1u);
  EXPECT_NEAR(m.bounds_min.z, 0.f, 1e-6);
  EXPECT_NEAR(m.bounds_max.z, 5.f, 1e-5);
  EXPECT_NEAR(m.bounds_min.x + m.bounds_max.x, 0.f, 1e-5);
  EXPECT_FALSE(m.normals_from_file);
  EXPECT_NEAR(std::abs(m.normals[0].y), 1.f, 1e-5);  // the file's z axis is now -y
}

TEST(ModelLoader, EveryShippedModelLoads) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  int n = 0;
  for (const auto& dir : fs::directory_iterator(data)) {
    if (dir.path().filename().string().rfind("models_", 0) != 0) continue;
    for (const auto& f : fs::directory_iterator(dir.path())) {
      const std::string ext = f.path().extension().string();
      if (ext != ".obj" && ext != ".glb" && ext != ".gltf") continue;
      ts::ModelOptions o;
      o.height_m = 2.0;
      const ts::Model m = ts::load_model(f.path().string(), o);
      EXPECT_GT(m.triangles(), 100u) << f.path();
      EXPECT_NEAR(m.bounds_max.z, 2.f, 1e-4) << f.path();
      for (const ts::Material& mat : m.materials)
        EXPECT_LT(mat.texture, int(m.textures.size())) << f.path();
      ++n;
    }
  }
  EXPECT_GE(n, 14);
}

TEST(ModelLoader, GltfNodeTransformsAndTextures) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  const ts::Model truck = ts::load_model(data + "/models_cesium_milk_truck/CesiumMilkTruck.glb");
  EXPECT_EQ(truck.triangles(), 3624u);  // the wheels mesh is drawn by two nodes
  EXPECT_EQ(truck.textures.size(), 1u);
  EXPECT_TRUE(truck.normals_from_file);
  ts::ModelOptions o;
  o.texture = data + "/models_scans/spot_texture.png";
  const ts::Model spot = ts::load_model(data + "/models_scans/spot.obj", o);
  ASSERT_EQ(spot.textures.size(), 1u);
  EXPECT_EQ(spot.materials[spot.parts[0].material].texture, 0);
}

TEST(ModelLoader, BrokenFilesFailNamingTheFile) {
  tstest::TempDir dir;
  write(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expect_input_error(dir / "range.obj");
  write(dir / "quad_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 7\n");
  expect_input_error(dir / "quad_range.obj");
  write(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_input_error(dir / "nan.obj");
  write(dir / "empty.obj", "v 0 0 0\nv 1 0 0\n");
  expect_input_error(dir / "empty.obj");
  write(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");  // y-up, zero height
  expect_input_error(dir / "flat.obj");
  write(dir / "tex.mtl", "newmtl m\nmap_Kd nowhere.png\n");
  write(dir / "tex.obj", "mtllib tex.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_input_error(dir / "tex.obj");
  ts::ModelOptions o;
  o.texture = dir / "missing.png";
  write(dir / "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_input_error(dir / "plain.obj", o);
  expect_input_error(dir / "absent.glb");
  write(dir / "garbage.glb", "glTF this is not a binary glTF");
  expect_input_error(dir / "garbage.glb");
  write(dir / "model.stl", "solid x\n");
  expect_input_error(dir / "model.stl");
}

TEST(ModelLoader, TruncatedGlbFails) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  std::ifstream in(data + "/models_kenney_nature/tree_oak_fall.glb", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  tstest::TempDir dir;
  for (double keep : {0.9, 0.5, 0.1}) {
    const std::string p = dir / "cut.glb";
    write(p, bytes.substr(0, std::size_t(bytes.size() * keep)));
    expect_input_error(p);
  }
}

TEST(ModelLoader, CliExitsTwoWithOneLine) {
  tstest::TempDir dir;
  write(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
  const tstest::CliResult r = tstest::run_cli("objects info --model " + (dir / "bad.obj"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("bad.obj"), std::string::npos);
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}
