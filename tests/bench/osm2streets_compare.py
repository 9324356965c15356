#!/usr/bin/python3
"""Compares our road surface with osm2streets' on its test cases.

For each case in SHARED/osm2streets/NAME: runs osmparse --geojson, unions our road quads +
joints (+ sidewalks), unions osm2streets' road + intersection polygons from geometry.json,
clips both to boundary.json, and prints areas and intersection over union. Areas are in
square metres (a local equal-area-enough projection around the case's centre).
Usage: osm2streets_compare.py OSMPARSE SHARED_OSM_DIR
Needs Debian's python3-shapely (installed by osm2streets_compare.sh).
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

from shapely.geometry import shape
from shapely.ops import transform, unary_union


def local_metres(lat0, lon0):
    kx = 111320.0 * math.cos(math.radians(lat0))
    return lambda x, y, z=None: ((x - lon0) * kx, (y - lat0) * 111320.0)


# Our default carriageway rule (osmparse/core/params.h RoadParams::classes, build_road_graph.cpp):
# used to restrict osm2streets' answer to the same ways for a like-for-like figure.
CLASSES = {'motorway', 'motorway_link', 'trunk', 'trunk_link', 'primary', 'primary_link', 'secondary',
           'secondary_link', 'tertiary', 'tertiary_link', 'unclassified', 'residential', 'living_street', 'service'}


def carriageway_ways(osm_path):
    ways = set()
    for way in ET.parse(osm_path).getroot().iter('way'):
        tags = {t.get('k'): t.get('v') for t in way.iter('tag')}
        if tags.get('highway') in CLASSES and tags.get('area') != 'yes' and tags.get('tunnel', 'no') == 'no':
            ways.add(int(way.get('id')))
    return ways


def union_of(features, kinds, key):
    return unary_union([shape(f['geometry']).buffer(0) for f in features if f['properties'].get(key) in kinds])


def main():
    osmparse, shared = sys.argv[1], sys.argv[2]
    root = os.path.join(shared, 'osm2streets')
    print(f"{'case':20} {'ours m2':>8} {'carriageway':>11} {'o2s m2':>7} {'overlap':>7} {'IoU':>5} {'IoU cw':>6}"
          f" {'o2s same ways':>13} {'IoU same ways':>13}")
    for name in sorted(os.listdir(root)):
        case = os.path.join(root, name)
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, 'out.geojson')
            subprocess.run([osmparse, '-q', os.path.join(case, 'input.osm'), '-o', os.path.join(tmp, 'x.scene'),
                            '--geojson', out], check=True)
            ours = json.load(open(out))['features']
        theirs = json.load(open(os.path.join(case, 'geometry.json')))['features']
        boundary = unary_union([shape(f['geometry']) for f in json.load(open(os.path.join(case, 'boundary.json')))['features']])
        c = boundary.centroid
        proj = local_metres(c.y, c.x)
        clip = transform(proj, boundary)
        ours_all = transform(proj, union_of(ours, {'road', 'joint', 'sidewalk'}, 'kind')).intersection(clip)
        ours_car = transform(proj, union_of(ours, {'road', 'joint'}, 'kind')).intersection(clip)
        peer = transform(proj, union_of(theirs, {'road', 'intersection'}, 'type')).intersection(clip)
        inter = ours_all.intersection(peer).area
        iou = inter / ours_all.union(peer).area
        iou_car = ours_car.intersection(peer).area / ours_car.union(peer).area
        # Like for like: only osm2streets roads made from ways we treat as carriageways
        # (no footways, no tunnels), plus its intersections.
        ways = carriageway_ways(os.path.join(case, 'input.osm'))
        same = [f for f in theirs if f['properties']['type'] == 'intersection' or
                any(w in ways for w in f['properties'].get('osm_way_ids', []))]
        peer_same = transform(proj, union_of(same, {'road', 'intersection'}, 'type')).intersection(clip)
        iou_same = ours_all.intersection(peer_same).area / ours_all.union(peer_same).area
        print(f"{name:20} {ours_all.area:8.0f} {ours_car.area:11.0f} {peer.area:7.0f} {inter:7.0f} {iou:5.2f} {iou_car:6.2f}"
              f" {peer_same.area:13.0f} {iou_same:13.2f}")


if __name__ == '__main__':
    main()
