// `pcsim check SCENE.yaml`: parses a scene and reports whether it is valid.
#include "command.hpp"

namespace {
int check_scene(const pcsim::app::CommandContext& ctx) {
  auto scene = ctx.load_scene();
  pcsim::app::print0(ctx, "%s: readable scene '%s'\n", ctx.scene_path.c_str(),
                     ctx.scene_name(scene).c_str());
  return 0;
}
}  // namespace

PCSIM_COMMAND("check", "read a scene file and report errors", check_scene);
