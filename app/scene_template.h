// The commented scene template that `railwear init` writes. It documents every key this version
// reads, with units, ranges and defaults, and loads with LoadScene as it stands.
#pragma once

#include <string_view>

namespace railwear::app {

std::string_view SceneTemplate();

}  // namespace railwear::app
