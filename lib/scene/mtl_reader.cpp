// MTL reader. Choices where practice is vague:
// - Colours take 3 numbers; "Kd r" with one number means grey (the spec's
//   "g and b are optional"); 'spectral' and 'xyz' colours are noted and
//   skipped.
// - 'd' is the opacity, 'Tr' its complement (as most exporters write it);
//   when both appear, the last one wins.
// - A map statement's options (-o -s -t take up to 3 numbers, -mm 2, -bm
//   -boost -texres -imfchan -type -blendu -blendv -cc -clamp 1) are skipped;
//   the rest of the line is the file name (names with blanks exist), with
//   '\' made '/' since Windows exporters write it.
// - Numbers that do not parse or are not finite skip their statement (noted):
//   a broken material must not make the whole OBJ unreadable.
#include "lib/scene/mtl_reader.h"

#include <cmath>
#include <map>
#include <new>
#include <string_view>

#include "lib/meshio/text_mesh_reading.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

constexpr size_t kMaxNotedKeywords = 32;

int option_arguments(std::string_view option) {
  if (option == "-o" || option == "-s" || option == "-t") return 3;
  if (option == "-mm") return 2;
  if (option == "-bm" || option == "-boost" || option == "-texres" || option == "-imfchan" ||
      option == "-type" || option == "-blendu" || option == "-blendv" || option == "-cc" ||
      option == "-clamp")
    return 1;
  return 0;
}

class MtlReader {
 public:
  MtlReader(const uint8_t* data, size_t size, ImportReport* report)
      : scanner_(data, size), report_(report) {}

  std::vector<MtlMaterial> read() {
    for (;;) {
      scanner_.skip_whitespace();
      if (scanner_.at_end()) break;
      if (scanner_.peek() == '#') {
        scanner_.skip_line();
        continue;
      }
      std::string keyword(scanner_.token_until('#'));
      if (!statement(keyword)) {
        // Bounded: a hostile file with a new keyword on every line gets
        // one note for all of them past the first few.
        auto it = skipped_.find(keyword);
        if (it == skipped_.end() && skipped_.size() < kMaxNotedKeywords)
          it = skipped_.emplace(keyword, 0).first;
        if (it != skipped_.end()) {
          ++it->second;
        } else {
          ++other_skipped_;
        }
      }
      scanner_.skip_line();
    }
    for (const auto& [keyword, count] : skipped_) {
      report_->notes.push_back("material library: ignored " + std::to_string(count) + " " +
                               quote_token(keyword) + " statement" + (count == 1 ? "" : "s"));
    }
    if (other_skipped_ != 0) {
      report_->notes.push_back("material library: ignored " + std::to_string(other_skipped_) +
                               " statements of other kinds");
    }
    return std::move(materials_);
  }

 private:
  // Reads one statement; false when it was not used.
  bool statement(const std::string& keyword) {
    if (keyword == "newmtl") {
      materials_.emplace_back();
      materials_.back().name = rest_of_line();
      return true;
    }
    if (materials_.empty()) return false;
    MtlMaterial& m = materials_.back();
    if (keyword == "Kd") return colour(&m.kd);
    if (keyword == "Ks") return colour(&m.ks);
    if (keyword == "Ke") return colour(&m.ke);
    if (keyword == "Ns") return number(&m.ns);
    if (keyword == "Pm") return number(&m.metallic);
    if (keyword == "Pr") return number(&m.roughness);
    if (keyword == "d") return number(&m.dissolve);
    if (keyword == "Tr") {
      if (!number(&m.dissolve)) return false;
      *m.dissolve = 1.0f - *m.dissolve;
      return true;
    }
    if (keyword == "map_Kd") return map(&m.diffuse_map);
    if (keyword == "map_Ke") return map(&m.emissive_map);
    if (keyword == "norm" || keyword == "map_Bump" || keyword == "map_bump" || keyword == "bump")
      return map(&m.normal_map);
    return false;
  }

  bool read_number(float* out) {
    std::string_view t = scanner_.token_until('#');
    return !t.empty() && parse_float(t, out) == NumberStatus::kOk && std::isfinite(*out);
  }

  bool number(std::optional<float>* out) {
    float v = 0;
    if (!read_number(&v)) return false;
    *out = v;
    return true;
  }

  bool colour(std::optional<MtlColour>* out) {
    MtlColour c{};
    if (!read_number(&c[0])) return false;
    if (scanner_.at_line_end()) {
      c[1] = c[2] = c[0];
    } else if (!read_number(&c[1]) || !read_number(&c[2])) {
      return false;
    }
    *out = c;
    return true;
  }

  bool map(std::string* out) {
    std::string name;
    for (;;) {
      std::string_view t = scanner_.token_until('#');
      if (t.empty()) break;
      if (name.empty() && t.size() > 1 && t[0] == '-') {
        const int arguments = option_arguments(t);
        for (int k = 0; k < arguments; ++k) {
          // -o -s -t take 1 to 3 numbers: stop at the first token that is not one.
          scanner_.skip_blanks();
          if (arguments == 3 && k > 0) {
            float ignored = 0;
            std::string_view next = peek_token();
            if (next.empty() || parse_float(next, &ignored) != NumberStatus::kOk) break;
          }
          scanner_.token_until('#');
        }
        continue;
      }
      if (!name.empty()) name += ' ';
      name += t;
    }
    if (name.empty()) return false;
    for (char& c : name)
      if (c == '\\') c = '/';
    *out = std::move(name);
    return true;
  }

  std::string_view peek_token() {
    TextScanner copy = scanner_;
    return copy.token_until('#');
  }

  std::string rest_of_line() {
    std::string s;
    for (;;) {
      std::string_view t = scanner_.token_until('#');
      if (t.empty()) break;
      if (!s.empty()) s += ' ';
      s += t;
    }
    return s;
  }

  TextScanner scanner_;
  ImportReport* report_;
  std::vector<MtlMaterial> materials_;
  std::map<std::string, uint64_t> skipped_;
  uint64_t other_skipped_ = 0;
};

}  // namespace

Result<std::vector<MtlMaterial>> parse_mtl(const uint8_t* data, size_t size, ImportReport* report) {
  try {
    std::vector<uint8_t> decoded;
    LODBAKE_RETURN_IF_ERROR(prepare_text_into_report(&data, &size, &decoded, report));
    return MtlReader(data, size, report).read();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading a material library");
  }
}

}  // namespace lodbake
