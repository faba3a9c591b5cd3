// Status and Result<T>: how every layer that touches bytes, files or user
// input reports failure. Modelled on Draco's Status/StatusOr: no exceptions
// cross a lodbake API; the tools map ErrorKind to their exit code.
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace lodbake {

// The kind of a failure. The numeric values ARE the documented exit codes
// shared by every tool (see docs/exit-codes.md), so keep them stable.
enum class ErrorKind : int {
  kOk = 0,
  kUsage = 1,         // wrong options or arguments
  kIo = 2,            // a file could not be read or written
  kInvalidInput = 3,  // malformed file or a mesh the algorithm cannot take
  kRuntime = 4,       // an algorithm failed or resources ran out
  kUnsupported = 5,   // valid but unsupported (newer version, unknown codec, ...)
  kValidation = 7,    // --validate / --strict found problems
};

// A status carries a kind, an optional stable numbered code (for container
// errors, the "LBK-Ennn" numbers of docs/format.md; 0 when none) and a
// one-line message that does not name the file: the caller knows the file
// and prefixes it.
class Status {
 public:
  Status() = default;
  Status(ErrorKind kind, std::string message, int code = 0)
      : kind_(kind), code_(code), message_(std::move(message)) {}

  static Status ok() { return Status(); }

  bool is_ok() const { return kind_ == ErrorKind::kOk; }
  ErrorKind kind() const { return kind_; }
  int code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  ErrorKind kind_ = ErrorKind::kOk;
  int code_ = 0;
  std::string message_;
};

inline Status invalid_input(std::string message, int code = 0) {
  return Status(ErrorKind::kInvalidInput, std::move(message), code);
}
inline Status unsupported(std::string message, int code = 0) {
  return Status(ErrorKind::kUnsupported, std::move(message), code);
}
inline Status io_error(std::string message) {
  return Status(ErrorKind::kIo, std::move(message));
}
inline Status runtime_error(std::string message) {
  return Status(ErrorKind::kRuntime, std::move(message));
}

// Either a value or a failed Status.
template <typename T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}         // NOLINT: implicit by design
  Result(Status status) : status_(std::move(status)) {  // NOLINT: implicit by design
    assert(!status_.is_ok() && "a Result made from a Status must carry an error");
  }

  bool is_ok() const { return status_.is_ok(); }
  const Status& status() const { return status_; }

  T& value() & {
    assert(is_ok());
    return *value_;
  }
  const T& value() const& {
    assert(is_ok());
    return *value_;
  }
  T&& value() && {
    assert(is_ok());
    return std::move(*value_);
  }

 private:
  Status status_;
  std::optional<T> value_;
};

}  // namespace lodbake

#define LODBAKE_CONCAT_INNER(a, b) a##b
#define LODBAKE_CONCAT(a, b) LODBAKE_CONCAT_INNER(a, b)

// Returns the status from the enclosing function when it is an error.
#define LODBAKE_RETURN_IF_ERROR(expr)                     \
  do {                                                    \
    ::lodbake::Status lodbake_status_ = (expr);           \
    if (!lodbake_status_.is_ok()) return lodbake_status_; \
  } while (false)

// Declares `lhs` from a Result-returning expression or returns its error.
#define LODBAKE_ASSIGN_OR_RETURN(lhs, expr) \
  LODBAKE_ASSIGN_OR_RETURN_IMPL(LODBAKE_CONCAT(lodbake_result_, __LINE__), lhs, expr)
#define LODBAKE_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                  \
  if (!tmp.is_ok()) return tmp.status();              \
  lhs = std::move(tmp).value()
