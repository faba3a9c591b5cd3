#include "lib/bake/pack_step.h"

#include <utility>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"

namespace lodbake {

nlohmann::json pack_meta_options(bool repair, int quantize_bits) {
  return {{"repair", repair},
          {"quantize_bits",
           quantize_bits == 0 ? nlohmann::json(nullptr) : nlohmann::json(quantize_bits)}};
}

Result<PackedMesh> pack_mesh(const TriangleMesh& mesh, const MetaInput& input, bool repair,
                             int quantize_bits) {
  MetaSection meta = make_meta("lodbake-pack");
  meta.options = pack_meta_options(repair, quantize_bits);
  meta.input = input;
  meta.counts = {{"vertices", mesh.vertex_count()}, {"triangles", mesh.triangle_count()}};
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  BaseEncodeOptions encoding;
  encoding.quantize = quantize_bits != 0;
  if (encoding.quantize) encoding.bits = quantize_bits;
  LODBAKE_ASSIGN_OR_RETURN(Bytes base_bytes, encode_base(mesh, encoding));
  PackedMesh out;
  out.meta_bytes = meta_bytes.size();
  out.base_bytes = base_bytes.size();
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kBaseTag, std::move(base_bytes)));
  LODBAKE_ASSIGN_OR_RETURN(out.file, writer.finish());
  return out;
}

}  // namespace lodbake
