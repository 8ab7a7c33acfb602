// The self-registering registries: schemes, paper tables and mesh providers. A scheme folder
// registers what it brings from inside the folder, in its scheme.cpp:
//
//   SDB_REGISTER_SCHEMES(cpatch, make_cpatch_schemes)          // std::vector<std::unique_ptr<Scheme>>()
//   SDB_REGISTER_PAPER_TABLES(cpatch, cpatch_paper_tables)     // std::vector<PaperTable>()
//   SDB_REGISTER_MESHES(geometry_image, analytic_meshes)       // MeshProvider()
//
// and sdb_add_scheme (schemes/CMakeLists.txt) links the folder's library whole, so that the
// registrations survive static linking. Factories run on first use, not during static
// initialisation. The order is fixed whatever the link order: peers first, then methods, then
// test schemes; within a role by family name; within a family in the factory's order (the report's
// colours follow it).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/paper_table.h"
#include "harness/core/scheme.h"

namespace sdb {

const std::vector<std::unique_ptr<Scheme>>& all_schemes();
const Scheme* find_scheme(std::string_view name);  // nullptr when unknown

// A scheme as spelled on the command line ("geometry-image:fit=129"), looked up and its parameters
// resolved against their declaration.
struct ResolvedScheme {
  const Scheme* scheme = nullptr;
  Parameters parameters;
  std::string spec;  // canonical: the name and the non-default parameters
};
// InputError for an unknown scheme or a bad parameter.
ResolvedScheme resolve_scheme(const std::string& spelled);

const std::vector<PaperTable>& paper_tables();

// Named meshes a scheme folder provides (the analytic geometry images, say), beside the
// generators of datasets/.
struct NamedMesh {
  std::string name;
  std::string description;
  std::function<ControlMesh()> make;
};
struct MeshProvider {
  std::vector<NamedMesh> builtins;  // listed by `list meshes`
  // Parametrised names (gim-sphere-<n>): the mesh, nullopt when the name is not this provider's;
  // InputError when it is, with bad parameters.
  std::function<std::optional<ControlMesh>(const std::string& name)> parse;
};
const std::vector<MeshProvider>& mesh_providers();

namespace registry_detail {
using SchemeFactory = std::vector<std::unique_ptr<Scheme>> (*)();
using PaperFactory = std::vector<PaperTable> (*)();
using MeshFactory = MeshProvider (*)();
bool add_schemes(const char* family, SchemeFactory make);
bool add_paper_tables(const char* family, PaperFactory make);
bool add_meshes(const char* family, MeshFactory make);
}  // namespace registry_detail

}  // namespace sdb

#define SDB_REGISTRY_CONCAT_(a, b) a##b
#define SDB_REGISTRY_NAME_(prefix, line) SDB_REGISTRY_CONCAT_(prefix, line)
#define SDB_REGISTER_SCHEMES(family, factory)                                                  \
  [[maybe_unused]] static const bool SDB_REGISTRY_NAME_(sdb_registered_schemes_, __LINE__) = \
      ::sdb::registry_detail::add_schemes(#family, factory)
#define SDB_REGISTER_PAPER_TABLES(family, factory)                                           \
  [[maybe_unused]] static const bool SDB_REGISTRY_NAME_(sdb_registered_papers_, __LINE__) = \
      ::sdb::registry_detail::add_paper_tables(#family, factory)
#define SDB_REGISTER_MESHES(family, factory)                                                 \
  [[maybe_unused]] static const bool SDB_REGISTRY_NAME_(sdb_registered_meshes_, __LINE__) = \
      ::sdb::registry_detail::add_meshes(#family, factory)
