// The c-patch paper's tables (ni2008-table4, ni2008-table5, ni2008-fig12): not built yet; the
// Vulkan variants they time come first.
#include "paper_tables.h"

namespace sdb {

std::vector<PaperTable> cpatch_paper_tables() { return {}; }

}  // namespace sdb
