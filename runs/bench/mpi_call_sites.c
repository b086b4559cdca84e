/* Counts the MPI collectives a process makes, by call stack: loaded with
 * LD_PRELOAD, it wraps MPI_Allreduce, MPI_Bcast, MPI_Reduce, MPI_Allgather
 * and MPI_Barrier (the PMPI profiling interface) and, at MPI_Finalize, rank 0
 * writes each distinct stack with its count to $MPI_CALL_SITES_OUT as lines
 * "site KIND COUNT" followed by "frame MODULE OFFSET SYMBOL" (the offset into
 * the module, for addr2line; SYMBOL "-" where the module exports none). Used by
 * runs/bench_reductions.sh. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <execinfo.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { kMaxSites = 4096, kDepth = 10 };

typedef struct {
  const char* kind;
  void* frames[kDepth];
  int depth;
  long count;
} Site;

static Site sites[kMaxSites];
static int site_count = 0;

static void count_call(const char* kind) {
  void* frames[kDepth + 1];
  int depth = backtrace(frames, kDepth + 1) - 1; /* without this function */
  for (int i = 0; i < site_count; ++i)
    if (sites[i].kind == kind && sites[i].depth == depth &&
        !memcmp(sites[i].frames, frames + 1, sizeof(void*) * depth)) {
      ++sites[i].count;
      return;
    }
  if (site_count == kMaxSites) return;
  Site* s = &sites[site_count++];
  s->kind = kind;
  s->depth = depth;
  s->count = 1;
  memcpy(s->frames, frames + 1, sizeof(void*) * depth);
}

int MPI_Allreduce(const void* in, void* out, int n, MPI_Datatype type, MPI_Op op, MPI_Comm comm) {
  count_call("Allreduce");
  return PMPI_Allreduce(in, out, n, type, op, comm);
}

int MPI_Bcast(void* buffer, int n, MPI_Datatype type, int root, MPI_Comm comm) {
  count_call("Bcast");
  return PMPI_Bcast(buffer, n, type, root, comm);
}

int MPI_Reduce(const void* in, void* out, int n, MPI_Datatype type, MPI_Op op, int root,
               MPI_Comm comm) {
  count_call("Reduce");
  return PMPI_Reduce(in, out, n, type, op, root, comm);
}

int MPI_Allgather(const void* in, int n_in, MPI_Datatype type_in, void* out, int n_out,
                  MPI_Datatype type_out, MPI_Comm comm) {
  count_call("Allgather");
  return PMPI_Allgather(in, n_in, type_in, out, n_out, type_out, comm);
}

int MPI_Barrier(MPI_Comm comm) {
  count_call("Barrier");
  return PMPI_Barrier(comm);
}

int MPI_Finalize(void) {
  int rank = 0;
  const char* path = getenv("MPI_CALL_SITES_OUT");
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  FILE* out = rank == 0 && path ? fopen(path, "w") : NULL;
  for (int i = 0; out && i < site_count; ++i) {
    fprintf(out, "site %s %ld\n", sites[i].kind, sites[i].count);
    for (int j = 0; j < sites[i].depth; ++j) {
      Dl_info info;
      if (!dladdr(sites[i].frames[j], &info) || !info.dli_fname) continue;
      /* return address - 1: the call instruction itself */
      fprintf(out, "frame %s %#lx %s\n", info.dli_fname,
              (unsigned long)((char*)sites[i].frames[j] - (char*)info.dli_fbase - 1),
              info.dli_sname ? info.dli_sname : "-");
    }
  }
  if (out) fclose(out);
  return PMPI_Finalize();
}
