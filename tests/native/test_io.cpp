// Tests for the mesh, label and report files: lossless round trips in every
// format, the syntax variants real files use, and one clear polycube::Error
// (naming the file) for every kind of broken input, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/byte_sink.h"
#include "io/json.h"
#include "io/labels_io.h"
#include "io/output_files.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

namespace {

using polycube::PolygonFaces;
using polycube::PolygonMesh;
using polycube::Vertices;

// A file name of the running test's own, so tests run in parallel processes
// (ctest -j) never share a file.
std::string temp_path(const std::string& name) {
  const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
  std::string prefix = std::string(test->test_suite_name()) + "_" + test->name() + "_";
  std::replace(prefix.begin(), prefix.end(), '/', '_');
  return testing::TempDir() + "polycube_io_" + prefix + name;
}

std::string save(const std::string& name, const std::string& bytes) {
  std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the polycube::Error that f throws, or a note that it threw
// none (any other exception fails the test by escaping).
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const polycube::Error& e) {
    return e.what();
  }
  return "<no polycube::Error thrown>";
}

// Expects reading the file made of `bytes` to fail with a message that names
// the file and contains `expected`.
void expect_read_error(const std::string& name, const std::string& bytes, const std::string& expected) {
  std::string path = save(name, bytes);
  std::string message = error_of([&] { polycube::read_mesh(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << message;
}

const double kPi = 3.141592653589793;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_vertices(const Vertices& a, const Vertices& b) {
  ASSERT_EQ(a.rows(), b.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(same_bits(a(i, c), b(i, c))) << i << "," << c << ": " << a(i, c) << " vs " << b(i, c);
}

void expect_same_faces(const PolygonFaces& a, const PolygonFaces& b) {
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.offsets, b.offsets);
}

// Vertices whose decimal forms are awkward: thirds, -0, extremes, a
// subnormal, the next double after 1.
PolygonMesh awkward_mesh() {
  PolygonMesh m;
  m.vertices.resize(8, 3);
  m.vertices << 0.1, 1.0 / 3.0, -0.0,                                                   //
      1e300, -1e-300, 5e-324,                                                           //
      std::nextafter(1.0, 2.0), kPi, -2.5,                                              //
      123456789.123456789, -0.000123, 7,                                                //
      std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(), 1e-7,  //
      0, 0, 0,                                                                          //
      1, 2, 3,                                                                          //
      -1.0 / 7.0, 2.0 / 3.0, 1e22;
  m.faces.add({0, 1, 2});        // triangle
  m.faces.add({2, 3, 4, 5});     // quad
  m.faces.add({7, 6, 5, 4, 3});  // pentagon
  m.faces.add({0, 2, 4, 6});
  return m;
}

// ------------------------------------------------------------ round trips

class IoRoundTrip : public testing::TestWithParam<std::string> {};

TEST_P(IoRoundTrip, AwkwardValuesPolygonsAreBitExact) {
  PolygonMesh m = awkward_mesh();
  std::string path = temp_path("round_trip" + GetParam());
  polycube::write_mesh(path, m.vertices, m.faces);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  PolygonMesh r = polycube::read_mesh(path);
  expect_same_vertices(m.vertices, r.vertices);
  expect_same_faces(m.faces, r.faces);
}

TEST_P(IoRoundTrip, EmptyMesh) {
  std::string path = temp_path("empty" + GetParam());
  polycube::write_mesh(path, Vertices(0, 3), PolygonFaces());
  PolygonMesh r = polycube::read_mesh(path);
  EXPECT_EQ(r.vertices.rows(), 0);
  EXPECT_EQ(r.faces.count(), 0);
}

TEST_P(IoRoundTrip, FaceWithMoreThan255Corners) {
  const int n = 300;
  Vertices v(n, 3);
  PolygonFaces f;
  for (int i = 0; i < n; ++i) {
    v.row(i) << std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 0;
    f.indices.push_back(i);
  }
  f.offsets.push_back(n);
  f.add({0, 1, 2});
  std::string path = temp_path("big_polygon" + GetParam());
  polycube::write_mesh(path, v, f);
  PolygonMesh r = polycube::read_mesh(path);
  expect_same_vertices(v, r.vertices);
  expect_same_faces(f, r.faces);
}

INSTANTIATE_TEST_SUITE_P(Formats, IoRoundTrip,
                         testing::Values(".obj", ".off", ".ply", ".OBJ", ".Off", ".PLY"),
                         [](const testing::TestParamInfo<std::string>& p) {
                           std::string s = p.param.substr(1);
                           return s + (std::islower(static_cast<unsigned char>(p.param[1])) ? "" : "_upper");
                         });

// Files written in chunks (byte_sink.h) are the bytes built whole in memory.
TEST(IoWriteMesh, ChunkedFilesEqualTheWholeText) {
  Vertices v(20000, 3);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (Eigen::Index i = 0; i < v.size(); ++i) v.data()[i] = coordinate(random);
  PolygonFaces f;
  for (int i = 0; i + 2 < v.rows(); ++i) f.add({i, i + 1, i + 2});
  for (const std::string extension : {".obj", ".off", ".ply"}) {
    const std::string path = temp_path("chunked" + extension);
    polycube::write_mesh(path, v, f);
    const std::string whole = polycube::mesh_file_bytes(path, v, f);
    EXPECT_GT(whole.size(), 4 * polycube::ByteSink::kChunk);
    EXPECT_TRUE(load(path) == whole) << extension;
  }
}

TEST(IoWriteMesh, PlyIsBinaryLittleEndianWithDoubles) {
  PolygonMesh m = awkward_mesh();
  std::string path = temp_path("format.ply");
  polycube::write_mesh(path, m.vertices, m.faces);
  std::string bytes = load(path);
  EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(bytes.find("property double x\n"), std::string::npos);
  EXPECT_NE(bytes.find("property list uchar int vertex_indices\n"), std::string::npos);
  // header + 8 vertices * 24 bytes + 4 list lengths + 16 indices * 4 bytes
  size_t header = bytes.find("end_header\n") + 11;
  EXPECT_EQ(bytes.size(), header + 8 * 24 + 4 + 16 * 4);
}

TEST(IoWriteMesh, FailureLeavesExistingFileAndNoTemporary) {
  std::string path = save("keep.obj", "v 0 0 0\n");
  PolygonMesh m = awkward_mesh();
  m.faces.add({0, 1, 99});
  std::string message = error_of([&] { polycube::write_mesh(path, m.vertices, m.faces); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 99"), std::string::npos) << message;
  EXPECT_EQ(load(path), "v 0 0 0\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

// The files in a fresh folder of the running test's own.
std::vector<std::string> folder_files(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(IoOutputFiles, AllOrNone) {
  const std::string folder = temp_path("outputs");
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder + "/taken");
  std::ofstream(folder + "/old.txt") << "old";
  {  // the second cannot be staged: neither appears, the old file keeps its contents
    polycube::OutputFiles outputs;
    outputs.stage(folder + "/new.txt", "new");
    outputs.stage(folder + "/old.txt", "replaced");
    EXPECT_NE(error_of([&] { outputs.stage(folder + "/taken", "x"); }).find("it is a directory"), std::string::npos);
  }
  EXPECT_EQ(folder_files(folder), (std::vector<std::string>{"old.txt", "taken"}));
  EXPECT_EQ(load(folder + "/old.txt"), "old");
  {  // staged but never committed (a later step failed): nothing either
    polycube::OutputFiles outputs;
    outputs.stage(folder + "/new.txt", "new");
  }
  EXPECT_EQ(folder_files(folder), (std::vector<std::string>{"old.txt", "taken"}));
  polycube::OutputFiles outputs;
  outputs.stage(folder + "/new.txt", "new");
  outputs.stage(folder + "/old.txt", "replaced");
  outputs.commit();
  EXPECT_EQ(folder_files(folder), (std::vector<std::string>{"new.txt", "old.txt", "taken"}));
  EXPECT_EQ(load(folder + "/old.txt"), "replaced");
  EXPECT_NE(error_of([] { polycube::write_file_atomically(std::string("a\0b", 3), "x"); }).find("NUL"),
            std::string::npos);
  std::filesystem::remove_all(folder);
}

TEST(IoWriteMesh, ReplacesExistingFile) {
  std::string path = save("replace.off", "old contents");
  PolygonMesh m = awkward_mesh();
  polycube::write_mesh(path, m.vertices, m.faces);
  EXPECT_EQ(polycube::read_mesh(path).faces.count(), 4);
}

TEST(IoWriteMesh, ClearErrors) {
  PolygonMesh m = awkward_mesh();
  auto message = [&](const std::string& path, const Vertices& v, const PolygonFaces& f) {
    std::string s = error_of([&] { polycube::write_mesh(path, v, f); });
    EXPECT_NE(s.find(path), std::string::npos) << s;
    return s;
  };
  std::string missing_dir = temp_path("no_such_dir/sub/out.obj");
  EXPECT_NE(message(missing_dir, m.vertices, m.faces).find("does not exist"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(missing_dir));
  EXPECT_NE(message(temp_path("out.stl"), m.vertices, m.faces).find("'.stl'"), std::string::npos);
  EXPECT_NE(message(temp_path("noext"), m.vertices, m.faces).find("extension"), std::string::npos);
  std::filesystem::create_directories(temp_path("dir.obj"));
  EXPECT_NE(message(temp_path("dir.obj"), m.vertices, m.faces).find("directory"), std::string::npos);

  Vertices nan = m.vertices;
  nan(3, 1) = std::nan("");
  EXPECT_NE(message(temp_path("nan.off"), nan, m.faces).find("vertex 3 has a non-finite"), std::string::npos);
  PolygonFaces two = m.faces;
  two.add({1, 2});
  EXPECT_NE(message(temp_path("two.ply"), m.vertices, two).find("at least 3"), std::string::npos);
  PolygonFaces broken = m.faces;
  broken.offsets.back() += 1;
  EXPECT_NE(message(temp_path("broken.obj"), m.vertices, broken).find("offsets"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(temp_path("nan.off")));
}

// ------------------------------------------------------------ reading: common

TEST(IoReadMesh, MissingFileUnknownExtensionDirectory) {
  std::string missing = temp_path("does_not_exist.off");
  std::string m = error_of([&] { polycube::read_mesh(missing); });
  EXPECT_NE(m.find(missing), std::string::npos) << m;
  EXPECT_NE(m.find("No such file"), std::string::npos) << m;

  std::string stl = save("mesh.stl", "solid x\nendsolid x\n");
  m = error_of([&] { polycube::read_mesh(stl); });
  EXPECT_NE(m.find(stl), std::string::npos) << m;
  EXPECT_NE(m.find("'.stl'"), std::string::npos) << m;

  std::filesystem::create_directories(temp_path("folder.obj"));
  m = error_of([&] { polycube::read_mesh(temp_path("folder.obj")); });
  EXPECT_NE(m.find("is a directory"), std::string::npos) << m;
}

// ------------------------------------------------------------ OFF

TEST(IoReadOff, HeaderVariantsCommentsAndColours) {
  // CGAL-style leading comments, counts on the OFF line, CRLF endings,
  // comments without a space, blank lines.
  std::string path = save("variants.off",
                          "# Output of a tool\r\n#CBP\r\nOFF 4 2 0\r\n\r\n"
                          "0 0 0\r\n1 0 0 # end comment\r\n  1 1 0\r\n0 1 0#x\r\n"
                          "3 0 1 2\r\n4 0 1 2 3 255 0 0\r\n");
  PolygonMesh m = polycube::read_mesh(path);
  EXPECT_EQ(m.vertices.rows(), 4);
  EXPECT_EQ(m.vertices(2, 1), 1.0);
  PolygonFaces expected;
  expected.add({0, 1, 2});
  expected.add({0, 1, 2, 3});
  expect_same_faces(expected, m.faces);

  // COFF with RGBA per vertex, NOFF with normals, STCNOFF with everything;
  // counts on the next line; + signs and exponents.
  for (std::string header : {"COFF", "NOFF", "CNOFF", "STCNOFF", "nOFF\n3"}) {
    std::string extra = header == "COFF"   ? " 0.5 0.5 0.5 1"
                        : header == "NOFF" ? " 0 0 1"
                                           : " 1 2 3 4 5 6 7 8 9";
    std::string text = header + "\n3 1 3\n" + "+1e0 2 3" + extra + "\n4 5 6" + extra + "\n7 8 9.5E-1" +
                       extra + "\n3 2 1 0 1 0 0 1\n";
    PolygonMesh c = polycube::read_mesh(save("variant.off", text));
    EXPECT_EQ(c.vertices.rows(), 3) << header;
    EXPECT_EQ(c.vertices(0, 0), 1.0) << header;
    EXPECT_EQ(c.vertices(2, 2), 0.95) << header;
    EXPECT_EQ(c.faces.indices, (std::vector<int>{2, 1, 0})) << header;
  }
}

TEST(IoReadOff, MalformedInputs) {
  expect_read_error("e.off", "", "is empty");
  expect_read_error("e.off", "PLY\n3 1 0\n", "line 1: expected an OFF header, got 'PLY'");
  expect_read_error("e.off", "3 1 0\n0 0 0\n", "line 1: expected an OFF header");
  expect_read_error("e.off", "4OFF\n1 0 0\n0 0 0 0\n", "4D");
  expect_read_error("e.off", "nOFF\n4\n1 0 0\n0 0 0 0\n", "only 3D");
  expect_read_error("e.off", "OFF BINARY\n", "binary OFF");
  expect_read_error("e.off", "OFF\n", "file ends before the vertex count");
  expect_read_error("e.off", "OFF\n3\n", "file ends before the face count");
  expect_read_error("e.off", "OFF\nthree 1 0\n", "line 2: expected the vertex count, got 'three'");
  expect_read_error("e.off", "OFF\n-3 1 0\n", "-3 vertices");
  // A bogus count must fail at once, not try to allocate it.
  expect_read_error("e.off", "OFF\n2000000000 2000000000 0\n0 0 0\n",
                    "more than the rest of the file can hold");
  expect_read_error("e.off", "OFF\n99999999999999 1 0\n", "not a usable count");
  // Long lines, so the counts pass the size check and the reader finds the end.
  expect_read_error("e.off", "OFF\n3 1 0\n0.000 0.000 0.000\n1.000 0.000 0.000\n",
                    "line 4: file ends after 2 of the 3 vertices");
  expect_read_error("e.off", "OFF\n3 2 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n3 0 1 2\n",
                    "line 6: file ends after 1 of the 2 faces");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "more than the rest of the file can hold");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n\n# c\n1 0\n0 1 0\n3 0 1 2\n",
                    "e.off line 6: expected 3 coordinates, got 2");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n",
                    "line 4: expected a number, got 'x'");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0,5 0\n0 1 0\n3 0 1 2\n",
                    "line 4: expected a number, got '0,5'");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
                    "line 4: vertex 1 has a non-finite");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 -inf 0\n0 1 0\n3 0 1 2\n",
                    "line 4: vertex 1 has a non-finite");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 1e400 0\n0 1 0\n3 0 1 2\n",
                    "line 4: vertex 1 has a non-finite");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 6: face 0 uses vertex 3");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "line 6: face 0 uses vertex -1");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1  \n", "line 6: face 0 has 2 vertices");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
                    "line 6: face 0 should list 4 vertex indices, got 3");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n",
                    "expected a vertex index, got '1.5'");
  expect_read_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
                    "line 7: data continues after the 1 faces");
  expect_read_error("e.off", std::string("OFF\n3 1 0\n0 0\0 0\n", 17), "not a text file");
}

TEST(IoReadOff, TinyValuesUnderflowToZero) {
  PolygonMesh m =
      polycube::read_mesh(save("tiny.off", "OFF\n3 1 0\n1e-400 -1e-999 0.0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(m.vertices(0, 0), 0.0);
  EXPECT_TRUE(std::signbit(m.vertices(0, 1)));
}

// ------------------------------------------------------------ OBJ

TEST(IoReadObj, AllIndexFormsAndIgnoredStatements) {
  std::string path = save("forms.obj",
                          "# comment\nmtllib x.mtl\no thing\ng group\ns off\nusemtl red\n"
                          "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n"
                          "vt 0 0\nvt 1 0\nvn 0 0 1\nvp 0.5\n"
                          "f 1 2 3\n"
                          "f 1/1 2/2 3/1 4/2\n"
                          "f 1//1 3//1 4//1\n"
                          "f 4/1/1 3/2/1 2/1/1 1/2/1 # trailing comment\n"
                          "l 1 2\n"
                          "v 2 2 2\n"
                          "f -1 -2 -3\n"              // 5, 4, 3 -> 0-based 4, 3, 2
                          "f -5/-1 -4//-1 -3/1/-1\n"  // 1, 2, 3
                          "\tf\t1 2\t5\r\n");
  PolygonMesh m = polycube::read_mesh(path);
  EXPECT_EQ(m.vertices.rows(), 5);
  EXPECT_EQ(m.vertices(4, 2), 2.0);
  EXPECT_EQ(m.vertices(1, 0), 1.0);
  PolygonFaces expected;
  expected.add({0, 1, 2});
  expected.add({0, 1, 2, 3});
  expected.add({0, 2, 3});
  expected.add({3, 2, 1, 0});
  expected.add({4, 3, 2});
  expected.add({0, 1, 2});
  expected.add({0, 1, 4});
  expect_same_faces(expected, m.faces);
}

TEST(IoReadObj, FacesMayComeBeforeTheirVertices) {
  PolygonMesh m = polycube::read_mesh(save("ahead.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  EXPECT_EQ(m.faces.count(), 1);
}

TEST(IoReadObj, MalformedInputs) {
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_read_error("e.obj", v3 + "f 1 2 0\n", "line 4: vertex index 0 is invalid");
  expect_read_error("e.obj", v3 + "f 1 2 4\nf 1 2 3\n",
                    "line 4: face uses vertex 4, but the file has only 3 vertices");
  expect_read_error("e.obj", v3 + "f -1 -2 -4\n",
                    "line 4: relative index '-4' reaches before the first vertex");
  expect_read_error("e.obj", v3 + "f 1 2\n", "line 4: face has 2 vertices, a face needs at least 3");
  expect_read_error("e.obj", v3 + "f 1 2 x\n",
                    "line 4: expected a vertex index like 7, 7/2, 7//3 or 7/2/3, got 'x'");
  expect_read_error("e.obj", v3 + "f 1 2 /3\n", "got '/3'");
  expect_read_error("e.obj", v3 + "f 1 2 99999999999\n", "too large");
  expect_read_error("e.obj", "v 0 0\n", "e.obj line 1: expected 3 coordinates, got 2");
  expect_read_error("e.obj", "# c\nv 0 zero 0\n", "line 2: expected a number, got 'zero'");
  expect_read_error("e.obj", "v 0 0 0\nv 0 NaN 0\n", "line 2: vertex 1 has a non-finite coordinate 'NaN'");
  expect_read_error("e.obj", std::string("v 0 0 0\n\0\0", 10), "not a text file");
}

// ------------------------------------------------------------ PLY

bool host_big_endian() {
  const uint16_t one = 1;
  return *reinterpret_cast<const unsigned char*>(&one) == 0;
}

// Appends values in the file's byte order.
struct Binary {
  bool big;
  std::string bytes;
  template <class T>
  Binary& operator()(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big != host_big_endian()) std::reverse(b, b + sizeof(T));
    bytes.append(b, sizeof(T));
    return *this;
  }
};

// Vertex x as float, other extras, a list inside the vertex element, an extra
// element with a list before the faces and one without after them, faces
// with a flag before the indices and another list after them.
const char* kPlyHeaderBody =
    "comment made by a test\nobj_info nothing\n"
    "element vertex 4\n"
    "property float x\nproperty uchar red\nproperty double y\nproperty int id\n"
    "property double z\nproperty list uchar float weights\n"
    "element material 2\nproperty list ushort int refs\nproperty float shininess\n"
    "element face 3\n"
    "property uchar flags\nproperty list uchar int vertex_indices\nproperty list int float texcoord\n"
    "element edge 2\nproperty int v1\nproperty short v2\n"
    "end_header\n";

const double kPlyXyz[4][3] = {{0.5, 1.0 / 3.0, -2}, {-1.25, 1e-17, 3}, {4, 5, 6.125}, {0, -0.0, 1e200}};

PolygonFaces ply_faces() {
  PolygonFaces f;
  f.add({0, 1, 2});
  f.add({3, 2, 1, 0});
  f.add({0, 1, 2, 3, 1});
  return f;
}

std::string binary_ply(bool big) {
  Binary b{big, std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\n" + kPlyHeaderBody};
  for (int i = 0; i < 4; ++i) {
    b(static_cast<float>(kPlyXyz[i][0]))(uint8_t(200))(kPlyXyz[i][1])(int32_t(-i))(kPlyXyz[i][2]);
    b(uint8_t(i));
    for (int k = 0; k < i; ++k) b(float(k));
  }
  b(uint16_t(3))(int32_t(1))(int32_t(2))(int32_t(3))(1.5f);
  b(uint16_t(0))(2.5f);
  PolygonFaces f = ply_faces();
  for (int i = 0; i < f.count(); ++i) {
    b(uint8_t(7))(uint8_t(f.size(i)));
    for (int k = f.offsets[i]; k < f.offsets[i + 1]; ++k) b(int32_t(f.indices[k]));
    b(int32_t(2))(0.25f)(0.75f);
  }
  b(int32_t(0))(int16_t(1))(int32_t(2))(int16_t(3));
  return b.bytes;
}

std::string ascii_ply() {
  return std::string("ply\nformat ascii 1.0\n") + kPlyHeaderBody +
         "0.5 200 0.33333333333333331 0 -2 0\n"
         "-1.25 200 1e-17 -1 3 1 0\n"
         "4 200 5 -2 6.125 2 0 1\n"
         "0 200 -0 -3 1e200 3 0 1 2\n"
         "3 1 2 3 1.5\n"
         "0 2.5\n"
         "7 3 0 1 2 2 0.25 0.75\n"
         "7 4 3 2 1 0 2 0.25 0.75\n"
         "7 5 0 1 2 3 1 0 \n"
         "0 1\n"
         "2 3\n";
}

void expect_ply_mesh(const PolygonMesh& m) {
  ASSERT_EQ(m.vertices.rows(), 4);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(m.vertices(i, c), kPlyXyz[i][c])) << i << "," << c;
  expect_same_faces(ply_faces(), m.faces);
}

TEST(IoReadPly, BinaryLittleEndianWithExtras) {
  expect_ply_mesh(polycube::read_mesh(save("le.ply", binary_ply(false))));
}

TEST(IoReadPly, BinaryBigEndianWithExtras) {
  expect_ply_mesh(polycube::read_mesh(save("be.ply", binary_ply(true))));
}

TEST(IoReadPly, AsciiWithExtras) {
  PolygonMesh m = polycube::read_mesh(save("ascii.ply", ascii_ply()));
  expect_ply_mesh(m);
}

TEST(IoReadPly, OtherTypesAndVertexIndexName) {
  // uint8 coordinates, ushort list length, uint indices, CRLF header lines.
  Binary b{true,
           "ply\r\nformat binary_big_endian 1.0\r\nelement vertex 3\r\nproperty uint8 x\r\n"
           "property int16 y\r\nproperty float64 z\r\nelement face 1\r\n"
           "property list uint16 uint32 vertex_index\r\nend_header\r\n"};
  b(uint8_t(1))(int16_t(-2))(3.0)(uint8_t(4))(int16_t(5))(6.0)(uint8_t(7))(int16_t(8))(9.0);
  b(uint16_t(3))(uint32_t(2))(uint32_t(0))(uint32_t(1));
  PolygonMesh m = polycube::read_mesh(save("types.ply", b.bytes));
  ASSERT_EQ(m.vertices.rows(), 3);
  EXPECT_EQ(m.vertices(0, 1), -2.0);
  EXPECT_EQ(m.vertices(2, 0), 7.0);
  EXPECT_EQ(m.faces.indices, (std::vector<int>{2, 0, 1}));
}

TEST(IoReadPly, PointCloudWithoutFaces) {
  PolygonMesh m =
      polycube::read_mesh(save("points.ply",
                               "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n1 2 3\n4 5 6\n"));
  EXPECT_EQ(m.vertices.rows(), 2);
  EXPECT_EQ(m.faces.count(), 0);
}

TEST(IoReadPly, EveryTruncationOfABinaryFileFails) {
  for (bool big : {false, true}) {
    std::string full = binary_ply(big);
    size_t header = full.find("end_header\n") + 11;
    // Cuts in the last header lines, and every cut in the data.
    for (size_t n = header - std::min<size_t>(header, 40); n < full.size(); ++n) {
      std::string path = save("cut.ply", full.substr(0, n));
      std::string m = error_of([&] { polycube::read_mesh(path); });
      EXPECT_NE(m.find(path), std::string::npos) << n << ": " << m;
      if (n >= header) {
        EXPECT_NE(m.find("truncated file"), std::string::npos) << n << ": " << m;
      }
    }
  }
}

TEST(IoReadPly, MalformedHeaders) {
  const std::string v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  expect_read_error("e.ply", "OFF\n", "not a PLY file");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\n" + v, "no end_header");
  expect_read_error("e.ply", "ply\n" + v + "end_header\n", "no format line");
  expect_read_error("e.ply", "ply\nformat binary 1.0\n", "line 2: unknown PLY format 'binary'");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nproperty float x\n",
                    "line 3: property comes before any element");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nelement vertex many\n",
                    "line 3: expected 'element <name> <count>'");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float128 x\n",
                    "line 4: unknown property type 'float128'");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty list float int x\n",
                    "line 4: a list length needs an integer type");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float\n",
                    "property has no name");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nelement vertex 3\nfoo bar\n",
                    "line 4: unexpected header line");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\nend_header\n", "no vertex element");
  expect_read_error(
      "e.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float z\nend_header\n0 0\n",
      "line 3: the vertex element has no property y");
  expect_read_error(
      "e.ply",
      "ply\nformat ascii 1.0\n" + v + "element face 1\nproperty list uchar int indices\nend_header\n",
      "line 7: the face element has no list property vertex_indices");
  expect_read_error("e.ply",
                    "ply\nformat ascii 1.0\n" + v +
                        "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
                    "integer type");
  expect_read_error("e.ply", "ply\nformat ascii 1.0\n" + v + v + "end_header\n", "second 'vertex' element");
  // Bogus counts fail before allocating anything.
  expect_read_error("e.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                    "property float y\nproperty float z\nend_header\n0000",
                    "more than the rest of the file can hold");
  expect_read_error("e.ply",
                    "ply\nformat ascii 1.0\nelement vertex 9999999999\nproperty float x\n"
                    "property float y\nproperty float z\nend_header\n",
                    "not a usable count");
}

TEST(IoReadPly, MalformedData) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string v3 = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(polycube::read_mesh(save("ok.ply", head + v3 + "3 0 1 2\n")).faces.count(), 1);
  expect_read_error("e.ply", head + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 has fewer values");
  expect_read_error("e.ply", head + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 has more values");
  expect_read_error("e.ply", head + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "line 11: expected a number, got 'x'");
  expect_read_error("e.ply", head + "0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 has a non-finite");
  expect_read_error("e.ply", head + v3 + "3 0 1 3\n", "line 13: face 0 uses vertex 3");
  expect_read_error("e.ply", head + v3 + "2 0 1\n", "line 13: face 0 has 2 vertices");
  expect_read_error("e.ply", head + v3 + "3 0 1.0 2\n", "line 13: expected an integer, got '1.0'");
  expect_read_error("e.ply", head + "0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n",
                    "line 12: file ends after 0 of the 1 'face' entries");
  expect_read_error("e.ply", head + v3, "line 7: the header announces 1 'face' entries, more than the rest");
  expect_read_error("e.ply", head + v3 + "3 0 1 2\n3 0 1 2\n",
                    "line 14: data continues after the last element");

  // Binary: non-finite coordinates, bad indices, short faces, negative lengths.
  auto binary = [](float y, uint8_t n, int32_t index) {
    Binary b{false,
             "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n"};
    for (int i = 0; i < 3; ++i) b(float(i))(i == 1 ? y : 0.f)(0.f);
    b(n);
    for (int i = 0; i < std::min(std::max<int>(int8_t(n), 0), 3); ++i) b(i == 1 ? index : int32_t(i));
    return b.bytes;
  };
  EXPECT_EQ(polycube::read_mesh(save("ok.ply", binary(1, 3, 1))).faces.count(), 1);
  expect_read_error("e.ply", binary(std::nanf(""), 3, 1), "vertex 1 has a non-finite coordinate");
  expect_read_error("e.ply", binary(INFINITY, 3, 1), "vertex 1 has a non-finite coordinate");
  expect_read_error("e.ply", binary(1, 3, 5), "face 0 uses vertex 5, but there are only 3 vertices");
  expect_read_error("e.ply", binary(1, 3, -1), "face 0 uses vertex -1");
  expect_read_error("e.ply", binary(1, 2, 1), "face 0 has 2 vertices, a face needs at least 3");
  expect_read_error("e.ply", binary(1, 0xFF, 1), "negative list length -1");
  expect_read_error("e.ply", binary(1, 100, 1), "file ends inside face 0 of 1 (truncated file?)");
}

// Random byte damage must give a polycube::Error or a consistent mesh, never
// a crash, a hang or another exception.
TEST(IoReadMesh, DamagedFilesFailCleanly) {
  PolygonMesh m = awkward_mesh();
  std::mt19937 random(12345);
  for (std::string ext : {".off", ".obj", ".ply", ".ply_ascii", ".ply_be"}) {
    std::string original;
    if (ext == ".ply_ascii") {
      original = ascii_ply(), ext = ".ply";
    } else if (ext == ".ply_be") {
      original = binary_ply(true), ext = ".ply";
    } else {
      polycube::write_mesh(temp_path("fuzz" + ext), m.vertices, m.faces);
      original = load(temp_path("fuzz" + ext));
    }
    for (int trial = 0; trial < 150; ++trial) {
      std::string bytes = original;
      int hits = 1 + trial % 4;
      for (int h = 0; h < hits; ++h) {
        size_t at = random() % bytes.size();
        const char pool[] = "0123456789 \n-+.eE#/x\xff";
        bytes[at] = trial % 2 ? static_cast<char>(random()) : pool[random() % (sizeof pool - 1)];
      }
      std::string path = save("fuzz_damaged" + ext, bytes);
      try {
        PolygonMesh r = polycube::read_mesh(path);
        EXPECT_TRUE(r.vertices.allFinite());
        EXPECT_EQ(r.faces.offsets.back(), static_cast<int>(r.faces.indices.size()));
        for (int f = 0; f < r.faces.count(); ++f) EXPECT_GE(r.faces.size(f), 3);
        for (int i : r.faces.indices) {
          EXPECT_GE(i, 0);
          EXPECT_LT(i, r.vertices.rows());
        }
      } catch (const polycube::Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      }
    }
  }
}

// ------------------------------------------------------------ labels

TEST(IoLabels, RoundTrip) {
  std::vector<int> labels{0, 1, 2, 3, 4, 5, -1, 0};
  std::string path = temp_path("labels.txt");
  polycube::write_labels(path, labels);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_EQ(load(path).rfind("# ", 0), 0u);
  EXPECT_EQ(polycube::read_labels(path, 8), labels);
  // Plain: nothing but the integers, read back the same.
  polycube::write_labels(path, labels, polycube::LabelsHeader::kPlain);
  EXPECT_EQ(load(path), "0\n1\n2\n3\n4\n5\n-1\n0\n");
  EXPECT_EQ(polycube::read_labels(path, 8), labels);
}

TEST(IoLabels, CommentsAndWhitespace) {
  std::string path = save("labels_comments.txt", "# header\n0 1\t2\r\n\n  3 # three\n4#four\n5\n-1 +2");
  EXPECT_EQ(polycube::read_labels(path, 8), (std::vector<int>{0, 1, 2, 3, 4, 5, -1, 2}));
  EXPECT_TRUE(polycube::read_labels(save("labels_empty.txt", "# nothing\n"), 0).empty());
}

TEST(IoLabels, Errors) {
  auto expect = [](const std::string& name, const std::string& text, int faces, const std::string& expected) {
    std::string path = save(name, text);
    std::string m = error_of([&] { polycube::read_labels(path, faces); });
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find(expected), std::string::npos) << "expected '" << expected << "' in: " << m;
  };
  expect("labels_bad.txt", "# c\n0\n1\n2\n3\n4\n9\n", 6,
         "labels_bad.txt line 7: label 9 is outside -1..5 (0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = unlabelled)");
  expect("labels_neg.txt", "0 -2", 2, "line 1: label -2 is outside -1..5");
  expect("labels_word.txt", "0\n+X\n", 2, "line 2: expected an integer label, got '+X'");
  expect("labels_float.txt", "0\n1.0\n", 2, "line 2: expected an integer label, got '1.0'");
  expect("labels_few.txt", "0 1 2", 4, "labels_few.txt has 3 labels but the mesh has 4 faces");
  expect("labels_many.txt", "0 1 2", 2, "has 3 labels but the mesh has 2 faces");
  std::string missing = temp_path("no_labels.txt");
  std::string m = error_of([&] { polycube::read_labels(missing, 1); });
  EXPECT_NE(m.find(missing), std::string::npos) << m;

  std::string out = temp_path("labels_out.txt");
  m = error_of([&] { polycube::write_labels(out, {0, 6}); });
  EXPECT_NE(m.find(out), std::string::npos) << m;
  EXPECT_NE(m.find("face 1 has label 6"), std::string::npos) << m;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// ------------------------------------------------------------ JSON

// What the reports rely on beyond nlohmann-json's defaults: keys in the order
// added, NaN as null, bytes that are not UTF-8 replaced rather than thrown.
TEST(IoJson, OrderNonFiniteAndBadUtf8) {
  polycube::Json json = {{"z", 1}, {"a", 0.1}, {"nan", std::nan("")}, {"inf", -INFINITY}, {"bad utf8", "x\xff y"}};
  EXPECT_EQ(polycube::json_text(json, -1),
            "{\"z\":1,\"a\":0.1,\"nan\":null,\"inf\":null,\"bad utf8\":\"x\xEF\xBF\xBD y\"}");
  EXPECT_EQ(polycube::Json::parse(polycube::json_text(json))["a"].get<double>(), 0.1);
}

// ------------------------------------------------------------ real meshes

#ifdef POLYCUBE_MESH_DATA
std::string mesh_data(const std::string& name) { return std::string(POLYCUBE_MESH_DATA) + "/" + name; }
#endif

TEST(IoMeshData, RealMeshesMatchTheirHeaders) {
#ifndef POLYCUBE_MESH_DATA
  GTEST_SKIP() << "POLYCUBE_MESH_DATA is not defined";
#else
  if (!std::filesystem::exists("/usr/share/doc/libcgal-dev/data.tar.gz"))
    GTEST_SKIP() << "libcgal-dev's data.tar.gz is not installed";
  if (!std::filesystem::exists(mesh_data("fandisk.off")))
    GTEST_SKIP() << mesh_data("fandisk.off") << " is missing; run `make data`";
  // The counts fandisk.off's header announces, read the simple way.
  std::ifstream in(mesh_data("fandisk.off"));
  std::string line;
  while (std::getline(in, line) && (line.empty() || line[0] == '#')) {
  }
  ASSERT_EQ(line.substr(0, 3), "OFF");
  int vertices = -1, faces = -1;
  if (!(std::istringstream(line.substr(3)) >> vertices >> faces)) {
    std::getline(in, line);
    ASSERT_TRUE(std::istringstream(line) >> vertices >> faces) << line;
  }
  struct Expected {
    const char* name;
    int vertices, faces;
  };
  for (Expected e : {Expected{"fandisk.off", vertices, faces}, Expected{"mesh_with_colors.off", 8, 4},
                     Expected{"sphere.ply", 162, 320}, Expected{"colored_tetra.ply", 4, 4}}) {
    PolygonMesh m = polycube::read_mesh(mesh_data(e.name));
    EXPECT_EQ(m.vertices.rows(), e.vertices) << e.name;
    EXPECT_EQ(m.faces.count(), e.faces) << e.name;
  }
  // A lossless rewrite of a real mesh in every format.
  PolygonMesh fandisk = polycube::read_mesh(mesh_data("fandisk.off"));
  for (std::string ext : {".obj", ".off", ".ply"}) {
    std::string path = temp_path("fandisk" + ext);
    polycube::write_mesh(path, fandisk.vertices, fandisk.faces);
    PolygonMesh r = polycube::read_mesh(path);
    expect_same_vertices(fandisk.vertices, r.vertices);
    expect_same_faces(fandisk.faces, r.faces);
  }
#endif
}

}  // namespace
