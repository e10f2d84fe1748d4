// Atomic output: data goes to a temporary file next to the destination,
// which is renamed over it only once complete. An interrupted or failed write
// leaves no partial file (the temporary is removed, also on SIGINT/SIGTERM
// through remove_pending_temporaries()).
#pragma once

#include <cstdio>
#include <string>

namespace sharpmesh::io {

class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* stream() { return file_; }
  void write(const void* data, std::size_t size);
  void write(const std::string& text) { write(text.data(), text.size()); }
  /// Flushes, closes and renames onto the destination. Throws InvalidInput on failure.
  void commit();

 private:
  std::string path_, temp_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
  int slot_ = -1;
};

/// Removes temporaries of writes still in progress; async-signal-safe.
void remove_pending_temporaries() noexcept;

}  // namespace sharpmesh::io
