// The options layer every lodbake tool shares: Boost.ProgramOptions parsing
// with the common flags (--help, --version, --json, --quiet), the exit-code
// table, and the one-line error/warning format on stderr:
//   lodbake-inspect: error: FILE: what is wrong
//   lodbake-inspect: error: unknown option '--frob'. See 'lodbake-inspect --help'.
#pragma once

#include <boost/program_options.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "formats/support/status.h"

namespace lodbake::cli {

namespace po = boost::program_options;

class Tool {
 public:
  // `synopsis` is the usage line after the tool name, e.g. "FILE [options]";
  // `description` one paragraph printed under it in --help.
  Tool(std::string name, std::string synopsis, std::string description);

  // Tool-specific options; add before parse().
  po::options_description& options() { return options_; }
  // Names a positional argument (in order); `max_count` -1 = any number.
  void positional(const std::string& name, int max_count);
  // Extra text printed at the end of --help (before the exit codes).
  void set_help_epilog(std::string text) { epilog_ = std::move(text); }

  // Parses the command line. Returns an exit code when the tool must stop
  // now (--help or --version printed: 0; a usage error printed: 1), or
  // nothing when it should go on. A negative number given to an option of
  // an unsigned type is a usage error (Boost would wrap it around).
  std::optional<int> parse(int argc, char** argv);

  const po::variables_map& args() const { return vm_; }
  bool has(const std::string& name) const { return vm_.count(name) != 0; }
  template <typename T>
  T get(const std::string& name) const {
    return vm_[name].as<T>();
  }
  std::vector<std::string> positionals(const std::string& name) const;
  // Stores the one positional argument `name` in `*value`; when there is
  // none or more than one, prints "missing LABEL" / "expected one LABEL,
  // got N" as a usage error and returns its exit code.
  std::optional<int> single_positional(const std::string& name, const std::string& label,
                                       std::string* value) const;

  const std::string& name() const { return name_; }
  bool json() const { return json_; }
  bool quiet() const { return quiet_; }

  // Prints "name: error: FILE: message" (or without FILE when empty) and
  // returns the exit code of the status' kind. With --json, when no report
  // was printed yet, also prints a JSON error report on stdout (schema
  // lodbake.error/1), so that stdout always holds exactly one JSON document.
  int fail(const std::string& file, const Status& status) const;
  // Prints `report` as indented JSON on stdout and remembers that the run's
  // report was printed. Strings that are not valid UTF-8 (file names on
  // Linux are bytes) get U+FFFD for each bad byte instead of making the dump
  // throw.
  void print_json(const nlohmann::json& report) const;
  // Checks, before the run does its work, that every non-empty path in
  // `outputs` can be written (check_output_path(): not a device such as
  // /dev/full, a folder or a FIFO, in a folder that exists and is writable);
  // prints the first failure and returns its exit code (2).
  std::optional<int> check_outputs(const std::vector<std::string>& outputs) const;
  // Prints a usage error ending in "See 'name --help'." and returns 1; with
  // --json also the JSON error report (lodbake.error/1, `file` empty).
  int usage_error(const std::string& message) const;
  // "name: warning: FILE: message", unless --quiet.
  void warn(const std::string& file, const std::string& message) const;
  // "name: FILE: message" for information, unless --quiet.
  void info(const std::string& file, const std::string& message) const;

  // Runs the tool body, turning exceptions that escaped it (which would be
  // bugs or std::bad_alloc) into exit code 4 with a one-line message.
  int run(const std::function<int()>& body) const;

 private:
  void print_help() const;

  std::string name_;
  std::string synopsis_;
  std::string description_;
  std::string epilog_;
  po::options_description options_;
  po::options_description hidden_;
  po::positional_options_description positional_;
  po::variables_map vm_;
  bool json_ = false;
  mutable bool json_printed_ = false;
  bool quiet_ = false;
};

// The exit-code table, printed at the end of every --help.
const char* exit_code_help();

// A progress line on stderr, drawn only when stderr is a terminal and the
// tool is not --quiet; cleared when it goes out of scope.
class Progress {
 public:
  Progress(const Tool& tool, std::string label);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  // Shows `fraction` (0..1) as a percentage; redraws only when it changes.
  void update(double fraction);

 private:
  bool enabled_;
  std::string label_;
  int last_percent_ = -1;
};

}  // namespace lodbake::cli
