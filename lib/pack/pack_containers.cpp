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
//   the compact codec predicts from the BASE as written. VTRE's base nodes
//   are given the written BASE's positions (mode vtrees checks them).
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
#include <utility>

#include "formats/container/container_writer.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "formats/sections/meta.h"
#include "formats/sections/open_container.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vspl_compact.h"
#include "formats/sections/vtre.h"
#include "formats/support/string_format.h"
#include "lib/core/parallel.h"

namespace lodbake {
namespace {

constexpr const char* kPackTool = "lodbake-pack";

// VTRE's base nodes carry BASE's positions (mode vtrees checks them against
// the hierarchy's, whose roots are BASE's vertices): when BASE was
// re-quantized or Draco-coded they follow it, as VSPL's records do. A VTRE
// over another vertex count is left for --validate to report. Nothing when
// no position moves (the payload stays as it is).
Result<std::optional<Bytes>> vtre_on_base(const uint8_t* raw, size_t raw_size,
                                          const TriangleMesh& base) {
  LODBAKE_ASSIGN_OR_RETURN(VertexTrees trees, decode_vtre(raw, raw_size));
  if (trees.base_vertex_count != base.vertex_count() ||
      trees.positions.size() < trees.base_vertex_count)
    return std::optional<Bytes>();
  bool moved = false;
  for (uint32_t v = 0; v < trees.base_vertex_count; ++v) {
    if (trees.positions[v] == base.positions[v]) continue;
    trees.positions[v] = base.positions[v];
    moved = true;
  }
  if (!moved) return std::optional<Bytes>();
  LODBAKE_ASSIGN_OR_RETURN(Bytes encoded, encode_vtre(trees));
  return std::optional<Bytes>(std::move(encoded));
}

// The written section is the input's, codec and bytes.
bool same_as_stored(const Section& input, SectionCodec codec, const Bytes& stored) {
  return input.entry.codec == static_cast<uint16_t>(codec) &&
         std::equal(stored.begin(), stored.end(), input.data, input.data + input.size);
}

std::string codec_text(uint16_t codec) {
  const char* name = codec_name(codec);
  return name != nullptr ? name : std::to_string(codec);
}

// One input's section chosen for the output: its stored bytes and its raw
// payload (the stored bytes again for kinds this build does not know).
struct Chosen {
  size_t input = 0;
  const Section* stored = nullptr;
  const Section* decoded = nullptr;
};

// The sections of one output group: one base mesh and what refines it.
struct OutGroup {
  std::map<std::string, Chosen> chosen;
  std::vector<std::string> order;  // first-seen order
};

struct InputFile {
  OpenedContainer file;
  std::optional<MetaSection> meta;
  std::vector<uint32_t> out_group;  // per input group
};

bool listed(const std::vector<std::string>& tags, const std::string& tag) {
  for (const std::string& t : tags) {
    if (t == tag) return true;
  }
  return false;
}

bool wanted_tag(const RepackOptions& options, const std::string& tag) {
  if (listed(options.drop, tag)) return false;
  return options.keep.empty() || listed(options.keep, tag) || tag == kMetaTag;
}

// An output group none of whose sections is written.
constexpr uint32_t kDroppedGroup = UINT32_MAX;

// Moves each input's bytes into its opened container.
Status read_inputs(std::vector<PackInput>* inputs, std::vector<InputFile>* files, size_t* failed) {
  for (size_t i = 0; i < inputs->size(); ++i) {
    *failed = i;
    LODBAKE_ASSIGN_OR_RETURN(OpenedContainer opened, open_container(std::move((*inputs)[i].bytes)));
    InputFile file{std::move(opened), std::nullopt, {}};
    if (const Section* meta = file.file.find(kMetaTag)) {
      LODBAKE_ASSIGN_OR_RETURN(MetaSection decoded, decode_meta(meta->data, meta->size));
      file.meta = std::move(decoded);
    }
    files->push_back(std::move(file));
  }
  *failed = inputs->size();
  return Status::ok();
}

// Two sections hold the same thing: known kinds by their raw payloads (a
// compact and a raw VSPL of the same records are the same), others by codec
// and stored bytes.
bool same_section(const Chosen& a, const Chosen& b) {
  if (!a.decoded->known) {
    return a.stored->entry.codec == b.stored->entry.codec &&
           a.stored->entry.decoded_size == b.stored->entry.decoded_size &&
           std::equal(a.stored->data, a.stored->data + a.stored->size, b.stored->data,
                      b.stored->data + b.stored->size);
  }
  return std::equal(a.decoded->data, a.decoded->data + a.decoded->size, b.decoded->data,
                    b.decoded->data + b.decoded->size);
}

// Places every input group into the first output group with the same BASE
// (or none) whose sections of the same tags are the same; else into a new
// group. META is left out: the output gets a new one.
std::vector<OutGroup> assign_groups(std::vector<InputFile>* files) {
  std::vector<OutGroup> groups;
  for (size_t i = 0; i < files->size(); ++i) {
    InputFile& in = (*files)[i];
    const Container& stored = in.file.stored();
    const Container& decoded = in.file.decoded();
    for (uint32_t g = 0; g < in.file.group_count(); ++g) {
      std::vector<Chosen> sections;
      for (size_t k = 0; k < decoded.sections.size(); ++k) {
        if (decoded.sections[k].group() != g || decoded.sections[k].tag() == kMetaTag) continue;
        sections.push_back(Chosen{i, &stored.sections[k], &decoded.sections[k]});
      }
      auto fits = [&](const OutGroup& out) {
        const bool has_base = out.chosen.count(kBaseTag) != 0;
        bool base_seen = false;
        for (const Chosen& c : sections) {
          base_seen = base_seen || c.stored->tag() == kBaseTag;
          auto it = out.chosen.find(c.stored->tag());
          if (c.stored->tag() == kBaseTag && it == out.chosen.end()) return false;
          if (it != out.chosen.end() && !same_section(it->second, c)) return false;
        }
        return base_seen == has_base;
      };
      size_t target = groups.size();
      for (size_t o = 0; o < groups.size() && target == groups.size(); ++o) {
        if (fits(groups[o])) target = o;
      }
      if (target == groups.size()) groups.emplace_back();
      OutGroup& out = groups[target];
      for (const Chosen& c : sections) {
        if (out.chosen.emplace(c.stored->tag(), c).second) out.order.push_back(c.stored->tag());
      }
      in.out_group.push_back(static_cast<uint32_t>(target));
    }
    // A container with META only still has group 0.
    if (in.out_group.empty()) in.out_group.push_back(0);
  }
  if (groups.empty()) groups.emplace_back();
  return groups;
}

Status merge_meta(const std::vector<PackInput>& inputs, const std::vector<InputFile>& files,
                  const nlohmann::json& meta_options, MetaSection* out, size_t* failed) {
  *out = make_meta(kPackTool);
  out->options = meta_options.is_null() ? nlohmann::json::object() : meta_options;
  nlohmann::json sources = nlohmann::json::array();
  auto add_source = [&](nlohmann::json source) {
    if (std::find(sources.begin(), sources.end(), source) == sources.end())
      sources.push_back(std::move(source));
  };
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
    // META's counts describe its own group 0; they go to the output's
    // counts when that is the output's group 0 too, else to the source.
    const uint32_t group = files[i].out_group.front();
    if (group == 0) {  // (a dropped group 0 is renumbered 0 too: it keeps META)
      for (const auto& [key, value] : meta.counts) {
        auto [it, inserted] = out->counts.emplace(key, value);
        if (!inserted && it->second != value) {
          return invalid_input("META counts." + key + " is " + std::to_string(value) +
                               ", an earlier input says " + std::to_string(it->second));
        }
      }
    }
    auto earlier = meta.extra.find("sources");
    if (meta.tool == kPackTool && earlier != meta.extra.end() && earlier->is_array()) {
      for (nlohmann::json source : *earlier) {
        // Its group numbers are the packed file's: renumber them.
        const uint64_t from = source.value("group", uint64_t{0});
        const uint32_t to =
            from < files[i].out_group.size() ? files[i].out_group[from] : files[i].out_group[0];
        if (to == kDroppedGroup) continue;
        if (to == 0) {
          source.erase("group");
        } else {
          source["group"] = to;
        }
        add_source(std::move(source));
      }
    } else {
      if (group == kDroppedGroup) continue;
      nlohmann::json source = {
          {"tool", meta.tool}, {"version", meta.version}, {"options", meta.options}};
      if (group != 0) {
        source["group"] = group;
        if (!meta.counts.empty()) source["counts"] = meta.counts;
      }
      add_source(std::move(source));
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

// Writes one output group's sections: META first (group 0 only), BASE,
// VSPL, then the others as first seen, recoded as `options` asks.
Status write_group(const std::vector<PackInput>& inputs, const OutGroup& group, uint32_t index,
                   const RepackOptions& options, const MetaSection& merged_meta,
                   ContainerWriter* writer, PackResult* result,
                   std::vector<PackedSection>* dropped) {
  const std::map<std::string, Chosen>& chosen = group.chosen;
  auto wanted = [&](const std::string& tag) { return wanted_tag(options, tag); };
  std::vector<std::string> out_order;
  if (index == 0) out_order.push_back(kMetaTag);
  for (const char* tag : {kBaseTag, kVsplTag}) {
    if (chosen.count(tag) != 0) out_order.push_back(tag);
  }
  for (const std::string& tag : group.order) {
    if (tag != kBaseTag && tag != kVsplTag) out_order.push_back(tag);
  }
  if (wanted(kVsplTag) && chosen.count(kVsplTag) != 0 && !wanted(kBaseTag))
    return invalid_input("VSPL is kept but BASE is dropped: VSPL needs its BASE");

  std::optional<TriangleMesh> written_base;  // the BASE as a reader will decode it
  // One section of the output, made by encode(); dropped ones only report.
  struct Encoded {
    bool write = false;
    bool dropped = false;
    Bytes stored;
    SectionCodec codec = SectionCodec::kRaw;
    uint64_t decoded_size = 0;
    bool required = false;
    PackedSection report;
  };
  auto encode = [&](const std::string& tag, Encoded* out) -> Status {
    PackedSection& report = out->report;
    Bytes& stored = out->stored;
    SectionCodec& codec = out->codec;
    uint64_t& decoded_size = out->decoded_size;
    report.tag = tag;
    report.group = index == kDroppedGroup ? 0 : index;
    auto it = chosen.find(tag);
    if (it != chosen.end()) {
      const Section& s = *it->second.stored;
      report.source = inputs[it->second.input].name;
      report.codec_before = codec_text(s.entry.codec);
      report.stored_before = s.entry.stored_size;
    }
    if (!wanted(tag)) {
      if (it == chosen.end()) return Status::ok();
      report.action = "dropped";
      out->dropped = true;
      return Status::ok();
    }
    out->write = true;
    // Known tags get the registry's required flag whatever the input said
    // (inputs written before the flags were settled, or by other writers);
    // an unknown section keeps its own.
    bool& required = out->required;
    required = section_required(tag);
    if (tag == kMetaTag) {
      // Counts describe group 0's sections (docs/format.md "META"): those of
      // sections left out go too, or the output would not validate.
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
      const Section& in = *c.decoded;  // the input's raw payload
      LODBAKE_ASSIGN_OR_RETURN(BaseSummary summary, read_base_summary(in.data, in.size));
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, decode_base(in.data, in.size));
      // The raw payload a reader decodes from the written section, when it
      // is not the input's own; otherwise the written BASE is `mesh`.
      std::optional<Bytes> written_raw;
      const bool draco_target = options.draco;
      if (base_as_requested(*c.stored, summary, options, draco_target)) {
        stored = Bytes(c.stored->data, c.stored->data + c.stored->size);
        codec = static_cast<SectionCodec>(c.stored->entry.codec);
        decoded_size = in.size;
        report.action = "copied";
      } else {
        if (options.quantize_bits != 0 && !draco_target &&
            !(summary.position_encoding == PositionEncoding::kQuantized &&
              summary.quantization_bits == options.quantize_bits)) {
          BaseEncodeOptions quantize;
          quantize.quantize = true;
          quantize.bits = options.quantize_bits;
          LODBAKE_ASSIGN_OR_RETURN(stored, encode_base(mesh, quantize));
          written_raw = stored;
        } else {
          stored = Bytes(in.data, in.data + in.size);
        }
        decoded_size = stored.size();
        if (draco_target) {
          Result<Bytes> draco = encode_base_draco(mesh, options.draco_options);
          if (draco.is_ok()) {
            stored = std::move(draco).value();
            codec = SectionCodec::kDraco;
            Section probe = *c.stored;
            probe.entry.codec = static_cast<uint16_t>(codec);
            probe.data = stored.data();
            probe.size = stored.size();
            LODBAKE_ASSIGN_OR_RETURN(written_raw, decode_base_stored(probe));
            decoded_size = written_raw->size();
          } else if (draco.status().kind() != ErrorKind::kUnsupported) {
            return draco.status();
          }
        }
        report.action = "recoded";
      }
      if (written_raw) {
        LODBAKE_ASSIGN_OR_RETURN(TriangleMesh decoded,
                                 decode_base(written_raw->data(), written_raw->size()));
        written_base = std::move(decoded);
      } else {
        written_base = std::move(mesh);
      }
      if (index == 0) {
        result->vertices = written_base->vertex_count();
        result->triangles = written_base->triangle_count();
      }
    } else if (tag == kVsplTag) {
      const Chosen& c = it->second;
      const Section& in = *c.decoded;  // the input's raw payload
      LODBAKE_ASSIGN_OR_RETURN(VsplSummary summary, read_vspl_summary(in.data, in.size));
      int bits = options.quantize_bits;
      if (bits == 0 && options.draco && summary.position_encoding == PositionEncoding::kFloat32)
        bits = options.draco_options.quantization_bits;
      // The raw payload to write: the input's, unless recoded into `owned`.
      Bytes owned;
      const uint8_t* raw = in.data;
      size_t raw_size = in.size;
      if (bits != 0 && !(summary.position_encoding == PositionEncoding::kQuantized &&
                         summary.quantization_bits == bits)) {
        // Re-encode against the input's own BASE: the records' implied vs
        // positions are those of the BASE they were decoded with.
        const Section& base_in = *chosen.at(kBaseTag).decoded;
        LODBAKE_ASSIGN_OR_RETURN(
            ProgressiveMesh pm,
            decode_progressive_mesh(base_in.data, base_in.size, in.data, in.size));
        VsplEncodeOptions quantize;
        quantize.quantize = true;
        quantize.bits = bits;
        LODBAKE_ASSIGN_OR_RETURN(owned, encode_vspl(pm, quantize));
        raw = owned.data();
        raw_size = owned.size();
      }
      if (options.error_bits != 0) {
        LODBAKE_ASSIGN_OR_RETURN(owned, round_vspl_errors(raw, raw_size, options.error_bits));
        raw = owned.data();
        raw_size = owned.size();
      }
      LODBAKE_ASSIGN_OR_RETURN(VsplSection section,
                               decode_vspl(raw, raw_size, written_base->positions));
      if (index == 0) {
        result->splits = section.splits.size();
        result->vertices = section.summary.full_vertex_count();
        result->triangles = full_triangle_count(written_base->triangle_count(), section.splits);
      }
      decoded_size = raw_size;
      if (options.compact) {
        VsplCompactOptions compact;
        compact.decoded = &section;  // decoded against the written BASE, as the codec does
        LODBAKE_ASSIGN_OR_RETURN(stored,
                                 encode_vspl_compact(raw, raw_size, *written_base, compact));
        codec = SectionCodec::kCompact;
      } else if (owned.empty()) {
        stored = Bytes(raw, raw + raw_size);
      } else {
        stored = std::move(owned);
      }
      report.action = same_as_stored(*c.stored, codec, stored) ? "copied" : "recoded";
    } else if (it->second.decoded->known &&
               (has_standalone_compact_codec(tag) || has_base_compact_codec(tag))) {
      const Chosen& c = it->second;
      Bytes owned;  // VTRE moved onto the written BASE
      const uint8_t* raw = c.decoded->data;
      size_t raw_size = c.decoded->size;
      if (tag == kVtreTag && written_base) {
        LODBAKE_ASSIGN_OR_RETURN(std::optional<Bytes> moved,
                                 vtre_on_base(raw, raw_size, *written_base));
        if (moved) {
          owned = std::move(*moved);
          raw = owned.data();
          raw_size = owned.size();
        }
      }
      decoded_size = raw_size;
      // FANH's and STRP's codecs use BASE's triangles, which recoding BASE
      // never changes; without BASE in the output they stay raw.
      const bool with_base = has_base_compact_codec(tag);
      const bool can_compact = !with_base || written_base.has_value();
      bool compacted = false;
      if (options.compact && can_compact) {
        // Tiny payloads can grow by the codec's header: they stay raw.
        Result<Bytes> compact = with_base
                                    ? encode_section_compact(tag, raw, raw_size, *written_base)
                                    : encode_section_compact(tag, raw, raw_size);
        if (compact.is_ok() && compact.value().size() < raw_size) {
          stored = std::move(compact).value();
          codec = SectionCodec::kCompact;
          compacted = true;
        } else if (!compact.is_ok() && compact.status().kind() != ErrorKind::kUnsupported) {
          return compact.status();
        }
      }
      if (!compacted) stored = owned.empty() ? Bytes(raw, raw + raw_size) : std::move(owned);
      report.action = same_as_stored(*c.stored, codec, stored) ? "copied" : "recoded";
    } else {
      const Section& s = *it->second.stored;
      stored = Bytes(s.data, s.data + s.size);
      codec = static_cast<SectionCodec>(s.entry.codec);
      decoded_size = s.entry.decoded_size;
      if (!is_known_section(tag)) required = s.required();
      report.action = "copied";
    }
    report.codec_after = codec_text(static_cast<uint16_t>(codec));
    report.stored_after = stored.size();
    report.decoded_after = decoded_size;
    return Status::ok();
  };

  // META and BASE first, one after the other: the sections after them are
  // coded against the BASE as written. Those are independent of each other
  // (the three VSPLs, FANH, VTRE and SETS of a bake's package take most of
  // its time), so they are coded side by side and written in order.
  std::vector<Encoded> encoded(out_order.size());
  size_t serial = 0;
  while (serial < out_order.size() &&
         (out_order[serial] == kMetaTag || out_order[serial] == kBaseTag)) {
    LODBAKE_RETURN_IF_ERROR(encode(out_order[serial], &encoded[serial]));
    ++serial;
  }
  std::vector<Status> statuses(out_order.size(), Status::ok());
  const ParallelScope scope(options.threads);
  scope.for_each_part(out_order.size() - serial, [&](size_t k) {
    statuses[serial + k] = encode(out_order[serial + k], &encoded[serial + k]);
  });
  for (const Status& status : statuses)
    LODBAKE_RETURN_IF_ERROR(status);
  for (size_t i = 0; i < out_order.size(); ++i) {
    Encoded& e = encoded[i];
    if (e.dropped) dropped->push_back(std::move(e.report));
    if (!e.write) continue;
    LODBAKE_RETURN_IF_ERROR(writer->add_stored_section(out_order[i], std::move(e.stored), e.codec,
                                                       e.decoded_size, e.required, index));
    result->sections.push_back(std::move(e.report));
  }
  return Status::ok();
}

Result<PackResult> repack_unchecked(std::vector<PackInput> inputs, const RepackOptions& options,
                                    const nlohmann::json& meta_options, size_t* failed) {
  *failed = inputs.size();
  if (inputs.empty()) return invalid_input("no input containers");
  PackResult result;
  for (const PackInput& input : inputs)
    result.input_bytes += input.bytes.size();
  std::vector<InputFile> files;
  LODBAKE_RETURN_IF_ERROR(read_inputs(&inputs, &files, failed));
  std::vector<OutGroup> groups = assign_groups(&files);
  // Groups whose every section is dropped are left out, and the others
  // renumbered, so the output's groups run 0, 1, 2, ... again.
  std::vector<uint32_t> renumber(groups.size(), kDroppedGroup);
  uint32_t kept = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
    bool any = g == 0;  // group 0 keeps META
    for (const std::string& tag : groups[g].order)
      any = any || wanted_tag(options, tag);
    if (any) renumber[g] = kept++;
  }
  for (InputFile& file : files) {
    for (uint32_t& g : file.out_group)
      g = renumber[g];
  }
  // The input hashes first: files of different inputs differ everywhere.
  MetaSection merged_meta;
  LODBAKE_RETURN_IF_ERROR(merge_meta(inputs, files, meta_options, &merged_meta, failed));
  ContainerWriter writer;
  std::vector<PackedSection> dropped;
  for (size_t g = 0; g < groups.size(); ++g) {
    LODBAKE_RETURN_IF_ERROR(write_group(inputs, groups[g], renumber[g], options, merged_meta,
                                        &writer, &result, &dropped));
  }
  for (PackedSection& d : dropped)
    result.sections.push_back(std::move(d));
  LODBAKE_ASSIGN_OR_RETURN(result.file, writer.finish());
  return result;
}

}  // namespace

Result<PackResult> repack_containers(std::vector<PackInput> inputs, const RepackOptions& options,
                                     const nlohmann::json& meta_options, size_t* failed_input) {
  const size_t count = inputs.size();
  size_t failed = count;
  Result<PackResult> result = [&]() -> Result<PackResult> {
    try {
      return repack_unchecked(std::move(inputs), options, meta_options, &failed);
    } catch (const std::bad_alloc&) {
      return runtime_error("out of memory while packing");
    }
  }();
  if (failed_input != nullptr) *failed_input = result.is_ok() ? count : failed;
  return result;
}

}  // namespace lodbake
