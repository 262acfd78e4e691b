// Known solids and the mesh-file writers used by the import tests.
//
// Every writer emits coordinates with 17 significant digits, so values exactly representable
// as float32 (small integers, halves, quarters) arrive in assimp's float storage unchanged and
// the tests can compare against the closed forms to rounding of the integration itself.
#include "mesh_fixtures.hpp"
#include "support/stl_writer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <locale>
#include <random>
#include <sstream>
#include <stdexcept>

namespace tumble::mesh_fixtures {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary writers copy little-endian host values");

/// A number in a form every parser reads back exactly (C locale, round-trip precision).
std::string num(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(17);
  out << value;
  return out.str();
}

template <typename T>
void append_binary(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

void append_vec3f(std::string& bytes, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) append_binary(bytes, static_cast<float>(v[i]));
}

void require_triangles(const Polyhedron& mesh, const char* writer) {
  for (const auto& face : mesh.faces) {
    if (face.size() != 3) throw std::invalid_argument(std::string(writer) + " needs triangles");
  }
}

Eigen::Vector3d face_normal(const Polyhedron& mesh, const std::vector<std::uint32_t>& face) {
  const Eigen::Vector3d& a = mesh.vertices[face[0]];
  const Eigen::Vector3d& b = mesh.vertices[face[1]];
  const Eigen::Vector3d& c = mesh.vertices[face[2]];
  return (b - a).cross(c - a).normalized();
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

template <typename Array>
std::string json_array(const Array& values) {
  std::vector<std::string> items;
  for (const auto value : values) items.push_back(num(static_cast<double>(value)));
  return "[" + join(items, ",") + "]";
}

/// Pads `bytes` with `fill` to a multiple of four bytes (glTF alignment).
void pad4(std::string& bytes, char fill) {
  while (bytes.size() % 4 != 0) bytes.push_back(fill);
}

}  // namespace

Polyhedron prism(const std::vector<Eigen::Vector2d>& outline, double z_low, double z_high) {
  Polyhedron out;
  const auto n = static_cast<std::uint32_t>(outline.size());
  for (const double z : {z_low, z_high}) {
    for (const Eigen::Vector2d& p : outline) out.vertices.emplace_back(p.x(), p.y(), z);
  }
  // Bottom cap faces -z (outline reversed), top cap +z, one quad per outline edge.
  std::vector<std::uint32_t> bottom, top;
  for (std::uint32_t i = 0; i < n; ++i) {
    bottom.push_back(n - 1 - i);
    top.push_back(n + i);
  }
  out.faces.push_back(bottom);
  out.faces.push_back(top);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t next = (i + 1) % n;
    out.faces.push_back({i, next, n + next, n + i});
  }
  return out;
}

Polyhedron box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  return prism({{low.x(), low.y()}, {high.x(), low.y()}, {high.x(), high.y()}, {low.x(), high.y()}},
               low.z(), high.z());
}

Polyhedron fan_triangulated(const Polyhedron& polyhedron) {
  Polyhedron out{polyhedron.vertices, {}};
  for (const auto& face : polyhedron.faces) {
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      out.faces.push_back({face[0], face[i], face[i + 1]});
    }
  }
  return out;
}

SolidMoments SolidMoments::operator+(const SolidMoments& other) const {
  return {volume + other.volume, first + other.first, second + other.second};
}

SolidMoments SolidMoments::transformed(const Eigen::Matrix3d& linear,
                                       const Eigen::Vector3d& translation) const {
  // y = L x + t with dV' = |det L| dV.
  const double jacobian = std::abs(linear.determinant());
  const Eigen::Vector3d& t = translation;
  const Eigen::Vector3d mapped_first = linear * first;
  SolidMoments out;
  out.volume = jacobian * volume;
  out.first = jacobian * (mapped_first + volume * t);
  out.second = jacobian * (linear * second * linear.transpose() + mapped_first * t.transpose() +
                           t * mapped_first.transpose() + volume * t * t.transpose());
  return out;
}

Eigen::Matrix3d SolidMoments::inertia(double density) const {
  const Eigen::Matrix3d central = second - first * first.transpose() / volume;
  return density * (central.trace() * Eigen::Matrix3d::Identity() - central);
}

SolidMoments box_moments(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  // Per axis: integrals of 1, x and x^2 over [low, high].
  const Eigen::Vector3d m0 = high - low;
  const Eigen::Vector3d m1 = (high.array().square() - low.array().square()) / 2.0;
  const Eigen::Vector3d m2 = (high.array().cube() - low.array().cube()) / 3.0;
  SolidMoments out;
  out.volume = m0.prod();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    out.first[i] = m1[i] * m0[j] * m0[k];
    out.second(i, i) = m2[i] * m0[j] * m0[k];
    out.second(i, j) = out.second(j, i) = m1[i] * m1[j] * m0[k];
  }
  return out;
}

SolidMoments prism_moments(const std::vector<Eigen::Vector2d>& outline, double z_low,
                           double z_high) {
  // Area moments of the outline from Green's theorem, edge by edge.
  double area = 0.0, ax = 0.0, ay = 0.0, axx = 0.0, ayy = 0.0, axy = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& p = outline[i];
    const Eigen::Vector2d& q = outline[(i + 1) % outline.size()];
    const double cross = p.x() * q.y() - q.x() * p.y();
    area += cross / 2.0;
    ax += (p.x() + q.x()) * cross / 6.0;
    ay += (p.y() + q.y()) * cross / 6.0;
    axx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * cross / 12.0;
    ayy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * cross / 12.0;
    axy +=
        (p.x() * q.y() + 2.0 * p.x() * p.y() + 2.0 * q.x() * q.y() + q.x() * p.y()) * cross / 24.0;
  }
  // Sweep along z: integrals of 1, z and z^2 over [z_low, z_high].
  const double z0 = z_high - z_low;
  const double z1 = (z_high * z_high - z_low * z_low) / 2.0;
  const double z2 = (z_high * z_high * z_high - z_low * z_low * z_low) / 3.0;
  SolidMoments out;
  out.volume = area * z0;
  out.first = Eigen::Vector3d(ax * z0, ay * z0, area * z1);
  out.second << axx * z0, axy * z0, ax * z1,  //
      axy * z0, ayy * z0, ay * z1,            //
      ax * z1, ay * z1, area * z2;
  return out;
}

Eigen::Matrix3d quaternion_matrix(double x, double y, double z, double w) {
  return Eigen::Quaterniond(w, x, y, z).toRotationMatrix();
}

TempDir::TempDir() {
  std::random_device seed;
  const auto base = std::filesystem::temp_directory_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    const auto candidate = base / ("tumble-mesh-" + std::to_string(seed()));
    if (std::filesystem::create_directory(candidate)) {
      path_ = candidate;
      return;
    }
  }
  throw std::runtime_error("cannot create a temporary directory in " + base.string());
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

void write_file(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string binary_stl_bytes(const Polyhedron& mesh, const std::string& header) {
  require_triangles(mesh, "binary STL");
  return tumble::testing::binary_stl_bytes(
      mesh.faces.size(),
      [&](std::size_t i) {
        const auto& face = mesh.faces[i];
        return tumble::testing::StlTriangle{face_normal(mesh, face), mesh.vertices[face[0]],
                                            mesh.vertices[face[1]], mesh.vertices[face[2]]};
      },
      header);
}

void write_stl_binary(const std::filesystem::path& file, const Polyhedron& mesh) {
  write_file(file, binary_stl_bytes(mesh));
}

void write_stl_ascii(const std::filesystem::path& file, const std::vector<Polyhedron>& solids) {
  std::string text;
  for (std::size_t s = 0; s < solids.size(); ++s) {
    const Polyhedron& mesh = solids[s];
    require_triangles(mesh, "ASCII STL");
    text += tumble::testing::ascii_stl_solid(
        "part" + std::to_string(s + 1), mesh.faces.size(), [&](std::size_t i) {
          const auto& face = mesh.faces[i];
          return tumble::testing::StlTriangle{face_normal(mesh, face), mesh.vertices[face[0]],
                                              mesh.vertices[face[1]], mesh.vertices[face[2]]};
        });
  }
  write_file(file, text);
}

void write_obj(const std::filesystem::path& file, const std::vector<Polyhedron>& objects) {
  std::string text = "# written by tumble's tests\n";
  std::size_t base = 1;  // OBJ indices are global and 1-based
  for (std::size_t o = 0; o < objects.size(); ++o) {
    const Polyhedron& mesh = objects[o];
    text += "o object" + std::to_string(o + 1) + "\n";
    for (const Eigen::Vector3d& p : mesh.vertices) {
      text += "v " + num(p.x()) + " " + num(p.y()) + " " + num(p.z()) + "\n";
    }
    for (const auto& face : mesh.faces) {
      text += "f";
      for (const std::uint32_t v : face) text.append(1, ' ').append(std::to_string(base + v));
      text += "\n";
    }
    base += mesh.vertices.size();
  }
  write_file(file, text);
}

void write_ply(const std::filesystem::path& file, const Polyhedron& mesh, bool binary) {
  std::string bytes = "ply\nformat ";
  bytes += binary ? "binary_little_endian" : "ascii";
  bytes += " 1.0\ncomment written by tumble's tests\n";
  bytes += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
  bytes += "property float x\nproperty float y\nproperty float z\n";
  bytes += "element face " + std::to_string(mesh.faces.size()) + "\n";
  bytes += "property list uchar int vertex_indices\nend_header\n";
  for (const Eigen::Vector3d& p : mesh.vertices) {
    if (binary) {
      append_vec3f(bytes, p);
    } else {
      bytes += num(p.x()) + " " + num(p.y()) + " " + num(p.z()) + "\n";
    }
  }
  for (const auto& face : mesh.faces) {
    if (binary) {
      append_binary(bytes, static_cast<std::uint8_t>(face.size()));
      for (const std::uint32_t v : face) append_binary(bytes, static_cast<std::int32_t>(v));
    } else {
      bytes += std::to_string(face.size());
      for (const std::uint32_t v : face) bytes.append(1, ' ').append(std::to_string(v));
      bytes += "\n";
    }
  }
  write_file(file, bytes);
}

void write_off(const std::filesystem::path& file, const Polyhedron& mesh) {
  std::string text = "OFF\n# written by tumble's tests\n";
  text += std::to_string(mesh.vertices.size()) + " " + std::to_string(mesh.faces.size()) + " 0\n";
  for (const Eigen::Vector3d& p : mesh.vertices) {
    text += num(p.x()) + " " + num(p.y()) + " " + num(p.z()) + "\n";
  }
  for (const auto& face : mesh.faces) {
    text += std::to_string(face.size());
    for (const std::uint32_t v : face) text.append(1, ' ').append(std::to_string(v));
    text += "\n";
  }
  write_file(file, text);
}

void write_gltf(const std::filesystem::path& file,
                const std::vector<std::vector<Polyhedron>>& meshes,
                const std::vector<GltfNode>& nodes, const std::vector<std::size_t>& roots,
                bool binary) {
  // One buffer; per primitive a position view/accessor then an index view/accessor.
  std::string buffer;
  std::vector<std::string> views, accessors, mesh_json;
  for (const auto& primitives : meshes) {
    std::vector<std::string> primitive_json;
    for (const Polyhedron& polygonal : primitives) {
      const Polyhedron mesh = fan_triangulated(polygonal);
      // Accessor bounds over finite values only: JSON has no NaN or infinity, and a test may
      // hide one in the binary buffer.
      Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
      const std::size_t position_offset = buffer.size();
      for (const Eigen::Vector3d& p : mesh.vertices) {
        append_vec3f(buffer, p);
        for (int i = 0; i < 3; ++i) {
          if (!std::isfinite(p[i])) continue;
          low[i] = std::min(low[i], p[i]);
          high[i] = std::max(high[i], p[i]);
        }
      }
      const std::size_t index_offset = buffer.size();
      for (const auto& face : mesh.faces) {
        for (const std::uint32_t v : face) append_binary(buffer, v);
      }
      const std::size_t position_accessor = accessors.size();
      views.push_back(R"({"buffer":0,"byteOffset":)" + std::to_string(position_offset) +
                      R"(,"byteLength":)" + std::to_string(index_offset - position_offset) +
                      R"(,"target":34962})");
      accessors.push_back(R"({"bufferView":)" + std::to_string(views.size() - 1) +
                          R"(,"componentType":5126,"count":)" +
                          std::to_string(mesh.vertices.size()) + R"(,"type":"VEC3","min":)" +
                          json_array(low) + R"(,"max":)" + json_array(high) + "}");
      views.push_back(R"({"buffer":0,"byteOffset":)" + std::to_string(index_offset) +
                      R"(,"byteLength":)" + std::to_string(buffer.size() - index_offset) +
                      R"(,"target":34963})");
      accessors.push_back(R"({"bufferView":)" + std::to_string(views.size() - 1) +
                          R"(,"componentType":5125,"count":)" +
                          std::to_string(3 * mesh.faces.size()) + R"(,"type":"SCALAR"})");
      primitive_json.push_back(R"({"attributes":{"POSITION":)" + std::to_string(position_accessor) +
                               R"(},"indices":)" + std::to_string(position_accessor + 1) +
                               R"(,"mode":4})");
    }
    mesh_json.push_back(R"({"primitives":[)" + join(primitive_json, ",") + "]}");
  }

  std::vector<std::string> node_json;
  for (const GltfNode& node : nodes) {
    std::vector<std::string> fields;
    if (node.mesh) fields.push_back(R"("mesh":)" + std::to_string(*node.mesh));
    if (node.translation) fields.push_back(R"("translation":)" + json_array(*node.translation));
    if (node.rotation) fields.push_back(R"("rotation":)" + json_array(*node.rotation));
    if (node.scale) fields.push_back(R"("scale":)" + json_array(*node.scale));
    if (!node.children.empty()) fields.push_back(R"("children":)" + json_array(node.children));
    node_json.push_back("{" + join(fields, ",") + "}");
  }

  std::string buffer_json = R"({"byteLength":)" + std::to_string(buffer.size());
  if (!binary)
    buffer_json += R"(,"uri":"data:application/octet-stream;base64,)" + base64(buffer) + "\"";
  buffer_json += "}";
  std::string json = R"({"asset":{"version":"2.0","generator":"tumble tests"},"scene":0,)";
  json += R"("scenes":[{"nodes":)" + json_array(roots) + "}],";
  json += R"("nodes":[)" + join(node_json, ",") + "],";
  json += R"("meshes":[)" + join(mesh_json, ",") + "],";
  json += R"("buffers":[)" + buffer_json + "],";
  json += R"("bufferViews":[)" + join(views, ",") + "],";
  json += R"("accessors":[)" + join(accessors, ",") + "]}";
  if (!binary) {
    write_file(file, json);
    return;
  }

  // GLB: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros.
  pad4(json, ' ');
  pad4(buffer, '\0');
  std::string glb;
  append_binary(glb, std::uint32_t{0x46546C67});  // "glTF"
  append_binary(glb, std::uint32_t{2});
  append_binary(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + buffer.size()));
  append_binary(glb, static_cast<std::uint32_t>(json.size()));
  append_binary(glb, std::uint32_t{0x4E4F534A});  // "JSON"
  glb += json;
  append_binary(glb, static_cast<std::uint32_t>(buffer.size()));
  append_binary(glb, std::uint32_t{0x004E4942});  // "BIN\0"
  glb += buffer;
  write_file(file, glb);
}

void write_fbx_ascii(const std::filesystem::path& file, const std::vector<FbxModel>& models,
                     double unit_scale_factor) {
  std::string text =
      "; FBX 7.4.0 project file\n"
      "; written by tumble's tests\n"
      "FBXHeaderExtension:  {\n"
      "\tFBXHeaderVersion: 1003\n"
      "\tFBXVersion: 7400\n"
      "\tCreator: \"tumble tests\"\n"
      "}\n"
      "GlobalSettings:  {\n"
      "\tVersion: 1000\n"
      "\tProperties70:  {\n"
      "\t\tP: \"UpAxis\", \"int\", \"Integer\", \"\",1\n"
      "\t\tP: \"UpAxisSign\", \"int\", \"Integer\", \"\",1\n"
      "\t\tP: \"FrontAxis\", \"int\", \"Integer\", \"\",2\n"
      "\t\tP: \"FrontAxisSign\", \"int\", \"Integer\", \"\",1\n"
      "\t\tP: \"CoordAxis\", \"int\", \"Integer\", \"\",0\n"
      "\t\tP: \"CoordAxisSign\", \"int\", \"Integer\", \"\",1\n"
      "\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\"," +
      num(unit_scale_factor) +
      "\n"
      "\t}\n"
      "}\n"
      "Objects:  {\n";
  std::string connections = "Connections:  {\n";
  const auto triple = [](const std::array<double, 3>& v) {
    return num(v[0]) + "," + num(v[1]) + "," + num(v[2]);
  };
  for (std::size_t m = 0; m < models.size(); ++m) {
    const FbxModel& model = models[m];
    const std::string geometry_id = std::to_string(1000 + 2 * m);
    const std::string model_id = std::to_string(1001 + 2 * m);
    // Polygon vertex indices: the last index of each polygon is stored as -(index + 1).
    std::vector<std::string> coordinates, indices;
    for (const Eigen::Vector3d& p : model.geometry.vertices) {
      for (int i = 0; i < 3; ++i) coordinates.push_back(num(p[i]));
    }
    for (const auto& face : model.geometry.faces) {
      for (std::size_t i = 0; i < face.size(); ++i) {
        const auto index = static_cast<std::int64_t>(face[i]);
        indices.push_back(std::to_string(i + 1 == face.size() ? -index - 1 : index));
      }
    }
    text += "\tGeometry: " + geometry_id + ", \"Geometry::part" + std::to_string(m + 1) +
            "\", \"Mesh\" {\n";
    text += "\t\tVertices: *" + std::to_string(coordinates.size()) +
            " {\n\t\t\ta: " + join(coordinates, ",") + "\n\t\t}\n";
    text += "\t\tPolygonVertexIndex: *" + std::to_string(indices.size()) +
            " {\n\t\t\ta: " + join(indices, ",") + "\n\t\t}\n";
    text += "\t\tGeometryVersion: 124\n\t}\n";
    text += "\tModel: " + model_id + ", \"Model::part" + std::to_string(m + 1) +
            "\", \"Mesh\" {\n\t\tVersion: 232\n\t\tProperties70:  {\n";
    text += "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\"," +
            triple(model.translation) + "\n";
    text += "\t\t\tP: \"Lcl Rotation\", \"Lcl Rotation\", \"\", \"A\"," +
            triple(model.rotation_degrees) + "\n";
    text +=
        "\t\t\tP: \"Lcl Scaling\", \"Lcl Scaling\", \"\", \"A\"," + triple(model.scaling) + "\n";
    text += "\t\t}\n\t\tShading: T\n\t\tCulling: \"CullingOff\"\n\t}\n";
    connections += "\tC: \"OO\"," + geometry_id + "," + model_id + "\n";
    connections += "\tC: \"OO\"," + model_id + ",0\n";
  }
  text += "}\n" + connections + "}\n";
  write_file(file, text);
}

std::string base64(const std::string& bytes) {
  static constexpr char alphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    // Up to three bytes make one 24-bit group of four sextets.
    std::uint32_t group = 0;
    const std::size_t count = std::min<std::size_t>(3, bytes.size() - i);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto byte = k < count ? static_cast<unsigned char>(bytes[i + k]) : 0u;
      group = (group << 8) | byte;
    }
    for (std::size_t k = 0; k < 4; ++k) {
      out.push_back(k <= count ? alphabet[(group >> (18 - 6 * k)) & 0x3F] : '=');
    }
  }
  return out;
}

std::filesystem::path fuzz_input_as_file(const std::string& name, const TempDir& dir) {
  std::ifstream in(
      std::filesystem::path(TUMBLE_SOURCE_DIR) / "tests/fuzz/corpus/mesh_import" / name,
      std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw std::runtime_error("missing fuzz input " + name);
  const char* extensions[] = {".stl", ".obj", ".ply", ".off"};
  const auto file = dir / (name + extensions[static_cast<unsigned char>(bytes[0]) % 4]);
  write_file(file, bytes.substr(1));
  return file;
}

}  // namespace tumble::mesh_fixtures
