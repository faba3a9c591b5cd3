// lodbake-simplify --memory-limit: the out-of-core run (lib/outofcore), in
// one process or as one of its stages (--stage split|block|merge).
#pragma once

#include <string>

#include "lib/simplify/simplify.h"
#include "tools/common/cli.h"

namespace lodbake::cli {

struct OutOfCoreRequest {
  std::string input;         // the mesh (one-shot and split)
  std::string output;        // the simplified mesh (one-shot and merge)
  std::string memory_limit;  // as given (one-shot and split)
  std::string stage;         // empty (one-shot), split, block or merge
  uint32_t block = 0;        // --stage block
  std::string work;          // the work folder (required with --stage)
  SimplifyOptions options;   // targets and engine options
};

// Runs the request; returns the exit code.
int run_out_of_core(const Tool& tool, const OutOfCoreRequest& request);

}  // namespace lodbake::cli
