"""A registration with a known answer, for the tests here and ColonMapViewer's self-test in 3D
Slicer: a straight tube (one segment, circumference 100 mm, so one flat unit is 100 mm) whose
prone image is the supine wall shifted by `shift` mm. Every linked camera is then the supine camera
shifted by `shift`, with the same directions. numpy + VTK only."""
import math

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray


def tube_registration(length_mm=300.0, around=48, along=120, shift=(10.0, 0.0, 0.0)):
    """vtkPolyData as registration.vtp holds it (LPS): points, triangles, point arrays
    SupineFlatUV, PronePosition, SegmentId. The tube runs along z, centred on the z axis."""
    radius = 100.0 / (2 * math.pi)
    n_u, n_v = around + 1, along + 1  # the cut: u = 0 and u = 1 are separate vertices
    i, j = np.meshgrid(np.arange(n_u), np.arange(n_v))
    i, j = i.ravel(), j.ravel()
    a = 2 * math.pi * (i % around) / around
    V = np.stack([radius * np.cos(a), radius * np.sin(a), length_mm * j / along], axis=1)
    uv = np.stack([i / around, (length_mm / 100.0) * j / along], axis=1)
    faces = []
    for jj in range(along):
        for ii in range(around):
            p, q = jj * n_u + ii, jj * n_u + ii + 1
            r, s = p + n_u, q + n_u
            faces += [(p, q, s), (p, s, r)]
    F = np.array(faces, dtype=np.int64)

    poly = vtk.vtkPolyData()
    points = vtk.vtkPoints()
    points.SetData(numpy_to_vtk(V, deep=True))
    poly.SetPoints(points)
    cells = vtk.vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(0, 3 * len(F) + 1, 3), deep=True),
                  numpy_to_vtkIdTypeArray(F.ravel(), deep=True))
    poly.SetPolys(cells)
    for name, values in (("SupineFlatUV", uv), ("PronePosition", V + np.asarray(shift, dtype=float)),
                         ("SegmentId", np.zeros(len(V), dtype=np.int32))):
        array = numpy_to_vtk(values, deep=True)
        array.SetName(name)
        poly.GetPointData().AddArray(array)
    return poly


def write_vtp(poly, path):
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(str(path))
    w.SetInputData(poly)
    if not w.Write():
        raise RuntimeError(f"cannot write {path}")
