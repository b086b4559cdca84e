#include "pcsim/output/provenance.hpp"

#include <H5public.h>
#include <mpi.h>
#include <petscsys.h>
#include <petscversion.h>
#include <slepcversion.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "output_guard.hpp"
#include "pcsim/core/blas_kernels.hpp"
#include "pcsim/core/version.hpp"

namespace pcsim::output {

namespace {

std::string petsc_options() {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (!initialized) return "";
  char* all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) != 0 || !all) return "";
  std::string text = all;
  PetscFree(all);
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

std::string host() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

// "model name" of /proc/cpuinfo (the first core), "" where there is none.
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? "" : line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "";
}

std::string hdf5_version() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(release);
}

std::string mpi_version() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string v(text, static_cast<std::size_t>(length));
  const auto end = v.find_first_of(",\n");  // "Open MPI v4.1.4, package: ..." -> first part
  return end == std::string::npos ? v : v.substr(0, end);
}

std::string dotted(int major, int minor, int subminor) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(subminor);
}

std::string shell_quoted(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                              "0123456789_-+=.,/:@%") == std::string::npos)
    return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string quoted_command_line(const std::vector<std::string>& arguments) {
  std::string line;
  for (const auto& a : arguments) line += (line.empty() ? "" : " ") + shell_quoted(a);
  return line;
}

nlohmann::json make_provenance(const ProvenanceInputs& in) {
  std::error_code ec;
  return {
      {"pcsim_version", version()},
      {"git_commit", git_commit()},
      {"results_schema", kResultsSchemaVersion},
      {"command", in.command},
      {"command_line", quoted_command_line(in.arguments)},
      {"working_directory", std::filesystem::current_path(ec).string()},
      {"scene_file", in.scene_file},
      {"scene_text", in.scene_text},
      {"resolved_scene", in.resolved_scene},
      {"overrides", in.overrides},
      {"inputs", in.inputs},
      {"inputs_fingerprint", in.inputs_fingerprint},
      {"petsc_options", petsc_options()},
      {"ranks", in.ranks},
      {"date", guard::utc_now()},
      {"host", host()},
      {"cpu_model", cpu_model()},
      {"compiler", std::string("g++ ") + __VERSION__},
      {"petsc_version", dotted(PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR)},
      {"slepc_version", dotted(SLEPC_VERSION_MAJOR, SLEPC_VERSION_MINOR, SLEPC_VERSION_SUBMINOR)},
      {"hdf5_version", hdf5_version()},
      {"mpi_version", mpi_version()},
      {"blas", blas_kernels().text()}};
}

void stamp_provenance(H5File& h5, const nlohmann::json& provenance) {
  if (!provenance.is_object()) return;
  for (const auto& [key, value] : provenance.items()) {
    if (value.is_number()) {
      h5.attribute("/", key, value.get<double>());
    } else if (value.is_string()) {
      h5.attribute("/", key, value.get<std::string>());
    } else if (value.is_array() && !value.empty()) {
      std::vector<std::string> items;
      for (const auto& v : value) items.push_back(v.is_string() ? v.get<std::string>() : v.dump());
      h5.attribute("/", key, items);
    } else if (value.is_array()) {
      h5.attribute("/", key, std::string());
    } else {
      h5.attribute("/", key, value.dump());
    }
  }
}

}  // namespace pcsim::output
