#include "io/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <vector>

#include "sharpmesh/errors.h"

namespace sharpmesh::io {
namespace {

// A fixed table of pending temporary paths, readable from a signal handler.
constexpr int kSlots = 16;
constexpr std::size_t kPathMax = 4096;
// Slot states: 0 free, 1 claimed (path being copied), 2 ready (handler may unlink).
std::array<std::atomic<int>, kSlots> slot_state{};
std::array<std::array<char, kPathMax>, kSlots> slot_path{};

int register_temp(const std::string& temp) {
  if (temp.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (slot_state[i].compare_exchange_strong(expected, 1)) {
      std::memcpy(slot_path[i].data(), temp.c_str(), temp.size() + 1);
      slot_state[i].store(2);
      return i;
    }
  }
  return -1;
}

void unregister_temp(int slot) {
  if (slot >= 0) slot_state[slot].store(0);
}

}  // namespace

void remove_pending_temporaries() noexcept {
  for (int i = 0; i < kSlots; ++i)
    if (slot_state[i].load() == 2) ::unlink(slot_path[i].data());
}

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
  std::string pattern = path + ".tmp.XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());
  if (fd < 0) throw InvalidArgument("cannot write '" + path + "': " + std::strerror(errno));
  temp_ = buffer.data();
  slot_ = register_temp(temp_);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    ::close(fd);
    ::unlink(temp_.c_str());
    unregister_temp(slot_);
    throw InvalidArgument("cannot write '" + path + "': " + std::strerror(errno));
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);
  if (!committed_) ::unlink(temp_.c_str());
  unregister_temp(slot_);
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (size && std::fwrite(data, 1, size, file_) != size)
    throw InvalidInput("cannot write '" + path_ + "': " + std::strerror(errno));
}

void AtomicFile::commit() {
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const int error = errno;
  std::fclose(file_);
  file_ = nullptr;
  if (!flushed) throw InvalidInput("cannot write '" + path_ + "': " + std::strerror(error));
  // Keep the permissions a newly created file would have (mkstemp uses 0600).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(temp_.c_str(), 0666 & ~mask);
  if (std::rename(temp_.c_str(), path_.c_str()) != 0)
    throw InvalidInput("cannot write '" + path_ + "': " + std::strerror(errno));
  committed_ = true;
}

}  // namespace sharpmesh::io
