#include "pcsim/output/modal_cache.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <openssl/evp.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <type_traits>

#include "pcsim/core/error.hpp"
#include "pcsim/output/h5_file.hpp"

#ifndef PCSIM_VERSION
#define PCSIM_VERSION "unknown"
#endif

namespace pcsim::output {

namespace {

constexpr int kCacheFormat =
    2;  // bump when the basis' content or layout changes (2: wire mass per unstressed length)

// Bytes of the values the key covers.
class KeyBuffer {
 public:
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void add(const std::string& s) {
    add(s.size());
    bytes_ += s;
  }
  template <typename T>
  void add_all(const std::vector<T>& values) {
    add(values.size());
    for (const auto& v : values) add(v);
  }
  std::string sha256_hex() const {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (EVP_Digest(bytes_.data(), bytes_.size(), digest, &length, EVP_sha256(), nullptr) != 1)
      throw SolverError("modal cache: SHA-256 failed");
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
      out += hex[digest[i] >> 4];
      out += hex[digest[i] & 15];
    }
    return out;
  }

 private:
  std::string bytes_;
};

void add_mesh(KeyBuffer& key, const catenary::CatenaryMesh& mesh) {
  key.add(mesh.nodes.size());
  for (const auto& n : mesh.nodes) {
    for (int c = 0; c < 3; ++c) key.add(n.position[c]), key.add(n.slope[c]);
    for (bool f : n.fixed) key.add(f);
  }
  for (const auto& w : mesh.wires) {
    key.add(w.mass_per_length), key.add(w.EA), key.add(w.EI), key.add(w.tension);
    key.add_all(w.nodes);
  }
  for (const auto& e : mesh.cables) {
    key.add(e.nodes), key.add(e.wire), key.add(e.ref_length), key.add(e.unstressed_length);
    key.add(e.section_factor);
  }
  for (const auto& b : mesh.bars) {
    key.add(b.nodes), key.add(b.kind), key.add(b.stiffness), key.add(b.mass);
    key.add(b.unstressed_length), key.add(b.slack);
  }
  for (const auto& p : mesh.point_masses) key.add(p.node), key.add(p.mass);
  const auto& c = mesh.conditions;
  if (c.any()) {  // (a line without conditions keeps the keys it had before they existed)
    key.add(std::string("conditions")), key.add(c.ice.contact), key.add(c.ice.messenger);
    key.add(c.ice.stitch), key.add(c.temperature_change_k);
    for (const auto& w : mesh.wires) key.add(w.thermal_expansion);
    if (c.wind.any()) {  // (an ice or temperature key stays as it was)
      key.add(std::string("wind")), key.add(c.wind.speed), key.add(c.wind.direction_deg);
      key.add(c.wind.air_density);
      for (const auto& w : mesh.wires)
        key.add(catenary::wire_diameter(w)), key.add(catenary::wire_drag_coefficient(w));
      key.add(std::string("modes' damping, lateral rows"));  // wind_damping, y rows
      key.add(std::string("bars' drag"));                    // catenary::bar_drag
      for (const auto& b : mesh.bars)
        key.add(catenary::bar_diameter(b)), key.add(catenary::bar_drag_coefficient(b));
      key.add(std::string("bars' damping and turbulence"));  // assembly::wind_bars
      if (c.wind.turbulence.on)  // the turbulence rows (catenary::turbulence_row_keys)
        key.add(std::string("turbulence rows")), key.add(c.wind.turbulence.grid_spacing);
    }
  }
  for (const auto& s : mesh.springs) {
    key.add(s.node), key.add(s.dof), key.add(s.stiffness);
    for (int c = 0; c < 3; ++c) key.add(s.direction[c]);
  }
  for (const auto& f : mesh.node_forces) {
    key.add(f.node);
    for (int c = 0; c < 3; ++c) key.add(f.force[c]);
  }
  for (const auto& d : mesh.tensioning_devices) {
    key.add(d.node), key.add(d.wire), key.add(d.kind), key.add(d.mass), key.add(d.stiffness);
    for (int c = 0; c < 3; ++c) key.add(d.direction[c]);
  }
  for (int c = 0; c < 3; ++c) key.add(mesh.gravity[c]);
  key.add_all(mesh.support_nodes);
  key.add(mesh.contact_wire);
  key.add_all(mesh.contact_wire_list());
}

// A dataset of doubles, floats or longs, whatever its size (HDF5 converts a
// stored type to T: a shift stored in double by an earlier pcsim is read
// rounded to float); false if absent.
template <typename T>
bool read_dataset(hid_t file, const char* path, std::vector<T>& out) {
  if (H5Lexists(file, path, H5P_DEFAULT) <= 0) return false;
  const hid_t set = H5Dopen2(file, path, H5P_DEFAULT);
  if (set < 0) return false;
  const hid_t space = H5Dget_space(set);
  out.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  H5Sclose(space);
  const hid_t type = std::is_same_v<T, long>    ? H5T_NATIVE_LONG
                     : std::is_same_v<T, float> ? H5T_NATIVE_FLOAT
                                                : H5T_NATIVE_DOUBLE;
  const bool ok = out.empty() || H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0;
  H5Dclose(set);
  return ok;
}

bool read_attribute(hid_t file, const char* name, double& value) {
  if (H5Aexists(file, name) <= 0) return false;
  const hid_t attr = H5Aopen(file, name, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Aread(attr, H5T_NATIVE_DOUBLE, &value) >= 0;
  if (attr >= 0) H5Aclose(attr);
  return ok;
}

// The key attribute: a variable-length string (H5File::attribute), or a
// fixed-length one (files of earlier versions).
bool read_key(hid_t file, std::string& key) {
  if (H5Aexists(file, "key") <= 0) return false;
  const hid_t attr = H5Aopen(file, "key", H5P_DEFAULT);
  const hid_t type = H5Aget_type(attr);
  bool ok = false;
  if (H5Tis_variable_str(type) > 0) {
    char* text = nullptr;
    const hid_t memory = H5Tcopy(H5T_C_S1);
    H5Tset_size(memory, H5T_VARIABLE);
    H5Tset_cset(memory, H5Tget_cset(type));
    ok = H5Aread(attr, memory, &text) >= 0 && text;
    if (ok) key = text;
    if (text) H5free_memory(text);
    H5Tclose(memory);
  } else {
    std::string value(H5Tget_size(type), '\0');
    ok = H5Aread(attr, type, value.data()) >= 0;
    key = value.c_str();
  }
  H5Tclose(type);
  H5Aclose(attr);
  return ok;
}

// Writes a row-major matrix (rows x cols) or nothing when empty.
template <typename T>
void write_matrix(H5File& h5, const char* path, const std::vector<T>& data, std::size_t rows) {
  if (rows == 0 || data.empty()) return;
  h5.write(path, data, rows, data.size() / rows);
}

// Runs read(h5) on 'file' opened read-only with HDF5's error printing off
// (a broken file is a miss, not noise); false if it is missing, cannot be
// opened or read returns false.
template <typename Read>
bool read_quietly(const std::string& file, Read read) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return false;  // (a folder it cannot look in too)
  H5E_auto2_t handler;
  void* client;
  H5Eget_auto2(H5E_DEFAULT, &handler, &client);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  bool ok = false;
  if (h5 >= 0) {
    // A damaged file is a miss too: only rank 0 reads, and an exception here
    // would leave the other ranks waiting for its broadcast.
    try {
      ok = read(h5);
    } catch (const std::exception&) {
      ok = false;
    }
    H5Fclose(h5);
  }
  H5Eset_auto2(H5E_DEFAULT, handler, client);
  return ok;
}

// Creates the folder if needed (InputError on key --cache if it cannot), has
// write(h5) fill file.tmp-<pid> and renames it to 'file' (a reader never sees
// half a file).
template <typename Write>
void write_atomically(const std::string& file, Write write) {
  const std::filesystem::path path(file);
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (ec)
    throw InputError(
        "command line", "--cache",
        "cannot create the cache folder '" + path.parent_path().string() + "': " + ec.message());
  const std::string tmp = file + ".tmp-" + std::to_string(getpid());
  try {
    H5File h5(tmp);
    write(h5);
    h5.close();
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), file.c_str()) != 0) {
    const int saved = errno;
    std::remove(tmp.c_str());
    throw OutputError(file, write_failure_reason(file, saved));
  }
}

bool read_basis_file(hid_t file, const std::string& key, catenary::ReducedBasis& b) {
  std::string stored;
  double eigenmodes = 0, dropped = 0;
  if (!read_key(file, stored) || stored != key) return false;
  if (!read_attribute(file, "cutoff_hz", b.cutoff_hz) ||
      !read_attribute(file, "eigenmodes", eigenmodes) ||
      !read_attribute(file, "dropped_modes", dropped) || !read_dataset(file, "/omega2", b.omega2) ||
      !read_dataset(file, "/row_keys", b.row_keys) || !read_dataset(file, "/rows", b.rows) ||
      !read_dataset(file, "/column_blocks", b.column_blocks))  // none: a file of an older pcsim
    return false;
  for (auto [path, v] : {std::pair{"/contact_flexibility", &b.contact_flexibility},
                         std::pair{"/wind_damping", &b.wind_damping}})
    if (H5Lexists(file, path, H5P_DEFAULT) > 0 && !read_dataset(file, path, *v)) return false;
  if (H5Lexists(file, "/shift", H5P_DEFAULT) > 0 && !read_dataset(file, "/shift", b.shift))
    return false;
  b.eigenmodes = static_cast<int>(eigenmodes);
  b.dropped_modes = static_cast<int>(dropped);
  const std::size_t n = b.size();
  const bool blocks = b.column_blocks.size() >= 2 && b.column_blocks.front() == 0 &&
                      b.column_blocks.back() == static_cast<long>(n) &&
                      std::is_sorted(b.column_blocks.begin(), b.column_blocks.end());
  return blocks && b.rows.size() == b.row_keys.size() * n &&
         (b.shift.empty() || b.shift.size() == n * n) &&
         (b.wind_damping.empty() || b.wind_damping.size() == n);
}

// Room in d.mode_rows for the basis's rows, which assemble_basis forms in
// place (the modes' and the droppers' shapes' columns: catenary/reduced_basis.hpp),
// as the modal data builder leaves it (without it: a copy more, no error).
void reserve_basis_room(hid_t file, catenary::ModalData& d) {
  std::size_t shape_entries = 0;
  if (H5Lexists(file, "/shape_rows", H5P_DEFAULT) > 0) {
    const hid_t set = H5Dopen2(file, "/shape_rows", H5P_DEFAULT);
    if (set >= 0) {
      const hid_t space = H5Dget_space(set);
      shape_entries = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
      H5Sclose(space);
      H5Dclose(set);
    }
  }
  d.mode_rows.reserve(d.row_keys.size() * d.omega2.size() + shape_entries);
}

bool read_file(hid_t file, const std::string& key, catenary::ModalData& d) {
  std::string stored;
  if (!read_key(file, stored) || stored != key) return false;
  bool ok = read_attribute(file, "cutoff_hz", d.cutoff_hz) &&
            read_attribute(file, "max_relative_residual", d.max_relative_residual) &&
            read_dataset(file, "/omega2", d.omega2) && read_dataset(file, "/row_keys", d.row_keys);
  if (ok) reserve_basis_room(file, d);
  ok = ok && read_dataset(file, "/mode_rows", d.mode_rows);
  // The shapes and the compliance are absent for complete bases.
  for (auto [path, v] :
       {std::pair{"/shape_rows", &d.shape_rows}, std::pair{"/mode_shape_mass", &d.mode_shape_mass},
        std::pair{"/shape_mass", &d.shape_mass},
        std::pair{"/shape_flexibility", &d.shape_flexibility},
        std::pair{"/contact_compliance", &d.contact_compliance},
        std::pair{"/shift_products", &d.shift_products},
        std::pair{"/wind_damping", &d.wind_damping}})
    if (H5Lexists(file, path, H5P_DEFAULT) > 0 && !read_dataset(file, path, *v)) return false;
  d.wall_time_s = 0;
  const std::size_t nd = d.shapes(), vectors = d.modes() + nd;
  return ok && (d.shift_products.empty() || d.shift_products.size() == vectors * vectors) &&
         (d.wind_damping.empty() || d.wind_damping.size() == d.modes()) &&
         d.mode_rows.size() == d.row_keys.size() * d.modes() &&
         d.mode_shape_mass.size() == d.modes() * nd && d.shape_mass.size() == nd * nd &&
         d.shape_flexibility.size() == nd * nd;
}

}  // namespace

bool read_mode_rows(const std::string& file, const std::string& key, std::size_t count,
                    std::vector<double>& mode_rows, std::size_t products,
                    std::vector<double>& shift_products) {
  return read_quietly(file, [&](hid_t h5) {
    std::string stored;
    std::vector<double> rows, g;
    if (!read_key(h5, stored) || stored != key || !read_dataset(h5, "/mode_rows", rows) ||
        rows.size() != count)
      return false;
    if (products > 0 && (!read_dataset(h5, "/shift_products", g) || g.size() != products))
      return false;
    mode_rows = std::move(rows);
    shift_products = std::move(g);
    return true;
  });
}

std::string modal_cache_key(const std::string& design_content, const catenary::CatenaryMesh& mesh,
                            bool form_finding, bool full_shapes, bool window_shift) {
  KeyBuffer key;
  key.add(std::string("pcsim " PCSIM_VERSION " modal data"));
  key.add(kCacheFormat);
  key.add(design_content);
  add_mesh(key, mesh);
  key.add(form_finding);
  key.add(full_shapes);
  if (window_shift) key.add(std::string("window shift: released ends, shift products"));
  return key.sha256_hex();
}

std::string modal_cache_file(const std::string& dir, const std::string& key, double cutoff_hz) {
  char cutoff[32];
  if (cutoff_hz > 0)
    std::snprintf(cutoff, sizeof(cutoff), "%.6gHz", cutoff_hz);
  else
    std::snprintf(cutoff, sizeof(cutoff), "all");
  return dir + "/modal-" + key.substr(0, 24) + "-" + cutoff + ".h5";
}

std::vector<std::string> modal_data_candidates(const std::string& dir, const std::string& key,
                                               double max_frequency_hz) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return {};
  const std::string prefix = "modal-" + key.substr(0, 24) + "-";
  std::vector<std::pair<double, std::string>> candidates;  // (cut-off, file)
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || name.size() < 3 || name.substr(name.size() - 3) != ".h5")
      continue;
    const std::string tail = name.substr(prefix.size());
    const double cutoff = tail.rfind("all", 0) == 0 ? 0.0 : std::atof(tail.c_str());
    // The name gives the cut-off to 6 digits; the file's own value decides
    // below. Every mode ('all') serves only a request for every mode: it has
    // no dropper shapes and no contact compliance (its basis is complete), so
    // a cut-off's basis restricted from it would lack them.
    const bool serves =
        max_frequency_hz <= 0 ? cutoff <= 0 : cutoff > 0 && cutoff >= max_frequency_hz * (1 - 1e-5);
    if (serves) candidates.emplace_back(cutoff <= 0 ? 1e300 : cutoff, entry.path().string());
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<std::string> files;
  for (const auto& c : candidates) files.push_back(c.second);
  return files;
}

bool find_modal_data(const std::string& dir, const std::string& key, double max_frequency_hz,
                     catenary::ModalData& data, std::string& file) {
  const auto covers = [&](double cutoff) {
    return max_frequency_hz <= 0 ? cutoff <= 0
                                 : cutoff > 0 && cutoff >= max_frequency_hz * (1 - 1e-12);
  };
  for (const auto& path : modal_data_candidates(dir, key, max_frequency_hz))
    if (read_modal_data(path, key, data) && covers(data.cutoff_hz)) {
      file = path;
      return true;
    }
  return false;
}

bool read_modal_data(const std::string& file, const std::string& key, catenary::ModalData& data) {
  catenary::ModalData read;
  const bool ok = read_quietly(file, [&](hid_t h5) { return read_file(h5, key, read); });
  if (ok) data = std::move(read);
  return ok;
}

void write_modal_data(const std::string& file, const std::string& key,
                      const catenary::ModalData& d) {
  write_atomically(file, [&](H5File& h5) {
    h5.write("/omega2", d.omega2);
    h5.write_int("/row_keys", std::vector<long>(d.row_keys.begin(), d.row_keys.end()));
    write_matrix(h5, "/mode_rows", d.mode_rows, d.row_keys.size());
    write_matrix(h5, "/shape_rows", d.shape_rows, d.row_keys.size());
    write_matrix(h5, "/mode_shape_mass", d.mode_shape_mass, d.modes());
    write_matrix(h5, "/shape_mass", d.shape_mass, d.shapes());
    write_matrix(h5, "/shape_flexibility", d.shape_flexibility, d.shapes());
    if (!d.contact_compliance.empty()) h5.write("/contact_compliance", d.contact_compliance);
    write_matrix(h5, "/shift_products", d.shift_products, d.modes() + d.shapes());
    if (!d.wind_damping.empty()) h5.write("/wind_damping", d.wind_damping);
    h5.attribute("/", "key", key);
    h5.attribute("/", "cutoff_hz", d.cutoff_hz);
    h5.attribute("/", "max_relative_residual", d.max_relative_residual);
    h5.attribute("/", "computed_in_s", d.wall_time_s);
  });
}

std::string basis_cache_file(const std::string& dir, const std::string& key) {
  KeyBuffer hashed;
  hashed.add(std::string("pcsim " PCSIM_VERSION " assembled basis"));
  hashed.add(kCacheFormat);
  hashed.add(key);
  return dir + "/basis-" + hashed.sha256_hex().substr(0, 24) + ".h5";
}

bool read_basis(const std::string& file, const std::string& key, catenary::ReducedBasis& basis) {
  catenary::ReducedBasis read;
  const bool ok = read_quietly(file, [&](hid_t h5) { return read_basis_file(h5, key, read); });
  if (ok) basis = std::move(read);
  return ok;
}

void write_basis(const std::string& file, const std::string& key, const catenary::ReducedBasis& b) {
  write_atomically(file, [&](H5File& h5) {
    h5.write("/omega2", b.omega2);
    h5.write_int("/row_keys", b.row_keys);
    h5.write_int("/column_blocks", b.column_blocks);
    write_matrix(h5, "/rows", b.rows, b.row_keys.size());
    if (!b.contact_flexibility.empty()) h5.write("/contact_flexibility", b.contact_flexibility);
    write_matrix(h5, "/shift", b.shift, b.size());
    if (!b.wind_damping.empty()) h5.write("/wind_damping", b.wind_damping);
    h5.attribute("/", "key", key);
    h5.attribute("/", "cutoff_hz", b.cutoff_hz);
    h5.attribute("/", "eigenmodes", static_cast<double>(b.eigenmodes));
    h5.attribute("/", "dropped_modes", static_cast<double>(b.dropped_modes));
  });
}

CacheLock::CacheLock(const std::string& file, const std::function<void()>& on_wait) {
  std::error_code ignored;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ignored);
  fd_ = ::open((file + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) return;
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  if (errno != EWOULDBLOCK) {
    ::close(fd_);
    fd_ = -1;
    return;
  }
  waited_ = true;
  if (on_wait) on_wait();
  while (::flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) {
      ::close(fd_);
      fd_ = -1;
      return;
    }
}

CacheLock::~CacheLock() {
  if (fd_ < 0) return;
  ::flock(fd_, LOCK_UN);
  ::close(fd_);
}

}  // namespace pcsim::output
