#!/usr/bin/env python3
"""Draw the five preset bodies of crashsim.vehicles.generator into docs/img/bodies.png.

    python3 scripts/draw_bodies.py [--out docs/img/bodies.png]

One row per preset: a shaded 3-D view, then a side view (from the right, -y) and a top view
(from above), both orthographic; the four light vehicles share one scale, so they compare in
size, and the bus (2.4 times as long) has its own, smaller one (its title says so). Dashed
circles show where the wheels would stand (the body itself has no wheels).
Uses each preset's class dimensions (crashsim.vehicles.generator.default_dims, from
crashsim.vehicles.vehicle_data)
and the presets' default shapes.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import trimesh  # noqa: E402
from crashsim.vehicles.generator import (  # noqa: E402
    PRESETS,
    BodyParams,
    body_params,
    default_dims,
    generate_body,
)
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
COLOURS = {
    "sedan": "#3b6fb6",
    "suv": "#2f8f6b",
    "pickup": "#c0612b",
    "van": "#7a5aa6",
    "bus": "#c9a227",
}
LIGHT = np.array([0.45, 0.55, 0.70]) / np.linalg.norm([0.45, 0.55, 0.70])


GLASS = "#27384a"


def glass_faces(mesh: trimesh.Trimesh, p: BodyParams) -> np.ndarray:
    """Faces drawn as windows: the cabin's sides, windshield and rear window above the
    beltline (a drawing aid only: the body is one solid)."""
    tri = mesh.triangles
    d = p.length / 2 - tri[:, :, 0]  # distance of each corner from the front face
    cabin = np.all((d >= p.windshield_base) & (d <= p.rear_window_end), axis=1)
    above = np.all(tri[:, :, 2] >= p.beltline - 1e-9, axis=1)
    return cabin & above & (mesh.face_normals[:, 2] < 0.95)


def shade(
    colours: np.ndarray, normals: np.ndarray, light: np.ndarray = LIGHT, ambient: float = 0.45
) -> np.ndarray:
    """RGBA per face: its RGB colour lit by a directional light plus ambient."""
    lit = ambient + (1.0 - ambient) * np.clip(normals @ light, 0.0, 1.0)
    rgb = np.clip(colours * lit[:, None] + 0.08 * lit[:, None], 0.0, 1.0)
    return np.column_stack([rgb, np.ones(len(rgb))])


def face_colours(mesh: trimesh.Trimesh, p: BodyParams, colour: str) -> np.ndarray:
    rgb = np.tile(matplotlib.colors.to_rgb(colour), (len(mesh.faces), 1))
    rgb[glass_faces(mesh, p)] = matplotlib.colors.to_rgb(GLASS)
    return rgb


def draw_3d(ax, mesh: trimesh.Trimesh, colours: np.ndarray) -> None:
    lo, hi = mesh.bounds
    # a soft ground shadow: the plan outline at z = 0
    plan = mesh.vertices[:, :2]
    hull = trimesh.convex.convex_hull(
        np.column_stack([plan, np.zeros(len(plan))]), qhull_options="QbB Pp QJ"
    )
    shadow = hull.vertices[:, :2]
    order = np.argsort(
        np.arctan2(shadow[:, 1] - shadow[:, 1].mean(), shadow[:, 0] - shadow[:, 0].mean())
    )
    ring = np.column_stack([shadow[order], np.zeros(len(order))])
    ax.add_collection3d(Poly3DCollection([ring * [1.03, 1.12, 1]], facecolors=(0, 0, 0, 0.12)))
    light = np.array([0.5, -0.6, 0.62]) / np.linalg.norm([0.5, -0.6, 0.62])
    faces = Poly3DCollection(
        mesh.triangles,
        facecolors=shade(colours, mesh.face_normals, light),
        edgecolors=(0, 0, 0, 0.06),
        linewidths=0.15,
    )
    ax.add_collection3d(faces)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1] - 0.1, hi[1] + 0.1)
    ax.set_zlim(0.0, hi[2])
    ax.set_box_aspect((hi[0] - lo[0], hi[1] - lo[1] + 0.2, hi[2]), zoom=1.0)
    ax.view_init(elev=20, azim=-58)
    ax.set_axis_off()


def draw_ortho(ax, mesh: trimesh.Trimesh, colours: np.ndarray, view: str) -> None:
    """Orthographic view with flat shading, faces drawn back to front: "side" looks from the
    right (-y) at the x-z plane (x to the right), "top" from above (+z) at the x-y plane.
    Faces set back from the nearest plane of the body are darkened (the wheel arches)."""
    tri, normals = mesh.triangles, mesh.face_normals
    if view == "side":
        near = -tri[:, :, 1].mean(axis=1)  # larger = nearer the viewer at -y
        uv, facing = tri[:, :, [0, 2]], normals[:, 1] < 0
        light = np.array([0.3, -0.8, 0.52])
    else:
        near = tri[:, :, 2].mean(axis=1)
        uv, facing = tri[:, :, [0, 1]], normals[:, 2] > 0
        light = np.array([0.3, -0.45, 0.84])
    light = light / np.linalg.norm(light)
    keep = np.flatnonzero(facing)
    keep = keep[np.argsort(near[keep], kind="stable")]
    rgba = shade(colours[keep], normals[keep], light, ambient=0.6)
    if view == "side":
        recess = np.clip((near.max() - near[keep]) / 0.25, 0.0, 1.0)
        rgba[:, :3] *= (1.0 - 0.55 * recess)[:, None]
    ax.add_collection(PolyCollection(uv[keep], facecolors=rgba, edgecolors=rgba, linewidths=0.3))


def wheels(ax, p: BodyParams) -> None:
    front = p.length / 2 - p.front_overhang
    for x in (front, front - p.wheelbase):
        ax.add_patch(
            Circle(
                (x, p.wheel_radius),
                p.wheel_radius,
                fill=False,
                ls=(0, (3, 2)),
                lw=0.9,
                ec="0.35",
                zorder=3,
            )
        )
        ax.plot([x], [p.wheel_radius], marker="+", color="0.35", ms=5, zorder=3)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO / "docs" / "img" / "bodies.png")
    args = parser.parse_args(argv)
    params = {pr: body_params(pr, **default_dims(pr)) for pr in PRESETS}
    meshes = {pr: generate_body(p) for pr, p in params.items()}
    # one scale for the light vehicles, one for the bus: (half length, top, half width) in m
    groups = {"bus": ["bus"], "light": [pr for pr in PRESETS if pr != "bus"]}
    limits = {
        name: (
            max(params[pr].length for pr in members) / 2 + 0.3,
            max(params[pr].height for pr in members) + 0.15,
            max(params[pr].width for pr in members) / 2 + 0.15,
        )
        for name, members in groups.items()
    }

    fig = plt.figure(figsize=(12, 16), dpi=110)
    outer = fig.add_gridspec(
        len(PRESETS),
        2,
        width_ratios=[1.0, 1.75],
        hspace=0.18,
        wspace=0.02,
        left=0.02,
        right=0.98,
        top=0.955,
        bottom=0.035,
    )
    fig.suptitle(
        "crashsim.vehicles.generator: the five preset bodies (one closed shell each; dimensions of "
        "the built-in vehicle classes)",
        fontsize=13,
        y=0.985,
    )
    for row, preset in enumerate(PRESETS):
        p, mesh = params[preset], meshes[preset]
        half_l, top_z, half_w = limits["bus" if preset == "bus" else "light"]
        colours = face_colours(mesh, p, COLOURS[preset])
        ax3 = fig.add_subplot(outer[row, 0], projection="3d")
        draw_3d(ax3, mesh, colours)
        ax3.set_title(preset, fontsize=14, fontweight="bold", loc="left", y=0.88)
        inner = outer[row, 1].subgridspec(2, 1, height_ratios=[top_z, 2 * half_w], hspace=0.08)
        side = fig.add_subplot(inner[0])
        draw_ortho(side, mesh, colours, "side")
        wheels(side, p)
        side.axhline(0.0, color="0.3", lw=0.8)
        side.set_xlim(-half_l, half_l)
        side.set_ylim(-0.05, top_z)
        side.set_aspect("equal", anchor="W")
        side.set_ylabel("z (m)")
        side.tick_params(labelbottom=False, labelsize=8)
        side.set_title(
            f"L {p.length:.2f} x W {p.width:.2f} x H {p.height:.2f} m, wheelbase "
            f"{p.wheelbase:.2f} m, {len(mesh.faces)} triangles"
            + (" (drawn at a smaller scale)" if preset == "bus" else ""),
            loc="right",
            fontsize=9,
            color="0.25",
            pad=3,
        )
        top = fig.add_subplot(inner[1], sharex=side)
        draw_ortho(top, mesh, colours, "top")
        top.set_ylim(-half_w, half_w)
        top.set_aspect("equal", anchor="W")
        top.set_ylabel("y (m)")
        top.tick_params(labelsize=8)
        for ax in (side, top):
            ax.grid(True, color="0.9", lw=0.6)
            ax.set_axisbelow(True)
            for spine in ax.spines.values():
                spine.set_color("0.7")
        if row == len(PRESETS) - 1:
            top.set_xlabel(
                "x (m), forward to the right; side view from the right (-y), top view "
                "from above; dashed: wheel positions"
            )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
