#include "core/asymmetric_top.hpp"
#include <stdexcept>

namespace terrace {
// Being written (issue 2): the Jacobi-elliptic solution replaces this.
void AsymmetricTop::freeRotate(State&, const BodyParams&, double) {
    throw std::logic_error("AsymmetricTop::freeRotate not yet implemented");
}
} // namespace terrace
