// Expanding `tumble inspect`'s inputs: directories and @LIST files into mesh files.
#include "app/inspect/inspect_inputs.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <string_view>
#include <system_error>

namespace tumble::app {
namespace {

namespace fs = std::filesystem;

/// Lists nest at most this deep (a list naming itself would never end).
constexpr int kMaxListDepth = 16;

/// A directory's files, or `input` itself as a mesh file.
void expand(const fs::path& input, bool recursive, std::vector<InspectInput>& out);

/// The mesh files of `dir`, sorted; directly inside, or below when `recursive`.
void expand_directory(const fs::path& dir, bool recursive, std::vector<InspectInput>& out) {
  std::vector<fs::path> files;
  std::error_code error;
  const auto take = [&](const fs::directory_entry& entry) {
    const std::string name = entry.path().filename().string();
    std::error_code ignored;
    if (!name.empty() && name[0] != '.' && entry.is_regular_file(ignored) &&
        mesh_extension(entry.path())) {
      files.push_back(entry.path());
    }
  };
  if (recursive) {
    // A sub-directory tumble may not read is left out, not the whole tree.
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, error),
        end;
    for (; !error && it != end; it.increment(error)) {
      // Hidden directories (.git, .cache) are not descended into.
      const std::string name = it->path().filename().string();
      std::error_code ignored;
      if (!name.empty() && name[0] == '.' && it->is_directory(ignored)) {
        it.disable_recursion_pending();
        continue;
      }
      take(*it);
    }
  } else {
    fs::directory_iterator it(dir, error), end;
    for (; !error && it != end; it.increment(error)) take(*it);
  }
  if (error) {
    out.push_back({dir, dir.string() + ": cannot read the directory (" + error.message() + ")"});
    return;
  }
  if (files.empty()) {
    out.push_back({dir, dir.string() + ": no mesh files in the directory" +
                            (recursive ? " or below it" : " (-r descends into sub-directories)")});
    return;
  }
  std::sort(files.begin(), files.end());
  for (fs::path& file : files) out.push_back({std::move(file), {}});
}

/// The files of the list file `list` (the text after '@').
void expand_list(const fs::path& list, bool recursive, int depth, std::vector<InspectInput>& out) {
  const fs::path named = "@" + list.string();
  if (depth >= kMaxListDepth) {
    out.push_back({named, list.string() + ": lists nested more than 16 deep (a list naming "
                                          "itself?)"});
    return;
  }
  std::error_code error;
  if (!fs::is_regular_file(list, error)) {
    out.push_back(
        {named, list.string() + (fs::exists(list, error) ? ": the list is not a regular file"
                                                         : ": no such list file")});
    return;
  }
  std::ifstream in(list);
  if (!in) {
    out.push_back({named, list.string() + ": cannot open the list file"});
    return;
  }
  const fs::path base = list.parent_path();
  std::string line;
  while (std::getline(in, line)) {
    // Trailing spaces and a Windows line end are not part of a path; leading spaces neither.
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string entry = line.substr(first);
    if (entry[0] == '@') {
      const fs::path nested = entry.substr(1);
      expand_list(nested.is_absolute() ? nested : base / nested, recursive, depth + 1, out);
    } else {
      const fs::path path = entry;
      expand(path.is_absolute() ? path : base / path, recursive, out);
    }
  }
}

void expand(const fs::path& input, bool recursive, std::vector<InspectInput>& out) {
  std::error_code error;
  if (fs::is_directory(input, error)) {
    expand_directory(input, recursive, out);
  } else {
    out.push_back({input, {}});
  }
}

}  // namespace

bool mesh_extension(const fs::path& file) {
  // assimp 5.2's mesh formats (not its motion-capture ones, BVH and CSM, which hold no solid).
  static constexpr std::array<std::string_view, 47> kExtensions = {
      "3d",  "3ds", "3mf", "ac",   "acc",  "amf", "ase",     "b3d", "blend", "cob",
      "dae", "dxf", "fbx", "glb",  "gltf", "hmp", "ifc",     "iqm", "irr",   "irrmesh",
      "lwo", "lws", "lxo", "m3d",  "md2",  "md3", "md5mesh", "mdc", "mdl",   "ms3d",
      "nff", "obj", "off", "ogex", "ply",  "q3o", "q3s",     "raw", "sib",   "smd",
      "stl", "ter", "x",   "x3d",  "xgl",  "zae", "zgl"};
  std::string extension = file.extension().string();
  if (extension.size() < 2) return false;
  extension.erase(0, 1);
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return std::find(kExtensions.begin(), kExtensions.end(), extension) != kExtensions.end();
}

std::vector<InspectInput> expand_inspect_inputs(const std::vector<fs::path>& inputs, bool recursive,
                                                bool& batch) {
  std::vector<InspectInput> out;
  batch = false;
  for (const fs::path& input : inputs) {
    const std::string text = input.string();
    std::error_code error;
    if (text == "@") {
      out.push_back({input, "@: expected the name of a list file after '@' (@LIST)"});
    } else if (!text.empty() && text[0] == '@') {
      batch = true;
      expand_list(text.substr(1), recursive, 0, out);
    } else {
      if (fs::is_directory(input, error)) batch = true;
      expand(input, recursive, out);
    }
  }
  return out;
}

}  // namespace tumble::app
