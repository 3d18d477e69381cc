"""Draw the bodies of a rockdem run file in 3-D at one output sample (matplotlib).

Fixed bodies (pedestals) are drawn grey at their stored pose; free bodies in colour at the
pose of the chosen sample: position [m] and quaternion (w, x, y, z), body frame to ground
frame, of /position and /quaternion. Axes are x, y, z in metres with equal scales, so
slenderness reads true."""
import textwrap

import numpy as np

from .runfile import Run

FIXED_COLOUR = "0.8"
TITLE_WIDTH = 50  # characters a title line
REFINE = 0.08   # largest drawn edge, as a fraction of the scene's size
AMBIENT = 0.45  # share of a face's colour it keeps facing away from the light
FREE_COLOURS = ("tab:orange", "tab:blue", "tab:green", "tab:red", "tab:purple", "tab:brown")


def quat_matrix(q):
    """Rotation matrix of the unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def body_triangles(run, name, k, sample):
    """Ground-frame triangles [nf, 3, 3] of body `name`; k is its free-body index or None."""
    v, f = run.body_geometry(name)
    if k is None:
        x = np.asarray(run.body_attr(name, "position", np.zeros(3)), float)
        q = np.asarray(run.body_attr(name, "quaternion", np.array([1.0, 0, 0, 0])), float)
    else:
        x = run.data("position")[sample, k]
        q = run.data("quaternion")[sample, k]
    w = v @ quat_matrix(q).T + x
    return w[f]


def refine(tri, max_edge):
    """Split triangles [n, 3, 3] into four at their edge midpoints until no edge exceeds
    max_edge: small faces let matplotlib's per-face depth sort draw a block in front of the
    large top face it stands on."""
    while True:
        e = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)
        big = e > max_edge
        if not big.any():
            return tri
        t = tri[big]
        m01, m12, m20 = 0.5 * (t[:, 0] + t[:, 1]), 0.5 * (t[:, 1] + t[:, 2]), 0.5 * (t[:, 2] + t[:, 0])
        parts = [np.stack(p, axis=1) for p in ((t[:, 0], m01, m20), (m01, t[:, 1], m12),
                                                (m20, m12, t[:, 2]), (m01, m12, m20))]
        tri = np.concatenate([tri[~big]] + parts)


def shade(tri, rgb):
    """Face colours [nf, 3]: rgb lit by a fixed light (Lambert, with a floor of ambient light)."""
    nrm = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-300)
    light = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])
    lit = AMBIENT + (1 - AMBIENT) * np.clip(nrm @ light, 0, 1)
    return np.clip(np.outer(lit, rgb), 0, 1)


def draw_scene(path, out, sample=0, title=None, dpi=300, elev=18, azim=-60):
    """Write a picture of run file `path` at output sample `sample` to `out` (PNG or PDF)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    with Run(path) as run:
        free = run.body_names()
        names = run.bodies().names  # every body, fixed ones too
        fig = plt.figure(figsize=(3.6, 3.6))
        ax = fig.add_subplot(projection="3d")
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        parts = [(n, body_triangles(run, n, free.index(n) if n in free else None, sample)) for n in names]
        span = max(np.ptp(np.concatenate([t.reshape(-1, 3) for _, t in parts]), axis=0))
        tris, colours = [], []
        for n, tri in parts:
            k = free.index(n) if n in free else None
            tri = refine(tri, REFINE * span)
            base = matplotlib.colors.to_rgb(FIXED_COLOUR if k is None else FREE_COLOURS[k % len(FREE_COLOURS)])
            tris.append(tri)
            colours.append(shade(tri, base))
            lo, hi = np.minimum(lo, tri.min(axis=(0, 1))), np.maximum(hi, tri.max(axis=(0, 1)))
        # one collection, so matplotlib sorts the faces of all bodies together by depth
        ax.add_collection3d(Poly3DCollection(np.concatenate(tris), facecolors=np.concatenate(colours),
                                             edgecolor="none"))
        half = 0.5 * (hi - lo).max()
        mid = 0.5 * (hi + lo)
        for set_lim, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
            set_lim(m - half, m + half)
        ax.set_box_aspect((1, 1, 1), zoom=0.82)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
        ax.view_init(elev=elev, azim=azim)
        t = run.time()[sample]
        ax.locator_params(nbins=4)
        text = title or "%s, t = %.2f s" % (run.title or path, t)
        ax.set_title(textwrap.fill(text, TITLE_WIDTH), fontsize=8)
        fig.tight_layout()
        fig.savefig(out, dpi=dpi)
        plt.close(fig)
