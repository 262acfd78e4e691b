// Welding and edge topology.
//
// Both run on meshes of millions of triangles inside `tumble inspect`, whose budget is the time
// assimp takes to read the file, so neither uses node-based hash maps:
// - welding: see engine/vertex_welding.hpp;
// - edge use is counted by bucketing each undirected edge under its smaller vertex (a CSR
//   layout), sorting the few edges of each bucket and comparing directions.
#include "engine/mesh_topology.hpp"

#include "engine/vertex_welding.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace tumble::engine {
namespace {

/// Disjoint-set forest with path halving, for connected parts.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t size) : parent_(size) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace

std::size_t weld_by_position(TriangleMesh& mesh) {
  const std::size_t count = mesh.positions.size();
  const WeldMap map = weld_positions<double>(count, [&](std::size_t i) {
    const Eigen::Vector3d& p = mesh.positions[i];
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  });
  for (std::size_t i = 0; i < map.kept.size(); ++i) mesh.positions[i] = mesh.positions[map.kept[i]];
  mesh.positions.resize(map.kept.size());
  for (auto& triangle : mesh.triangles) {
    for (std::uint32_t& v : triangle) v = map.new_index[v];
  }
  return count - map.kept.size();
}

std::size_t remove_degenerate_triangles(TriangleMesh& mesh) {
  const auto degenerate = [](const std::array<std::uint32_t, 3>& t) {
    return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
  };
  const auto removed = std::remove_if(mesh.triangles.begin(), mesh.triangles.end(), degenerate);
  const auto count = static_cast<std::size_t>(mesh.triangles.end() - removed);
  mesh.triangles.erase(removed, mesh.triangles.end());
  return count;
}

std::size_t remove_unreferenced_vertices(TriangleMesh& mesh) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> new_index(mesh.positions.size(), kUnused);
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t v : t) new_index[v] = 0;
  }
  std::uint32_t kept = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (new_index[i] == kUnused) continue;
    new_index[i] = kept;
    mesh.positions[kept++] = mesh.positions[i];
  }
  const std::size_t removed = mesh.positions.size() - kept;
  if (removed == 0) return 0;
  mesh.positions.resize(kept);
  for (auto& t : mesh.triangles) {
    for (std::uint32_t& v : t) v = new_index[v];
  }
  return removed;
}

Topology analyze_topology(const TriangleMesh& mesh) {
  const std::size_t vertex_count = mesh.positions.size();
  if (vertex_count >= (std::size_t{1} << 31)) {
    throw std::length_error("analyze_topology: more than 2^31 vertices");
  }
  Topology topology;

  // Bucket each edge under its smaller vertex: the entry is (larger vertex << 1 | reversed).
  std::vector<std::size_t> bucket_start(vertex_count + 1, 0);
  for (const auto& t : mesh.triangles) {
    for (int corner = 0; corner < 3; ++corner) {
      ++bucket_start[std::min(t[corner], t[(corner + 1) % 3]) + 1];
    }
  }
  std::partial_sum(bucket_start.begin(), bucket_start.end(), bucket_start.begin());
  std::vector<std::uint32_t> edges(bucket_start.back());
  {
    std::vector<std::size_t> fill(bucket_start.begin(), bucket_start.end() - 1);
    for (const auto& t : mesh.triangles) {
      for (int corner = 0; corner < 3; ++corner) {
        const std::uint32_t from = t[corner];
        const std::uint32_t to = t[(corner + 1) % 3];
        const std::uint32_t low = std::min(from, to);
        const std::uint32_t high = std::max(from, to);
        edges[fill[low]++] = (high << 1) | (from > to ? 1u : 0u);
      }
    }
  }

  // In each bucket, count each edge's uses in both directions.
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const auto begin = edges.begin() + static_cast<std::ptrdiff_t>(bucket_start[v]);
    const auto end = edges.begin() + static_cast<std::ptrdiff_t>(bucket_start[v + 1]);
    std::sort(begin, end);
    for (auto run = begin; run != end;) {
      const std::uint32_t other = *run >> 1;
      std::size_t forward = 0;
      std::size_t backward = 0;
      for (; run != end && (*run >> 1) == other; ++run) ((*run & 1u) ? backward : forward)++;
      if (forward + backward == 1) {
        ++topology.boundary_edges;
      } else if (forward != backward) {
        ++topology.inconsistent_edges;
      } else if (forward + backward > 2) {
        ++topology.non_manifold_edges;
      }
    }
  }

  // Connected parts through shared vertices, numbered in order of first triangle.
  DisjointSets sets(vertex_count);
  for (const auto& t : mesh.triangles) {
    sets.unite(t[0], t[1]);
    sets.unite(t[1], t[2]);
  }
  constexpr std::uint32_t kUnassigned = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> part_of_root(vertex_count, kUnassigned);
  topology.triangle_part.resize(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    std::uint32_t& part = part_of_root[sets.find(mesh.triangles[i][0])];
    if (part == kUnassigned) part = static_cast<std::uint32_t>(topology.parts++);
    topology.triangle_part[i] = part;
  }
  return topology;
}

}  // namespace tumble::engine
