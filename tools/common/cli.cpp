#include "tools/common/cli.h"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>

#include "formats/container/container_layout.h"
#include "formats/support/file_io.h"
#include "formats/support/version.h"

namespace lodbake::cli {
namespace {

template <typename T>
bool holds(const po::value_semantic* semantic) {
  return dynamic_cast<const po::typed_value<T>*>(semantic) != nullptr;
}

// Boost's lexical_cast reads "-5" into an unsigned option as 2^64 - 5 (or
// 2^32 - 5) without complaint, which would turn `--triangles -5` into "no
// limit": such a value is refused like any other invalid argument.
void refuse_negative_unsigned(const po::parsed_options& parsed,
                              const po::options_description& all) {
  for (const po::option& option : parsed.options) {
    if (option.unregistered || option.string_key.empty()) continue;
    const po::option_description* description = all.find_nothrow(option.string_key, false);
    if (description == nullptr) continue;
    const po::value_semantic* semantic = description->semantic().get();
    if (!holds<unsigned short>(semantic) && !holds<unsigned>(semantic) &&
        !holds<unsigned long>(semantic) && !holds<unsigned long long>(semantic))
      continue;
    for (const std::string& token : option.value) {
      size_t first = token.find_first_not_of(" \t");
      if (first != std::string::npos && token[first] == '-') {
        po::invalid_option_value error(token);
        error.set_option_name(option.string_key);
        error.set_prefix(po::command_line_style::allow_long);
        throw error;
      }
    }
  }
}

// True while a Progress line is drawn on stderr without its newline: an
// error, warning or note printed meanwhile clears it first, so that it is a
// line of its own instead of the progress line's tail.
bool progress_drawn = false;

void clear_progress_line() {
  if (!progress_drawn) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  progress_drawn = false;
}

}  // namespace

const char* exit_code_help() {
  return "Exit codes:\n"
         "  0  success\n"
         "  1  usage error (unknown option, missing or extra argument)\n"
         "  2  I/O error (a file cannot be read or written)\n"
         "  3  invalid input (malformed file, or a mesh the tool cannot take)\n"
         "  4  runtime error (an algorithm failed, out of memory)\n"
         "  5  unsupported (newer format version, unknown codec or format)\n"
         "  7  validation failed (--validate or --strict found problems)\n";
}

Tool::Tool(std::string name, std::string synopsis, std::string description)
    : name_(std::move(name)),
      synopsis_(std::move(synopsis)),
      description_(std::move(description)),
      options_("Options"),
      hidden_("Hidden") {
  // An interrupted or killed run leaves no temporary output behind.
  remove_temporaries_on_signals();
  options_.add_options()("help,h", "print this help and exit")(
      "version", "print the lodbake version and exit")("json",
                                                       "print the report as JSON on stdout")(
      "quiet,q", "print no progress, notes or warnings on stderr");
}

void Tool::positional(const std::string& name, int max_count) {
  hidden_.add_options()(name.c_str(), po::value<std::vector<std::string>>(), "");
  positional_.add(name.c_str(), max_count);
}

std::vector<std::string> Tool::positionals(const std::string& name) const {
  if (!vm_.count(name)) return {};
  return vm_[name].as<std::vector<std::string>>();
}

std::optional<int> Tool::single_positional(const std::string& name, const std::string& label,
                                           std::string* value) const {
  std::vector<std::string> values = positionals(name);
  if (values.empty()) return usage_error("missing " + label);
  if (values.size() > 1)
    return usage_error("expected one " + label + ", got " + std::to_string(values.size()));
  *value = values.front();
  return std::nullopt;
}

std::optional<int> Tool::parse(int argc, char** argv) {
  po::options_description all;
  all.add(options_).add(hidden_);
  // Known before parsing, so that a usage error is reported as JSON too.
  for (int i = 1; i < argc && std::strcmp(argv[i], "--") != 0; ++i) {
    if (std::strcmp(argv[i], "--json") == 0) json_ = true;
  }
  try {
    po::parsed_options parsed =
        po::command_line_parser(argc, argv)
            .options(all)
            .positional(positional_)
            .style(po::command_line_style::unix_style ^ po::command_line_style::allow_guessing)
            .run();
    refuse_negative_unsigned(parsed, all);
    po::store(parsed, vm_);
    if (vm_.count("help")) {
      print_help();
      return 0;
    }
    if (vm_.count("version")) {
      if (json_) {
        print_json({{"schema", "lodbake.version/1"},
                    {"tool", name_},
                    {"version", kLodbakeVersion},
                    {"container_format",
                     std::to_string(kFormatMajor) + "." + std::to_string(kFormatMinor)}});
      } else {
        std::cout << name_ << " " << kLodbakeVersion << "\n";
      }
      return 0;
    }
    po::notify(vm_);
  } catch (const po::error& e) {
    return usage_error(e.what());
  }
  json_ = vm_.count("json") != 0;
  quiet_ = vm_.count("quiet") != 0;
  return std::nullopt;
}

void Tool::print_help() const {
  std::cout << "Usage: " << name_ << " " << synopsis_ << "\n\n" << description_ << "\n\n";
  std::cout << options_ << "\n";
  if (!epilog_.empty()) std::cout << epilog_ << "\n";
  std::cout << exit_code_help();
}

void Tool::print_json(const nlohmann::json& report) const {
  std::cout << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  json_printed_ = true;
}

int Tool::fail(const std::string& file, const Status& status) const {
  clear_progress_line();
  std::cerr << name_ << ": error: " << (file.empty() ? "" : file + ": ") << status.message()
            << "\n";
  int code = static_cast<int>(status.kind());
  if (code == 0) code = static_cast<int>(ErrorKind::kRuntime);
  if (json_ && !json_printed_) {
    print_json({{"schema", "lodbake.error/1"},
                {"tool", name_},
                {"file", file},
                {"error", status.message()},
                {"exit_code", code}});
  }
  return code;
}

std::optional<int> Tool::check_outputs(const std::vector<std::string>& outputs) const {
  for (const std::string& output : outputs) {
    if (output.empty()) continue;
    if (Status writable = check_output_path(output); !writable.is_ok())
      return fail(output, writable);
  }
  return std::nullopt;
}

int Tool::usage_error(const std::string& message) const {
  std::string text = message;
  while (!text.empty() && (text.back() == '.' || text.back() == ' '))
    text.pop_back();
  clear_progress_line();
  std::cerr << name_ << ": error: " << text << ". See '" << name_ << " --help'.\n";
  const int code = static_cast<int>(ErrorKind::kUsage);
  if (json_ && !json_printed_) {
    print_json({{"schema", "lodbake.error/1"},
                {"tool", name_},
                {"file", ""},
                {"error", text},
                {"exit_code", code}});
  }
  return code;
}

void Tool::warn(const std::string& file, const std::string& message) const {
  if (quiet_) return;
  clear_progress_line();
  std::cerr << name_ << ": warning: " << (file.empty() ? "" : file + ": ") << message << "\n";
}

void Tool::info(const std::string& file, const std::string& message) const {
  if (quiet_) return;
  clear_progress_line();
  std::cerr << name_ << ": " << (file.empty() ? "" : file + ": ") << message << "\n";
}

int Tool::run(const std::function<int()>& body) const {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return fail("", runtime_error("out of memory"));
  } catch (const std::exception& e) {
    return fail("", runtime_error(std::string("internal error: ") + e.what()));
  }
}

Progress::Progress(const Tool& tool, std::string label)
    : enabled_(!tool.quiet() && ::isatty(STDERR_FILENO) == 1), label_(std::move(label)) {}

Progress::~Progress() {
  if (enabled_) clear_progress_line();
}

void Progress::update(double fraction) {
  if (!enabled_) return;
  int percent = static_cast<int>(fraction * 100.0);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  std::fprintf(stderr, "\r%s %3d%%", label_.c_str(), percent);
  std::fflush(stderr);
  progress_drawn = true;
}

}  // namespace lodbake::cli
