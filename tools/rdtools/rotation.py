"""Quaternions (w, x, y, z; body -> ground frame, as rockdem writes them) and world vertices."""
import numpy as np


def quat_to_matrix(q):
    """Rotation matrices [..., 3, 3] from unit quaternions [..., 4] (w, x, y, z).
    The quaternion is normalised first, so small drift in stored values does not scale bodies."""
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    R = np.empty(q.shape[:-1] + (3, 3))
    R[..., 0, 0] = 1 - 2 * (y * y + z * z)
    R[..., 0, 1] = 2 * (x * y - w * z)
    R[..., 0, 2] = 2 * (x * z + w * y)
    R[..., 1, 0] = 2 * (x * y + w * z)
    R[..., 1, 1] = 1 - 2 * (x * x + z * z)
    R[..., 1, 2] = 2 * (y * z - w * x)
    R[..., 2, 0] = 2 * (x * z - w * y)
    R[..., 2, 1] = 2 * (y * z + w * x)
    R[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return R


def lean_direction(quaternion):
    """Direction (rad from +x, in [0, 2 pi)) the body leans towards at each sample: the
    horizontal part of its rest vertical axis, the rest pose being the first sample (the output
    starts when shaking starts, after settling). quaternion [n, 4] -> [n]."""
    R = quat_to_matrix(quaternion)
    z = R @ (R[0].T @ np.array([0.0, 0.0, 1.0]))
    return np.mod(np.arctan2(z[:, 1], z[:, 0]), 2 * np.pi)


def alpha_toward(table, psi):
    """Static tipping angle (rad) towards lean directions psi, interpolated (periodically) from
    a precariousness table [n][3] (direction, alpha, g tan alpha; /bodies/precariousness)."""
    t = np.asarray(table, float)
    d = np.mod(t[:, 0], 2 * np.pi)
    o = np.argsort(d)
    return np.interp(np.asarray(psi, float), d[o], t[o, 1], period=2 * np.pi)


def world_vertices(position, quaternion, vertices):
    """x = p + R(q) v for one pose: position [3], quaternion [4], vertices [nv, 3]."""
    R = quat_to_matrix(quaternion)
    return np.asarray(position, float)[None, :] + np.asarray(vertices, float) @ R.T


def base_point(vertices, rel_tol=1e-6):
    """Centre of the lowest face-set of a body at rest (body frame): mean of the vertices whose z
    is within rel_tol * size of the lowest. rockdem measures slide at the base centre."""
    v = np.asarray(vertices, float)
    size = max(np.ptp(v, axis=0).max(), 1e-300)
    low = v[:, 2] <= v[:, 2].min() + rel_tol * size
    return v[low].mean(axis=0)
