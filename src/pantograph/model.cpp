#include "pcsim/pantograph/model.hpp"

namespace pcsim::pantograph {

PantographModel::~PantographModel() = default;

}  // namespace pcsim::pantograph
