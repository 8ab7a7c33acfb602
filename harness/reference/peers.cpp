#include "peers.h"

#include "peer_schemes.h"

namespace sdb {

std::vector<std::unique_ptr<Scheme>> make_peer_schemes() {
  std::vector<std::unique_ptr<Scheme>> peers;
  peers.push_back(make_osd_uniform(SubdivisionRule::CatmullClark));
  peers.push_back(make_osd_uniform(SubdivisionRule::Loop));
  peers.push_back(make_osd_bfr());
  peers.push_back(make_embree_subdiv());
  return peers;
}

}  // namespace sdb
