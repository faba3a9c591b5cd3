// Repacking containers (issue 7): merge sections of several files baked from
// one input, drop or keep tags, recode BASE, VSPL and the kinds with a
// compact codec of their own (formats/sections/compact_sections.h).
//
// Choices:
// - Inputs must agree on META's input SHA-256 when there are several (one
//   input needs no META). A tag found in two inputs must have the same
//   payload: BASE and VSPL are compared decoded (a compact and a raw VSPL
//   of the same records are the same), as are the kinds with a compact
//   codec; other kinds by codec and stored bytes. META is never compared:
//   the output gets a new one.
// - The kinds with a compact codec of their own (VHIE, RFIN, DAGE, VTRE,
//   SETS, and FANH and STRP against BASE) are written compact, or raw
//   without options.compact. A valid raw payload the codec cannot
//   reproduce (laid out unlike the reference writer), or one the codec
//   would not make smaller, stays raw; a malformed one is an error, as for
//   BASE and VSPL.
// - Kinds this file does not recode (anything else) are copied with their
//   codec, flags and sizes, byte for byte: their own tools define their
//   codecs, and a copy can never damage what pack does not understand.
// - Every known kind gets the required flag of the section registry, as
//   from every other lodbake writer, whatever flag its input carried.
// - Idempotence: a BASE already stored as requested (same codec and Draco
//   options, or raw with the requested quantization) is copied, never
//   re-quantized, because quantizing dequantized values again need not give
//   the same integers (nor Draco the same bitstream). VSPL's compact coding
//   is lossless and deterministic, so re-encoding it gives the same bytes.
// - A re-quantized or Draco-coded BASE moves the base vertices within the
//   quantization error; VSPL records that leave vs in place (no stored vs
//   positions) take vs's position from BASE when read, so they follow, and
//   the compact codec predicts from the BASE as written.
// - The output META is "lodbake-pack" with the options, the common input,
//   the union of the inputs' counts (a disagreement is an error) and the
//   inputs' provenance in "sources"; a source that is itself a pack
//   contributes its own sources instead, so packing a packed file with the
//   same options writes the same META.
#include "lib/pack/pack_containers.h"

#include <algorithm>
#include <map>
#include <new>
#include <optional>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "formats/sections/meta.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vspl_compact.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

constexpr const char* kPackTool = "lodbake-pack";

std::string codec_text(uint16_t codec) {
  const char* name = codec_name(codec);
  return name != nullptr ? name : std::to_string(codec);
}

// One input's section chosen for the output, with its raw payload when it
// is a kind pack recodes.
struct Chosen {
  size_t input = 0;
  const Section* section = nullptr;
  Bytes raw;  // BASE and VSPL only
};

struct InputFile {
  Container container;
  std::optional<MetaSection> meta;
  std::optional<TriangleMesh> base;  // its BASE decoded, when it has one
};

bool listed(const std::vector<std::string>& tags, const std::string& tag) {
  for (const std::string& t : tags) {
    if (t == tag) return true;
  }
  return false;
}

Status read_inputs(const std::vector<PackInput>& inputs, std::vector<InputFile>* files,
                   size_t* failed) {
  for (size_t i = 0; i < inputs.size(); ++i) {
    *failed = i;
    InputFile file;
    LODBAKE_ASSIGN_OR_RETURN(file.container,
                             read_container(inputs[i].bytes.data(), inputs[i].bytes.size()));
    if (const Section* meta = file.container.find(kMetaTag)) {
      LODBAKE_ASSIGN_OR_RETURN(MetaSection decoded, decode_meta(meta->data, meta->size));
      file.meta = std::move(decoded);
    }
    files->push_back(std::move(file));
  }
  *failed = inputs.size();
  return Status::ok();
}

// The decoded BASE of input `i` (decoded once).
Result<const TriangleMesh*> input_base(std::vector<InputFile>* files, size_t i) {
  InputFile& file = (*files)[i];
  if (!file.base) {
    LODBAKE_ASSIGN_OR_RETURN(const Section* base, file.container.require(kBaseTag));
    LODBAKE_ASSIGN_OR_RETURN(Bytes raw, decode_base_stored(*base));
    LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, decode_base(raw.data(), raw.size()));
    file.base = std::move(mesh);
  }
  return &*file.base;
}

Result<Bytes> raw_payload(std::vector<InputFile>* files, size_t i, const Section& section) {
  if (section.tag() == kBaseTag) return decode_base_stored(section);
  if (has_standalone_compact_codec(section.tag())) return decode_stored_payload(section);
  LODBAKE_ASSIGN_OR_RETURN(const TriangleMesh* base, input_base(files, i));
  if (has_base_compact_codec(section.tag())) return decode_with_base_stored(section, *base);
  return decode_vspl_stored(section, *base);
}

Status merge_meta(const std::vector<PackInput>& inputs, const std::vector<InputFile>& files,
                  const nlohmann::json& meta_options, MetaSection* out, size_t* failed) {
  *out = make_meta(kPackTool);
  out->options = meta_options.is_null() ? nlohmann::json::object() : meta_options;
  nlohmann::json sources = nlohmann::json::array();
  for (size_t i = 0; i < files.size(); ++i) {
    *failed = i;
    if (!files[i].meta) {
      if (files.size() > 1)
        return invalid_input("has no META section: merging needs the input hash of every file");
      continue;
    }
    const MetaSection& meta = *files[i].meta;
    if (files.size() > 1 && !meta.input)
      return invalid_input("META names no input: merging needs the input hash of every file");
    if (meta.input) {
      if (!out->input) {
        out->input = meta.input;
      } else if (out->input->sha256_hex != meta.input->sha256_hex) {
        return invalid_input("was baked from another input (META input sha256 " +
                             meta.input->sha256_hex.substr(0, 16) + "..., " + inputs[0].name +
                             " has " + out->input->sha256_hex.substr(0, 16) + "...)");
      }
    }
    for (const auto& [key, value] : meta.counts) {
      auto [it, inserted] = out->counts.emplace(key, value);
      if (!inserted && it->second != value) {
        return invalid_input("META counts." + key + " is " + std::to_string(value) +
                             ", an earlier input says " + std::to_string(it->second));
      }
    }
    auto earlier = meta.extra.find("sources");
    if (meta.tool == kPackTool && earlier != meta.extra.end() && earlier->is_array()) {
      for (const nlohmann::json& source : *earlier) {
        if (std::find(sources.begin(), sources.end(), source) == sources.end())
          sources.push_back(source);
      }
    } else {
      nlohmann::json source = {
          {"tool", meta.tool}, {"version", meta.version}, {"options", meta.options}};
      if (std::find(sources.begin(), sources.end(), source) == sources.end())
        sources.push_back(std::move(source));
    }
  }
  *failed = inputs.size();
  out->extra["sources"] = std::move(sources);
  return Status::ok();
}

bool base_as_requested(const Section& section, const BaseSummary& summary,
                       const RepackOptions& options, bool draco_target) {
  if (draco_target) {
    if (section.entry.codec != static_cast<uint16_t>(SectionCodec::kDraco)) return false;
    Result<DracoOptions> stored = read_draco_base_options(section.data, section.size);
    return stored.is_ok() && stored.value() == options.draco_options;
  }
  if (section.entry.codec != static_cast<uint16_t>(SectionCodec::kRaw)) return false;
  return options.quantize_bits == 0 || (summary.position_encoding == PositionEncoding::kQuantized &&
                                        summary.quantization_bits == options.quantize_bits);
}

Result<PackResult> repack_unchecked(const std::vector<PackInput>& inputs,
                                    const RepackOptions& options,
                                    const nlohmann::json& meta_options, size_t* failed) {
  *failed = inputs.size();
  if (inputs.empty()) return invalid_input("no input containers");
  std::vector<InputFile> files;
  LODBAKE_RETURN_IF_ERROR(read_inputs(inputs, &files, failed));
  // The input hashes first: files of different inputs differ everywhere.
  MetaSection merged_meta;
  LODBAKE_RETURN_IF_ERROR(merge_meta(inputs, files, meta_options, &merged_meta, failed));
  PackResult result;
  for (const PackInput& input : inputs)
    result.input_bytes += input.bytes.size();

  // The first occurrence of each tag, in first-seen order; later ones must match.
  std::map<std::string, Chosen> chosen;
  std::vector<std::string> order;
  for (size_t i = 0; i < files.size(); ++i) {
    *failed = i;
    for (const Section& section : files[i].container.sections) {
      const std::string& tag = section.tag();
      const bool recoded = tag == kBaseTag || tag == kVsplTag || has_base_compact_codec(tag) ||
                           has_standalone_compact_codec(tag);
      auto it = chosen.find(tag);
      if (it == chosen.end()) {
        Chosen c{i, &section, {}};
        if (recoded) {
          LODBAKE_ASSIGN_OR_RETURN(c.raw, raw_payload(&files, i, section));
        }
        chosen.emplace(tag, std::move(c));
        order.push_back(tag);
        continue;
      }
      if (tag == kMetaTag) continue;
      bool same = false;
      if (recoded) {
        LODBAKE_ASSIGN_OR_RETURN(Bytes raw, raw_payload(&files, i, section));
        same = raw == it->second.raw;
      } else {
        const Section& first = *it->second.section;
        same = first.entry.codec == section.entry.codec &&
               first.entry.decoded_size == section.entry.decoded_size &&
               Bytes(first.data, first.data + first.size) ==
                   Bytes(section.data, section.data + section.size);
      }
      if (!same) {
        return invalid_input("section " + tag + " differs from the one in " +
                             inputs[it->second.input].name);
      }
    }
  }
  *failed = inputs.size();

  auto wanted = [&](const std::string& tag) {
    if (listed(options.drop, tag)) return false;
    return options.keep.empty() || listed(options.keep, tag) || tag == kMetaTag;
  };
  // Output order: META, BASE, VSPL, then the others as first seen.
  std::vector<std::string> out_order;
  for (const char* tag : {kMetaTag, kBaseTag, kVsplTag}) {
    if (chosen.count(tag) != 0 || std::string(tag) == kMetaTag) out_order.push_back(tag);
  }
  for (const std::string& tag : order) {
    if (tag != kMetaTag && tag != kBaseTag && tag != kVsplTag) out_order.push_back(tag);
  }
  if (wanted(kVsplTag) && chosen.count(kVsplTag) != 0 && !wanted(kBaseTag))
    return invalid_input("VSPL is kept but BASE is dropped: VSPL needs its BASE");

  ContainerWriter writer;
  std::vector<PackedSection> dropped;
  std::optional<TriangleMesh> written_base;  // the BASE as a reader will decode it
  std::optional<BaseSummary> base_summary;
  for (const std::string& tag : out_order) {
    PackedSection report;
    report.tag = tag;
    auto it = chosen.find(tag);
    if (it != chosen.end()) {
      const Section& s = *it->second.section;
      report.source = inputs[it->second.input].name;
      report.codec_before = codec_text(s.entry.codec);
      report.stored_before = s.entry.stored_size;
    }
    if (!wanted(tag)) {
      if (it == chosen.end()) continue;
      report.action = "dropped";
      dropped.push_back(std::move(report));
      continue;
    }
    Bytes stored;
    SectionCodec codec = SectionCodec::kRaw;
    uint64_t decoded_size = 0;
    // Known tags get the registry's required flag whatever the input said
    // (inputs written before the flags were settled, or by other writers);
    // an unknown section keeps its own.
    bool required = section_required(tag);
    if (tag == kMetaTag) {
      // Counts describe sections (docs/format.md "META"): those of sections
      // left out go too, or the output would not validate.
      MetaSection meta = merged_meta;
      const bool writes_base = chosen.count(kBaseTag) != 0 && wanted(kBaseTag);
      const bool writes_vspl = chosen.count(kVsplTag) != 0 && wanted(kVsplTag);
      if (!writes_base) {
        meta.counts.erase("vertices");
        meta.counts.erase("triangles");
      }
      if (!writes_vspl) {
        for (const char* key : {"splits", "full_vertices", "full_triangles"})
          meta.counts.erase(key);
      }
      LODBAKE_ASSIGN_OR_RETURN(stored, encode_meta(meta));
      decoded_size = stored.size();
      report.action = "rewritten";
    } else if (tag == kBaseTag) {
      const Chosen& c = it->second;
      LODBAKE_ASSIGN_OR_RETURN(BaseSummary summary, read_base_summary(c.raw.data(), c.raw.size()));
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, decode_base(c.raw.data(), c.raw.size()));
      base_summary = summary;
      bool draco_target = options.draco;
      if (base_as_requested(*c.section, summary, options, draco_target)) {
        stored = Bytes(c.section->data, c.section->data + c.section->size);
        codec = static_cast<SectionCodec>(c.section->entry.codec);
        decoded_size = c.raw.size();
        report.action = "copied";
      } else {
        Bytes raw = c.raw;
        if (options.quantize_bits != 0 && !draco_target &&
            !(summary.position_encoding == PositionEncoding::kQuantized &&
              summary.quantization_bits == options.quantize_bits)) {
          BaseEncodeOptions quantize;
          quantize.quantize = true;
          quantize.bits = options.quantize_bits;
          LODBAKE_ASSIGN_OR_RETURN(raw, encode_base(mesh, quantize));
        }
        stored = raw;
        decoded_size = raw.size();
        if (draco_target) {
          Result<Bytes> draco = encode_base_draco(mesh, options.draco_options);
          if (draco.is_ok()) {
            stored = std::move(draco).value();
            codec = SectionCodec::kDraco;
            Section probe = *c.section;
            probe.entry.codec = static_cast<uint16_t>(codec);
            probe.data = stored.data();
            probe.size = stored.size();
            LODBAKE_ASSIGN_OR_RETURN(raw, decode_base_stored(probe));
            decoded_size = raw.size();
          } else if (draco.status().kind() != ErrorKind::kUnsupported) {
            return draco.status();
          }
        }
        report.action = "recoded";
      }
      Section probe = *c.section;
      probe.entry.codec = static_cast<uint16_t>(codec);
      probe.data = stored.data();
      probe.size = stored.size();
      LODBAKE_ASSIGN_OR_RETURN(Bytes written_raw, decode_base_stored(probe));
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh decoded,
                               decode_base(written_raw.data(), written_raw.size()));
      written_base = std::move(decoded);
      result.vertices = written_base->vertex_count();
      result.triangles = written_base->triangle_count();
    } else if (tag == kVsplTag) {
      const Chosen& c = it->second;
      LODBAKE_ASSIGN_OR_RETURN(VsplSummary summary, read_vspl_summary(c.raw.data(), c.raw.size()));
      int bits = options.quantize_bits;
      if (bits == 0 && options.draco && summary.position_encoding == PositionEncoding::kFloat32)
        bits = options.draco_options.quantization_bits;
      Bytes raw = c.raw;
      if (bits != 0 && !(summary.position_encoding == PositionEncoding::kQuantized &&
                         summary.quantization_bits == bits)) {
        // Re-encode against the input's own BASE: the records' implied vs
        // positions are those of the BASE they were decoded with.
        const Chosen& base = chosen.at(kBaseTag);
        LODBAKE_ASSIGN_OR_RETURN(
            ProgressiveMesh pm,
            decode_progressive_mesh(base.raw.data(), base.raw.size(), c.raw.data(), c.raw.size()));
        VsplEncodeOptions quantize;
        quantize.quantize = true;
        quantize.bits = bits;
        LODBAKE_ASSIGN_OR_RETURN(raw, encode_vspl(pm, quantize));
      }
      if (options.error_bits != 0) {
        LODBAKE_ASSIGN_OR_RETURN(raw,
                                 round_vspl_errors(raw.data(), raw.size(), options.error_bits));
      }
      LODBAKE_ASSIGN_OR_RETURN(VsplSection section,
                               decode_vspl(raw.data(), raw.size(), written_base->positions));
      result.splits = section.splits.size();
      result.vertices = section.summary.full_vertex_count();
      result.triangles = full_triangle_count(written_base->triangle_count(), section.splits);
      decoded_size = raw.size();
      if (options.compact) {
        LODBAKE_ASSIGN_OR_RETURN(stored,
                                 encode_vspl_compact(raw.data(), raw.size(), *written_base));
        codec = SectionCodec::kCompact;
      } else {
        stored = std::move(raw);
      }
      report.action = c.section->entry.codec == static_cast<uint16_t>(codec) &&
                              stored == Bytes(c.section->data, c.section->data + c.section->size)
                          ? "copied"
                          : "recoded";
    } else if (has_standalone_compact_codec(tag) || has_base_compact_codec(tag)) {
      const Chosen& c = it->second;
      decoded_size = c.raw.size();
      stored = c.raw;
      // FANH's and STRP's codecs use BASE's triangles, which recoding BASE
      // never changes; without BASE in the output they stay raw.
      const bool with_base = has_base_compact_codec(tag);
      const bool can_compact = !with_base || written_base.has_value();
      if (options.compact && can_compact) {
        // Tiny payloads can grow by the codec's header: they stay raw.
        Result<Bytes> compact =
            with_base ? encode_section_compact(tag, c.raw.data(), c.raw.size(), *written_base)
                      : encode_section_compact(tag, c.raw.data(), c.raw.size());
        if (compact.is_ok() && compact.value().size() < c.raw.size()) {
          stored = std::move(compact).value();
          codec = SectionCodec::kCompact;
        } else if (!compact.is_ok() && compact.status().kind() != ErrorKind::kUnsupported) {
          return compact.status();
        }
      }
      report.action = c.section->entry.codec == static_cast<uint16_t>(codec) &&
                              stored == Bytes(c.section->data, c.section->data + c.section->size)
                          ? "copied"
                          : "recoded";
    } else {
      const Section& s = *it->second.section;
      stored = Bytes(s.data, s.data + s.size);
      codec = static_cast<SectionCodec>(s.entry.codec);
      decoded_size = s.entry.decoded_size;
      if (!is_known_section(tag)) required = s.required();
      report.action = "copied";
    }
    report.codec_after = codec_text(static_cast<uint16_t>(codec));
    report.stored_after = stored.size();
    report.decoded_after = decoded_size;
    LODBAKE_RETURN_IF_ERROR(
        writer.add_stored_section(tag, std::move(stored), codec, decoded_size, required));
    result.sections.push_back(std::move(report));
  }
  for (PackedSection& d : dropped)
    result.sections.push_back(std::move(d));
  LODBAKE_ASSIGN_OR_RETURN(result.file, writer.finish());
  return result;
}

}  // namespace

Result<PackResult> repack_containers(const std::vector<PackInput>& inputs,
                                     const RepackOptions& options,
                                     const nlohmann::json& meta_options, size_t* failed_input) {
  size_t failed = inputs.size();
  Result<PackResult> result = [&]() -> Result<PackResult> {
    try {
      return repack_unchecked(inputs, options, meta_options, &failed);
    } catch (const std::bad_alloc&) {
      return runtime_error("out of memory while packing");
    }
  }();
  if (failed_input != nullptr) *failed_input = result.is_ok() ? inputs.size() : failed;
  return result;
}

}  // namespace lodbake
