#!/usr/bin/python3
"""A copy of a scene file at another render size, for the result scripts (ms_ceiling.sh, gallery.sh): the frame
and lightmap sizes replaced, a warm-up added where the scene has none, and mesh paths made absolute (they are
relative to the scene's folder, which the copy leaves).

Usage: resized_scene.py SCENE COPY --size N --lightmap N [--warmup N]
"""
import argparse
import json
import os


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene")
    parser.add_argument("copy")
    parser.add_argument("--size", type=int, required=True, help="frame width and height in pixels")
    parser.add_argument("--lightmap", type=int, required=True, help="lightmap size in pixels")
    parser.add_argument("--warmup", type=int, help="warm-up frames, for a scene without its own")
    args = parser.parse_args()
    with open(args.scene) as f:
        scene = json.load(f)
    scene["render"].update({"width": args.size, "height": args.size, "lightmap_size": args.lightmap})
    if args.warmup is not None:
        scene["render"].setdefault("warmup_frames", args.warmup)
    for obstacle in scene.get("obstacles", []):
        if "file" in obstacle:
            obstacle["file"] = os.path.join(os.path.dirname(os.path.abspath(args.scene)), obstacle["file"])
    with open(args.copy, "w") as f:
        json.dump(scene, f, indent=1)


if __name__ == "__main__":
    main()
