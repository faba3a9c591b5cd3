// Format detection and dispatch. Content decides before the file name: a
// PLY saved as .obj is still a PLY (and the report says so), and garbage
// named .stl goes to the STL reader, which rejects it with a precise reason.
#include "lib/meshio/mesh_import.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <optional>

#include "lib/dracoio/draco_io.h"
#include "lib/meshio/file_name.h"
#include "lib/meshio/gzip.h"
#include "lib/meshio/mesh_readers.h"

namespace lodbake {
namespace {

// Decompressed meshes larger than this are refused (a gzip bomb guard; the
// largest real mesh we know, the full dragon, is 34 MB of ASCII, and 1 GiB
// of OBJ text is about 30 million triangles).
constexpr uint64_t kMaxDecompressedBytes = uint64_t{1} << 30;

std::string strip_gz(const std::string& file_name) {
  return lower_extension(file_name) == "gz" ? file_name.substr(0, file_name.size() - 3) : file_name;
}

bool starts_with(const Bytes& bytes, const char* prefix) {
  size_t n = std::strlen(prefix);
  return bytes.size() >= n && std::memcmp(bytes.data(), prefix, n) == 0;
}

std::optional<MeshFormat> format_from_extension(const std::string& ext) {
  if (ext == "obj") return MeshFormat::kObj;
  if (ext == "off") return MeshFormat::kOff;
  if (ext == "ply") return MeshFormat::kPly;
  if (ext == "stl") return MeshFormat::kStl;
  if (ext == "gltf") return MeshFormat::kGltf;
  if (ext == "glb") return MeshFormat::kGlb;
  if (ext == "drc") return MeshFormat::kDraco;
  return std::nullopt;
}

// The first token of the first line that is not blank or a '#' comment,
// looked for in the first 64 KiB only.
std::string first_keyword(const Bytes& bytes) {
  size_t end = std::min<size_t>(bytes.size(), 1 << 16);
  size_t i = 0;
  while (i < end) {
    while (i < end && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
      ++i;
    if (i < end && bytes[i] == '#') {
      while (i < end && bytes[i] != '\n')
        ++i;
      continue;
    }
    size_t start = i;
    while (i < end && std::isgraph(bytes[i]))
      ++i;
    return std::string(bytes.begin() + static_cast<std::ptrdiff_t>(start),
                       bytes.begin() + static_cast<std::ptrdiff_t>(i));
  }
  return "";
}

// What the bytes themselves say, when they say something unambiguous.
std::optional<MeshFormat> format_from_content(const Bytes& bytes) {
  if (starts_with(bytes, "ply\n") || starts_with(bytes, "ply\r")) return MeshFormat::kPly;
  if (starts_with(bytes, "glTF")) return MeshFormat::kGlb;
  if (starts_with(bytes, "DRACO")) return MeshFormat::kDraco;
  if (bytes.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (uint64_t{84} + uint64_t{50} * count == bytes.size()) return MeshFormat::kStl;
  }
  std::string keyword = first_keyword(bytes);
  if (keyword.size() >= 3 && keyword.size() <= 8 &&
      keyword.compare(keyword.size() - 3, 3, "OFF") == 0)
    return MeshFormat::kOff;
  if (keyword == "solid") return MeshFormat::kStl;
  if (!keyword.empty() && keyword[0] == '{') return MeshFormat::kGltf;
  if (keyword == "v" || keyword == "vn" || keyword == "vt" || keyword == "f" || keyword == "o" ||
      keyword == "g" || keyword == "mtllib" || keyword == "usemtl" || keyword == "s")
    return MeshFormat::kObj;
  return std::nullopt;
}

}  // namespace

const char* mesh_format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::kObj:
      return "OBJ";
    case MeshFormat::kOff:
      return "OFF";
    case MeshFormat::kPly:
      return "PLY";
    case MeshFormat::kStl:
      return "STL";
    case MeshFormat::kGltf:
      return "glTF";
    case MeshFormat::kGlb:
      return "GLB";
    case MeshFormat::kDraco:
      return "Draco";
  }
  return "unknown";
}

Result<MeshFormat> detect_mesh_format(const std::string& file_name, const Bytes& bytes) {
  if (std::optional<MeshFormat> by_content = format_from_content(bytes)) return *by_content;
  if (std::optional<MeshFormat> by_name = format_from_extension(lower_extension(file_name)))
    return *by_name;
  return unsupported(
      "cannot tell the mesh format from the content or the name (supported: .obj .off .ply .stl "
      ".gltf .glb .drc, each optionally .gz)");
}

Result<MeshContent> prepare_mesh_content(const std::string& file_name, const Bytes& bytes,
                                         ImportReport* report) {
  MeshContent content;
  content.file_name = file_name;
  // Nested gzip (.gz.gz) is undone layer by layer, each layer bounded.
  while (is_gzip(content.bytes(bytes))) {
    const Bytes& packed = content.bytes(bytes);
    LODBAKE_ASSIGN_OR_RETURN(Bytes inflated,
                             gunzip(packed.data(), packed.size(), kMaxDecompressedBytes));
    report->notes.push_back("decompressed gzip input (" + std::to_string(packed.size()) + " -> " +
                            std::to_string(inflated.size()) + " bytes)");
    content.inflated = std::move(inflated);
    content.decompressed = true;
    content.file_name = strip_gz(content.file_name);
  }
  const Bytes& data = content.bytes(bytes);
  if (data.empty()) return invalid_input("file is empty");
  LODBAKE_ASSIGN_OR_RETURN(content.format, detect_mesh_format(content.file_name, data));
  std::optional<MeshFormat> by_name = format_from_extension(lower_extension(content.file_name));
  const MeshFormat format = content.format;
  if (by_name && *by_name != format &&
      !(*by_name == MeshFormat::kGltf && format == MeshFormat::kGlb) &&
      !(*by_name == MeshFormat::kGlb && format == MeshFormat::kGltf)) {
    report->notes.push_back(std::string("the content is ") + mesh_format_name(format) +
                            " although the name says " + mesh_format_name(*by_name) + "; read as " +
                            mesh_format_name(format));
  }
  return content;
}

Result<TriangleMesh> import_mesh(const std::string& file_name, const Bytes& bytes,
                                 ImportReport* report, const SceneResources* resources) {
  LODBAKE_ASSIGN_OR_RETURN(MeshContent content, prepare_mesh_content(file_name, bytes, report));
  const Bytes& data_bytes = content.bytes(bytes);
  const uint8_t* data = data_bytes.data();
  size_t size = data_bytes.size();
  switch (content.format) {
    case MeshFormat::kObj:
      return parse_obj(data, size, report);
    case MeshFormat::kOff:
      return parse_off(data, size, report);
    case MeshFormat::kPly:
      return parse_ply(data, size, report);
    case MeshFormat::kStl:
      return parse_stl(data, size, report);
    case MeshFormat::kGltf:
    case MeshFormat::kGlb: {
      SceneResources folder;
      if (resources != nullptr) {
        folder = *resources;
      } else {
        const size_t slash = file_name.find_last_of('/');
        folder.folder = slash == std::string::npos ? "." : file_name.substr(0, slash + 1);
        if (folder.folder.size() > 1) folder.folder.pop_back();  // "a/b/" -> "a/b", "/" stays
      }
      return parse_gltf(data, size, report, folder);
    }
    case MeshFormat::kDraco:
      return parse_draco(data, size, report);
  }
  return unsupported("unknown mesh format");
}

Result<TriangleMesh> import_mesh_file(const std::string& path, ImportReport* report) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(path));
  return import_mesh(path, bytes, report);
}

}  // namespace lodbake
