// Dead end: a node with one edge (osm2streets' terminus). The quad ends square at the
// node: the cut stays at zero on both sides, and there is no joint.
#include "osmparse/roads/layout_state.h"

namespace citygen {

void lay_out_dead_end(LayoutState& state, NodeLayout& node) {
    node.kind = JoinKind::End;
    state.cut_of(node.ends[0]) = {0, 0};
}

}  // namespace citygen
