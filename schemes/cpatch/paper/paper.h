// The c-patch paper tables (paper.cpp, fps.cpp, fig12.cpp), registered by scheme.cpp.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/bench/paper_output.h"
#include "harness/core/control_mesh.h"
#include "harness/core/paper_table.h"

namespace sdb {

// ni2008-table4, ni2008-table5, ni2008-fig12.
std::vector<PaperTable> cpatch_paper_tables();

}  // namespace sdb

namespace sdb::cpatch {

// ni2008-table4 (cpatch-2pass) and ni2008-table5 (cpatch-1pass): frames per second in render mode.
int run_table4(const PaperTableOptions& options, std::ostream& out);
int run_table5(const PaperTableOptions& options, std::ostream& out);
// ni2008-fig12: deviation from the Catmull-Clark limit per mesh, and heat maps.
int run_fig12(const PaperTableOptions& options, std::ostream& out);

// "(verts, quads, eqs%)" of a mesh as the paper lists its models, for the mesh as given (before
// quadrangulation), plus the quads after it when it had other faces.
std::string mesh_shape(MeasureContext& context, const std::string& mesh, const ControlMesh& quads);

}  // namespace sdb::cpatch
