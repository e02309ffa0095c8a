#pragma once
// A file written through a POSIX descriptor: every failure (disk full, file-size limit, folder
// removed) is an OutputError naming the file and the system's reason, never a short file
// without a word.
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

namespace fissure {

class OutputFile : private std::streambuf {
 public:
  enum class Mode { truncate, append };
  // Creates or opens the file; OutputError if it cannot be.
  OutputFile(std::string path, Mode mode);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  // Closes the descriptor; an error is not reported here (close() reports it): a file dropped
  // without close() is one whose writing already failed.
  ~OutputFile() override;

  // Writes buffered through the stream throw OutputError when the file refuses them.
  std::ostream& stream() { return stream_; }
  // Hands everything written so far to the file; OutputError on failure.
  void flush();
  // flush() and close(2); OutputError on failure.
  void close();

 private:
  int_type overflow(int_type c) override;
  int sync() override;
  [[noreturn]] void fail(const std::string& what, int error) const;  // error: an errno value

  std::string path_;
  int fd_ = -1;
  std::vector<char> buffer_;
  std::ostream stream_;
};

}  // namespace fissure
