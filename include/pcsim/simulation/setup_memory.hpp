// What a process keeps between the runs it makes (the cases of an MPI
// sweep's group, a study's variants): the last kKeptStatics static
// configurations, each under the modal cache's key of the mesh solved, the
// number of ranks (the partition, the sums' order) and every PETSc option
// (the static solver's tolerances); and the last kKeptBases modal bases,
// assembled (catenary::assemble_basis), each under the modal cache's key
// (output/modal_cache.hpp: design, mesh, conditions, form-finding, full
// shapes), the settings the assembly reads and the cache file it came from.
// A run takes a kept basis only when that file is still the one the cache
// folder would serve (catenary_setup.cpp), so it gets the basis a process of
// its own would read: two runs in one process give the figures of two
// processes (tests/simulation/test_two_runs.sh). Thread-safe. A basis is
// shared, never copied: it is immutable once assembled, and the kept one and
// a run's model (assembly::ModalCatenary) hold the same memory (a copy of the
// 1000-span window's basis at 108.8 Hz was 266 MB of a first run's peak).
#pragma once

#include <memory>
#include <string>

#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/statics.hpp"

namespace pcsim::simulation {

// Bounded: two bases (a sweep alternating between two designs keeps both);
// the oldest is dropped first. One basis of the EN 50318 line at 69.8 Hz is
// 2852 rows x 2736 vectors, 62 MB.
constexpr std::size_t kKeptBases = 2;

constexpr std::size_t kKeptStatics = 2;

// The design file's content (a key's part).
std::string file_content(const std::string& path);

// The static configuration of 'mesh' (simulation::static_configuration with
// the options prefix "static_"): a copy of the one kept by an earlier run of
// this process if every rank of ctx has it, else solved and kept. 'kept'
// says which.
StaticConfiguration kept_static_configuration(const Context& ctx, const std::string& design_path,
                                              const catenary::CatenaryMesh& mesh, bool form_finding,
                                              bool& kept);

// The key of a basis: the cache key and the settings assemble_basis reads.
std::string kept_basis_key(const std::string& cache_key, const catenary::ModalSettings& settings);

// An assembled basis, shared by whoever holds it.
using SharedBasis = std::shared_ptr<const catenary::ReducedBasis>;

// The basis kept under 'key' from 'file'; null if there is none (or it came
// from another file).
SharedBasis find_kept_basis(const std::string& key, const std::string& file);
void keep_basis(const std::string& key, const std::string& file, SharedBasis basis);
// Forgets the bases kept under the cache key 'cache_key' (any settings): a
// raised cut-off's data supersede them (ModalExtensionScope).
void forget_kept_bases(const std::string& cache_key);
// How many bases this process keeps now (tests).
std::size_t kept_bases();

}  // namespace pcsim::simulation
