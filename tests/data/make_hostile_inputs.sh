#!/usr/bin/env bash
# Writes the hostile inputs of issue 8 into DIR: small OSM files (made here, a few hundred KB
# at most) and scene files (made by build/bin/make_hostile_scenes, which encodes without the
# loader's checks). Run by tests/hostile/run_hostile.sh; nothing here is checked in as a blob.
# Usage: make_hostile_inputs.sh DIR BIN_DIR
set -euo pipefail
dir=$1 bin=$2
mkdir -p "$dir"

header() { printf '<?xml version="1.0" encoding="UTF-8"?>\n<osm version="0.6" generator="make_hostile_inputs.sh">\n'; }
footer() { printf '</osm>\n'; }
node() { printf '  <node id="%s" version="1" lat="%s" lon="%s"/>\n' "$1" "$2" "$3"; }
# A small town: one building (nodes 1-4, way 100) and one street (nodes 5-6, way 200).
# town_nodes EXTRA_NODES... / town_ways EXTRA_WAYS...: the extras are printed in id order.
town_nodes() {
    node 1 52.50000 13.40000; node 2 52.50000 13.40030
    node 3 52.50020 13.40030; node 4 52.50020 13.40000
    node 5 52.49980 13.39950; node 6 52.49980 13.40100
}
building_way() { printf '  <way id="100" version="1"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="1"/><tag k="building" v="yes"/></way>\n'; }
street_way() { printf '  <way id="200" version="1"><nd ref="5"/><nd ref="6"/><tag k="highway" v="residential"/></way>\n'; }
town() { town_nodes; building_way; street_way; }

# A two-node road 10 degrees long (grew 50 MB/s in build_sidewalks, never ended).
{ header; town_nodes; node 7 52.49990 13.39950; node 8 62.49990 13.39950; building_way; street_way
  printf '  <way id="201" version="1"><nd ref="7"/><nd ref="8"/><tag k="highway" v="residential"/></way>\n'; footer; } > "$dir/far_road.osm"

# A building with one node 10 degrees away (the same in narrow_roads).
{ header; town_nodes; node 11 52.50100 13.40000; node 12 52.50100 13.40030; node 13 42.50120 13.40030; building_way
  printf '  <way id="101" version="1"><nd ref="11"/><nd ref="12"/><nd ref="13"/><nd ref="11"/><tag k="building" v="yes"/></way>\n'
  street_way; footer; } > "$dir/far_building_node.osm"

# A duplicate node id whose second copy is 4,700 km away (a bad merge of two extracts): the
# town's building and its street share the moved node.
{ header; node 1 52.50000 13.40000; node 2 52.50000 13.40030; node 3 10.20000 -20.00000; node 3 52.50020 13.40030
  node 4 52.50020 13.40000; node 5 52.49980 13.39950; node 6 52.49980 13.40100; building_way
  printf '  <way id="200" version="1"><nd ref="5"/><nd ref="3"/><nd ref="6"/><tag k="highway" v="residential"/></way>\n'
  footer; } > "$dir/duplicate_node.osm"

# A building outline of 100,000 nodes (over the ring limit: dropped and counted).
ring_osm() {  # ring_osm N RADIUS_DEG ZIGZAG: a closed building way of N nodes beside the town
    local n=$1 r=$2 zigzag=$3
    header; town_nodes
    awk -v n="$n" -v r="$r" -v z="$zigzag" 'BEGIN {
        pi = 3.14159265358979
        for (i = 0; i < n; i++) {
            rr = (z && i % 2) ? r * 0.2 : r
            k = z ? (i * 7) % n : i   # a star polygon crosses itself at every edge
            printf "  <node id=\"%d\" version=\"1\" lat=\"%.8f\" lon=\"%.8f\"/>\n", 1000 + i, 52.51 + rr * sin(2 * pi * k / n), 13.41 + rr * cos(2 * pi * k / n)
        }
    }'
    building_way; street_way
    awk -v n="$n" 'BEGIN {
        printf "  <way id=\"300\" version=\"1\">"
        for (i = 0; i < n; i++) printf "<nd ref=\"%d\"/>", 1000 + i
        printf "<nd ref=\"1000\"/><tag k=\"building\" v=\"yes\"/></way>\n"
    }'
    footer
}
ring_osm 100000 0.004 0 > "$dir/ring_100k_nodes.osm"
# Just under the limit: 9,999 nodes, simple (took seconds in the pairwise test), and a star
# that crosses itself everywhere (split at every crossing).
ring_osm 9999 0.004 0 > "$dir/ring_9999_nodes.osm"
ring_osm 2999 0.004 1 > "$dir/star_2999_nodes.osm"

# Located objects beyond the scene limits that no earlier stage dropped (issue 24): a mapped
# tree 20 degrees from the town (dropped), a pond with one node 15 degrees away (clipped to the
# limits), a coastline in a file whose bounds are the whole world (the sea is clipped to them).
{ header; town_nodes; building_way; street_way
  printf '  <node id="21" version="1" lat="32.5" lon="13.4"><tag k="natural" v="tree"/></node>\n'; footer; } > "$dir/far_tree.osm"
{ header; town_nodes; node 30 52.50100 13.40100; node 31 52.50100 13.40200; node 32 37.50200 13.40200
  building_way; street_way
  printf '  <way id="400" version="1"><nd ref="30"/><nd ref="31"/><nd ref="32"/><nd ref="30"/><tag k="natural" v="water"/></way>\n'
  footer; } > "$dir/far_pond_node.osm"
{ header; printf '  <bounds minlat="-90" minlon="-180" maxlat="90" maxlon="180"/>\n'; town_nodes
  node 40 52.49900 13.39900; node 41 52.49900 13.40200; building_way; street_way
  printf '  <way id="500" version="1"><nd ref="40"/><nd ref="41"/><tag k="natural" v="coastline"/></way>\n'
  footer; } > "$dir/world_bounds_coast.osm"

"$bin/make_hostile_scenes" "$dir"
