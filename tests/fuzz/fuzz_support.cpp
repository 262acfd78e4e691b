// What the fuzz targets share: the input as text or as a temporary file.
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include "fuzz_target.hpp"

namespace tumble::fuzz {

std::string as_text(const std::uint8_t* data, std::size_t size) {
  return size == 0 ? std::string() : std::string(reinterpret_cast<const char*>(data), size);
}

TemporaryInputFile::TemporaryInputFile(const std::uint8_t* data, std::size_t size,
                                       const std::string& extension)
    : path_(std::filesystem::temp_directory_path() /
            ("tumble-fuzz-" + std::to_string(::getpid()) + extension)) {
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  if (size > 0) out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  // Not an input error: the harness itself cannot work without its file.
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path_.string());
}

TemporaryInputFile::~TemporaryInputFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace tumble::fuzz
