#pragma once
/// @file What every fuzz target defines (libFuzzer's entry point) and what the targets share.
///
/// Each target feeds its bytes to one of tumble's readers of untrusted input. A clean refusal
/// (tumble::InputError) is the reader doing its job; anything else thrown, and any sanitizer
/// report, is a bug and crashes the run.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace tumble::fuzz {

/// The input as text, byte for byte.
std::string as_text(const std::uint8_t* data, std::size_t size);

/// A file holding the input, removed again when this goes out of scope. Its name is unique to
/// the process and ends in `extension` (".stl"), since the readers choose a format by it.
class TemporaryInputFile {
 public:
  TemporaryInputFile(const std::uint8_t* data, std::size_t size, const std::string& extension);
  ~TemporaryInputFile();
  TemporaryInputFile(const TemporaryInputFile&) = delete;
  TemporaryInputFile& operator=(const TemporaryInputFile&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace tumble::fuzz
