#!/usr/bin/env python3
"""Writes empty_block.osm (invented coordinates and ids): two blocks of a residential grid,
the left one with six mapped houses, the right one empty (for --fill-empty-blocks).
Local metres around 49.4N 7.7E. Run from this folder, then tests/golden/regenerate.sh."""
import math

LAT0, LON0 = 49.4, 7.7
M_LAT = 111320.0
M_LON = 111320.0 * math.cos(math.radians(LAT0))
nodes, ways = {}, []

def node(nid, x, y):
    nodes[nid] = (x, y)

for i, x in enumerate((0, 100, 200)):
    node(1 + i, x, 0)
    node(11 + i, x, 80)
RES = {'highway': 'residential'}
ways += [(101, [1, 2, 3], RES), (102, [11, 12, 13], RES),
         (103, [1, 11], RES), (104, [2, 12], RES), (105, [3, 13], RES)]
nid = 1000
for k, (x, y) in enumerate([(30, 12), (50, 12), (70, 12), (30, 56), (50, 56), (70, 56)]):
    ring = []
    for dx, dy in ((0, 0), (12, 0), (12, 9), (0, 9)):
        nid += 1
        node(nid, x + dx, y + dy)
        ring.append(nid)
    ways.append((200 + k, ring + [ring[0]], {'building': 'house'}))

lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<osm version="0.6" generator="make_block_fixture.py">',
         '  <!-- Two blocks of a residential grid: six mapped houses on the left, nothing on the right. -->']
for i, (x, y) in sorted(nodes.items()):
    lines.append(f'  <node id="{i}" version="1" lat="{LAT0 + y / M_LAT:.8f}" lon="{LON0 + x / M_LON:.8f}"/>')
for wid, refs, tags in ways:
    lines.append(f'  <way id="{wid}" version="1">')
    lines += [f'    <nd ref="{r}"/>' for r in refs]
    lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
    lines.append('  </way>')
lines.append('</osm>')
open('empty_block.osm', 'w').write('\n'.join(lines) + '\n')
