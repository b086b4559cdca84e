// pcsim's version (CMake project()) and the git commit of the source tree when
// it was configured ("unknown" outside a git checkout; "-dirty" when the tree
// had uncommitted changes).
#pragma once

namespace pcsim {

const char* version();
const char* git_commit();

}  // namespace pcsim
