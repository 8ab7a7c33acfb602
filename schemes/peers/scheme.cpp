#include "harness/core/registry.h"
#include "schemes/peers/peers.h"

namespace sdb {

std::vector<std::unique_ptr<Scheme>> make_peer_schemes() {
  std::vector<std::unique_ptr<Scheme>> peers;
  peers.push_back(make_osd_uniform(SubdivisionRule::CatmullClark));
  peers.push_back(make_osd_uniform(SubdivisionRule::Loop));
  peers.push_back(make_osd_bfr());
  peers.push_back(make_embree_subdiv());
  return peers;
}

SDB_REGISTER_SCHEMES(peers, make_peer_schemes);

}  // namespace sdb
