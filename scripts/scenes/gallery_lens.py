#!/usr/bin/python3
"""Writes the gallery seen through a thin lens focused on the post, the
depth-of-field scene of scripts/isg_study.sh and the pictures.

Usage: gallery_lens.py GALLERY_JSON OUT_JSON"""
import json
import sys

scene = json.load(open(sys.argv[1]))
scene["name"] = "gallery_lens"
scene["camera"].update({"type": "thin_lens", "aperture_radius_m": 0.15, "focus_distance_m": 4.6})
json.dump(scene, open(sys.argv[2], "w"), indent=1)
