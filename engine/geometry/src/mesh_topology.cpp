// Welding and edge topology.
//
// Both run on meshes of millions of triangles inside `tumble inspect`, whose budget is the time
// assimp takes to read the file, so neither uses node-based hash maps:
// - welding: see vertex_welding.hpp;
// - edge use is counted by bucketing each undirected edge under its smaller vertex (a CSR
//   layout), sorting the few edges of each bucket and comparing directions.
#include "engine/geometry/mesh_topology.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "engine/geometry/prefetch.hpp"
#include "engine/geometry/vertex_welding.hpp"

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
  /// Hints that x's parent will be needed soon (prefetch.hpp).
  void prefetch(std::uint32_t x) const { detail::prefetch<true>(parent_.data() + x); }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

/// Sorts eight values with the 19-comparator network of Knuth, TAOCP vol. 3, 5.3.4 (optimal
/// for n = 8); min/max compile to conditional moves, so no branch depends on the data.
void sort8(std::array<std::uint32_t, 8>& e) {
  const auto exchange = [&e](int i, int j) {
    const std::uint32_t low = std::min(e[i], e[j]);
    e[j] = std::max(e[i], e[j]);
    e[i] = low;
  };
  exchange(0, 2), exchange(1, 3), exchange(4, 6), exchange(5, 7);
  exchange(0, 4), exchange(1, 5), exchange(2, 6), exchange(3, 7);
  exchange(0, 1), exchange(2, 3), exchange(4, 5), exchange(6, 7);
  exchange(2, 4), exchange(3, 5);
  exchange(1, 4), exchange(3, 6);
  exchange(1, 2), exchange(3, 4), exchange(5, 6);
}

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
  // Most meshes use every vertex: then nothing moves.
  const auto first_unused = std::find(new_index.begin(), new_index.end(), kUnused);
  if (first_unused == new_index.end()) return 0;
  auto kept = static_cast<std::uint32_t>(first_unused - new_index.begin());
  for (std::size_t i = 0; i < kept; ++i) new_index[i] = static_cast<std::uint32_t>(i);
  for (std::size_t i = kept; i < mesh.positions.size(); ++i) {
    if (new_index[i] == kUnused) continue;
    new_index[i] = kept;
    mesh.positions[kept++] = mesh.positions[i];
  }
  const std::size_t removed = mesh.positions.size() - kept;
  mesh.positions.resize(kept);
  for (auto& t : mesh.triangles) {
    for (std::uint32_t& v : t) v = new_index[v];
  }
  return removed;
}

void count_edge_uses(const TriangleMesh& mesh, Topology& topology) {
  const std::size_t vertex_count = mesh.positions.size();
  if (vertex_count >= (std::size_t{1} << 31)) {
    throw std::length_error("analyze_topology: more than 2^31 vertices");
  }
  topology.boundary_edges = topology.inconsistent_edges = topology.non_manifold_edges = 0;
  topology.unpaired_non_manifold_edges = 0;

  // Bucket each edge under its smaller vertex: the entry is (larger vertex << 1 | reversed).
  // Counting sort with 32-bit offsets, filled back to front so that the offsets end up at each
  // bucket's start without a second offset array; the edge array gets huge pages (see
  // advise_huge_pages). The order inside a bucket does not matter: it is sorted next.
  const std::size_t edge_count = 3 * mesh.triangles.size();
  if (edge_count >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("analyze_topology: more than 2^32 - 1 edges");
  }
  std::vector<std::uint32_t> bucket(vertex_count + 1, 0);
  for (const auto& t : mesh.triangles) {
    ++bucket[std::min(t[0], t[1])];
    ++bucket[std::min(t[1], t[2])];
    ++bucket[std::min(t[2], t[0])];
  }
  std::inclusive_scan(bucket.begin(), bucket.end(), bucket.begin());
  const auto edges = std::make_unique_for_overwrite<std::uint32_t[]>(edge_count);
  advise_huge_pages(edges.get(), edge_count * sizeof(std::uint32_t));
  for (const auto& t : mesh.triangles) {
    for (int corner = 0; corner < 3; ++corner) {
      const std::uint32_t from = t[corner];
      const std::uint32_t to = t[corner == 2 ? 0 : corner + 1];
      const std::uint32_t low = std::min(from, to);
      const std::uint32_t high = std::max(from, to);
      edges[--bucket[low]] = (high << 1) | (from > to ? 1u : 0u);
    }
  }

  // In each bucket, count each edge's uses in both directions. Buckets hold about six entries
  // (three edges per triangle, two triangles per vertex): those of up to eight are sorted by a
  // branch-free network, and a bucket whose sorted entries pair up as (forward, backward) of
  // distinct edges, which is every bucket of a clean closed mesh, is done after one test.
  const auto count_runs = [&topology](const std::uint32_t* begin, const std::uint32_t* end) {
    for (const std::uint32_t* run = begin; run != end;) {
      const std::uint32_t other = *run >> 1;
      std::size_t forward = 0;
      std::size_t backward = 0;
      for (; run != end && (*run >> 1) == other; ++run) ((*run & 1u) ? backward : forward)++;
      if (forward + backward == 1) {
        ++topology.boundary_edges;
      } else if (forward + backward > 2) {
        ++topology.non_manifold_edges;
        if (forward != backward) ++topology.unpaired_non_manifold_edges;
      } else if (forward != backward) {
        ++topology.inconsistent_edges;
      }
    }
  };
  constexpr std::uint32_t kPad = std::numeric_limits<std::uint32_t>::max();
  for (std::size_t v = 0; v < vertex_count; ++v) {
    std::uint32_t* const begin = edges.get() + bucket[v];
    const std::size_t size = bucket[v + 1] - bucket[v];
    if (size > 8) {
      std::sort(begin, begin + size);
      count_runs(begin, begin + size);
      continue;
    }
    std::array<std::uint32_t, 8> e;
    e.fill(kPad);
    std::copy_n(begin, size, e.begin());
    sort8(e);
    // Clean: an even count, each pair (b << 1, b << 1 | 1), each b above the previous pair's.
    bool clean = size % 2 == 0;
    for (std::size_t i = 0; i < 8; i += 2) {
      const bool in_bucket = i < size;
      const bool pair = (e[i] & 1u) == 0 && e[i + 1] == (e[i] | 1u);
      const bool distinct = i == 0 || (e[i] >> 1) != (e[i - 1] >> 1);
      clean &= !in_bucket || (pair && distinct);
    }
    if (!clean) count_runs(e.data(), e.data() + size);
  }
}

void find_parts(const TriangleMesh& mesh, Topology& topology) {
  // Connected parts through shared vertices, numbered in order of first triangle.
  const std::size_t vertex_count = mesh.positions.size();
  topology.parts = 0;
  // Each triangle's parents are fetched a few triangles ahead (prefetch.hpp).
  DisjointSets sets(vertex_count);
  const std::size_t triangle_count = mesh.triangles.size();
  for (std::size_t i = 0; i < triangle_count; ++i) {
    if (i + detail::kPrefetchDistance < triangle_count) {
      for (const std::uint32_t v : mesh.triangles[i + detail::kPrefetchDistance]) sets.prefetch(v);
    }
    const auto& t = mesh.triangles[i];
    sets.unite(t[0], t[1]);
    sets.unite(t[1], t[2]);
  }
  constexpr std::uint32_t kUnassigned = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> part_of_root(vertex_count, kUnassigned);
  topology.triangle_part.resize(triangle_count);
  for (std::size_t i = 0; i < triangle_count; ++i) {
    if (i + detail::kPrefetchDistance < triangle_count) {
      sets.prefetch(mesh.triangles[i + detail::kPrefetchDistance][0]);
    }
    std::uint32_t& part = part_of_root[sets.find(mesh.triangles[i][0])];
    if (part == kUnassigned) part = static_cast<std::uint32_t>(topology.parts++);
    topology.triangle_part[i] = part;
  }
}

Topology analyze_topology(const TriangleMesh& mesh) {
  Topology topology;
  count_edge_uses(mesh, topology);
  find_parts(mesh, topology);
  return topology;
}

bool bounds_outward_solids(const TriangleMesh& mesh) {
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
  }
  Topology topology;
  count_edge_uses(mesh, topology);
  if (!topology.closed()) return false;
  find_parts(mesh, topology);
  // Six times each part's signed volume: the divergence theorem over its triangles.
  std::vector<double> volume(topology.parts, 0.0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    volume[topology.triangle_part[f]] +=
        mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  }
  return std::all_of(volume.begin(), volume.end(), [](double v) { return v > 0.0; });
}

}  // namespace tumble::engine
