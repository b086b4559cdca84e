#include "pcsim/simulation/catenary_setup.hpp"

#include <malloc.h>
#include <petsctime.h>

#include <algorithm>
#include <cstdio>

#include "cache_written.hpp"
#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/window.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/output/modal_cache.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/memory_estimate.hpp"
#include "pcsim/simulation/modal_basis.hpp"
#include "pcsim/simulation/run_session.hpp"
#include "pcsim/simulation/setup_memory.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::simulation {

namespace {

template <typename T>
void broadcast(std::vector<T>& v, MPI_Comm comm) {
  unsigned long n = v.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, comm);
  v.resize(n);
  // In pieces of at most 1 GiB: a count is an int (a large line's rows are
  // more bytes than an int holds).
  constexpr std::size_t kPiece = std::size_t{1} << 30;
  auto* bytes = reinterpret_cast<char*>(v.data());
  for (std::size_t done = 0, total = n * sizeof(T); done < total; done += kPiece)
    MPI_Bcast(bytes + done, static_cast<int>(std::min(kPiece, total - done)), MPI_BYTE, 0, comm);
}

void broadcast(catenary::ModalData& d, MPI_Comm comm) {
  for (auto* v : {&d.omega2, &d.mode_rows, &d.shape_rows, &d.mode_shape_mass, &d.shape_mass,
                  &d.shape_flexibility, &d.contact_compliance, &d.shift_products, &d.wind_damping})
    broadcast(*v, comm);
  broadcast(d.row_keys, comm);
  double scalars[3] = {d.cutoff_hz, d.max_relative_residual, d.wall_time_s};
  MPI_Bcast(scalars, 3, MPI_DOUBLE, 0, comm);
  d.cutoff_hz = scalars[0];
  d.max_relative_residual = scalars[1];
  d.wall_time_s = scalars[2];
}

void broadcast(catenary::ReducedBasis& b, MPI_Comm comm) {
  for (auto* v : {&b.omega2, &b.rows, &b.contact_flexibility, &b.wind_damping}) broadcast(*v, comm);
  broadcast(b.shift, comm);
  broadcast(b.row_keys, comm);
  broadcast(b.column_blocks, comm);
  int counts[2] = {b.eigenmodes, b.dropped_modes};
  MPI_Bcast(counts, 2, MPI_INT, 0, comm);
  MPI_Bcast(&b.cutoff_hz, 1, MPI_DOUBLE, 0, comm);
  b.eigenmodes = counts[0];
  b.dropped_modes = counts[1];
}

// A moving window's shift (catenary/window.hpp) as a matrix over the
// system's DOFs: S(g, h) = 1 where DOF g takes the displacement of DOF h,
// the same DOF of the node 'shift' further along; rows of the window's
// front (nothing beyond) empty. Rows set where owned.
Mat window_shift_matrix(const assembly::CatenarySystem& system, double shift) {
  const auto& layout = system.layout();
  const auto& mesh = system.mesh();
  const auto partner = catenary::shifted_nodes(mesh, shift);
  Mat S;
  PCSIM_PETSC(MatCreateAIJ(system.comm(), layout.local_size(), layout.local_size(), PETSC_DETERMINE,
                           PETSC_DETERMINE, 1, nullptr, 1, nullptr, &S));
  const PetscInt lo = layout.first_owned(), hi = lo + layout.local_size();
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int c = 0; c < catenary::kNodeDofs; ++c) {
      const PetscInt g = layout.global_dof(static_cast<int>(n), c);
      if (g < lo || g >= hi || partner[n] < 0) continue;
      const PetscInt h = layout.global_dof(partner[n], c);
      if (h >= 0) PCSIM_PETSC(MatSetValue(S, g, h, 1.0, INSERT_VALUES));
    }
  PCSIM_PETSC(MatAssemblyBegin(S, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(S, MAT_FINAL_ASSEMBLY));
  return S;
}

// What the last modal data of this process were computed with, while a
// ModalExtensionScope lives: a higher cut-off of the same key computes only
// the modes above (ModalDataBuilder).
struct KeptBuilder {
  std::string key;
  std::unique_ptr<assembly::CatenarySystem> system;
  Vec x = nullptr;
  Mat shift = nullptr;
  std::unique_ptr<simulation::ModalDataBuilder> builder;
  ~KeptBuilder() {
    builder.reset();
    MatDestroy(&shift);
    VecDestroy(&x);
  }
};
int extension_scopes = 0;
bool no_later_extension = false;
std::unique_ptr<KeptBuilder> kept_builder;
ModalComputation last_computation;

std::unique_ptr<KeptBuilder> new_builder(const Context& ctx, const scene::RunScene& run,
                                         const simulation::StaticConfiguration& statics,
                                         const std::string& key, bool full_shapes) {
  auto b = std::make_unique<KeptBuilder>();
  b->key = key;
  b->system =
      std::make_unique<assembly::CatenarySystem>(ctx.comm, statics.mesh, 0, &statics.node_owner);
  b->x = b->system->create_vector();
  assembly::set_state_from_node_values(*b->system, statics.result.node_values, b->x);
  if (run.window) b->shift = window_shift_matrix(*b->system, 2.0 * run.window->span_length);
  b->builder = std::make_unique<simulation::ModalDataBuilder>(*b->system, b->x, full_shapes,
                                                              b->shift, ctx.cache_dir);
  return b;
}

// The mode count's note on parts computed apart (modal_basis_internal.hpp,
// component_groups) and, on several ranks, on the slices of the frequency
// interval computed at once (solvers/spectrum.hpp, configure_slicing).
std::string parts_text(int parts, MPI_Comm comm) {
  std::string text;
  if (parts > 1)
    text = "; " + std::to_string(parts) + " parts that share no element, each on its own";
  const int slices = solvers::slicing_parts(comm, "modal_");
  if (slices > 1) text += "; the interval in " + std::to_string(slices) + " slices at once";
  return text;
}

// Refuses a basis of 'modes' modes that would not fit in memory, now that
// their number is known (the inertia below the cut-off), before they are
// computed: an error of the scene's cut-off if it set one, else of its model.
void check_basis_memory(const Context& ctx, const scene::RunScene& run,
                        const KeptBuilder& computation, long modes, long computed,
                        double cutoff_hz) {
  const simulation::ModalDataBuilder& builder = *computation.builder;
  simulation::ModalMemoryNeed need;
  need.rows = builder.kept_rows();
  need.modes = modes;
  need.vectors = modes + builder.shapes();
  need.cutoff_hz = cutoff_hz;
  need.window = run.window.has_value();
  need.computed = computed;
  PetscInt dofs = 0;
  PCSIM_PETSC(VecGetSize(computation.x, &dofs));
  need.dofs = dofs;
  double resident = simulation::resident_memory_bytes();  // the largest rank's: one verdict
  MPI_Allreduce(MPI_IN_PLACE, &resident, 1, MPI_DOUBLE, MPI_MAX, ctx.comm);
  // The tests' -pcsim_debug_modal_memory_above_hz F: a cut-off above F as if
  // its basis did not fit (the accuracy pilot's raise that the machine
  // cannot hold: tests/simulation/test_modal_memory.sh).
  PetscReal above_hz = 0;
  PetscBool debug = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetReal(nullptr, nullptr, "-pcsim_debug_modal_memory_above_hz", &above_hz,
                                  &debug));
  const bool refused = debug && cutoff_hz > above_hz;
  simulation::check_modal_memory(
      need, resident, ctx.size, simulation::counted_node_processes(),
      refused ? 1.0 : simulation::machine_memory_bytes(), run.catenary.scene_file,
      run.catenary.modal_cutoff_given ? "catenary.max_frequency_hz" : "catenary.model");
}

// The last data's rows (and a window's shift products) given back to the
// kept builder from the cache file this process wrote them to (rank 0
// reads, every rank gets them); false if it wrote none or the file has been
// replaced since (another process's modes, whose signs may differ): the
// modes are then computed again.
bool give_back_rows(const Context& ctx, simulation::ModalDataBuilder& builder,
                    const std::string& key) {
  const auto count = static_cast<std::size_t>(builder.kept_rows() * builder.modes());
  const auto vectors = static_cast<std::size_t>(builder.modes() + builder.shapes());
  std::vector<double> rows, products;
  int ok = 0;
  if (ctx.rank == 0) {
    const std::string file = unchanged_data_file(key, builder.cutoff_hz());
    ok = !file.empty() &&
         output::read_mode_rows(file, key, count, rows, builder.has_shift() ? vectors * vectors : 0,
                                products);
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, ctx.comm);
  if (!ok) return false;
  broadcast(rows, ctx.comm);
  broadcast(products, ctx.comm);
  builder.give_back_rows(std::move(rows), std::move(products));
  return true;
}

catenary::ModalData compute_data(const Context& ctx, const scene::RunScene& run,
                                 const simulation::StaticConfiguration& statics,
                                 const std::string& key, double cutoff_hz, bool full_shapes) {
  const std::string kept_key = key + "@" + std::to_string(ctx.size);
  bool extends = kept_builder && kept_builder->key == kept_key && cutoff_hz > 0 &&
                 kept_builder->builder->cutoff_hz() > 0 &&
                 cutoff_hz >= kept_builder->builder->cutoff_hz();
  PetscLogDouble start;
  PetscTime(&start);
  const bool keep = extension_scopes > 0 && !no_later_extension && cutoff_hz > 0;
  double again_below_hz = 0;  // the lower cut-off whose modes are computed again
  if (extends) {
    forget_kept_bases(key);  // the lower cut-off's bases: superseded,
    malloc_trim(0);          // and their memory given back (modal_basis_internal.hpp)
    auto& kept = *kept_builder->builder;
    if (kept.rows_given_away() && !give_back_rows(ctx, kept, key)) {
      again_below_hz = kept.cutoff_hz();
      extends = false;
    }
  }
  const double from_hz = extends ? kept_builder->builder->cutoff_hz() : 0;
  const long kept_modes = extends ? kept_builder->builder->modes() : 0;
  auto builder =
      extends ? std::move(kept_builder) : new_builder(ctx, run, statics, kept_key, full_shapes);
  kept_builder.reset();  // (another key's: freed before this computation)
  // A line per chunk of modes: how many, the time so far and the ETA (the
  // chunks are about equal in modes and cost); before the first, whether
  // the basis fits in memory.
  const auto progress = [&](long done, long total, int parts) {
    if (done == 0) check_basis_memory(ctx, run, *builder, kept_modes + total, total, cutoff_hz);
    PetscLogDouble now;
    PetscTime(&now);
    const double elapsed = now - start;
    if (done == 0 && extends)
      print0(ctx, "  modes: %ld between %.1f and %.1f Hz to compute (the %ld below, kept%s)\n",
             total, from_hz, cutoff_hz, kept_modes, parts_text(parts, ctx.comm).c_str());
    else if (done == 0)
      print0(ctx, "  modes: %ld below %.1f Hz to compute (dropper shapes and factor: %.1f s%s)\n",
             total, cutoff_hz, elapsed, parts_text(parts, ctx.comm).c_str());
    else
      print0(ctx, "  modes: %ld of %ld (%.0f%%), %.1f s, ETA %.0f s\n", done, total,
             100.0 * done / std::max(total, 1L), elapsed,
             done < total ? elapsed * (total - done) / done : 0.0);
  };
  auto data = builder->builder->extend(cutoff_hz, progress, keep);
  last_computation.serial++;
  last_computation.computed = static_cast<long>(data.modes()) - kept_modes;
  last_computation.kept = kept_modes;
  last_computation.kept_below_hz = from_hz;
  last_computation.again_below_hz = again_below_hz;
  if (keep) kept_builder = std::move(builder);
  return data;
}

// The modal data from the cache (rank 0 reads, every rank gets them) or
// computed and stored (a cache that cannot be written costs a warning, not
// the run).
catenary::ModalData cached_data(const Context& ctx, const scene::RunScene& run,
                                const simulation::StaticConfiguration& statics,
                                const std::string& key, double cutoff_hz, bool full_shapes,
                                CatenarySetup& out) {
  catenary::ModalData data;
  int hit = 0;
  // Rank 0 of each process group: a miss takes the entry's lock, and looks
  // again once it has it (another group may have computed the data meanwhile).
  std::unique_ptr<output::CacheLock> lock;
  if (ctx.rank == 0) {
    hit = output::find_modal_data(ctx.cache_dir, key, cutoff_hz, data, out.cache_file) ? 1 : 0;
    if (!hit) {
      const std::string file = output::modal_cache_file(ctx.cache_dir, key, cutoff_hz);
      lock = std::make_unique<output::CacheLock>(file, [&] {
        std::printf("  waiting for another process computing the same modes (%s.lock)\n",
                    file.c_str());
        std::fflush(stdout);
      });
      if (lock->waited())
        hit = output::find_modal_data(ctx.cache_dir, key, cutoff_hz, data, out.cache_file) ? 1 : 0;
    }
  }
  MPI_Bcast(&hit, 1, MPI_INT, 0, ctx.comm);
  out.cache_hit = hit != 0;
  if (out.cache_hit) {
    broadcast(data, ctx.comm);
    return data;
  }
  out.cache_file = output::modal_cache_file(ctx.cache_dir, key, cutoff_hz);
  print0(ctx, "  computing the catenary's modes below %.1f Hz (cached in %s)\n", cutoff_hz,
         out.cache_file.c_str());
  data = compute_data(ctx, run, statics, key, cutoff_hz, full_shapes);
  out.basis_seconds = data.wall_time_s;
  if (ctx.rank == 0) {
    try {
      output::write_modal_data(out.cache_file, key, data);
      note_data_written(key, data.cutoff_hz, out.cache_file);  // (a raise reads it back)
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pcsim: warning: the modal data are not cached: %s\n", e.what());
    }
  }
  return data;
}

// The cache file a process of its own would read the data of 'key' from
// first, with its modification time and size (a file renamed over is
// another); "" if there is none. Rank 0 looks, every rank gets it.
std::string cache_file_served(const Context& ctx, const std::string& key, double cutoff_hz) {
  std::string served;
  if (ctx.rank == 0) {
    const auto files = output::modal_data_candidates(ctx.cache_dir, key, cutoff_hz);
    const std::string stamp = files.empty() ? "" : file_stamp(files.front());
    if (!stamp.empty()) served = files.front() + "@" + stamp;
  }
  return broadcast_text(ctx.comm, served);
}

// The assembled basis of 'kept_key' from the data file 'served' (its name,
// time and size), stored in the cache folder by an earlier process
// (output::read_basis; rank 0 reads, every rank gets it); null if there is
// none or no data file is served.
SharedBasis stored_basis(const Context& ctx, const std::string& kept_key, const std::string& served,
                         CatenarySetup& out) {
  if (served.empty()) return nullptr;
  const std::string key = kept_key + " from " + served;
  const std::string file = output::basis_cache_file(ctx.cache_dir, key);
  catenary::ReducedBasis basis;
  int hit = ctx.rank == 0 && output::read_basis(file, key, basis) ? 1 : 0;
  MPI_Bcast(&hit, 1, MPI_INT, 0, ctx.comm);
  if (!hit) return nullptr;
  broadcast(basis, ctx.comm);
  out.cache_hit = true;
  out.cache_file = served.substr(0, served.rfind('@'));
  out.basis_file = file;
  return std::make_shared<const catenary::ReducedBasis>(std::move(basis));
}

// Stores an assembled basis for later processes (rank 0; a cache that cannot
// be written costs a warning, not the run).
void store_basis(const Context& ctx, const std::string& kept_key, const std::string& served,
                 const catenary::ReducedBasis& basis, CatenarySetup& out) {
  if (served.empty() || ctx.rank != 0) return;
  const std::string key = kept_key + " from " + served;
  const std::string file = output::basis_cache_file(ctx.cache_dir, key);
  try {
    output::write_basis(file, key, basis);
    note_basis_written(served, file);
    out.basis_file = file;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pcsim: warning: the assembled basis is not cached: %s\n", e.what());
  }
}

// The run's basis: kept in this process's memory by an earlier run
// (setup_memory.hpp) if the cache folder still serves it from the same file
// (every rank must have it), else read as assembled by an earlier process
// from that file, else assembled from the cache's data or from data computed
// now, kept and stored.
SharedBasis modal_basis(const Context& ctx, const scene::RunScene& run,
                        const simulation::StaticConfiguration& statics,
                        const catenary::ModalSettings& settings, CatenarySetup& out) {
  const std::string key =
      output::modal_cache_key(file_content(run.catenary.design_path), run.catenary.mesh,
                              run.catenary.form_finding, settings.full_shapes);
  const std::string kept_key = kept_basis_key(key, settings);
  const std::string served = cache_file_served(ctx, key, settings.max_frequency_hz);
  auto kept = find_kept_basis(kept_key, served);
  int mine = kept ? 1 : 0, everywhere = 0;
  MPI_Allreduce(&mine, &everywhere, 1, MPI_INT, MPI_MIN, ctx.comm);
  if (everywhere) {
    out.cache_hit = out.basis_kept = true;
    out.cache_file = served.substr(0, served.rfind('@'));
    return kept;
  }
  if (auto stored = stored_basis(ctx, kept_key, served, out)) {
    keep_basis(kept_key, served, stored);
    return stored;
  }
  // Assembled once, on rank 0, and broadcast: every rank holds the same bits
  // (Eigen's sums depend on the data's alignment in memory), those stored.
  auto data =
      cached_data(ctx, run, statics, key, settings.max_frequency_hz, settings.full_shapes, out);
  catenary::ReducedBasis basis;
  std::string failure;  // an error on rank 0 fails every rank (none waits)
  if (ctx.rank == 0) try {
      basis = catenary::assemble_basis(std::move(data), statics.mesh, settings);
    } catch (const std::exception& e) {
      failure = e.what();
    }
  data = catenary::ModalData();  // freed before the basis is broadcast and kept,
  malloc_trim(0);                // and given back to the system
  failure = broadcast_text(ctx.comm, failure);
  if (!failure.empty()) throw SolverError("the modal basis: " + failure);
  broadcast(basis, ctx.comm);
  out.basis_assembled = true;
  auto shared = std::make_shared<const catenary::ReducedBasis>(std::move(basis));
  const std::string now_served = cache_file_served(ctx, key, settings.max_frequency_hz);
  keep_basis(kept_key, now_served, shared);
  store_basis(ctx, kept_key, now_served, *shared, out);
  return shared;
}

}  // namespace

ModalComputation last_modal_computation() {
  return last_computation;
}

ModalExtensionScope::ModalExtensionScope() {
  ++extension_scopes;
}

ModalExtensionScope::~ModalExtensionScope() {
  if (--extension_scopes > 0) return;
  kept_builder.reset();
  no_later_extension = false;
}

void ModalExtensionScope::last_computation_next() {
  no_later_extension = true;
}

nlohmann::json CatenarySetup::facts() const {
  nlohmann::json j;
  if (!modal) return j;
  j["cutoff_hz"] = cutoff_hz;
  j["basis_size"] = basis_size;
  j["eigenmodes"] = eigenmodes;
  j["dropped_modes"] = dropped_modes;
  j["column_blocks"] = column_blocks;
  j["cache_hit"] = cache_hit;
  j["cache_file"] = cache_file;
  j["basis_file"] = basis_file;
  j["basis_assembled"] = basis_assembled;
  j["basis_kept_in_memory"] = basis_kept;
  j["basis_compute_s"] = basis_seconds;
  j["basis_setup_s"] = setup_seconds;
  return j;
}

CatenarySetup make_catenary_model(const Context& ctx, const scene::RunScene& run,
                                  const simulation::StaticConfiguration& statics,
                                  PetscInt extra_dofs) {
  CatenarySetup out;
  if (run.catenary.fidelity != catenary::CatenaryFidelity::modal) {
    out.model = std::make_unique<assembly::FECatenary>(ctx.comm, statics.mesh,
                                                       statics.result.node_values, extra_dofs,
                                                       run.catenary.fidelity, &statics.node_owner);
    return out;
  }
  constexpr PetscInt kMaxAllModes = 4000;
  catenary::ModalSettings settings = run.catenary.modal;
  settings.full_shapes = run.snapshot_every > 0;
  if (settings.max_frequency_hz <= 0 && statics.catenary_dofs > kMaxAllModes)
    throw InputError(run.catenary.scene_file, "catenary.max_frequency_hz",
                     "'all' modes is for structures up to " + std::to_string(kMaxAllModes) +
                         " unknowns (this one has " + std::to_string(statics.catenary_dofs) +
                         "): give a cut-off frequency");
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  auto basis = modal_basis(ctx, run, statics, settings, out);
  PetscTime(&t1);
  out.modal = true;
  out.setup_seconds = t1 - t0;
  out.basis_size = static_cast<int>(basis->size());
  out.eigenmodes = basis->eigenmodes;
  out.dropped_modes = basis->dropped_modes;
  out.column_blocks = std::max<int>(1, static_cast<int>(basis->column_blocks.size()) - 1);
  out.cutoff_hz = settings.max_frequency_hz;
  out.model = std::make_unique<assembly::ModalCatenary>(
      ctx.comm, statics.mesh, statics.result.node_values, std::move(basis), settings, extra_dofs);
  return out;
}

std::unique_ptr<assembly::CoupledSystem> make_coupled_system(
    const Context& ctx, scene::RunScene& run, const simulation::StaticConfiguration& statics,
    CatenarySetup& setup) {
  std::vector<assembly::PantographSlot> slots;
  PetscInt panto_dofs = 0;
  for (std::size_t p = 0; p < run.pantographs.size(); ++p) {
    assembly::PantographSlot slot;
    slot.run = run.pantographs[p];
    slot.model = std::move(run.models[p]);
    panto_dofs += slot.dof_count();
    slots.push_back(std::move(slot));
  }
  setup = make_catenary_model(ctx, run, statics, panto_dofs);
  return std::make_unique<assembly::CoupledSystem>(std::move(setup.model), std::move(slots),
                                                   run.effects, run.contact_stiffness);
}

}  // namespace pcsim::simulation
