#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <system_error>

#include "core/error.hpp"
#include "io/output_file.hpp"

namespace fissure {

namespace {

// Removes the temporary file a failed write left; what to add to the error if that fails too.
std::string discard(const std::string& temporary) {
  if (std::remove(temporary.c_str()) == 0) return "";
  const int error = errno;
  if (error == ENOENT) return "";
  return "; removing " + temporary + " failed too: " + std::generic_category().message(error);
}

}  // namespace

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = path + ".tmp";
  try {
    OutputFile file(temporary, OutputFile::Mode::truncate);
    write(file.stream());
    file.close();
  } catch (const OutputError& e) {
    const std::string reason = e.reason() + " (writing " + temporary + ")";
    throw OutputError(path, reason + discard(temporary) +
                                "; the file's previous version, if any, "
                                "is untouched");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason =
        "cannot rename " + temporary + " to it: " + std::generic_category().message(errno);
    throw OutputError(path, reason + discard(temporary));
  }
}

}  // namespace fissure
