#include "pcsim/simulation/setup_memory.hpp"

#include <petscsys.h>

#include <cstdio>
#include <deque>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>

#include "pcsim/output/modal_cache.hpp"

namespace pcsim::simulation {

namespace {

struct KeptBasis {
  std::string key, file;
  SharedBasis basis;
};

std::mutex& kept_mutex() {
  static std::mutex m;
  return m;
}

std::deque<KeptBasis>& kept() {  // newest last
  static std::deque<KeptBasis> bases;
  return bases;
}

struct KeptStatics {
  std::string key;
  StaticConfiguration statics;
};

std::deque<KeptStatics>& kept_statics() {  // newest last
  static std::deque<KeptStatics> statics;
  return statics;
}

// Every option of PETSc's database as text.
std::string petsc_options() {
  char* text = nullptr;
  PCSIM_PETSC(PetscOptionsGetAll(nullptr, &text));
  std::string all = text ? text : "";
  PCSIM_PETSC(PetscFree(text));
  return all;
}

std::optional<StaticConfiguration> find_statics(const std::string& key) {
  const std::lock_guard<std::mutex> lock(kept_mutex());
  for (const auto& k : kept_statics())
    if (k.key == key) return k.statics;
  return std::nullopt;
}

void keep_statics(const std::string& key, const StaticConfiguration& statics) {
  const std::lock_guard<std::mutex> lock(kept_mutex());
  auto& all = kept_statics();
  for (auto it = all.begin(); it != all.end();) it = it->key == key ? all.erase(it) : it + 1;
  if (all.size() >= kKeptStatics) all.pop_front();
  all.push_back({key, statics});
}

}  // namespace

std::string file_content(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

StaticConfiguration kept_static_configuration(const Context& ctx, const std::string& design_path,
                                              const catenary::CatenaryMesh& mesh, bool form_finding,
                                              bool& kept) {
  const std::string key =
      output::modal_cache_key(file_content(design_path), mesh, form_finding, false) +
      " statics on " + std::to_string(ctx.size) + " rank(s), options " + petsc_options();
  auto found = find_statics(key);
  int mine = found ? 1 : 0, everywhere = 0;
  MPI_Allreduce(&mine, &everywhere, 1, MPI_INT, MPI_MIN, ctx.comm);
  kept = everywhere != 0;
  if (kept) return std::move(*found);
  auto statics = static_configuration(ctx.comm, mesh, form_finding, "static_");
  keep_statics(key, statics);
  return statics;
}

namespace {

// How every kept basis key of a cache key begins (forget_kept_bases).
std::string kept_basis_prefix(const std::string& cache_key) {
  return cache_key + " cut-off ";
}

}  // namespace

std::string kept_basis_key(const std::string& cache_key, const catenary::ModalSettings& s) {
  char settings[160];
  std::snprintf(settings, sizeof settings, "%.17g shapes %d flexibility %d vertical %d %.17g",
                s.max_frequency_hz, s.dropper_shapes ? 1 : 0, s.contact_flexibility ? 1 : 0,
                s.vertical_only ? 1 : 0, s.participation);
  return kept_basis_prefix(cache_key) + settings;
}

SharedBasis find_kept_basis(const std::string& key, const std::string& file) {
  const std::lock_guard<std::mutex> lock(kept_mutex());
  for (const auto& k : kept())
    if (k.key == key && k.file == file && !file.empty()) return k.basis;
  return nullptr;
}

void keep_basis(const std::string& key, const std::string& file, SharedBasis basis) {
  if (file.empty() || !basis) return;
  const std::lock_guard<std::mutex> lock(kept_mutex());
  auto& bases = kept();
  for (auto it = bases.begin(); it != bases.end();) it = it->key == key ? bases.erase(it) : it + 1;
  if (bases.size() >= kKeptBases) bases.pop_front();
  bases.push_back({key, file, std::move(basis)});
}

void forget_kept_bases(const std::string& cache_key) {
  const std::lock_guard<std::mutex> lock(kept_mutex());
  auto& bases = kept();
  const std::string prefix = kept_basis_prefix(cache_key);
  for (auto it = bases.begin(); it != bases.end();)
    it = it->key.compare(0, prefix.size(), prefix) == 0 ? bases.erase(it) : it + 1;
}

std::size_t kept_bases() {
  const std::lock_guard<std::mutex> lock(kept_mutex());
  return kept().size();
}

}  // namespace pcsim::simulation
