#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Draws a mesh that `tessera mesh` wrote (PLY, VTK, VTU, OBJ: what meshio reads) as a shaded
surface in its first three coordinates (for a large problem, the view it was written in, e.g.
lambda, epsilon, max:u) and saves the picture.

    python3 scripts/plot_mesh.py bvp.ply -o bvp.png [--azimuth -110] [--elevation 20]

Needs Debian's python3-meshio and python3-matplotlib (apt-get install python3-matplotlib).
A stop-gap until `tessera render` (issue 12) draws pictures itself.
"""
import argparse
import re
import sys


def coordinate_names(path):
    """The axis names tessera writes into a PLY header ("comment coordinate names: a b c")."""
    try:
        with open(path, "rb") as f:
            header = f.read(4096).split(b"end_header")[0].decode("ascii", "replace")
    except OSError:
        return None
    match = re.search(r"comment coordinate names: (.*)", header)
    return match.group(1).split() if match else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh", help="a mesh file tessera wrote")
    parser.add_argument("-o", "--output", required=True, help="picture file (.png, .svg, .pdf)")
    parser.add_argument("--azimuth", type=float, default=-110.0, help="degrees (default -110)")
    parser.add_argument("--elevation", type=float, default=20.0, help="degrees (default 20)")
    parser.add_argument("--dpi", type=int, default=150, help="resolution of a raster picture")
    args = parser.parse_args()
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import meshio
    except ImportError as e:
        sys.exit(f"plot_mesh.py: {e.name} is missing: apt-get install python3-matplotlib python3-meshio")
    try:
        mesh = meshio.read(args.mesh)
    except Exception as e:  # meshio raises several types for unreadable files
        sys.exit(f"plot_mesh.py: cannot read {args.mesh}: {e}")
    triangles = [c.data for c in mesh.cells if c.type == "triangle"]
    points = mesh.points
    if not triangles or points.shape[1] < 3:
        sys.exit(f"plot_mesh.py: {args.mesh} has no triangles in three coordinates")
    names = coordinate_names(args.mesh) or ["x", "y", "z"]

    figure = plt.figure(figsize=(7, 6))
    axes = figure.add_subplot(projection="3d")
    surface = axes.plot_trisurf(points[:, 0], points[:, 1], points[:, 2], triangles=triangles[0],
                                cmap="viridis", linewidth=0.1, edgecolor=(0, 0, 0, 0.15))
    surface.set_array(points[triangles[0]][:, :, 2].mean(axis=1))  # colour by the third axis
    axes.set_xlabel(names[0])
    axes.set_ylabel(names[1])
    axes.set_zlabel(names[2])
    axes.view_init(elev=args.elevation, azim=args.azimuth)
    figure.colorbar(surface, ax=axes, shrink=0.6, label=names[2])
    figure.tight_layout()
    figure.savefig(args.output, dpi=args.dpi)
    print(f"wrote {args.output}: {len(points)} vertices, {len(triangles[0])} triangles")


if __name__ == "__main__":
    main()
