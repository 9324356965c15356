#!/usr/bin/env python3
"""Writes the hand-made roof fixture roofs.osm (invented coordinates and ids).

Every roof:shape on four footprints: a rectangle, an L, a courtyard (multipolygon with a
hole) and a concave U; plus buildings with bad roof and colour tags. Local metres around
49.4N 7.7E, converted to WGS84 here. Run from this folder, then tests/golden/regenerate.sh.
"""
import math

LAT0, LON0 = 49.4, 7.7
M_LAT = 111320.0
M_LON = 111320.0 * math.cos(math.radians(LAT0))

SHAPES = ['flat', 'skillion', 'gabled', 'hipped', 'half-hipped', 'pyramidal', 'gambrel', 'mansard',
          'dome', 'onion', 'round']
FOOTPRINTS = {
    'rectangle': ([(0, 0), (12, 0), (12, 8), (0, 8)], None),
    'L': ([(0, 0), (14, 0), (14, 6), (6, 6), (6, 12), (0, 12)], None),
    'courtyard': ([(0, 0), (20, 0), (20, 20), (0, 20)], [(6, 6), (6, 14), (14, 14), (14, 6)]),
    'concave': ([(0, 0), (16, 0), (16, 12), (11, 12), (11, 5), (5, 5), (5, 12), (0, 12)], None),
}

nodes, ways, relations = [], [], []
next_id = [1000]


def new_id():
    next_id[0] += 1
    return next_id[0]


def ring(points, ox, oy):
    ids = []
    for x, y in points:
        nid = new_id()
        nodes.append((nid, ox + x, oy + y))
        ids.append(nid)
    return ids + [ids[0]]


def building(points, hole, ox, oy, tags):
    if hole is None:
        ways.append((new_id(), ring(points, ox, oy), tags))
        return
    outer, inner = new_id(), new_id()
    ways.append((outer, ring(points, ox, oy), {}))
    ways.append((inner, ring(hole, ox, oy), {}))
    relations.append((new_id(), [(outer, 'outer'), (inner, 'inner')], dict(tags, type='multipolygon')))


for row, (name, (points, hole)) in enumerate(FOOTPRINTS.items()):
    for col, shape in enumerate(SHAPES):
        tags = {'building': 'house', 'height': '10', 'roof:shape': shape}
        if col % 2 == 0:
            tags['roof:height'] = '4'
        building(points, hole, col * 30, row * 30, tags)

rect = FOOTPRINTS['rectangle'][0]
bad = [
    {'building': 'house', 'height': '6', 'roof:shape': 'gabled', 'roof:height': '9'},   # above height
    {'building': 'house', 'height': '9', 'roof:shape': 'gabled', 'roof:angle': '95'},   # absurd angle
    {'building': 'house', 'height': '9', 'roof:shape': 'pancake'},                       # unknown shape
    {'building': 'house', 'height': '9', 'building:colour': 'blurple', 'roof:colour': '#12345'},
    {'building': 'house', 'height': '9', 'roof:shape': 'skillion', 'roof:direction': 'SW',
     'building:colour': '#c84', 'roof:colour': 'darkslategray', 'building:material': 'brick',
     'roof:material': 'slate'},
    {'building': 'house', 'building:levels': '2', 'roof:shape': 'gabled', 'roof:levels': '1',
     'roof:orientation': 'across'},
]
for col, tags in enumerate(bad):
    building(rect, None, col * 30, 4 * 30, tags)

lines = ['<?xml version="1.0" encoding="UTF-8"?>',
         '<osm version="0.6" generator="make_roof_fixtures.py">',
         '  <!-- Every roof:shape on a rectangle, an L, a courtyard and a concave U; then bad roof and colour tags. -->']
for nid, x, y in nodes:
    lines.append(f'  <node id="{nid}" version="1" lat="{LAT0 + y / M_LAT:.8f}" lon="{LON0 + x / M_LON:.8f}"/>')
for wid, refs, tags in ways:
    lines.append(f'  <way id="{wid}" version="1">')
    lines += [f'    <nd ref="{r}"/>' for r in refs]
    lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
    lines.append('  </way>')
for rid, members, tags in relations:
    lines.append(f'  <relation id="{rid}" version="1">')
    lines += [f'    <member type="way" ref="{ref}" role="{role}"/>' for ref, role in members]
    lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
    lines.append('  </relation>')
lines.append('</osm>')
with open('roofs.osm', 'w') as f:
    f.write('\n'.join(lines) + '\n')
