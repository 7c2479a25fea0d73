"""Linked endoluminal cameras (DESIGN 2.5) in plain Python: numpy and VTK, no `slicer` import, so
that it runs and is tested outside 3D Slicer and is the same mapping ColonEndoluminalViews uses
(Libs/Views: CameraLink, SkeletonCorrespondence, CameraWall, CameraPose).

A supine camera at o looking at wall point p0 (its view axis hits the wall there) with its up
axis hitting wall point p1 becomes the prone camera at c looking at q0 with up towards q1:
q0, q1 are the images of p0, p1 under the registration (PronePosition combined over the hit
triangle), and c = P(l) + R(l) (o - S(l)) with l the nearest point of the supine skeleton to o,
S and P the supine and prone skeleton points there (row k of one flattened centreline is row k of
the other) and R the rotation that carries that loop of wall from supine to prone.
Frame: e3 = (q0 - c)/|q0 - c|, e1 = (q1 - c) x e3 normalised, e2 = e3 x e1 (the view-up).

Everything comes from registration.vtp alone, in LPS millimetres (the file's frame); 3D Slicer's
scene is RAS, so its cameras go through ras_to_lps / lps_to_ras (x and y negated).
"""
import math

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

# As Libs/Views/SkeletonCorrespondence.h (SkeletonOptions): rows per flat width (one loop
# around), and how many of 8 sectors around a row must be covered for it to count as a loop.
ROWS_PER_WIDTH = 24
SECTORS = 8
MIN_SECTORS = 7


class CameraPose:
    """A VTK / Slicer camera: position, focal point, view-up (numpy 3-vectors, mm)."""

    def __init__(self, position, focal_point, view_up):
        self.position = np.asarray(position, dtype=float)
        self.focal_point = np.asarray(focal_point, dtype=float)
        self.view_up = np.asarray(view_up, dtype=float)

    def flipped_xy(self):
        """The same camera in the other of LPS and RAS (x and y negated)."""
        s = np.array([-1.0, -1.0, 1.0])
        return CameraPose(s * self.position, s * self.focal_point, s * self.view_up)


def ras_to_lps(pose):
    return pose.flipped_xy()


def lps_to_ras(pose):
    return pose.flipped_xy()


def camera_from_points(c, q0, q1):
    """The camera at c looking at q0 with view-up e2 of the DESIGN 2.5 frame (towards q1)."""
    axis = q0 - c
    if not np.linalg.norm(axis) > 1e-9:
        raise ValueError("camera frame: the view-axis point coincides with the camera point")
    e3 = axis / np.linalg.norm(axis)
    side = np.cross(q1 - c, e3)
    if not np.linalg.norm(side) > 1e-6 * max(1.0, np.linalg.norm(q1 - c)):
        raise ValueError("camera frame: the up-axis point lies on the view axis")
    e1 = side / np.linalg.norm(side)
    return CameraPose(c, q0, np.cross(e3, e1))


def _kabsch(h):
    """The proper rotation R minimising sum w |R x - y|^2 from H = sum w x y^T (centred)."""
    u, _, vt = np.linalg.svd(h)
    v = vt.T
    d = np.eye(3)
    d[2, 2] = -1.0 if np.linalg.det(v @ u.T) < 0 else 1.0
    return v @ d @ u.T


def _quaternion(r):
    """Unit quaternion (w, x, y, z) of a rotation matrix."""
    t = np.trace(r)
    if t > 0:
        s = 2.0 * math.sqrt(t + 1.0)
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * math.sqrt(max(0.0, 1.0 + r[i, i] - r[j, j] - r[k, k]))
        q = [0.0] * 4
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    q = np.array(q)
    return q / np.linalg.norm(q)


def _matrix(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _slerp(a, b, t):
    """Spherical interpolation along the shorter arc (as Eigen's Quaternion::slerp)."""
    d = float(np.dot(a, b))
    sign = -1.0 if d < 0 else 1.0
    d = abs(d)
    if d >= 1.0 - 1e-12:
        s0, s1 = 1.0 - t, t
    else:
        theta = math.acos(d)
        s0 = math.sin((1.0 - t) * theta) / math.sin(theta)
        s1 = math.sin(t * theta) / math.sin(theta)
    q = s0 * a + sign * s1 * b
    return q / np.linalg.norm(q)


class RegistrationSurface:
    """The arrays of registration.vtp the linking needs: supine V (n x 3), F (m x 3), SupineFlatUV,
    PronePosition, SegmentId (optional)."""

    def __init__(self, polydata, what="registration"):
        if polydata is None or polydata.GetNumberOfPoints() == 0:
            raise ValueError(f"{what}: no points")
        self.polydata = polydata
        self.V = vtk_to_numpy(polydata.GetPoints().GetData()).astype(float)
        polys = polydata.GetPolys()
        offsets = vtk_to_numpy(polys.GetOffsetsArray())
        if len(offsets) < 2 or np.any(np.diff(offsets) != 3):
            raise ValueError(f"{what}: the surface must be made of triangles")
        self.F = vtk_to_numpy(polys.GetConnectivityArray()).reshape(-1, 3).astype(np.int64)

        def array(name, components, required=True):
            a = polydata.GetPointData().GetArray(name)
            if a is None or a.GetNumberOfTuples() != len(self.V) or a.GetNumberOfComponents() != components:
                if required:
                    raise ValueError(f"{what}: no point array {name} with {components} components")
                return None
            return vtk_to_numpy(a).astype(float).reshape(len(self.V), components)

        self.uv = array("SupineFlatUV", 2)
        self.image = array("PronePosition", 3)
        segment = array("SegmentId", 1, required=False)
        self.segment = None if segment is None else np.rint(segment[:, 0]).astype(int)

    @classmethod
    def read(cls, path):
        """registration.vtp (or any copy of it) from disk, LPS."""
        r = vtk.vtkXMLPolyDataReader()
        r.SetFileName(str(path))
        r.Update()
        if r.GetErrorCode() != 0 or r.GetOutput().GetNumberOfPoints() == 0:
            raise ValueError(f"registration '{path}': cannot be read")
        return cls(r.GetOutput(), f"registration '{path}'")


class LinkedSkeleton:
    """Supine and prone skeletons from the flattened rows (SkeletonCorrespondence.h)."""

    def __init__(self, reg, what="registration"):
        V, F, uv, image = reg.V, reg.F, reg.uv, reg.image
        a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
        face_area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1) / 3.0
        area = np.zeros(len(V))
        for k in range(3):
            np.add.at(area, F[:, k], face_area)
        used = np.nonzero(area > 0)[0]
        segment = reg.segment if reg.segment is not None else np.zeros(len(V), dtype=int)
        rows = []
        for s in sorted(set(segment[used].tolist()), reverse=True):  # anal end first: R, S, D, T, A
            ids = used[segment[used] == s]
            u, v = uv[ids, 0], uv[ids, 1]
            u0, u1, v0, v1 = u.min(), u.max(), v.min(), v.max()
            width = u1 - u0
            if not width > 0:
                continue
            dv = width / ROWS_PER_WIDTH
            n_rows = max(1, int(math.ceil((v1 - v0) / dv)))
            k = np.clip(np.floor((v - v0) / dv).astype(int), 0, n_rows - 1)
            sector = np.clip(np.floor((u - u0) / width * SECTORS).astype(int), 0, SECTORS - 1)
            w = area[ids]
            x, y = V[ids], image[ids]
            sw = np.bincount(k, w, n_rows)
            swv = np.bincount(k, w * v, n_rows)
            swx = np.stack([np.bincount(k, w * x[:, i], n_rows) for i in range(3)], axis=1)
            swy = np.stack([np.bincount(k, w * y[:, i], n_rows) for i in range(3)], axis=1)
            swxy = np.zeros((n_rows, 3, 3))
            for i in range(3):
                for j in range(3):
                    swxy[:, i, j] = np.bincount(k, w * x[:, i] * y[:, j], n_rows)
            covered = np.zeros((n_rows, SECTORS), dtype=bool)
            covered[k, sector] = True
            for r in range(n_rows):
                if not sw[r] > 0 or covered[r].sum() < MIN_SECTORS:
                    continue
                sup, pro = swx[r] / sw[r], swy[r] / sw[r]
                rows.append((s, swv[r] / sw[r], sw[r], sup, pro, _kabsch(swxy[r] - sw[r] * np.outer(sup, pro))))
        if len(rows) < 2:
            raise ValueError(f"{what}: fewer than two loops around the flattened segments (no skeleton)")
        self.segment = np.array([r[0] for r in rows])
        self.supine = np.array([r[3] for r in rows])
        self.prone = np.array([r[4] for r in rows])
        self.rotations = np.array([r[5] for r in rows])
        self.quaternions = np.array([_quaternion(r[5]) for r in rows])
        self.arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(self.supine, axis=0), axis=1))])
        # Per polyline piece, for Project.
        self._a = self.supine[:-1]
        self._d = self.supine[1:] - self.supine[:-1]
        self._len2 = np.einsum("ij,ij->i", self._d, self._d)

    def project(self, p):
        """Nearest point of the supine skeleton polyline: (row, t, distance)."""
        p = np.asarray(p, dtype=float)
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.where(self._len2 > 0, np.einsum("ij,ij->i", p - self._a, self._d) / self._len2, 0.0)
        t = np.clip(t, 0.0, 1.0)
        dist = np.linalg.norm(self._a + t[:, None] * self._d - p, axis=1)
        k = int(np.argmin(dist))  # the first of equal minima, as the C++ loop
        return k, float(t[k]), float(dist[k])

    def arc_at(self, row, t):
        return self.arc[row] + t * (self.arc[row + 1] - self.arc[row])

    def at_arc(self, arc):
        """(row, t) of the supine skeleton point at arc length `arc` (clamped)."""
        arc = min(max(arc, 0.0), self.arc[-1])
        k = int(np.searchsorted(self.arc, arc, side="right"))
        k = min(max(k, 1), len(self.arc) - 1) - 1
        length = self.arc[k + 1] - self.arc[k]
        return k, (min(max((arc - self.arc[k]) / length, 0.0), 1.0) if length > 0 else 0.0)

    def supine_at(self, row, t):
        return (1 - t) * self.supine[row] + t * self.supine[row + 1]

    def prone_at(self, row, t):
        return (1 - t) * self.prone[row] + t * self.prone[row + 1]

    def rotation_at(self, row, t):
        return _matrix(_slerp(self.quaternions[row], self.quaternions[row + 1], t))

    def map_point(self, o):
        """The prone point matching supine point o (on the skeleton: the matching skeleton point)."""
        row, t, _ = self.project(o)
        return self.prone_at(row, t) + self.rotation_at(row, t) @ (np.asarray(o, dtype=float) - self.supine_at(row, t))


class Wall:
    """First wall hit of a ray and nearest wall point, through a VTK cell locator (built once;
    a query then takes well under a millisecond)."""

    def __init__(self, reg):
        self.V, self.F = reg.V, reg.F
        self._poly = vtk.vtkPolyData()
        self._poly.SetPoints(reg.polydata.GetPoints())
        self._poly.SetPolys(reg.polydata.GetPolys())
        self._locator = vtk.vtkCellLocator()
        self._locator.SetDataSet(self._poly)
        self._locator.BuildLocator()
        lo, hi = reg.V.min(axis=0), reg.V.max(axis=0)
        self._reach = 4.0 * float(np.linalg.norm(hi - lo)) + 1.0

    def _bary(self, face, x):
        a, b, c = self.V[self.F[face]]
        e1, e2, d = b - a, c - a, x - a
        d11, d12, d22, d1, d2 = e1 @ e1, e1 @ e2, e2 @ e2, d @ e1, d @ e2
        det = d11 * d22 - d12 * d12
        if not abs(det) > 0:
            return np.array([1.0, 0.0, 0.0])
        l1, l2 = (d22 * d1 - d12 * d2) / det, (d11 * d2 - d12 * d1) / det
        w = np.maximum(np.array([1 - l1 - l2, l1, l2]), 0.0)
        return w / w.sum()

    def cast(self, origin, direction):
        """(face, barycentric, point) of the first wall hit along origin + t direction, or None."""
        n = np.linalg.norm(direction)
        if not n > 0:
            return None
        origin = np.asarray(origin, dtype=float)
        end = origin + self._reach * np.asarray(direction, dtype=float) / n
        t, x, pc = vtk.reference(0.0), [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        sub, cell = vtk.reference(0), vtk.reference(-1)
        # A tiny parametric tolerance: with 0 a ray through a vertex or along an edge can miss
        # every triangle that shares it (the C++ test counts edges as inside).
        if not self._locator.IntersectWithLine(origin.tolist(), end.tolist(), 1e-9, t, x, pc, sub, cell):
            return None
        x = np.array(x)
        return int(cell), self._bary(int(cell), x), x

    def nearest(self, p):
        closest, cell, sub, d2 = [0.0, 0.0, 0.0], vtk.reference(-1), vtk.reference(0), vtk.reference(0.0)
        self._locator.FindClosestPoint(np.asarray(p, dtype=float).tolist(), closest, cell, sub, d2)
        x = np.array(closest)
        return int(cell), self._bary(int(cell), x), x

    def face_normal(self, face, points=None):
        a, b, c = (self.V if points is None else points)[self.F[face]]
        n = np.cross(b - a, c - a)
        return n / np.linalg.norm(n)


class CameraLinker:
    """The prone twin of a supine camera (ColonEndoluminalViews' CameraLinker, DESIGN 2.5)."""

    def __init__(self, reg):
        self.reg = reg
        self.wall = Wall(reg)
        self.skeleton = LinkedSkeleton(reg)

    @classmethod
    def from_file(cls, path):
        return cls(RegistrationSurface.read(path))

    def _image(self, hit):
        face, bary, _ = hit
        return bary @ self.reg.image[self.reg.F[face]]

    def _link(self, o, h0, h1):
        q0, q1 = self._image(h0), self._image(h1)
        row, t, _ = self.skeleton.project(o)
        c = self.skeleton.prone_at(row, t) + self.skeleton.rotation_at(row, t) @ (o - self.skeleton.supine_at(row, t))
        return camera_from_points(o, h0[2], h1[2]), camera_from_points(c, q0, q1)

    def link_camera(self, supine):
        """(supine camera re-aimed at its wall points, prone camera) for a supine CameraPose (LPS).
        Raises ValueError when an axis does not hit the wall (e.g. it leaves through an open end)."""
        o = supine.position
        axis = supine.focal_point - o
        if not np.linalg.norm(axis) > 1e-9:
            raise ValueError("camera: focal point equals position")
        d = axis / np.linalg.norm(axis)
        up = supine.view_up - (supine.view_up @ d) * d
        if not np.linalg.norm(up) > 1e-9:
            raise ValueError("camera: view-up is parallel to the view axis")
        h0, h1 = self.wall.cast(o, d), self.wall.cast(o, up / np.linalg.norm(up))
        if h0 is None:
            raise ValueError("camera: the view axis does not hit the colon wall")
        if h1 is None:
            raise ValueError("camera: the up axis does not hit the colon wall")
        return self._link(o, h0, h1)

    def link_finding(self, finding, distance_mm=25.0, up_hint=(0.0, -1.0, 0.0)):
        """A camera on the supine skeleton `distance_mm` before the finding (towards the anal end)
        looking through it, up = anterior (superior when looking anteriorly), and its prone twin:
        (supine camera, prone camera), as ColonEndoluminalViews --findings."""
        finding = np.asarray(finding, dtype=float)
        row, t, _ = self.skeleton.project(finding)
        o = self.skeleton.supine_at(*self.skeleton.at_arc(self.skeleton.arc_at(row, t) - distance_mm))
        axis = finding - o
        if not np.linalg.norm(axis) > 0.5:
            raise ValueError("finding: too close to the skeleton to look at")
        d = axis / np.linalg.norm(axis)
        h0 = self.wall.cast(o, d) or self.wall.nearest(finding)
        hint = np.asarray(up_hint, dtype=float)
        up = hint - (hint @ d) * d
        if np.linalg.norm(up) < 0.3 * np.linalg.norm(hint):
            superior = np.array([0.0, 0.0, 1.0])
            up = superior - (superior @ d) * d
        h1 = self.wall.cast(o, up / np.linalg.norm(up))
        if h1 is None:
            raise ValueError("finding: the camera's up axis does not hit the colon wall")
        return self._link(o, h0, h1)

    def map_near_wall_point(self, p):
        """The prone image of a supine point near the wall (its foot mapped, its height kept)."""
        p = np.asarray(p, dtype=float)
        foot = self.wall.nearest(p)
        h = (p - foot[2]) @ self.wall.face_normal(foot[0])
        return self._image(foot) + h * self.wall.face_normal(foot[0], self.reg.image)
