#include "core/append_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "core/error.h"

namespace countershade {

namespace fs = std::filesystem;

void sync_directory(const fs::path& dir) {
  int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

AppendOnlyFile AppendOnlyFile::create(const fs::path& path, const std::string& header) {
  AppendOnlyFile f;
  f.path_ = path;
  f.fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (f.fd_ < 0) {
    if (errno == EEXIST)
      throw_input_error(
          path.string(),
          "already exists; a session is never overwritten (use --resume to continue it, "
          "or another --session number)");
    throw_input_error(path.string(), std::string("cannot create: ") + std::strerror(errno));
  }
  f.append(header);
  f.sync();
  sync_directory(path.parent_path());
  return f;
}

AppendOnlyFile AppendOnlyFile::open_existing(const fs::path& path) {
  AppendOnlyFile f;
  f.path_ = path;
  f.fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (f.fd_ < 0)
    throw_input_error(path.string(),
                      std::string("cannot open for appending: ") + std::strerror(errno));
  return f;
}

AppendOnlyFile AppendOnlyFile::open_or_create(const fs::path& path) {
  AppendOnlyFile f;
  f.path_ = path;
  f.fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (f.fd_ < 0)
    throw_input_error(path.string(),
                      std::string("cannot open for appending: ") + std::strerror(errno));
  return f;
}

AppendOnlyFile AppendOnlyFile::open_to_resume(const fs::path& path, const std::string& header) {
  AppendOnlyFile f = open_or_create(path);
  struct stat st {};
  if (::fstat(f.fd_, &st) != 0)
    throw_input_error(path.string(), std::string("cannot read its size: ") + std::strerror(errno));
  if (st.st_size == 0) {
    f.append(header);
    f.sync();
    sync_directory(path.parent_path());
  }
  return f;
}

AppendOnlyFile::AppendOnlyFile(AppendOnlyFile&& other) noexcept
    : fd_(other.fd_), path_(std::move(other.path_)) {
  other.fd_ = -1;
}

AppendOnlyFile& AppendOnlyFile::operator=(AppendOnlyFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    path_ = std::move(other.path_);
    other.fd_ = -1;
  }
  return *this;
}

AppendOnlyFile::~AppendOnlyFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendOnlyFile::append(const std::string& text) {
  ssize_t written = ::write(fd_, text.data(), text.size());
  if (written != ssize_t(text.size()))
    throw std::runtime_error(path_.string() + ": write failed: " + std::strerror(errno));
}

void AppendOnlyFile::sync() {
  if (::fsync(fd_) != 0)
    throw std::runtime_error(path_.string() + ": fsync failed: " + std::strerror(errno));
}

}  // namespace countershade
