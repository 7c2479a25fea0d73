"""ColonMapViewer's logic outside 3D Slicer (numpy + VTK): camera linking, run folders, and a
synthetic registration with a known answer for the tests."""
