#include "harness/core/registry.h"
#include "schemes/peers/peers.h"

namespace sdb {

std::vector<std::unique_ptr<Scheme>> make_peer_schemes() {
  std::vector<std::unique_ptr<Scheme>> peers;
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) peers.push_back(make_osd_uniform(rule));
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) peers.push_back(make_osd_bfr(rule));
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) peers.push_back(make_osd_stencil(rule));
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) peers.push_back(make_osd_glcompute(rule));
  peers.push_back(make_embree_subdiv());
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop})
    peers.push_back(make_openmesh_subdivider(rule));
  return peers;
}

SDB_REGISTER_SCHEMES(peers, make_peer_schemes);

}  // namespace sdb
