// The mesh a container stands for, for a tool that builds a structure of its
// own from another tool's output: every tool reads what every tool writes.
#pragma once

#include <optional>
#include <string>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/meta.h"
#include "formats/sections/open_container.h"
#include "formats/support/status.h"

namespace lodbake {

struct ContainerMesh {
  /// The input mesh: the fully refined mesh of a progressive mesh in the
  /// input's vertex order, or a BASE that is the input itself.
  TriangleMesh mesh;
  /// "progressive mesh" or "base mesh", for reports.
  std::string source;
  /// The group the mesh came from.
  uint32_t group = 0;
  /// The original input as META records it (the mesh file the container
  /// was baked from), when the container has META with an input.
  std::optional<MetaInput> input;
  /// Set when the container holds an asset (SCNE) of several meshes: the
  /// structures build on one of them, which the tool must say.
  uint32_t asset_meshes = 0;
};

/// The mesh of the first group with BASE + VSPL (fully refined, in the
/// input's vertex order), else the BASE of the first group that no
/// structure refines from a coarser mesh (no VSPL or VHIE in its group:
/// what lodbake-pack MESH, lodbake-fan and lodbake-strips --strips-only
/// write). Normals and texture coordinates are not carried.
/// \return kInvalidInput (LBK-E023 / E024) for a malformed progressive mesh
///         or a container with neither.
Result<ContainerMesh> container_input_mesh(const OpenedContainer& file);

/// META's input record of `file`'s group 0, when it has one.
std::optional<MetaInput> container_meta_input(const OpenedContainer& file);

}  // namespace lodbake
