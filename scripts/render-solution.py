#!/usr/bin/python3
"""Pictures of a solution from the conefeti driver's HDF5 output (docs/output.md, "HDF5 + XDMF files").

    build/conefeti -options_file petsc-options/brick.opts -scene_refine 8 -output /tmp/brick
    scripts/render-solution.py /tmp/brick.h5 docs/figures/solution-brick.png [--scale S] [--title T]

One PNG with three panels:
  * the deformed bodies (displacements magnified by --scale; by default so that the largest one is 8% of
    the bodies' size), their boundary coloured by the von Mises stress of the tetrahedron behind each face;
  * the contact nodes in the contact plane coloured by status (separated, stick, slip), with the friction
    traction on the first body of the zone as arrows (the opposite of /contact/tangential_stress);
  * the same nodes coloured by the contact pressure.

With --pvpython and ParaView's pvpython on the PATH (Debian: python3-paraview), the deformed bodies are
drawn by ParaView instead (Warp By Vector, coloured by von_mises) into <png>-paraview.png; the default is
matplotlib (mplot3d, a Poly3DCollection of the boundary triangles), which needs only python3-matplotlib.

The boundary: the volume file has one copy of each interface node per subdomain, so the nodes are first
merged per body by their coordinates; a triangle of a tetrahedron then lies on the boundary when no other
tetrahedron of the same body has it. Faces on a contact between two bodies are boundary faces of both.
"""
import argparse, os, shutil, subprocess, sys, tempfile

import h5py
import numpy as np


def boundary(coords, conn, body):
    """Boundary triangles (merged node ids into `points`), the element behind each, and the merged points."""
    nb = body.reshape(-1)
    node_body = np.empty(len(coords), dtype=np.int64)
    node_body[conn.reshape(-1)] = np.repeat(nb, 4)
    scale = np.abs(coords).max() or 1.0
    key = np.round(coords / scale * 1e9).astype(np.int64)
    key = np.concatenate([node_body[:, None], key], axis=1)
    uniq, first, merged = np.unique(key, axis=0, return_index=True, return_inverse=True)
    merged = merged.reshape(-1)
    c = merged[conn]
    faces = np.concatenate([c[:, [1, 2, 3]], c[:, [0, 3, 2]], c[:, [0, 1, 3]], c[:, [0, 2, 1]]])  # outward for positive tets
    elem = np.tile(np.arange(len(conn)), 4)
    s = np.sort(faces, axis=1)
    _, inv, counts = np.unique(s, axis=0, return_inverse=True, return_counts=True)
    once = counts[inv.reshape(-1)] == 1
    return faces[once], elem[once], first


def closed(tris, bodies):
    """Whether the triangles are the boundaries of `bodies` solids without holes: every edge belongs to exactly
    two triangles (closed surfaces) and the Euler characteristic V - E + F is 2 per body (one sphere-like
    surface each; subdomains whose interface nodes were not merged would add a surface each)."""
    e = np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    chi = len(np.unique(tris)) - len(counts) + len(tris)
    return bool(len(tris)) and bool(np.all(counts == 2)) and chi == 2 * bodies


def contact_plane(x, normal=None, touching=None):
    """Two in-plane axes of the contact nodes: drop the coordinate axis along which the normals of the nodes in
    contact point most (a curved zone, e.g. a hemisphere's surface), else the axis with the least spread."""
    if normal is not None and touching is not None and touching.any():
        drop = int(np.argmax(np.abs(normal[touching]).mean(axis=0)))
    else:
        drop = int(np.argmin(x.max(axis=0) - x.min(axis=0)))
    return [i for i in range(3) if i != drop]


def contact_window(C, i, j, touching):
    """The nodes to draw: all, or, when the nodes in contact cover a small part of the zone, those within a square
    twice the size of the part in contact (the Hertz cases: a contact disk of a tenth of the face)"""
    if not touching.any():
        return np.ones(len(C), dtype=bool)
    lo, hi = C[touching][:, [i, j]].min(axis=0), C[touching][:, [i, j]].max(axis=0)
    ext = max(hi - lo)
    span = max(np.ptp(C[:, i]), np.ptp(C[:, j]))
    if ext <= 0 or ext > 0.3 * span:
        return np.ones(len(C), dtype=bool)
    centre, half = 0.5 * (lo + hi), ext
    return (np.abs(C[:, i] - centre[0]) <= half) & (np.abs(C[:, j] - centre[1]) <= half)


def render_matplotlib(h, png, scale, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    X = h["volume/coordinates"][()]
    U = h["volume/displacement"][()]
    T = h["volume/connectivity"][()].astype(np.int64)
    vm = h["volume/von_mises"][()].reshape(-1)
    body = h["volume/body"][()]
    tris, elem, first = boundary(X, T, body)
    size = np.linalg.norm(X.max(axis=0) - X.min(axis=0))
    umax = np.linalg.norm(U, axis=1).max()
    if scale is None:
        scale = 0.08 * size / umax if umax > 0 else 1.0
    P = X + scale * U  # each merged point takes the displacement of its first copy (copies agree to the gluing residual)
    Pm = P[first]
    has_contact = "contact" in h
    fig = plt.figure(figsize=(13, 6.2) if has_contact else (8, 6.2))
    gs = fig.add_gridspec(2, 2, width_ratios=[1.6, 1]) if has_contact else fig.add_gridspec(1, 1)
    ax = fig.add_subplot(gs[:, 0], projection="3d")
    norm = colors.Normalize(vmin=vm.min(), vmax=np.percentile(vm, 99.5))
    cmap = matplotlib.colormaps["viridis"]
    poly = Poly3DCollection(Pm[tris], facecolors=cmap(norm(vm[elem])), edgecolors=(0, 0, 0, 0.15), linewidths=0.2)
    ax.add_collection3d(poly)
    lo, hi = Pm.min(axis=0), Pm.max(axis=0)
    ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=22, azim=-58)
    ax.set_xlabel("x [m]"); ax.set_ylabel("y [m]"); ax.set_zlabel("z [m]")
    sm = cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=ax, shrink=0.6, pad=0.12, label="von Mises stress [Pa]")
    ax.set_title("deformed (displacements x %.3g; largest %.2e m), von Mises stress" % (scale, umax), fontsize=9)
    if has_contact:
        C = h["contact/coordinates"][()]
        st = h["contact/status"][()].reshape(-1)
        p = h["contact/pressure"][()].reshape(-1)
        tau = -h["contact/tangential_stress"][()]  # friction traction on the first body
        nrm = h["contact/normal"][()] if "contact/normal" in h else None
        i, j = contact_plane(C, nrm, st != 0)
        keep = contact_window(C, i, j, st != 0)
        C, st, p, tau = C[keep], st[keep], p[keep], tau[keep]
        names = "xyz"
        span = max(np.ptp(C[:, i]), np.ptp(C[:, j])) or 1.0
        ms = max(4.0, min(60.0, 2.2e4 / len(C) * (1 if len(C) > 1 else 1)))
        axs = fig.add_subplot(gs[0, 1])
        labels = {0: "separated", 1: "stick", 2: "slip"}
        pal = {0: "#bbbbbb", 1: "#1f77b4", 2: "#d62728"}
        for s in (0, 1, 2):
            k = st == s
            axs.scatter(C[k, i], C[k, j], s=ms, c=pal[s], marker="s", label="%s (%d)" % (labels[s], k.sum()), edgecolors="none")
        tn = np.linalg.norm(tau[:, [i, j]], axis=1)
        if tn.max() > 0:
            axs.quiver(C[:, i], C[:, j], tau[:, i], tau[:, j], angles="xy", scale_units="xy", scale=max(np.percentile(tn, 90), 1e-3 * tn.max()) / (0.08 * span), width=0.004, color="k", alpha=0.7)
        axs.set_aspect("equal"); axs.set_xlabel("%s [m]" % names[i]); axs.set_ylabel("%s [m]" % names[j])
        axs.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0), markerscale=1.5)
        axs.set_title("contact nodes by status; arrows: friction traction on the body\n(the 90th percentile of its size is 8% of the zone)", fontsize=8)
        axp = fig.add_subplot(gs[1, 1])
        sc = axp.scatter(C[:, i], C[:, j], s=ms, c=p, cmap="magma_r", marker="s", edgecolors="none")
        axp.set_aspect("equal"); axp.set_xlabel("%s [m]" % names[i]); axp.set_ylabel("%s [m]" % names[j])
        fig.colorbar(sc, ax=axp, label="contact pressure [Pa]", shrink=0.9)
        axp.set_title("contact pressure (largest %.2e Pa)" % p.max(), fontsize=9)
    a = h.attrs
    text = title or "%s: %d nodes, %d tetrahedra, %s" % (_s(a.get("scene", "")), int(a.get("nodes", 0)), int(a.get("tetrahedra", 0)), _s(a.get("reason", "")))
    fig.suptitle(text, fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    plt.close(fig)
    return scale, len(tris), closed(tris, len(np.unique(body)))


def _s(v):
    return v.decode() if isinstance(v, bytes) else str(v)


PVSCRIPT = r"""
import sys
from paraview.simple import *
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipeline()
w = WarpByVector(Input=r, Vectors=['POINTS', 'displacement'], ScaleFactor=float(sys.argv[3]))
d = Show(w)
ColorBy(d, ('CELLS', 'von_mises'))
d.SetScalarBarVisibility(GetActiveViewOrCreate('RenderView'), True)
view = GetActiveViewOrCreate('RenderView')
view.ViewSize = [1200, 700]
view.CameraPosition = [-2.0, -4.5, 3.0]
ResetCamera()
SaveScreenshot(sys.argv[2], view)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("h5", help="the driver's -output file, <basename>.h5")
    ap.add_argument("png")
    ap.add_argument("--scale", type=float, help="magnification of the displacements (default: the largest is 8%% of the size)")
    ap.add_argument("--title")
    ap.add_argument("--pvpython", action="store_true", help="also draw the deformed bodies with ParaView's pvpython, when present")
    ap.add_argument("--check", action="store_true", help="exit 1 unless the drawn boundary is one closed surface per body (every edge in two triangles, "
                    "Euler characteristic 2 per body: bodies without holes) and the PNG was written")
    a = ap.parse_args()
    with h5py.File(a.h5, "r") as h:
        scale, ntri, isclosed = render_matplotlib(h, a.png, a.scale, a.title)
    print("render-solution.py: wrote %s (displacements x %.3g; %d boundary triangles, %s)" % (
        a.png, scale, ntri, "one closed surface per body" if isclosed else "NOT one closed surface per body"))
    if a.check:
        ok = isclosed and os.path.getsize(a.png) > 10000
        print("check: %s" % ("passed" if ok else "failed"))
        if not ok:
            sys.exit(1)
    if a.pvpython:
        pv = shutil.which("pvpython")
        xmf = os.path.splitext(a.h5)[0] + ".xmf"
        if not pv:
            print("render-solution.py: pvpython not found (Debian: python3-paraview); the matplotlib picture is the only one")
        else:
            out = os.path.splitext(a.png)[0] + "-paraview.png"
            with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
                f.write(PVSCRIPT)
            try:
                subprocess.run([pv, "--force-offscreen-rendering", f.name, xmf, out, "%g" % scale], check=True)
            finally:
                os.remove(f.name)
            print("render-solution.py: wrote %s (pvpython)" % out)


if __name__ == "__main__":
    main()
