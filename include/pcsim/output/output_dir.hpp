// Output directory written atomically: results go to "<dir>.partial" and the
// folder is renamed to "<dir>" only by commit(). If the run fails (exception,
// bad input) the partial folder is removed, so no half-written results remain.
// Collective over the communicator; only rank 0 touches the file system.
#pragma once

#include <mpi.h>

#include <string>

namespace pcsim {

class OutputDir {
 public:
  OutputDir(MPI_Comm comm, std::string final_dir);
  ~OutputDir();  // removes the partial folder unless committed
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  // Path of a file inside the (partial) folder.
  std::string file(const std::string& name) const;
  const std::string& final_dir() const { return final_; }
  const std::string& partial_dir() const { return partial_; }
  // Replaces any previous <dir> by the finished results.
  void commit();

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  std::string final_, partial_;
  bool committed_ = false;
};

// Default output folder for a scene: out/<scene name>.
std::string default_output_dir(const std::string& scene_name);

}  // namespace pcsim
