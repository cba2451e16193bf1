// Shared helper of the enum name tables (enum_names.h).
#include "adaptex/core/enum_names.h"

namespace adaptex {

std::string or_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k) out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return out;
}

}  // namespace adaptex
