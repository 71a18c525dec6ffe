// SPDX-License-Identifier: MIT
// Hostile model files, each made here: refused in one short line naming the
// file, quickly and without running out of stack or memory.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/model.h"
#include "terrasprite/objects/object_layout.h"
#include "test_util.h"

namespace ts = terrasprite;
namespace fs = std::filesystem;

namespace {

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The message loading `path` fails with; empty (and a test failure) if it loads.
std::string load_error(const std::string& path, const ts::ModelOptions& o = {}) {
  try {
    ts::load_model(path, o);
    ADD_FAILURE() << path << " loaded";
  } catch (const ts::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(fs::path(path).filename().string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_LT(what.size(), 400u) << what.substr(0, 400);
    return what;
  }
  return {};
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8 |
                       (unsigned char)bytes[i + 2];
    for (int s : {18, 12, 6, 0}) out += k[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    unsigned v = (unsigned char)bytes[i] << 16;
    if (i + 1 < bytes.size()) v |= (unsigned char)bytes[i + 1] << 8;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string float_bytes(const std::vector<float>& v) {
  std::string b(v.size() * 4, '\0');
  std::memcpy(b.data(), v.data(), b.size());
  return b;
}

// A glTF of one triangle (`positions`, 9 floats) in an embedded buffer;
// `nodes` and `extra` replace the node list and add top-level members.
std::string gltf_json(const std::vector<float>& positions,
                      const std::string& nodes = R"([{"mesh": 0}])", const std::string& extra = "",
                      const std::string& buffer_uri = "") {
  const std::string bytes = float_bytes(positions);
  const std::string uri =
      buffer_uri.empty() ? "data:application/octet-stream;base64," + base64(bytes) : buffer_uri;
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],)"
         R"("buffers": [{"byteLength": )" +
         std::to_string(bytes.size()) + R"(, "uri": ")" + uri + R"("}],)" +
         R"("bufferViews": [{"buffer": 0, "byteLength": )" + std::to_string(bytes.size()) +
         R"(}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3,)"
         R"("type": "VEC3"}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],)"
         R"("nodes": )" +
         nodes + extra + "}";
}

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

// A .glb holding `json` as its only chunk.
std::string glb(std::string json) {
  while (json.size() % 4) json += ' ';
  std::string out = "glTF";
  auto u32 = [&out](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  u32(std::uint32_t(12 + 8 + json.size()));
  u32(std::uint32_t(json.size()));
  u32(0x4E4F534A);
  return out + json;
}

}  // namespace

// 0.01 s.
TEST(HostileModels, NonFiniteCoordinatesAnywhereOnTheLine) {
  tstest::TempDir dir;
  write_text(dir / "indented.obj", "v 0 0 0\nv 1 0 0\n  v nan nan nan\n\tv 0 1 0\nf 1 2 4\n");
  EXPECT_NE(load_error(dir / "indented.obj").find("line 3"), std::string::npos);
  write_text(dir / "huge.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
  load_error(dir / "huge.obj");
  write_text(dir / "hex.obj", "v 0 0 0\nv 0x10 0 0\nv 0 1 0\nf 1 2 3\n");
  load_error(dir / "hex.obj");
  write_text(dir / "uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt inf 0\nf 1/1 2/1 3/1\n");
  load_error(dir / "uv.obj");
  write_text(dir / "nan.gltf", gltf_json({0, 0, 0, NAN, 0, 0, 0, 1, 0}));
  load_error(dir / "nan.gltf");
  // Finite in the file, infinite once the node's scale applies.
  write_text(dir / "scaled.gltf", gltf_json(kTriangle, R"([{"mesh": 0, "scale": [1e300, 1, 1]}])"));
  load_error(dir / "scaled.gltf");
}

// 0.01 s.
TEST(HostileModels, ExtentBeyondWhatAFloatHoldsOrTheHeightLimit) {
  tstest::TempDir dir;
  write_text(dir / "wide.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(load_error(dir / "wide.obj").find("spans"), std::string::npos);
  // A sliver 1e-30 tall scaled to 1 m is 1e30 m wide.
  write_text(dir / "sliver.obj", "v 0 0 0\nv 1 0 0\nv 0 1e-30 0\nf 1 2 3\n");
  ts::ModelOptions o;
  o.height_m = 1;
  load_error(dir / "sliver.obj", o);
  write_text(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  for (double h : {1e308, double(INFINITY), double(NAN), -1.0, 10001.0}) {
    o.height_m = h;
    EXPECT_NE(load_error(dir / "t.obj", o).find("height"), std::string::npos) << h;
  }
  o.height_m = 1e4;
  EXPECT_NEAR(ts::load_model(dir / "t.obj", o).bounds_max.z, 1e4f, 1.f);
}

// 0.01 s.
TEST(HostileModels, TruncatedObjRefused) {
  tstest::TempDir dir;
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n";
  for (const std::string tail : {
           "f 2 4",                  // a face cut to two corners
           "f 2 4 3",                // a last line without its end
           "f 2 4 3\nv 1 2\n",       // a vertex cut to two coordinates
           "f 2 4 3\nv 1 2 3.5e\n",  // a number cut short
           "f 2 4/\n",               // a corner cut after its slash
           "f 2 4 30\n",             // past the vertices
           "f 2 4 3 1 50\n",         // past the vertices, in a polygon
           "f 2 4 -9\n",             // before the first vertex
           "f 1/5 2/5 3/5\n",        // past the uvs
       }) {
    write_text(dir / "cut.obj", head + tail);
    const std::string what = load_error(dir / "cut.obj");
    EXPECT_FALSE(what.empty()) << tail;
  }
  write_text(dir / "ok.obj", head + "f 2 4 3\n# the end, without a line end");
  EXPECT_EQ(ts::load_model(dir / "ok.obj").triangles(), 2u);
}

// 0.1 s.
TEST(HostileModels, HugePolygonRefusedQuickly) {
  tstest::TempDir dir;
  std::string obj;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    obj += fmt::format("v {} {} 0\n", std::cos(a), std::sin(a));
  }
  obj += "f";
  for (int i = 1; i <= n; ++i) obj += " " + std::to_string(i);
  write_text(dir / "disc.obj", obj + "\n");
  EXPECT_NE(load_error(dir / "disc.obj").find("at most 1000"), std::string::npos);
  // The largest accepted polygon: a disc of 1000 corners, 998 triangles.
  std::string small = "v 0 0 -1\n";
  for (int i = 0; i < 1000; ++i) {
    const double a = 2 * M_PI * i / 1000;
    small += fmt::format("v {} {} 0\n", std::cos(a), std::sin(a));
  }
  small += "f";
  for (int i = 2; i <= 1001; ++i) small += " " + std::to_string(i);
  write_text(dir / "small_disc.obj", small + "\nf 1 2 3\n");
  ts::ModelOptions o;
  o.up = ts::UpAxis::kZ;
  EXPECT_EQ(ts::load_model(dir / "small_disc.obj", o).triangles(), 999u);
}

// 0.2 s.
TEST(HostileModels, DeepJsonRefusedBeforeParsing) {
  tstest::TempDir dir;
  const int depth = 1000000;
  const std::string deep = std::string(depth, '[') + std::string(depth, ']');
  const std::string json = gltf_json(kTriangle, R"([{"mesh": 0}])", ", \"extras\": " + deep);
  write_text(dir / "deep.gltf", json);
  EXPECT_NE(load_error(dir / "deep.gltf").find("nests deeper"), std::string::npos);
  write_text(dir / "deep.glb", glb(json));
  EXPECT_NE(load_error(dir / "deep.glb").find("nests deeper"), std::string::npos);
  // Brackets inside strings are text, not nesting.
  write_text(dir / "strings.gltf", gltf_json(kTriangle, R"([{"mesh": 0, "name": ")" +
                                                            std::string(1000, '[') + R"(\""}])"));
  EXPECT_EQ(ts::load_model(dir / "strings.gltf").triangles(), 1u);
}

// 0.01 s.
TEST(HostileModels, NodeGraphWithExponentiallyManyPathsRefused) {
  tstest::TempDir dir;
  // Node i has node i + 1 as both its children: 2^24 paths to the last node.
  std::string nodes = "[";
  for (int i = 0; i < 24; ++i)
    nodes += fmt::format(R"({{"mesh": 0, "children": [{}, {}]}},)", i + 1, i + 1);
  nodes += R"({"mesh": 0}])";
  write_text(dir / "paths.gltf", gltf_json(kTriangle, nodes));
  EXPECT_NE(load_error(dir / "paths.gltf").find("reaches nodes over 100000 times"),
            std::string::npos);
}

// 0.05 s.
TEST(HostileModels, MessagesSayWhatIsWrongInOneShortLine) {
  tstest::TempDir dir;
  fs::create_directory(dir / "adir");
  fs::create_directory(dir / "model.obj");
  EXPECT_NE(load_error(dir / "model.obj").find("is a directory"), std::string::npos);
  write_text(dir / "buffer_dir.gltf", gltf_json(kTriangle, R"([{"mesh": 0}])", "", "adir"));
  EXPECT_NE(load_error(dir / "buffer_dir.gltf").find("is a directory"), std::string::npos);
  std::string img = gltf_json(kTriangle);
  img.insert(img.size() - 1, R"(, "images": [{"uri": "adir"}], "textures": [{"source": 0}],)"
                             R"("materials": [{"pbrMetallicRoughness": {"baseColorTexture":)"
                             R"({"index": 0}}}])");
  write_text(dir / "image_dir.gltf", img);
  EXPECT_NE(load_error(dir / "image_dir.gltf").find("is a directory"), std::string::npos);
  // An embedded buffer of 2 MB whose byteLength is wrong: tinygltf's
  // message quotes the whole URI.
  std::vector<float> big(500000, 0.f);
  std::copy(kTriangle.begin(), kTriangle.end(), big.begin());
  std::string wrong = gltf_json(big);
  const std::string len = "\"byteLength\": " + std::to_string(big.size() * 4);
  wrong.replace(wrong.find(len), len.size(), "\"byteLength\": 7");
  write_text(dir / "length.gltf", wrong);
  EXPECT_LT(load_error(dir / "length.gltf").size(), 250u);
}

// 0.01 s.
TEST(HostileModels, BadUpAxisNamesTheSceneAndTheModel) {
  ts::Heightfield h;
  h.width = h.height = 3;
  h.spacing_x = h.spacing_y = 10;
  h.heights.assign(9, 0.f);
  try {
    ts::parse_object_layout(R"({"models": [{"name": "bunny", "file": "b.obj", "up": "x"}]})",
                            "scene.json", ".", h);
    ADD_FAILURE() << "parsed";
  } catch (const ts::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene.json"), std::string::npos) << what;
    EXPECT_NE(what.find("bunny"), std::string::npos) << what;
  }
}
