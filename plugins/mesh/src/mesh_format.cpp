// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "mesh_format.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

#include <assimp/BaseImporter.h>
#include <assimp/importerdesc.h>
#include <assimp/Importer.hpp>

#include "file_extension.h"

namespace cubespring {
namespace {

struct KnownExtension {
  std::string_view extension;
  MeshFormat format;
};

constexpr std::array<KnownExtension, 7> kExtensions{{{".obj", MeshFormat::kObj},
                                                     {".stl", MeshFormat::kStl},
                                                     {".ply", MeshFormat::kPly},
                                                     {".off", MeshFormat::kOff},
                                                     {".gltf", MeshFormat::kGltf},
                                                     {".glb", MeshFormat::kGltf},
                                                     {".dae", MeshFormat::kCollada}}};

// How much of a file's start is looked at for a format's mark: assimp's own token search reads 200.
constexpr std::size_t kHeadBytes = 200;

std::string lowered(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool begins_with(const std::string& text, std::string_view start) { return text.compare(0, start.size(), start) == 0; }

// A format off the list that assimp would recognise in these bytes is not looked for: the file
// is refused unless it is one of the list's.
std::optional<MeshFormat> format_of_content(const std::string& head) {
  const std::string low = lowered(head);
  // PLY and OFF as their checks (ply_file.h, off_file.h) and assimp take them: by their first word
  if (begins_with(head, "ply")) return MeshFormat::kPly;
  if (begins_with(low, "off")) return MeshFormat::kOff;
  if (begins_with(head, "glTF")) return MeshFormat::kGltf;  // the binary container's magic
  const std::size_t text = low.find_first_not_of(" \t\r\n");
  if (text != std::string::npos && low.compare(text, 5, "solid") == 0) return MeshFormat::kStl;
  if (low.find("<collada") != std::string::npos) return MeshFormat::kCollada;
  return std::nullopt;
}

}  // namespace

const char* supported_mesh_formats() {
  return "OBJ (.obj), STL (.stl), PLY (.ply), OFF (.off), glTF (.gltf, .glb), COLLADA (.dae)";
}

Result<MeshFormat> mesh_format_of(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  const auto known = std::find_if(kExtensions.begin(), kExtensions.end(),
                                  [&](const KnownExtension& entry) { return entry.extension == extension; });
  if (known != kExtensions.end()) return known->format;
  const std::string named = extension.empty() ? "it has no extension" : "its extension is '" + extension + "'";
  // assimp picks a reader by the extension first: a format it reads and the list does not have
  if (!extension.empty() && Assimp::Importer().IsExtensionSupported(extension)) {
    return Status::error(path + ": " + named + ", a format cubespring does not read (it reads " +
                         supported_mesh_formats() + "); convert the file to one of them");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status::error(path + ": cannot open: no such file, or it is not readable");
  std::string head(kHeadBytes, '\0');
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(file.gcount(), 0)));
  if (const std::optional<MeshFormat> format = format_of_content(head)) return *format;
  return Status::error(path + ": " + named + " and its first bytes are none of the formats cubespring reads (" +
                       supported_mesh_formats() + ")");
}

void keep_only_readers_of(Assimp::Importer& importer, MeshFormat format) {
  const auto extension = std::find_if(kExtensions.begin(), kExtensions.end(),
                                      [&](const KnownExtension& entry) { return entry.format == format; });
  const std::string wanted(extension->extension.substr(1));  // without its dot, as assimp lists it
  for (std::size_t index = importer.GetImporterCount(); index-- > 0;) {
    const aiImporterDesc* description = importer.GetImporterInfo(index);
    std::istringstream listed(
        description != nullptr && description->mFileExtensions != nullptr ? description->mFileExtensions : "");
    bool reads_it = false;
    for (std::string word; listed >> word;) reads_it = reads_it || word == wanted;
    if (reads_it) continue;
    // unregistered, a reader is the caller's to delete
    std::unique_ptr<Assimp::BaseImporter> reader(importer.GetImporter(index));
    if (importer.UnregisterLoader(reader.get()) != AI_SUCCESS) reader.release();  // still the importer's
  }
}

}  // namespace cubespring
