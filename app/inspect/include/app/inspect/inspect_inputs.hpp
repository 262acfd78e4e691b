#pragma once
/// @file The files a `tumble inspect` batch names: mesh files, directories and @LIST files,
/// expanded into one list in a fixed order.

#include <filesystem>
#include <string>
#include <vector>

namespace tumble::app {

/// One file to inspect, or an input that could not be expanded (a missing list, an
/// unreadable directory): then `error` is its one-line message and the batch goes on.
struct InspectInput {
  std::filesystem::path file;
  std::string error;
};

/// The inputs' files in order. A directory gives the files directly inside it (with
/// `recursive`, below it too) whose extension is one assimp reads (mesh_extension), sorted by
/// path; hidden entries (".name") and sub-directories tumble may not read are skipped, and a
/// directory without any is an error. "@LIST" gives the paths listed in LIST, one a line, relative
/// to LIST's folder unless absolute; blank lines and lines starting with '#' are skipped, and a
/// listed directory or list is expanded in turn. Anything else is taken as a mesh file (a missing
/// one fails when inspected). `batch` is set when a directory or a list was given, so that the JSON
/// report is an array even of one file.
std::vector<InspectInput> expand_inspect_inputs(const std::vector<std::filesystem::path>& inputs,
                                                bool recursive, bool& batch);

/// Whether `file`'s extension (any case) is one of the mesh formats a directory's files are
/// taken for, assimp's mesh formats: 3d 3ds 3mf ac acc amf ase b3d blend cob dae dxf fbx glb gltf
/// hmp ifc iqm irr irrmesh lwo lws lxo m3d md2 md3 md5mesh mdc mdl ms3d nff obj off ogex ply q3o
/// q3s raw sib smd stl ter x x3d xgl zae zgl.
bool mesh_extension(const std::filesystem::path& file);

}  // namespace tumble::app
