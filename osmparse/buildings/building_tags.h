// The tags of every building area by OSM identity, for the stages after build_buildings that
// read more of them (roofs, colours and materials).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "osmparse/core/osm_data.h"

namespace citygen {

class BuildingTagIndex {
public:
    // Copies the tags of every building area that roofs and colours read.
    explicit BuildingTagIndex(const OsmData& osm) { add(osm.building_areas); }
    // The same from building areas nothing reads after: those are freed (the index is kept
    // from the heights to the roofs and colours, which run last: see pipeline.cpp).
    explicit BuildingTagIndex(std::vector<OsmArea>&& areas) {
        add(areas);
        std::vector<OsmArea>().swap(areas);
    }
    // The tags of the area `ref` that roofs and colours read, or an empty set when there is
    // none (hand-made scenes).
    const OsmTags& find(OsmRef ref) const {
        static const OsmTags none;
        auto it = std::lower_bound(entries_.begin(), entries_.end(), ref,
                                   [](const auto& e, OsmRef r) { return e.first < r; });
        return it != entries_.end() && it->first == ref ? it->second : none;
    }

    // The keys build_roofs.cpp and building_colours.cpp read: roof:* and building:* (e.g.
    // building:colour, building:facade:material). Others are not kept.
    static bool is_kept(const std::string& key) { return key.rfind("roof:", 0) == 0 || key.rfind("building:", 0) == 0; }

private:
    void add(const std::vector<OsmArea>& areas) {
        std::vector<uint32_t> order(areas.size());
        for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return areas[a].ref < areas[b].ref; });
        for (size_t k = 0; k < order.size(); ++k) {
            const OsmArea& area = areas[order[k]];
            if (k > 0 && areas[order[k - 1]].ref == area.ref) continue;  // the first area of a ref is found
            OsmTags kept;
            for (const auto& tag : area.tags.entries)
                if (is_kept(tag.first)) kept.entries.push_back(tag);
            if (!kept.entries.empty()) entries_.push_back({area.ref, std::move(kept)});  // else: none
        }
        entries_.shrink_to_fit();
    }
    std::vector<std::pair<OsmRef, OsmTags>> entries_;  // by ref
};

}  // namespace citygen
