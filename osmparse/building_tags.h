// The tags of every building area by OSM identity, for the stages after build_buildings that
// read more of them (roofs, colours and materials).
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

#include "osm_data.h"

namespace citygen {

class BuildingTagIndex {
public:
    explicit BuildingTagIndex(const OsmData& osm) {
        for (const OsmArea& area : osm.building_areas) entries_.push_back({area.ref, &area.tags});
        std::stable_sort(entries_.begin(), entries_.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
    }
    // The tags of the area `ref`, or an empty set when there is none (hand-made scenes).
    const OsmTags& find(OsmRef ref) const {
        static const OsmTags none;
        auto it = std::lower_bound(entries_.begin(), entries_.end(), ref,
                                   [](const auto& e, OsmRef r) { return e.first < r; });
        return it != entries_.end() && it->first == ref ? *it->second : none;
    }

private:
    std::vector<std::pair<OsmRef, const OsmTags*>> entries_;
};

}  // namespace citygen
