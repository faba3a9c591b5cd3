// Turning a container's stored bytes into section payloads: every section
// stored with a codec other than raw (docs/format.md "Codecs") is decoded,
// so the section decoders (decode_base(), decode_vspl(), ...) read raw
// payloads whatever the file stored.
#pragma once

#include <vector>

#include "formats/container/container_reader.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"

namespace lodbake {

/// The raw BASE payload of a BASE section stored with any codec (a copy for
/// raw). \return as decode_section_codecs() (the size is not checked here).
Result<Bytes> decode_base_stored(const Section& base);

/// The raw VSPL payload of a VSPL section stored with any codec, against
/// its decoded BASE mesh (needed by the compact codec).
Result<Bytes> decode_vspl_stored(const Section& vspl, const TriangleMesh& base);

/// The raw payload of a section of a kind whose compact codec is coded
/// against BASE (FANH, STRP: compact_sections.h), stored with any codec,
/// against its decoded BASE mesh.
Result<Bytes> decode_with_base_stored(const Section& section, const TriangleMesh& base);

/// The raw payload of a section of a kind that needs no other section to
/// decode (raw, or compact for the kinds of compact_sections.h); a copy for
/// raw. \return LBK-E020 for a codec the kind does not define; the codec
/// decoder's LBK-E023.
Result<Bytes> decode_stored_payload(const Section& section);

/// Decodes the coded sections of `container` in place: afterwards each
/// Section's data and size are its raw payload (owned by `*storage`, which
/// must outlive the container's use); entries keep the stored codec and
/// sizes. Each group's BASE is decoded before its VSPL, FANH and STRP, whose
/// compact codecs need it. Sections of kinds the reader does not know
/// (Section::known false) keep their stored bytes.
/// \return LBK-E020 (kUnsupported) for a codec this build cannot decode or
///         that is not defined for the section's kind; the codec decoder's
///         LBK-E023; LBK-E024 when a compact VSPL, FANH or STRP has no BASE; LBK-E021 when
///         the decoded payload's size differs from the entry's decoded size.
Status decode_section_codecs(Container* container, std::vector<Bytes>* storage);

}  // namespace lodbake
