#include "formats/sections/open_container.h"

#include <new>

#include "formats/container/container_errors.h"
#include "formats/sections/section_payloads.h"

namespace lodbake {
namespace {

std::string joined(const std::vector<const char*>& tags) {
  std::string out;
  for (const char* tag : tags)
    out += (out.empty() ? "" : " + ") + std::string(tag);
  return out;
}

}  // namespace

const Section& OpenedContainer::stored_of(const Section& decoded) const {
  return stored_.sections[static_cast<size_t>(&decoded - decoded_.sections.data())];
}

Result<uint32_t> OpenedContainer::group_with(const std::vector<const char*>& tags,
                                             const std::string& purpose,
                                             const std::string& producer) const {
  for (uint32_t group = 0; group < group_count(); ++group) {
    bool all = true;
    for (const char* tag : tags)
      all = all && find(tag, group) != nullptr;
    if (all) return group;
  }
  const std::string needs = purpose + " needs " + joined(tags) + " (" + producer + ")";
  for (const char* tag : tags) {
    bool anywhere = false;
    for (const Section& section : decoded_.sections)
      anywhere = anywhere || section.tag() == tag;
    if (!anywhere) {
      return container_error(ContainerError::kMissingSection,
                             "the container has no " + std::string(tag) + " section; " + needs);
    }
  }
  return container_error(
      ContainerError::kMissingSection,
      "no group of the container holds " + joined(tags) + " together over one base mesh; " + needs);
}

Result<OpenedContainer> open_container(Bytes file) {
  try {
    OpenedContainer opened;
    opened.file_ = std::move(file);
    LODBAKE_ASSIGN_OR_RETURN(opened.stored_,
                             read_container(opened.file_.data(), opened.file_.size()));
    opened.decoded_ = opened.stored_;
    LODBAKE_RETURN_IF_ERROR(decode_section_codecs(&opened.decoded_, &opened.payloads_));
    return opened;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while opening the container");
  }
}

Result<OpenedContainer> open_container_file(const std::string& path) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(path));
  return open_container(std::move(bytes));
}

}  // namespace lodbake
