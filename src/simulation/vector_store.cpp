// Vectors kept in blocks, full blocks on an unlinked file (vector_store.hpp).
#include "vector_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>

#include "pcsim/core/error.hpp"

namespace pcsim::simulation::modal_detail {

namespace {

// An unnamed file in 'dir' (made and unlinked), or -1.
int unnamed_file(const std::string& dir) {
  if (dir.empty()) return -1;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::string path = dir + "/.pcsim-vectors-XXXXXX";
  const int fd = mkstemp(path.data());
  if (fd >= 0) unlink(path.c_str());
  return fd;
}

// All of 'size' bytes at 'offset' by pread or pwrite (which may do part).
template <typename Transfer>
bool transfer_all(Transfer transfer, char* data, std::size_t size, off_t offset) {
  while (size > 0) {
    const ssize_t n = transfer(data, size, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n, size -= static_cast<std::size_t>(n), offset += n;
  }
  return true;
}

}  // namespace

VectorStore::VectorStore(long rows, const std::string& spill_dir)
    : rows_(rows), fd_(unnamed_file(spill_dir)) {}

VectorStore::~VectorStore() {
  if (fd_ >= 0) close(fd_);
}

long VectorStore::width(std::size_t b) const {
  return std::min<long>(kBlock, count_ - static_cast<long>(b) * kBlock);
}

void VectorStore::append(const double* v) {
  if (cleared_) throw SolverError("vector store: appended after it was cleared");
  if (count_ % kBlock == 0) {
    blocks_.emplace_back(rows_, kBlock);
    on_file_.push_back(false);
  }
  std::copy(v, v + rows_, blocks_.back().col(count_ % kBlock).data());
  if (++count_ % kBlock == 0) spill(blocks_.size() - 1);
}

// A full block to the file (kept in memory if it cannot be written).
void VectorStore::spill(std::size_t b) {
  if (fd_ < 0) return;
  const std::size_t bytes = sizeof(double) * static_cast<std::size_t>(rows_ * kBlock);
  const off_t offset = static_cast<off_t>(b * bytes);
  const auto write = [this](char* d, std::size_t n, off_t at) { return pwrite(fd_, d, n, at); };
  if (!transfer_all(write, reinterpret_cast<char*>(blocks_[b].data()), bytes, offset)) return;
  blocks_[b] = Eigen::MatrixXd();
  on_file_[b] = true;
}

const Eigen::MatrixXd& VectorStore::block(std::size_t b, Eigen::MatrixXd& scratch) const {
  if (cleared_) throw SolverError("vector store: read after it was cleared");
  if (!on_file_[b]) return blocks_[b];
  scratch.resize(rows_, kBlock);
  const std::size_t bytes = sizeof(double) * static_cast<std::size_t>(rows_ * kBlock);
  const auto read = [this](char* d, std::size_t n, off_t at) { return pread(fd_, d, n, at); };
  if (!transfer_all(read, reinterpret_cast<char*>(scratch.data()), bytes,
                    static_cast<off_t>(b * bytes)))
    throw SolverError("modal window shift: the vectors stored on file cannot be read back");
  return scratch;
}

void VectorStore::clear() {
  blocks_.clear();
  blocks_.shrink_to_fit();
  cleared_ = true;
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

}  // namespace pcsim::simulation::modal_detail
