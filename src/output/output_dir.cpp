#include "pcsim/output/output_dir.hpp"

#include <filesystem>
#include <system_error>

#include "pcsim/error.hpp"

namespace fs = std::filesystem;

namespace pcsim {

OutputDir::OutputDir(MPI_Comm comm, std::string final_dir)
    : comm_(comm), final_(std::move(final_dir)) {
  while (final_.size() > 1 && final_.back() == '/') final_.pop_back();
  partial_ = final_ + ".partial";
  MPI_Comm_rank(comm_, &rank_);
  int ok = 1;
  std::string why;
  if (rank_ == 0) {
    std::error_code ec;
    fs::remove_all(partial_, ec);
    fs::create_directories(partial_, ec);
    if (ec) {
      ok = 0;
      why = ec.message();
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm_);
  if (!ok) throw InputError(final_, "-o", "cannot create output folder: " + why);
}

OutputDir::~OutputDir() {
  if (!committed_ && rank_ == 0) {
    std::error_code ec;
    fs::remove_all(partial_, ec);
  }
}

std::string OutputDir::file(const std::string& name) const {
  return partial_ + "/" + name;
}

void OutputDir::commit() {
  MPI_Barrier(comm_);
  int ok = 1;
  if (rank_ == 0) {
    std::error_code ec;
    fs::remove_all(final_, ec);
    fs::rename(partial_, final_, ec);
    ok = ec ? 0 : 1;
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm_);
  if (!ok) throw SolverError("cannot rename " + partial_ + " to " + final_);
  committed_ = true;
}

std::string default_output_dir(const std::string& scene_name) {
  return "out/" + scene_name;
}

}  // namespace pcsim
