// The kinematic tree of a robot file's links from its joints.
#include "link_tree.hpp"

#include <cstddef>
#include <map>

#include "base/errors.hpp"

namespace tumble::app::robot {
namespace {

/// The index of the link named `name`; throws naming the joint and its `role` link.
std::size_t link_index(const std::map<std::string, std::size_t, std::less<>>& indices,
                       const std::string& name, const JointEdge& joint, const char* role,
                       const std::string& file) {
  const auto found = indices.find(name);
  if (found == indices.end()) {
    throw InputError(file + ": joint '" + joint.name + "': " + role + " link '" + name +
                     "' is not a link of the file");
  }
  return found->second;
}

}  // namespace

void build_link_tree(std::vector<Link>& links, const std::vector<JointEdge>& joints,
                     const std::string& file, bool compose_frames) {
  std::map<std::string, std::size_t, std::less<>> indices;
  for (std::size_t i = 0; i < links.size(); ++i) indices.emplace(links[i].name, i);
  // The joint whose child each link is (links.size(): none, a root).
  std::vector<std::size_t> parent_joint(links.size(), joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const JointEdge& joint = joints[j];
    link_index(indices, joint.parent, joint, "parent", file);
    const std::size_t child = link_index(indices, joint.child, joint, "child", file);
    if (parent_joint[child] != joints.size()) {
      throw InputError(file + ": joint '" + joint.name + "': link '" + joint.child +
                       "' already has a parent (joint '" + joints[parent_joint[child]].name +
                       "'): a link has at most one parent");
    }
    parent_joint[child] = j;
  }
  // Each link's frame from its root down: walk up to a root or a link already placed.
  std::vector<bool> placed(links.size(), false);
  for (std::size_t start = 0; start < links.size(); ++start) {
    std::vector<std::size_t> chain;  // from `start` up, not yet placed
    std::size_t at = start;
    while (!placed[at] && parent_joint[at] != joints.size()) {
      chain.push_back(at);
      if (chain.size() > links.size()) {
        throw InputError(file + ": joint '" + joints[parent_joint[at]].name +
                         "': the joints form a cycle through link '" + links[at].name + "'");
      }
      at = link_index(indices, joints[parent_joint[at]].parent, joints[parent_joint[at]], "parent",
                      file);
    }
    placed[at] = true;
    for (auto link = chain.rbegin(); link != chain.rend(); ++link) {
      const JointEdge& joint = joints[parent_joint[*link]];
      links[*link].parent = joint.parent;
      if (compose_frames) {
        links[*link].frame = links[indices.find(joint.parent)->second].frame * joint.origin;
      }
      placed[*link] = true;
    }
  }
}

}  // namespace tumble::app::robot
