// Warm start of a wheel's contact across calls (contact_warm_start.h).
#include "core/contact/contact_warm_start.h"

#include "core/contact/potential_area.h"

namespace railwear {

ContactWarmStart::ContactWarmStart() = default;
ContactWarmStart::~ContactWarmStart() = default;
ContactWarmStart::ContactWarmStart(ContactWarmStart&&) noexcept = default;
ContactWarmStart& ContactWarmStart::operator=(ContactWarmStart&&) noexcept = default;

void ContactWarmStart::Clear() { state_.reset(); }

void ContactWarmStart::Keep(std::unique_ptr<internal::WarmStartState> state) {
  state_ = std::move(state);
}

}  // namespace railwear
