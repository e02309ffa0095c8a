#pragma once
// Errors that the user can fix: each names the file, the key path and the reason.
#include <stdexcept>
#include <string>

namespace fissure {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, std::string reason)
      : std::runtime_error(format(file, key, reason)),
        file_(std::move(file)),
        key_(std::move(key)),
        reason_(std::move(reason)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string format(const std::string& file, const std::string& key,
                            const std::string& reason) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (!key.empty()) s += ": " + key;
    return s + ": " + reason;
  }
  std::string file_, key_, reason_;
};

// A run that cannot continue (non-finite state, ...): reported with exit code 3.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Output that cannot be written (disk full, file-size limit, folder removed): a RunError naming
// the file and the system's reason.
class OutputError : public RunError {
 public:
  OutputError(std::string path, std::string reason)
      : RunError("cannot write " + path + ": " + reason),
        path_(std::move(path)),
        reason_(std::move(reason)) {}
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_, reason_;
};

}  // namespace fissure
