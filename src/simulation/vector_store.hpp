// The local parts of many vectors, appended one by one and read back in
// blocks of columns (modal_shift.cpp: a moving window's shift products need
// every mode's vector, n x c doubles: 557 MB for the 11-span window of
// 4409 vectors). Full blocks go to an unnamed file in a folder (the modal
// cache's), so that only the block being filled stays in memory; a folder
// that takes no file, or a block that cannot be written (a full disk),
// keeps them in memory instead. The file is unlinked when made: nothing is
// left behind, whatever ends the process.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace pcsim::simulation::modal_detail {

class VectorStore {
 public:
  static constexpr long kBlock = 256;  // columns per block
  // spill_dir "": every block in memory.
  VectorStore(long rows, const std::string& spill_dir);
  ~VectorStore();
  VectorStore(const VectorStore&) = delete;
  VectorStore& operator=(const VectorStore&) = delete;
  void append(const double* v);
  long count() const { return count_; }
  std::size_t blocks() const { return blocks_.size(); }
  long width(std::size_t b) const;  // columns in block b
  // Block b (rows x kBlock, width(b) columns filled): the one in memory, or
  // read into 'scratch'.
  const Eigen::MatrixXd& block(std::size_t b, Eigen::MatrixXd& scratch) const;
  bool spilled(std::size_t b) const { return b < on_file_.size() && on_file_[b]; }
  void clear();  // frees every block (count() stays)

 private:
  void spill(std::size_t b);
  long rows_;
  long count_ = 0;
  int fd_ = -1;
  std::vector<Eigen::MatrixXd> blocks_;  // empty once spilled
  std::vector<bool> on_file_;
  bool cleared_ = false;
};

}  // namespace pcsim::simulation::modal_detail
