// The cache of modal data (catenary/reduced_basis.hpp): the modes and the
// droppers' static shapes cost seconds to minutes of SLEPc and are the same
// for every run of one design and mesh, so `pcsim run` keeps them in a cache
// folder (--cache DIR, default out/.pcsim-cache) as
//   modal-<key>-<cut-off>.h5,
// <key> the SHA-256 of the pcsim version and cache format, the design file's
// content, the mesh (nodes, elements, properties), the form-finding flag and
// whether every node's rows are kept (field snapshots) and, for a moving
// window, that its ends are released and the shift's products kept. Data computed at a
// cut-off serve any lower cut-off (the basis is assembled from them), so a
// run looks for the file of its key with the smallest cut-off at least its
// own. A file is written to a temporary name and renamed over (atomic: a
// reader never sees half a file); a file that cannot be read or whose key
// differs is a miss.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/reduced_basis.hpp"

namespace pcsim::output {

// Default cache folder (relative to the working directory).
constexpr const char* kDefaultCacheDir = "out/.pcsim-cache";

std::string modal_cache_key(const std::string& design_content, const catenary::CatenaryMesh& mesh,
                            bool form_finding, bool full_shapes, bool window_shift = false);
// The file for data of this key computed at cutoff_hz (<= 0: every mode).
std::string modal_cache_file(const std::string& dir, const std::string& key, double cutoff_hz);

// The files of 'key' whose names say they serve max_frequency_hz, in the
// order find_modal_data tries them (the smallest cut-off first); a listing
// of the folder, nothing read.
std::vector<std::string> modal_data_candidates(const std::string& dir, const std::string& key,
                                               double max_frequency_hz);
// The cached data of 'key' that serve max_frequency_hz (the smallest cut-off
// at least that; every mode's data (<= 0) serve only every mode: they have
// no dropper shapes or contact compliance), and their file; false if there
// are none (or none readable).
bool find_modal_data(const std::string& dir, const std::string& key, double max_frequency_hz,
                     catenary::ModalData& data, std::string& file);
// False (data untouched) if the file is missing, unreadable or for another key.
bool read_modal_data(const std::string& file, const std::string& key, catenary::ModalData& data);
// The modes' kept rows (mode_rows, 'count' of them) and, if 'products' > 0,
// that many shift products alone; false (both untouched) as
// read_modal_data, or if the counts differ.
bool read_mode_rows(const std::string& file, const std::string& key, std::size_t count,
                    std::vector<double>& mode_rows, std::size_t products,
                    std::vector<double>& shift_products);
// Creates the folder if needed (InputError on key --cache if it cannot);
// writes file.tmp-<pid> and renames it to file.
void write_modal_data(const std::string& file, const std::string& key,
                      const catenary::ModalData& data);

// The bases assembled from a data file (catenary::assemble_basis: the kept
// modes, the droppers' Ritz vectors, a moving window's shift in the basis;
// seconds for a window of 4400 vectors) are kept in the same folder as
// basis-<hash>.h5, the hash of 'key' (the data's key, the settings the
// assembly reads, the data file's name, time and size), so that a later
// process reads the basis instead of assembling it again. The same atomic
// write as the data; a file that cannot be read or whose key differs is a
// miss.
std::string basis_cache_file(const std::string& dir, const std::string& key);
bool read_basis(const std::string& file, const std::string& key, catenary::ReducedBasis& basis);
void write_basis(const std::string& file, const std::string& key,
                 const catenary::ReducedBasis& basis);

// An exclusive lock on the cache entry 'file' between processes (flock on
// file.lock, created in the folder and left there; released by the
// destructor or when the process ends, even by SIGKILL): the first process
// that misses computes the data, the others wait and then read its file
// instead of computing the same modes. on_wait is called once, before
// waiting, when another process holds the lock. A folder or lock file that
// cannot be made gives no lock (nothing waits; the data are computed).
class CacheLock {
 public:
  CacheLock(const std::string& file, const std::function<void()>& on_wait);
  ~CacheLock();
  CacheLock(const CacheLock&) = delete;
  CacheLock& operator=(const CacheLock&) = delete;
  bool waited() const { return waited_; }

 private:
  int fd_ = -1;
  bool waited_ = false;
};

}  // namespace pcsim::output
