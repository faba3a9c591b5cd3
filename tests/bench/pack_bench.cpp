// Progressive-mesh container sizes and codec speed (issue 7), side by side
// in one run on the same input:
//   - lodbake: the engine's full PM (down to --base-triangles) stored as
//     BASE + VSPL raw float32, raw quantized, compact float32, compact
//     quantized, compact quantized with a Draco BASE; the compact VSPL's
//     parts (permutation, errors) measured by re-encoding without them, and
//     the bits per split of each part as the range coder spends them (vs,
//     wings, positions, errors, permutation); the ratio to Draco of the
//     whole PM and of its topology and positions alone (what Draco stores);
//   - OpenMesh's progressive mesh file (DecimaterT + ModQuadricT +
//     ModProgMeshT::write(): 24 bytes per split), and the .spm OpenMesh's
//     VDPM analyzer (OpenMesh-Analyzer, Debian libopenmesh-apps, run as a
//     subprocess; --analyzer PATH) makes of it: the vertex hierarchy with
//     its refinement data (about 80 bytes per split); left out with a note
//     when the analyzer is not installed;
//   - the streaming paper's 96 bits of topology per vsplit packet (Kim, Lee,
//     Kobbelt), a constant;
//   - Draco single-rate of the full mesh: the draco_encoder defaults (qp 11,
//     cl 7, edgebreaker) and cl 10 qp 14;
//   - Draco point clouds of the split vertices' positions in PM order
//     (sequential, which keeps the order, and kd-tree, which does not), to
//     compare Draco with the compact codec's predicted positions.
// Sizes are exact; times are medians of --runs runs (noisy on a shared
// machine: compare the ratios of one run).
//
//   bench_pack [--runs N] [--bits Q] [--base-triangles T] [--analyzer PATH] [--markdown]
//              FILE...
#include <unistd.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModProgMeshT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/compression/encode.h"
#include "draco/mesh/mesh.h"
#include "draco/point_cloud/point_cloud.h"
#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vspl_compact.h"
#include "lib/core/unreferenced_vertices.h"
#include "lib/meshio/mesh_import.h"
#include "lib/pack/pack_containers.h"
#include "lib/simplify/simplify.h"
#include "tests/bench/bench_support.h"

namespace {

using namespace lodbake;
using lodbake::bench::median_seconds;

Bytes raw_container(const ProgressiveMesh& pm, int bits) {
  BaseEncodeOptions base_options;
  VsplEncodeOptions vspl_options;
  if (bits != 0) {
    base_options.quantize = vspl_options.quantize = true;
    base_options.bits = vspl_options.bits = bits;
  }
  MetaSection meta = make_meta("bench_pack");
  ContainerWriter writer;
  writer.add_section(kMetaTag, encode_meta(meta).value(), false);
  writer.add_section(kBaseTag, encode_base(pm.base, base_options).value(), true);
  writer.add_section(kVsplTag, encode_vspl(pm, vspl_options).value(), false);
  return writer.finish().value();
}

uint64_t section_size(const Bytes& file, const char* tag) {
  Result<Container> c = read_container(file.data(), file.size());
  if (!c.is_ok()) return 0;
  const Section* s = c.value().find(tag);
  return s == nullptr ? 0 : s->size;
}

Bytes repack(const Bytes& file, const RepackOptions& options) {
  Result<PackResult> r = repack_containers({{"in.lbk", file}}, options, {}, nullptr);
  if (!r.is_ok()) {
    std::fprintf(stderr, "bench_pack: error: %s\n", r.status().message().c_str());
    std::exit(4);
  }
  return r.value().file;
}

// OpenMesh's two progressive-mesh files of the same decimation: the .pm
// ModProgMeshT writes, and the .spm OpenMesh's VDPM analyzer
// (OpenMesh-Analyzer, Debian libopenmesh-apps) makes of it, run as a
// subprocess: the vertex hierarchy with its refinement data.
struct OpenMeshFiles {
  uint64_t pm_bytes = 0;
  uint64_t pm_splits = 0;  ///< detail vertices in the .pm header
  uint64_t spm_bytes = 0;  ///< 0 when there is no .spm (spm_note says why)
  uint64_t spm_splits = 0;
  std::string spm_note;
};

uint32_t u32_at(const Bytes& bytes, size_t offset) {
  uint32_t value = 0;
  if (offset + 4 <= bytes.size()) std::memcpy(&value, bytes.data() + offset, 4);
  return value;
}

OpenMeshFiles openmesh_files(const TriangleMesh& input, uint64_t base_triangles,
                             const std::string& analyzer) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
  OpenMeshFiles files;
  Mesh mesh;
  std::vector<Mesh::VertexHandle> handles;
  for (const Vec3f& p : input.positions)
    handles.push_back(mesh.add_vertex({p[0], p[1], p[2]}));
  for (const Triangle& t : input.triangles)
    mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
  Decimater decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModProgMeshT<Mesh>::Handle progressive;
  decimater.add(quadric);
  decimater.add(progressive);
  decimater.module(quadric).unset_max_err();
  if (!decimater.initialize()) return files;
  decimater.decimate_to_faces(0, base_triangles);
  const std::string scratch = "/tmp/bench_pack_" + std::to_string(getpid());
  const std::string pm = scratch + ".pm", spm = scratch + ".spm", log = scratch + ".log";
  if (!decimater.module(progressive).write(pm)) return files;
  // "ProgMesh", base vertices, base faces, detail vertices.
  if (Result<Bytes> bytes = read_file(pm); bytes.is_ok()) {
    files.pm_bytes = bytes.value().size();
    files.pm_splits = u32_at(bytes.value(), 16);
  }
  if (!bench::tool_installed(analyzer)) {
    files.spm_note =
        analyzer + " is not installed (Debian libopenmesh-apps; make bench installs it)";
  } else {
    const bench::ToolRun run = bench::run_tool({analyzer, "-o", spm, pm}, log);
    Result<Bytes> bytes = read_file(spm);
    // "VDProgMesh", base vertices, base faces, detail vertices.
    if (run.exit_status != 0 || !bytes.is_ok() || bytes.value().size() < 22 ||
        std::memcmp(bytes.value().data(), "VDProgMesh", 10) != 0) {
      files.spm_note = analyzer + " failed (exit status " + std::to_string(run.exit_status) +
                       ", see its output in " + log + ")";
      std::remove(pm.c_str());
      std::remove(spm.c_str());
      return files;
    }
    files.spm_bytes = bytes.value().size();
    files.spm_splits = u32_at(bytes.value(), 18);
    std::remove(log.c_str());
  }
  std::remove(pm.c_str());
  std::remove(spm.c_str());
  return files;
}

struct DracoResult {
  uint64_t bytes = 0;
  double encode_seconds = 0;
  double decode_seconds = 0;
};

DracoResult draco_single_rate(const TriangleMesh& input, int qp, int cl, int runs) {
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<uint32_t>(input.vertex_count()));
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, 12, 0);
  const int id = mesh.AddAttribute(position, true, static_cast<uint32_t>(input.vertex_count()));
  for (size_t v = 0; v < input.vertex_count(); ++v)
    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(v)),
                                          input.positions[v].data());
  for (const Triangle& t : input.triangles)
    mesh.AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
  draco::Encoder encoder;
  // qp 0, cl -1: the library's own defaults (no quantization, speed 5).
  if (cl >= 0) encoder.SetSpeedOptions(10 - cl, 10 - cl);
  if (qp > 0) encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, qp);
  DracoResult r;
  draco::EncoderBuffer buffer;
  r.encode_seconds = median_seconds(runs, [&] {
    buffer.Clear();
    encoder.EncodeMeshToBuffer(mesh, &buffer);
  });
  r.bytes = buffer.size();
  r.decode_seconds = median_seconds(runs, [&] {
    draco::DecoderBuffer in;
    in.Init(buffer.data(), buffer.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) std::fprintf(stderr, "bench_pack: Draco decoding failed\n");
  });
  return r;
}

uint64_t draco_points(const ProgressiveMesh& pm, int qp, bool kd_tree) {
  draco::PointCloud cloud;
  const uint32_t n = static_cast<uint32_t>(pm.splits.size());
  if (n == 0) return 0;
  cloud.set_num_points(n);
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, 12, 0);
  const int id = cloud.AddAttribute(position, true, n);
  for (uint32_t i = 0; i < n; ++i)
    cloud.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i),
                                           pm.splits[i].vt_position.data());
  draco::Encoder encoder;
  encoder.SetSpeedOptions(0, 0);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, qp);
  encoder.SetEncodingMethod(kd_tree ? draco::POINT_CLOUD_KD_TREE_ENCODING
                                    : draco::POINT_CLOUD_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  if (!encoder.EncodePointCloudToBuffer(cloud, &buffer).ok()) return 0;
  return buffer.size();
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  int bits = 14;
  uint64_t base_triangles = 100;
  bool markdown = false;
  std::string analyzer = "/usr/bin/OpenMesh-Analyzer";
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--bits" && i + 1 < argc) {
      bits = std::atoi(argv[++i]);
    } else if (arg == "--base-triangles" && i + 1 < argc) {
      base_triangles = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--analyzer" && i + 1 < argc) {
      analyzer = argv[++i];
    } else if (arg == "--markdown") {
      markdown = true;
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty() || bits < 1 || bits > 30) {
    std::fprintf(stderr,
                 "usage: bench_pack [--runs N] [--bits Q] [--base-triangles T] [--analyzer PATH] "
                 "[--markdown] FILE...\n");
    return 1;
  }
  int status = 0;
  for (const std::string& file : files) {
    ImportReport report;
    Result<TriangleMesh> loaded = import_mesh_file(file, &report);
    if (!loaded.is_ok()) {
      std::fprintf(stderr, "bench_pack: error: %s: %s\n", file.c_str(),
                   loaded.status().message().c_str());
      status = 2;
      continue;
    }
    TriangleMesh input = std::move(loaded).value();
    remove_unreferenced_vertices(input);
    input.normals = {};
    input.texcoords = {};
    SimplifyOptions options;
    options.target_triangles = base_triangles;
    options.record_pm = true;
    Result<SimplifyResult> simplified = simplify(input, options);
    if (!simplified.is_ok() || !simplified.value().pm) {
      std::fprintf(stderr, "bench_pack: error: %s: simplify failed\n", file.c_str());
      status = 4;
      continue;
    }
    const ProgressiveMesh& pm = *simplified.value().pm;
    const double v = static_cast<double>(pm.full_vertex_count());
    const double splits = static_cast<double>(pm.splits.size());
    const std::string name = file.substr(file.find_last_of('/') + 1);

    struct Row {
      std::string what;
      uint64_t bytes;
      double encode_s = -1;
      double decode_s = -1;
    };
    std::vector<Row> rows;
    const Bytes raw_float = raw_container(pm, 0);
    const Bytes raw_quantized = raw_container(pm, bits);
    rows.push_back({"raw float32 (BASE+VSPL)", raw_float.size()});
    rows.push_back({"raw " + std::to_string(bits) + "-bit", raw_quantized.size()});
    RepackOptions compact;
    rows.push_back({"compact float32", repack(raw_float, compact).size()});
    Bytes packed;
    const double encode_s =
        median_seconds(runs, [&] { packed = repack(raw_quantized, RepackOptions{}); });
    const double decode_s = median_seconds(runs, [&] {
      Result<Container> c = read_container(packed.data(), packed.size());
      std::vector<Bytes> storage;
      if (!c.is_ok() || !decode_section_codecs(&c.value(), &storage).is_ok()) std::exit(4);
      const Section* b = c.value().find(kBaseTag);
      const Section* s = c.value().find(kVsplTag);
      if (!decode_progressive_mesh(b->data, b->size, s->data, s->size).is_ok()) std::exit(4);
    });
    rows.push_back({"compact " + std::to_string(bits) + "-bit", packed.size(), encode_s, decode_s});
    RepackOptions draco;
    draco.draco = true;
    draco.draco_options.quantization_bits = bits;
    draco.draco_options.compression_level = 10;
    const Bytes with_draco = repack(raw_quantized, draco);
    rows.push_back({"compact " + std::to_string(bits) + "-bit + Draco BASE", with_draco.size()});
    // lodbake-pack --error-bits 8: every error rounded up to 8 significant
    // bits (a bound within 1/128 above the exact one); the rest unchanged.
    RepackOptions rounded_errors;
    rounded_errors.error_bits = 8;
    Bytes rounded;
    const double rounded_encode_s =
        median_seconds(runs, [&] { rounded = repack(raw_quantized, rounded_errors); });
    rows.push_back({"compact " + std::to_string(bits) + "-bit, errors at 8 significant bits",
                    rounded.size(), rounded_encode_s});
    // The compact VSPL's parts, by re-encoding without them.
    ProgressiveMesh no_permutation = pm;
    for (size_t k = 0; k < no_permutation.input_vertex.size(); ++k)
      no_permutation.input_vertex[k] = static_cast<uint32_t>(k);
    const Bytes without_permutation = repack(raw_container(no_permutation, bits), RepackOptions{});
    ProgressiveMesh no_errors = no_permutation;
    for (VertexSplit& s : no_errors.splits)
      s.error = 0;
    const Bytes without_errors = repack(raw_container(no_errors, bits), RepackOptions{});
    // Float32 positions are copied by the compact codec (12 bytes a split):
    // what remains of the float32 file without errors is the topology.
    const Bytes float_without_errors = repack(raw_container(no_errors, 0), RepackOptions{});
    const uint64_t topology_bytes =
        section_size(float_without_errors, kVsplTag) - 12 * pm.splits.size();
    rows.push_back({"  .. without the permutation", without_permutation.size()});
    rows.push_back({"  .. and without errors (topology + positions)", without_errors.size()});
    rows.push_back({"  .. of which VSPL topology (vs, vl, vr)", topology_bytes});
    const OpenMeshFiles openmesh = openmesh_files(input, base_triangles, analyzer);
    rows.push_back({"OpenMesh .pm (float32, 24 B/split)", openmesh.pm_bytes});
    if (openmesh.spm_bytes != 0) {
      rows.push_back({"OpenMesh .spm (VDPM analyzer of that .pm)", openmesh.spm_bytes});
    }
    rows.push_back(
        {"streaming paper topology (96 bits/split)", static_cast<uint64_t>(pm.splits.size()) * 12});
    const DracoResult d_library = draco_single_rate(input, 0, -1, runs);
    rows.push_back({"Draco single-rate, library defaults (float32, speed 5)", d_library.bytes,
                    d_library.encode_seconds, d_library.decode_seconds});
    const DracoResult d_default = draco_single_rate(input, 11, 7, runs);
    const DracoResult d_14 = draco_single_rate(input, bits, 10, runs);
    rows.push_back({"Draco single-rate qp 11 cl 7 (draco_encoder defaults)", d_default.bytes,
                    d_default.encode_seconds, d_default.decode_seconds});
    rows.push_back({"Draco single-rate qp " + std::to_string(bits) + " cl 10", d_14.bytes,
                    d_14.encode_seconds, d_14.decode_seconds});
    rows.push_back({"Draco points of vt, sequential qp " + std::to_string(bits),
                    draco_points(pm, bits, false)});
    rows.push_back({"Draco points of vt, kd-tree qp " + std::to_string(bits) + " (reorders)",
                    draco_points(pm, bits, true)});

    std::fprintf(stderr, "bench_pack: %s: %zu vertices, %zu splits from %zu base vertices\n",
                 name.c_str(), pm.full_vertex_count(), pm.splits.size(), pm.base.vertex_count());
    if (markdown) {
      std::printf("\n%s: %zu vertices, %zu splits (base %zu vertices)\n\n", name.c_str(),
                  pm.full_vertex_count(), pm.splits.size(), pm.base.vertex_count());
      std::printf("| stored as | bytes | bits/vertex | bits/split | encode s | decode s |\n");
      std::printf("|---|---:|---:|---:|---:|---:|\n");
    } else {
      std::printf("%s: %zu vertices, %zu splits\n", name.c_str(), pm.full_vertex_count(),
                  pm.splits.size());
    }
    for (const Row& r : rows) {
      const double b = static_cast<double>(r.bytes) * 8;
      char enc[32] = "";
      char dec[32] = "";
      if (r.encode_s >= 0) std::snprintf(enc, sizeof(enc), "%.4f", r.encode_s);
      if (r.decode_s >= 0) std::snprintf(dec, sizeof(dec), "%.4f", r.decode_s);
      if (markdown) {
        std::printf("| %s | %llu | %.2f | %.2f | %s | %s |\n", r.what.c_str(),
                    static_cast<unsigned long long>(r.bytes), b / v, b / splits, enc, dec);
      } else {
        std::printf("  %-52s %10llu B %8.2f b/v %8.2f b/split %8s %8s\n", r.what.c_str(),
                    static_cast<unsigned long long>(r.bytes), b / v, b / splits, enc, dec);
      }
    }
    const double goal = static_cast<double>(packed.size()) / static_cast<double>(d_14.bytes);
    std::printf("%scompact %d-bit PM / Draco single-rate qp %d cl 10 = %.2f (goal < 2)%s\n",
                markdown ? "\n" : "  ", bits, bits, goal, markdown ? "\n" : "");
    std::printf("%s.. with the errors at 8 significant bits (--error-bits 8) / Draco = %.2f%s\n",
                markdown ? "" : "  ",
                static_cast<double>(rounded.size()) / static_cast<double>(d_14.bytes),
                markdown ? "\n" : "");
    const double without =
        static_cast<double>(without_errors.size()) / static_cast<double>(d_14.bytes);
    std::printf(
        "%s.. without the permutation and the errors (topology + positions, what Draco "
        "stores) / Draco = %.2f%s\n",
        markdown ? "" : "  ", without, markdown ? "\n" : "");
    std::printf("%sVSPL alone: compact %.2f bits/split, raw %d-bit %.2f bits/split%s\n",
                markdown ? "" : "  ", section_size(packed, kVsplTag) * 8.0 / splits, bits,
                section_size(raw_quantized, kVsplTag) * 8.0 / splits, markdown ? "\n" : "");
    // The compact VSPL's parts as the range coder spends them.
    VsplEncodeOptions vspl_options;
    vspl_options.quantize = true;
    vspl_options.bits = bits;
    const Bytes raw_vspl = encode_vspl(pm, vspl_options).value();
    VsplCompactStats parts;
    VsplCompactOptions compact_options;
    compact_options.stats = &parts;
    if (!encode_vspl_compact(raw_vspl.data(), raw_vspl.size(), pm.base, compact_options).is_ok())
      std::exit(4);
    const Bytes rounded_vspl = round_vspl_errors(raw_vspl.data(), raw_vspl.size(), 8).value();
    VsplCompactStats rounded_parts;
    compact_options.stats = &rounded_parts;
    if (!encode_vspl_compact(rounded_vspl.data(), rounded_vspl.size(), pm.base, compact_options)
             .is_ok())
      std::exit(4);
    std::printf(
        "%sbits per split in the compact %d-bit VSPL: vs %.2f, wings %.2f, positions "
        "%.2f, errors %.2f (at 8 significant bits %.2f), permutation %.2f (%.2f per vertex)%s\n",
        markdown ? "" : "  ", bits, parts.vs_bits / splits, parts.wing_bits / splits,
        parts.position_bits / splits, parts.error_bits / splits, rounded_parts.error_bits / splits,
        parts.permutation_bits / splits, parts.permutation_bits / v, markdown ? "\n" : "");
    // OpenMesh's files per split of OpenMesh's own PM (its decimation, so its
    // split count), the figures the anchors quote.
    const auto per_split = [](uint64_t bytes, uint64_t count) {
      return count == 0 ? 0.0 : static_cast<double>(bytes) / static_cast<double>(count);
    };
    std::printf("%sOpenMesh's own PM: %llu splits; .pm %.2f bytes (%.1f bits) per split",
                markdown ? "" : "  ", static_cast<unsigned long long>(openmesh.pm_splits),
                per_split(openmesh.pm_bytes, openmesh.pm_splits),
                8 * per_split(openmesh.pm_bytes, openmesh.pm_splits));
    if (openmesh.spm_bytes != 0) {
      std::printf(", .spm %.2f bytes (%.1f bits) per split (%llu splits)%s\n",
                  per_split(openmesh.spm_bytes, openmesh.spm_splits),
                  8 * per_split(openmesh.spm_bytes, openmesh.spm_splits),
                  static_cast<unsigned long long>(openmesh.spm_splits), markdown ? "\n" : "");
    } else {
      std::printf("; no .spm: %s%s\n", openmesh.spm_note.c_str(), markdown ? "\n" : "");
      std::fprintf(stderr, "bench_pack: no .spm row: %s\n", openmesh.spm_note.c_str());
    }
  }
  return status;
}
