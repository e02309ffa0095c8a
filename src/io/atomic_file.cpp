#include "io/atomic_file.hpp"

#include <filesystem>
#include <fstream>

#include "core/error.hpp"

namespace fissure {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw RunError("cannot write " + temporary);
    write(out);
    out.flush();
    if (!out) throw RunError("failed writing " + temporary + " (disk full?)");
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace fissure
