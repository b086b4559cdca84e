// The BLAS behind libblas.so.3 and BLIS's kernels (core/blas_kernels.hpp).
#include "pcsim/core/blas_kernels.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace pcsim {

namespace {

BlasKernels& found() {
  static BlasKernels k;
  return k;
}

// The real path of the library that defines dgemm_ in this process.
std::string loaded_blas() {
  Dl_info info{};
  void* symbol = dlsym(RTLD_DEFAULT, "dgemm_");
  if (!symbol || !dladdr(symbol, &info) || !info.dli_fname) return "";
  std::error_code ec;
  const auto real = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::string(info.dli_fname) : real.string();
}

// The kernels BLIS would take for a processor it does not know: its AVX-512
// or AVX2 ones where the processor has their instructions, else none.
const char* fitting_kernels() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl"))
    return "skx";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "haswell";
  return nullptr;
}

// BLIS's answers, from its library beside libblas.so.3 (a copy of its own:
// asking it sets nothing in the one that runs pcsim's BLAS calls).
void ask_blis(const std::filesystem::path& dir, bool blis_started, BlasKernels& k) {
  void* blis = dlopen((dir / "libblis.so.4").c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!blis) return;
  using QueryId = int (*)();
  using ArchString = const char* (*)(int);
  using Version = const char* (*)();
  const auto query = reinterpret_cast<QueryId>(dlsym(blis, "bli_arch_query_id"));
  const auto name = reinterpret_cast<ArchString>(dlsym(blis, "bli_arch_string"));
  const auto version = reinterpret_cast<Version>(dlsym(blis, "bli_info_get_version_str"));
  if (query && name && version) {
    k.blis = version();
    const int id = query();
    k.detected = k.kernels = name(id);
    // The generic kernels are the last configuration: the others come before.
    const char* wanted = k.detected == "generic" ? fitting_kernels() : nullptr;
    for (int i = 0; wanted && i < id; ++i)
      if (std::strcmp(name(i), wanted) == 0) {
        if (blis_started) {
          k.too_late = std::to_string(i) + " (its " + wanted + " kernels)";
        } else {
          setenv("BLIS_ARCH_TYPE", std::to_string(i).c_str(), 1);
          k.kernels = wanted;
          k.chosen = true;
        }
        break;
      }
  }
  dlclose(blis);
}

}  // namespace

std::string BlasKernels::text() const {
  if (library.empty()) return "unknown";
  if (!is_blis) return library;
  std::string t = "BLIS" + (blis.empty() ? "" : " " + blis) + " (" + library + ")";
  if (!kernels.empty()) t += ", kernels " + kernels;
  if (chosen) t += " (chosen by pcsim: BLIS's detection takes " + detected + " here)";
  if (!too_late.empty())
    t += " (BLIS started before pcsim could choose; BLIS_ARCH_TYPE=" + too_late +
         " in the environment before the process starts)";
  return t;
}

bool BlasKernels::optimised() const {
  if (is_blis) return kernels != "generic" && !kernels.empty();
  for (const char* name : {"openblas", "mkl"})
    if (library.find(name) != std::string::npos) return true;
  return false;
}

void select_blas_kernels(bool blis_started) {
  static bool done = false;
  if (done) return;
  done = true;
  BlasKernels& k = found();
  k.library = loaded_blas();
  if (k.library.empty()) return;
  const std::filesystem::path dir = std::filesystem::path(k.library).parent_path();
  k.is_blis = dir.filename().string().find("blis") != std::string::npos;
  if (!k.is_blis) return;
  if (const char* user = std::getenv("BLIS_ARCH_TYPE")) {
    k.kernels = std::string("BLIS_ARCH_TYPE=") + user;
    return;
  }
  ask_blis(dir, blis_started, k);
}

const BlasKernels& blas_kernels() {
  return found();
}

}  // namespace pcsim
