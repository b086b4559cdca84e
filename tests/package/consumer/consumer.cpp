// Uses the installed pcsim libraries: reads a catenary design, builds its mesh and
// prints what it found, with the library's version.
//   consumer DESIGN.yaml
#include <cstdio>

#include "pcsim/core/error.hpp"
#include "pcsim/core/version.hpp"
#include "pcsim/scene/design_reader.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer DESIGN.yaml\n");
    return 2;
  }
  try {
    const auto mesh = pcsim::scene::load_catenary_design(argv[1]);
    std::printf("pcsim %s: design %s, %zu nodes, %zu spans\n", pcsim::version(), mesh.name.c_str(),
                mesh.nodes.size(), mesh.support_x.size() - 1);
  } catch (const pcsim::InputError& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 2;
  }
  return 0;
}
