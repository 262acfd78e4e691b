// Binary STL read straight into a welded mesh (see binary_stl.hpp for why and for the format).
#include "binary_stl.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/mman.h>
#include <unistd.h>
#define TUMBLE_HAS_MMAP 1
#else
#define TUMBLE_HAS_MMAP 0
#endif

#include "base/errors.hpp"
#include "engine/geometry/vertex_welding.hpp"
#include "input_file.hpp"
#include "split_in_two.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::size_t kHeaderBytes = 84;    // 80 free bytes, then the triangle count
constexpr std::size_t kRecordBytes = 50;    // normal, three corners, attribute word
constexpr std::size_t kCornersOffset = 12;  // the corners follow the normal

/// The little-endian uint32 at `bytes` (a plain load on little-endian machines).
std::uint32_t little_uint32(const unsigned char* bytes) {
  return std::uint32_t{bytes[0]} | std::uint32_t{bytes[1]} << 8 | std::uint32_t{bytes[2]} << 16 |
         std::uint32_t{bytes[3]} << 24;
}

bool has_stl_extension(const std::filesystem::path& file) {
  return lower_extension(file) == ".stl";
}

/// The bytes of a file from `offset` on, mapped read-only where the system can (no copy, and
/// no fresh pages to zero: on a 50 MB file those cost more than the welding), read into memory
/// otherwise. A mapped file that another program truncates while it is read raises SIGBUS, as
/// with any memory-mapped input; tumble does not guard against that race.
class FileBytes {
 public:
  FileBytes(std::FILE* stream, std::size_t offset, std::size_t count) : count_(count) {
    if (count == 0) return;
#if TUMBLE_HAS_MMAP
    const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t lead = offset % page;
    int flags = MAP_PRIVATE;
#if defined(MAP_POPULATE)
    flags |= MAP_POPULATE;  // fault every page in at once
#endif
    void* const mapped = mmap(nullptr, lead + count, PROT_READ, flags, fileno(stream),
                              static_cast<off_t>(offset - lead));
    if (mapped != MAP_FAILED) {
      mapping_ = static_cast<unsigned char*>(mapped);
      mapping_bytes_ = lead + count;
      data_ = mapping_ + lead;
      return;
    }
#endif
    // No mapping: read the bytes into fresh memory (huge pages: see advise_huge_pages).
    buffer_ = std::make_unique_for_overwrite<unsigned char[]>(count);
    advise_huge_pages(buffer_.get(), count);
    if (std::fseek(stream, static_cast<long>(offset), SEEK_SET) == 0 &&
        std::fread(buffer_.get(), 1, count, stream) == count) {
      data_ = buffer_.get();
    }
  }
  ~FileBytes() {
#if TUMBLE_HAS_MMAP
    if (mapping_ != nullptr) munmap(mapping_, mapping_bytes_);
#endif
  }
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  /// The bytes, or nullptr when they could not be read (never for zero bytes).
  const unsigned char* data() const {
    return count_ == 0 ? &empty_ : data_;
  }

 private:
  std::size_t count_ = 0;
  const unsigned char* data_ = nullptr;
  unsigned char* mapping_ = nullptr;
  std::size_t mapping_bytes_ = 0;
  std::unique_ptr<unsigned char[]> buffer_;
  static constexpr unsigned char empty_ = 0;
};

}  // namespace

std::optional<BinaryStl> read_binary_stl(const std::filesystem::path& file, std::uintmax_t size) {
  // Claim only files named *.stl whose size is that of a binary STL (assimp chooses its reader
  // by the name first, so any other name is left to it).
  if (!has_stl_extension(file) || size < kHeaderBytes) return std::nullopt;
  const CFile stream(std::fopen(file.string().c_str(), "rb"));
  if (!stream) fail(file, "cannot be opened for reading");
  unsigned char header[kHeaderBytes];
  if (std::fread(header, 1, kHeaderBytes, stream.get()) != kHeaderBytes) {
    fail(file, "could not be read to the end");
  }
  const std::size_t triangles = little_uint32(header + 80);
  if (size != kHeaderBytes + kRecordBytes * triangles) return std::nullopt;
  // Every corner gets a 32-bit index before welding.
  if (triangles > (std::numeric_limits<std::uint32_t>::max() - 1) / 3) {
    fail(file, "has " + std::to_string(triangles) + " triangles, more than one body can hold (" +
                   std::to_string((std::numeric_limits<std::uint32_t>::max() - 1) / 3) + ")");
  }

  // The records, which the welding reads in order.
  const FileBytes records(stream.get(), kHeaderBytes, kRecordBytes * triangles);
  if (records.data() == nullptr) fail(file, "could not be read to the end");
  const unsigned char* const body = records.data();

  // Weld the corners on the file's own float bits. Corner v is corner v % 3 of record v / 3.
  const auto corner = [body](std::size_t v) {
    const unsigned char* const bytes =
        body + (v / 3) * kRecordBytes + kCornersOffset + (v % 3) * 12;
    return std::array<float, 3>{std::bit_cast<float>(little_uint32(bytes)),
                                std::bit_cast<float>(little_uint32(bytes + 4)),
                                std::bit_cast<float>(little_uint32(bytes + 8))};
  };
  const std::size_t corners = 3 * triangles;
  const WeldMap weld = weld_positions<float>(corners, corner);

  // Widen the survivors to doubles and index the triangles, on two threads for large files;
  // the output arrays are fresh memory, so they get huge pages too.
  BinaryStl result;
  result.welded_vertices = corners - weld.kept.size();
  TriangleMesh& mesh = result.mesh;
  mesh.positions.reserve(weld.kept.size());
  advise_huge_pages(mesh.positions.data(), weld.kept.size() * sizeof(Eigen::Vector3d));
  mesh.positions.resize(weld.kept.size());  // Eigen leaves the new vectors uninitialised
  split_in_two(weld.kept.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::array<float, 3> p = corner(weld.kept[i]);
      mesh.positions[i] = Eigen::Vector3d(p[0], p[1], p[2]);
    }
  });
  mesh.triangles.reserve(triangles);
  advise_huge_pages(mesh.triangles.data(), triangles * sizeof(mesh.triangles[0]));
  mesh.triangles.resize(triangles);
  split_in_two(triangles, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      mesh.triangles[t] = {weld.new_index[3 * t], weld.new_index[3 * t + 1],
                           weld.new_index[3 * t + 2]};
    }
  });
  return result;
}

void check_binary_stl_size(const std::filesystem::path& file, std::uintmax_t size) {
  if (!has_stl_extension(file)) return;
  const CFile stream(std::fopen(file.string().c_str(), "rb"));
  if (!stream) fail(file, "cannot be opened for reading");
  constexpr std::size_t kAsciiProbe = 500;  // the bytes assimp 5.2 tests for ASCII
  std::array<unsigned char, kHeaderBytes + kAsciiProbe> head{};
  const std::size_t got = std::fread(head.data(), 1, head.size(), stream.get());
  std::size_t start = 0;
  while (start < got && std::isspace(head[start])) ++start;
  const bool solid = got >= start + 6 && std::memcmp(head.data() + start, "solid", 5) == 0;
  const bool text = std::all_of(
      head.begin() + static_cast<std::ptrdiff_t>(start),
      head.begin() + static_cast<std::ptrdiff_t>(std::min(got, start + std::size_t{kAsciiProbe})),
      [](unsigned char c) { return c != 0 && c <= 127; });
  // A name in UTF-8 ("solid Würfel") is not binary: its facets follow.
  const std::string_view probe(reinterpret_cast<const char*>(head.data()), got);
  const bool facets = probe.find("facet") != std::string_view::npos ||
                      probe.find("endsolid") != std::string_view::npos;
  if (solid && (text || facets)) return;  // ASCII: assimp's to read
  if (got < kHeaderBytes) {
    fail(file, "cannot be read as a mesh: neither ASCII STL nor binary STL (" +
                   std::to_string(size) + " bytes, less than a binary STL's 84-byte header)");
  }
  const std::uint64_t triangles = little_uint32(head.data() + 80);
  const std::uint64_t expected = kHeaderBytes + kRecordBytes * triangles;
  if (size == expected) return;
  fail(file, "cannot be read as a mesh: a binary STL declaring " + std::to_string(triangles) +
                 " triangles takes " + std::to_string(expected) + " bytes, but the file has " +
                 std::to_string(size) + (size < expected ? " (truncated)" : " (not one STL?)"));
}

}  // namespace tumble::engine::detail
