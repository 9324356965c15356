#!/usr/bin/env python3
"""Writes the hand-made road fixtures road_*.osm (invented coordinates and ids).

Each fixture is described in local metres (x east, y north) around 52.5N 13.4E and
converted to WGS84 here, so the shapes stay readable. Run from this folder; then run
tests/golden/regenerate.sh and review the diff.
"""
import math

LAT0, LON0 = 52.5, 13.4
M_LAT = 111320.0
M_LON = 111320.0 * math.cos(math.radians(LAT0))


def write(name, comment, nodes, ways):
    """nodes: {id: (x, y)}; ways: [(id, [node ids], {tags})]."""
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<osm version="0.6" generator="make_road_fixtures.py">',
             f'  <!-- {comment} -->']
    for nid, (x, y) in sorted(nodes.items()):
        lines.append(f'  <node id="{nid}" version="1" lat="{LAT0 + y / M_LAT:.8f}" lon="{LON0 + x / M_LON:.8f}"/>')
    for wid, refs, tags in ways:
        lines.append(f'  <way id="{wid}" version="1">')
        lines += [f'    <nd ref="{r}"/>' for r in refs]
        lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
        lines.append('  </way>')
    lines.append('</osm>')
    with open(f'road_{name}.osm', 'w') as f:
        f.write('\n'.join(lines) + '\n')


RES = {'highway': 'residential'}

write('straight', 'one straight residential street; the middle node is merged away',
      {1: (0, 0), 2: (50, 0.05), 3: (100, 0)}, [(10, [1, 2, 3], RES)])

write('bend', 'a residential street turning by about 37 degrees: two quads on one miter',
      {1: (0, 0), 2: (50, 0), 3: (90, 30)}, [(10, [1, 2, 3], RES)])

write('t', 'a residential street meeting a primary road: a T joint',
      {1: (-50, 0), 2: (0, 0), 3: (50, 0), 4: (0, 50)},
      [(10, [1, 2, 3], {'highway': 'primary'}), (11, [2, 4], RES)])

write('cross', 'two residential streets crossing at right angles: a square joint',
      {1: (-50, 0), 2: (0, 0), 3: (50, 0), 4: (0, -50), 5: (0, 50)},
      [(10, [1, 2, 3], RES), (11, [4, 2, 5], RES)])

star = {1: (0, 0)}
for k in range(5):
    a = math.radians(90 + 72 * k)
    star[2 + k] = (40 * math.cos(a), 40 * math.sin(a))
write('star5', 'five residential streets meeting at one node, 72 degrees apart',
      star, [(10 + k, [1, 2 + k], RES) for k in range(5)])

ring = {}
for k in range(12):
    a = math.radians(30 * k)
    ring[100 + k] = (15 * math.cos(a), 15 * math.sin(a))
nodes = dict(ring)
ways = [(10, [100 + k for k in range(12)] + [100],
         {'highway': 'tertiary', 'junction': 'roundabout', 'width': '7'})]
for q in range(4):
    a = math.radians(90 * q)
    nodes[200 + q] = (60 * math.cos(a), 60 * math.sin(a))
    ways.append((20 + q, [200 + q, 100 + 3 * q], RES))
write('roundabout', 'a 12-node roundabout (7 m wide) with four residential approaches',
      nodes, ways)

write('dead_end', 'a service road branching off a residential street and ending after 20 m',
      {1: (-40, 0), 2: (0, 0), 3: (40, 0), 4: (0, 20)},
      [(10, [1, 2, 3], RES), (11, [2, 4], {'highway': 'service'})])

write('short_edge', 'a primary road with two junctions only 3 m apart (a 3 m edge between joints)',
      {1: (-50, 0), 2: (0, 0), 3: (3, 0), 4: (50, 0), 5: (0, 40), 6: (3, -40)},
      [(10, [1, 2, 3, 4], {'highway': 'primary'}), (11, [2, 5], RES), (12, [3, 6], RES)])

write('near_parallel', 'two residential streets leaving a junction only 8 degrees apart',
      {1: (-50, 0), 2: (0, 0), 3: (60, 0), 4: (60 * math.cos(math.radians(8)), 60 * math.sin(math.radians(8)))},
      [(10, [1, 2, 3], RES), (11, [2, 4], RES)])

write('brushing_building', 'a residential street (6 m by default) whose edge reaches 1 m into a building',
      {1: (0, 0), 2: (100, 0), 3: (30, 2), 4: (50, 2), 5: (50, 20), 6: (30, 20)},
      [(10, [1, 2], RES), (20, [3, 4, 5, 6, 3], {'building': 'yes', 'height': '10'})])
