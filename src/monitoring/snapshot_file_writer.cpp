// SnapshotFileWriter: the state snapshots written on a thread of their own, each durably (temporary
// file, fsync, rename, fsync of the directory), the newest encoded state replacing one not yet picked up.
#include "rocking_monitor/monitoring/state_snapshot.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>

#include "rocking_monitor/private_files.hpp"

namespace rocking_monitor::core {

std::string write_file_durably(const std::string& path, const std::uint8_t* data, std::size_t size) {
  auto failed = [](const std::string& what, const std::string& p) { return what + " " + p + ": " + std::strerror(errno); };
  std::string tmp;
  const int fd = create_temp_beside(path, tmp);  // 0600, a fresh name: never an existing file or link
  if (fd < 0) return failed("cannot create a temporary file beside", path);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string e = failed("cannot write", tmp);
      ::close(fd);
      ::unlink(tmp.c_str());
      return e;
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string e = failed("cannot fsync", tmp);
    ::close(fd);
    ::unlink(tmp.c_str());
    return e;
  }
  ::close(fd);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string e = failed("cannot rename " + tmp + " to", path);
    ::unlink(tmp.c_str());
    return e;
  }
  // The rename itself is durable only once the directory is synced.
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    const int rc = ::fsync(dfd);
    ::close(dfd);
    if (rc != 0) return failed("cannot fsync the directory", dir);
  }
  return {};
}

SnapshotFileWriter::SnapshotFileWriter(std::string path) : path_(std::move(path)) {
  const std::filesystem::path dir = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  thread_ = std::thread([this] { run(); });
}

SnapshotFileWriter::~SnapshotFileWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::vector<std::uint8_t>& SnapshotFileWriter::buffer() {
  std::lock_guard<std::mutex> lock(mutex_);
  const int idx = writing_ == 0 ? 1 : 0;
  if (pending_ == idx) {  // not picked up yet: the newer state replaces it
    pending_ = -1;
    ++status_.superseded;
  }
  encoding_ = idx;
  return buffers_[idx];
}

void SnapshotFileWriter::submit() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (encoding_ < 0) return;
    pending_ = encoding_;
    encoding_ = -1;
  }
  wake_.notify_one();
}

void SnapshotFileWriter::flush() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return pending_ < 0 && writing_ < 0; });
}

SnapshotFileWriter::Status SnapshotFileWriter::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

void SnapshotFileWriter::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || pending_ >= 0; });
    if (pending_ < 0) return;  // stopping with nothing to write
    writing_ = pending_;
    pending_ = -1;
    std::vector<std::uint8_t>& buf = buffers_[writing_];
    lock.unlock();
    const auto t0 = std::chrono::steady_clock::now();
    seal_snapshot(buf);  // the checksums here, off the sample path (~1 ms per MB)
    const std::string e = write_file_durably(path_, buf.data(), buf.size());
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lock.lock();
    if (e.empty()) {
      ++status_.written;
      status_.last_error.clear();
      status_.last_bytes = buf.size();
    } else {
      ++status_.failed;
      status_.last_error = e;
    }
    status_.last_write_s = s;
    status_.max_write_s = std::max(status_.max_write_s, s);
    writing_ = -1;
    idle_.notify_all();
    if (stop_ && pending_ < 0) return;
  }
}

}  // namespace rocking_monitor::core