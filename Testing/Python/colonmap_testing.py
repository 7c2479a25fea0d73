"""Shared helpers of the module tests that run ColonMap programs as a user does."""
import os
import re
import subprocess


class Checks:
    """Counts checks; prints each failure; ends with the 'N passed, N failed' line."""

    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, condition, message):
        if condition:
            self.passed += 1
        else:
            self.failed += 1
            print("FAIL: " + message)
        return condition

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 1 if self.failed else 0


def run_program(*args):
    """Runs a command with no standard input; returns the CompletedProcess (text output)."""
    return subprocess.run(list(args), capture_output=True, text=True, stdin=subprocess.DEVNULL)


def return_parameters(path):
    """The `name = value` lines of a --returnparameterfile, as a dict ({} when missing)."""
    if not os.path.exists(path):
        return {}
    return {m.group(1): m.group(2).strip() for m in re.finditer(r"^(\w+) = (.*)$", open(path).read(), re.M)}


def _flip_ras_lps(polydata):
    """Points (x, y) negated as Slicer's model storage does between LPS files and its RAS scene."""
    import vtk
    transform = vtk.vtkTransform()
    transform.Scale(-1, -1, 1)
    f = vtk.vtkTransformPolyDataFilter()
    f.SetTransform(transform)
    f.SetInputData(polydata)
    f.Update()
    out = vtk.vtkPolyData()
    out.ShallowCopy(f.GetOutput())
    return out


def slicer_model_copy(src, dst):
    """What Slicer 5 hands a CLI module for a geometry input: the model loaded from `src` (a file
    without SPACE is taken as LPS and flipped to RAS), then written to the temporary `dst` flipped
    back to LPS with a SPACE=LPS string in the field data, zlib-compressed, appended. Nothing
    written beside `src` comes along."""
    import vtk
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(src)
    r.Update()
    scene = _flip_ras_lps(r.GetOutput())
    data = _flip_ras_lps(scene)
    space = vtk.vtkStringArray()
    space.SetName("SPACE")
    space.InsertNextValue("LPS")
    data.GetFieldData().AddArray(space)
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(dst)
    w.SetInputData(data)
    w.SetCompressorTypeToZLib()
    w.SetDataModeToAppended()
    if not w.Write():
        raise RuntimeError(f"cannot write {dst}")


def without_field_data(src, dst):
    """A copy of a .vtp without its field data (as files written before it existed)."""
    import vtk
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(src)
    r.Update()
    data = vtk.vtkPolyData()
    data.DeepCopy(r.GetOutput())
    data.SetFieldData(vtk.vtkFieldData())
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(dst)
    w.SetInputData(data)
    if not w.Write():
        raise RuntimeError(f"cannot write {dst}")
