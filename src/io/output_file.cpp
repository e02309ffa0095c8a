#include "io/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "core/error.hpp"

namespace fissure {

OutputFile::OutputFile(std::string path, Mode mode)
    : path_(std::move(path)), buffer_(1 << 16), stream_(this) {
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mode == Mode::append ? O_APPEND : O_TRUNC);
  fd_ = ::open(path_.c_str(), flags, 0666);
  if (fd_ < 0) fail("cannot create or open it", errno);
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  // A failing overflow() throws; the stream passes the OutputError on instead of setting badbit.
  stream_.exceptions(std::ios::badbit);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::fail(const std::string& what, int error) const {
  throw OutputError(path_, what + ": " + std::generic_category().message(error));
}

void OutputFile::flush() {
  const char* at = pbase();
  while (at < pptr()) {
    const ssize_t written = ::write(fd_, at, static_cast<std::size_t>(pptr() - at));
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) fail("write failed", errno);
    if (written == 0) throw OutputError(path_, "write failed: the file took no byte");
    at += written;
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

void OutputFile::close() {
  flush();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close failed", errno);
}

OutputFile::int_type OutputFile::overflow(int_type c) {
  flush();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int OutputFile::sync() {
  flush();
  return 0;
}

}  // namespace fissure
