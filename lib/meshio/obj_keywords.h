// The OBJ statements that lodbake reads past, shared by the in-memory and
// the streaming OBJ readers so that both move over a file the same way.
#pragma once

#include <string_view>

namespace lodbake {

/// True for a statement of the OBJ spec that lodbake reads past (its tokens
/// are read to the end of the line, continuations included); anything else
/// is "unknown" (its keyword may be binary junk, unfit for a note) and only
/// skipped to the next line end.
inline bool is_obj_ignored_keyword(std::string_view k) {
  static const char* const kKeywords[] = {
      "o",     "g",     "s",      "mg",       "usemtl",   "mtllib",     "l",
      "p",     "vp",    "cstype", "deg",      "bmat",     "step",       "curv",
      "curv2", "surf",  "parm",   "trim",     "hole",     "scrv",       "sp",
      "end",   "con",   "lod",    "usemap",   "maplib",   "shadow_obj", "trace_obj",
      "ctech", "stech", "bevel",  "c_interp", "d_interp", "call",       "csh"};
  for (const char* known : kKeywords) {
    if (k == known) return true;
  }
  return false;
}

}  // namespace lodbake
