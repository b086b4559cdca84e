// The job's processes on this node (run_session.hpp): for the record thread's
// and the pilot's spare core, and for the memory check (app/inputs.cpp).
#include <unistd.h>

#include "pcsim/simulation/run_session.hpp"
#include "pcsim/simulation/step_cpu.hpp"

namespace pcsim::simulation {

namespace {

// This node's processes of the job (count_node_processes; 0: not counted).
int node_processes = 0;

// The ranks of comm on this node (collective on comm).
int ranks_on_node(MPI_Comm comm) {
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks = 1;
  MPI_Comm_size(node, &ranks);
  MPI_Comm_free(&node);
  return ranks;
}

}  // namespace

bool core_to_spare_here(MPI_Comm comm) {
  const int cpus = process_cpu_count();  // (not a pinned stepping thread's one CPU)
  const int processes = node_processes > 0 ? node_processes : ranks_on_node(comm);
  return cpus > 1 && sysconf(_SC_NPROCESSORS_ONLN) > processes;
}

void count_node_processes(MPI_Comm world) {
  node_processes = ranks_on_node(world);
}

int counted_node_processes() {
  return node_processes;
}

}  // namespace pcsim::simulation
