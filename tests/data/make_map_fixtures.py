#!/usr/bin/env python3
"""Writes the hand-made map-content fixtures map_*.osm (invented coordinates and ids).

Shapes are given in local metres (x east, y north) around 43.7N 7.4E and converted to WGS84
here. Every fixture has <bounds> of x, y in [-200, 200]: the extract edge the sea is clipped
to. Run from this folder; then run tests/golden/regenerate.sh and review the diff.
"""
import math

LAT0, LON0 = 43.7, 7.4
M_LAT = 111320.0
M_LON = 111320.0 * math.cos(math.radians(LAT0))
HALF = 200


def lat(y):
    return LAT0 + y / M_LAT


def lon(x):
    return LON0 + x / M_LON


def write(name, comment, nodes, ways, relations=(), node_tags=None):
    """nodes: {id: (x, y)}; ways: [(id, [node ids], {tags})]; relations: [(id, [(role, way id)], {tags})]."""
    node_tags = node_tags or {}
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<osm version="0.6" generator="make_map_fixtures.py">',
             f'  <!-- {comment} -->',
             f'  <bounds minlat="{lat(-HALF):.8f}" minlon="{lon(-HALF):.8f}" maxlat="{lat(HALF):.8f}" maxlon="{lon(HALF):.8f}"/>']
    for nid, (x, y) in sorted(nodes.items()):
        tags = node_tags.get(nid)
        if tags:
            lines.append(f'  <node id="{nid}" version="1" lat="{lat(y):.8f}" lon="{lon(x):.8f}">')
            lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
            lines.append('  </node>')
        else:
            lines.append(f'  <node id="{nid}" version="1" lat="{lat(y):.8f}" lon="{lon(x):.8f}"/>')
    for wid, refs, tags in ways:
        lines.append(f'  <way id="{wid}" version="1">')
        lines += [f'    <nd ref="{r}"/>' for r in refs]
        lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
        lines.append('  </way>')
    for rid, members, tags in relations:
        lines.append(f'  <relation id="{rid}" version="1">')
        lines += [f'    <member type="way" ref="{w}" role="{role}"/>' for role, w in members]
        lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
        lines.append('  </relation>')
    lines.append('</osm>')
    with open(f'map_{name}.osm', 'w') as f:
        f.write('\n'.join(lines) + '\n')


def square(first_id, cx, cy, half, ccw=True):
    pts = [(cx - half, cy - half), (cx + half, cy - half), (cx + half, cy + half), (cx - half, cy + half)]
    if not ccw:
        pts.reverse()
    nodes = {first_id + i: p for i, p in enumerate(pts)}
    return nodes, [first_id, first_id + 1, first_id + 2, first_id + 3, first_id]


COAST = {'natural': 'coastline'}
HOUSE = {'building': 'house'}

# A coastline across the extract (its ends lie beyond the bounds, as in a 'complete ways'
# extract), drawn west -> east: land on its left (north), the sea south. Houses on land.
nodes = {1: (-400, 10), 2: (-100, -20), 3: (0, 5), 4: (120, -15), 5: (400, 0)}
h, ring = square(100, 0, 100, 8)
nodes.update(h)
write('coast_cut', 'coastline across the extract, west to east: sea in the south', nodes,
      [(10, [1, 2, 3], COAST), (11, [3, 4, 5], COAST), (20, ring, HOUSE)])

# The same line east -> west: the land is south now, the sea north.
nodes = {1: (-400, 10), 2: (-100, -20), 3: (0, 5), 4: (120, -15), 5: (400, 0)}
h, ring = square(100, 0, -100, 8)
nodes.update(h)
write('coast_cut_reversed', 'coastline across the extract, east to west: sea in the north', nodes,
      [(10, [5, 4, 3], COAST), (11, [3, 2, 1], COAST), (20, ring, HOUSE)])

# A coastline that enters at the west edge and leaves at the south edge: a corner of sea.
nodes = {1: (-300, -50), 2: (-120, -60), 3: (-60, -120), 4: (-50, -300)}
write('coast_corner', 'coastline cutting off the south-west corner, which is land (on its left): sea elsewhere', nodes,
      [(10, [4, 3, 2, 1], COAST)])

# An island: a closed coastline ring, counter-clockwise (land on the left), in an extract of sea.
nodes = {1: (-50, -40), 2: (60, -50), 3: (70, 40), 4: (-40, 60)}
h, ring = square(100, 0, 0, 10)
nodes.update(h)
write('island', 'a closed coastline ring: an island in a sea that fills the extract', nodes,
      [(10, [1, 2, 3, 4, 1], COAST), (20, ring, HOUSE)])

# The coastline of a clipped extract: its nodes beyond the bounds are missing from the file,
# so the way stops 10-15 m inside; its ends are carried to the edge and the sea is south.
nodes = {2: (-190, 10), 3: (-100, -20), 4: (0, 5), 5: (120, -15), 6: (185, 0)}
h, ring = square(100, 0, 100, 8)
nodes.update(h)
write('coast_clipped', 'a coastline whose nodes beyond the bounds are missing: ends carried to the edge', nodes,
      [(10, [1, 2, 3, 4, 5, 6, 7], COAST), (20, ring, HOUSE)])

# A coastline ending inside the extract: broken, so no sea (never a flooded city).
nodes = {1: (-400, 10), 2: (-100, -20), 3: (50, 5)}
write('coast_broken', 'a coastline that ends inside the extract: no sea, counted', nodes,
      [(10, [1, 2, 3], COAST)])

# A lake with an island: natural=water multipolygon, outer and inner ways.
o, outer = square(1, 0, 0, 100)
i, inner = square(11, 10, 0, 30, ccw=False)
nodes = {**o, **i}
write('lake_island', 'a lake (multipolygon) with an island (its inner ring)', nodes,
      [(10, outer, {}), (11, inner, {})],
      [(100, [('outer', 10), ('inner', 11)], {'type': 'multipolygon', 'natural': 'water'})])

# A park with a pond in it, a square and a parking lot beside it, in a residential area.
p, park = square(1, 0, 0, 80)
q, pond = square(11, 10, 10, 20)
s, plaza = square(21, 130, 0, 30)
r, resid = square(31, 0, 0, 190)
nodes = {**p, **q, **s, **r}
write('park_pond', 'a park with a pond, a square beside it, all in a residential area', nodes,
      [(10, park, {'leisure': 'park'}), (11, pond, {'natural': 'water'}),
       (12, plaza, {'place': 'square'}), (13, resid, {'landuse': 'residential'})])

# A riverbank multipolygon whose inner member is missing from the extract: skipped, counted.
o, outer = square(1, 0, 0, 100)
write('riverbank_missing_member', 'a riverbank multipolygon with a member missing', o,
      [(10, outer, {})],
      [(100, [('outer', 10), ('inner', 99)], {'type': 'multipolygon', 'waterway': 'riverbank'})])

# Trees: two mapped trees (one with absurd tags), a tree row, and a forest crossed by a
# road, with a house and a pond in it: no scattered tree on the road, in the house or pond.
f, forest = square(1, 0, 0, 150)
hs, house = square(11, 60, 60, 8)
pd, pond = square(21, -60, 60, 15)
nodes = {**f, **hs, **pd, 31: (-190, -20), 32: (190, -20), 41: (-180, 180), 42: (-20, 180),
         51: (170, 170), 52: (175, 160)}
write('trees', 'mapped trees (one with height=-3, diameter_crown=1e9), a tree row, a forest with a road, house and pond',
      nodes,
      [(10, forest, {'landuse': 'forest'}), (11, house, HOUSE), (12, pond, {'natural': 'water'}),
       (13, [31, 32], {'highway': 'residential'}), (14, [41, 42], {'natural': 'tree_row'})],
      node_tags={51: {'natural': 'tree', 'height': '-3', 'diameter_crown': '1e9'},
                 52: {'natural': 'tree', 'height': '12', 'leaf_type': 'needleleaved'}})

# Paths and rails: a footway crossing a residential street (sharing a node, as crossings
# do), a mapped sidewalk along the street's north side, a railway and a railway in a tunnel.
nodes = {1: (-150, 0), 2: (0, 0), 3: (150, 0), 11: (0, 100), 12: (0, -60), 21: (-100, 7), 22: (100, 7),
         31: (-190, -90), 32: (190, -90), 41: (-190, -130), 42: (190, -130), 51: (60, 60), 52: (60, 100)}
write('paths', 'a footway crossing a street, a mapped sidewalk, steps, a railway and one in a tunnel', nodes,
      [(10, [1, 2, 3], {'highway': 'residential', 'sidewalk': 'both'}),
       (11, [11, 2, 12], {'highway': 'footway'}),
       (12, [21, 22], {'highway': 'footway', 'footway': 'sidewalk'}),
       (13, [31, 32], {'railway': 'rail'}),
       (14, [41, 42], {'railway': 'rail', 'tunnel': 'yes'}),
       (15, [51, 52], {'highway': 'steps', 'width': '3'})])

# Lanes and markings: a 4-lane primary road with turn lanes meeting a residential street at
# traffic signals, a zebra crossing on the residential street, an unmarked crossing (no
# zebra), and a residential street with lanes=banana (falls back, counted).
nodes = {1: (-150, 0), 2: (0, 0), 3: (150, 0), 4: (0, 150), 5: (0, 40), 6: (-50, 0), 7: (-150, 80),
         8: (150, 80), 9: (0, 100)}
write('lanes', 'a 4-lane primary with turn lanes, signals, a zebra crossing, lanes=banana', nodes,
      [(10, [1, 6, 2], {'highway': 'primary', 'lanes': '4', 'turn:lanes:forward': 'left|through',
                        'cycleway': 'lane'}),
       (11, [2, 3], {'highway': 'primary', 'lanes': '4'}),
       (12, [2, 5, 9, 4], {'highway': 'residential'}),
       (13, [7, 8], {'highway': 'residential', 'lanes': 'banana'})],
      node_tags={5: {'highway': 'crossing', 'crossing': 'zebra'},
                 9: {'highway': 'crossing', 'crossing': 'unmarked'},
                 6: {'highway': 'traffic_signals'}})
