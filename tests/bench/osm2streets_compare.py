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

from shapely.geometry import shape
from shapely.ops import transform, unary_union


def local_metres(lat0, lon0):
    kx = 111320.0 * math.cos(math.radians(lat0))
    return lambda x, y, z=None: ((x - lon0) * kx, (y - lat0) * 111320.0)


def union_of(features, kinds, key):
    return unary_union([shape(f['geometry']).buffer(0) for f in features if f['properties'].get(key) in kinds])


def main():
    osmparse, shared = sys.argv[1], sys.argv[2]
    root = os.path.join(shared, 'osm2streets')
    print(f"{'case':22} {'ours m2':>9} {'(carriageway)':>13} {'osm2streets m2':>14} {'overlap m2':>10} {'IoU':>6} {'IoU carriageway':>15}")
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
        print(f"{name:22} {ours_all.area:9.0f} {ours_car.area:13.0f} {peer.area:14.0f} {inter:10.0f} {iou:6.2f} {iou_car:15.2f}")


if __name__ == '__main__':
    main()
