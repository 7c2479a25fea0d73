"""ColonMapViewer: a ColonSupineProne run in 3D Slicer (issue 23, DESIGN 2.5).

Loads an output folder into the scene (the two CTs, the registration and the surfaces, the findings
and their prone images, the error table), shows the supine and the prone CT with Slicer's own
volume rendering in two 3D views side by side, and keeps the prone camera linked to the supine one
while the user flies through: each change of the supine camera is mapped through the registration
(ColonMapViewerLib.CameraLinking, the same mapping as ColonEndoluminalViews), at most once per
UPDATE_INTERVAL_MS so that the views stay interactive. A list of findings jumps both views to a
finding; a check box unlinks the views.

The Slicer-facing code is here; the mapping and the folder reading are plain Python + numpy + VTK
in ColonMapViewerLib (tested outside Slicer). The scene is RAS, our files are LPS.
"""
import os

import ctk
import numpy as np
import qt
import slicer
import vtk
from slicer.ScriptedLoadableModule import (ScriptedLoadableModule, ScriptedLoadableModuleLogic,
                                           ScriptedLoadableModuleTest, ScriptedLoadableModuleWidget)

from ColonMapViewerLib.CameraLinking import CameraLinker, CameraPose, lps_to_ras, ras_to_lps
from ColonMapViewerLib.RunFolder import RunFolder

# One camera update takes well under a millisecond (measured: docs/slicer.md); the throttle keeps
# the prone view from re-rendering on every mouse event of the supine one.
UPDATE_INTERVAL_MS = 30
# Air transparent, the wall (the air/tissue edge at about -500 HU) opaque: the endoluminal look of
# ColonEndoluminalViews' preset.
WALL_OPACITY = ((-1024.0, 0.0), (-650.0, 0.0), (-450.0, 1.0), (3000.0, 1.0))
WALL_COLOUR = ((-1024.0, (0.0, 0.0, 0.0)), (-450.0, (0.86, 0.55, 0.45)), (300.0, (1.0, 0.85, 0.75)))


class ColonMapViewer(ScriptedLoadableModule):
    def __init__(self, parent):
        ScriptedLoadableModule.__init__(self, parent)
        self.parent.title = "Colon Map Viewer"
        self.parent.categories = ["ColonMap"]
        self.parent.dependencies = []
        self.parent.contributors = ["ColonMap developers"]
        self.parent.helpText = (
            "Loads a Colon Supine Prone output folder and shows the supine and prone CTs side by side in two "
            "3D views, the prone camera linked to the supine one through the registration. Click a finding to "
            "look at it in both views. See docs/slicer.md in the ColonMap repository.")
        self.parent.acknowledgementText = "Research software, not for clinical use."


class ColonMapViewerWidget(ScriptedLoadableModuleWidget):
    def setup(self):
        ScriptedLoadableModuleWidget.setup(self)
        self.logic = ColonMapViewerLogic()
        form = qt.QFormLayout()
        box = ctk.ctkCollapsibleButton()
        box.text = "Run"
        box.setLayout(form)
        self.layout.addWidget(box)
        self.folderButton = ctk.ctkDirectoryButton()
        self.folderButton.caption = "Colon Supine Prone output folder"
        form.addRow("Output folder:", self.folderButton)
        self.loadButton = qt.QPushButton("Load")
        self.loadButton.toolTip = "Load the run into the scene and show the two linked 3D views"
        form.addRow(self.loadButton)
        self.linkBox = qt.QCheckBox("Link the prone camera to the supine camera")
        self.linkBox.checked = True
        form.addRow(self.linkBox)
        self.findingsList = qt.QListWidget()
        self.findingsList.toolTip = "Click a finding to look at it in both views"
        form.addRow("Findings:", self.findingsList)
        self.statusLabel = qt.QLabel("")
        self.statusLabel.wordWrap = True
        form.addRow(self.statusLabel)
        self.layout.addStretch(1)
        self.loadButton.connect("clicked(bool)", self.onLoad)
        self.linkBox.connect("toggled(bool)", self.onLinkToggled)
        self.findingsList.connect("currentRowChanged(int)", self.onFinding)
        self.logic.statusCallback = self.showStatus

    def cleanup(self):
        self.logic.stopLinking()

    def showStatus(self, text):
        self.statusLabel.text = text

    def onLoad(self):
        try:
            with slicer.util.tryWithErrorDisplay("Could not load the ColonMap run.", waitCursor=True):
                self.logic.load(self.folderButton.directory)
                self.findingsList.clear()
                for label, _, _, words in self.logic.findings:
                    self.findingsList.addItem(label + (f" ({words})" if words else ""))
                self.logic.showSideBySide()
                if self.linkBox.checked:
                    self.logic.startLinking()
        except Exception:  # shown to the user by tryWithErrorDisplay
            pass

    def onLinkToggled(self, linked):
        if linked:
            self.logic.startLinking()
        else:
            self.logic.stopLinking()

    def onFinding(self, row):
        if row >= 0:
            self.logic.jumpToFinding(row)


class ColonMapViewerLogic(ScriptedLoadableModuleLogic):
    def __init__(self):
        ScriptedLoadableModuleLogic.__init__(self)
        self.run = None
        self.linker = None
        self.findings = []
        self.nodes = {}
        self.views = None  # (supine view node, prone view node)
        self.statusCallback = None
        self._observed = None
        self._timer = qt.QTimer()
        self._timer.setSingleShot(True)
        self._timer.setInterval(UPDATE_INTERVAL_MS)
        self._timer.connect("timeout()", self.updateProneCamera)

    def status(self, text):
        if self.statusCallback:
            self.statusCallback(text)
        else:
            print(text)

    # Loading.
    def load(self, folder):
        """Reads the run, builds the camera linker (about 0.3 s on a 60 000-vertex registration) and
        loads what the folder has into the scene."""
        self.stopLinking()
        self.run = RunFolder(folder)
        self.linker = CameraLinker.from_file(self.run.registration)
        self.findings = self.run.findings()
        self.nodes = {}
        for scan, path in self.run.volumes.items():
            if path:
                self.nodes[scan + "Volume"] = slicer.util.loadVolume(path, {"show": False})
        self.nodes["registration"] = slicer.util.loadModel(self.run.registration)
        for scan, path in self.run.surfaces.items():
            if path:
                self.nodes[scan + "Surface"] = slicer.util.loadModel(path)
        for name, path in self.run.markups.items():
            if path:
                self.nodes[name] = slicer.util.loadMarkups(path)
        if self.run.table:
            self.nodes["errors"] = slicer.util.loadTable(self.run.table)
        for name in ("registration", "supineSurface", "proneSurface"):
            if name in self.nodes:
                self.nodes[name].GetDisplayNode().SetVisibility(False)  # the volumes are what we fly through
        missing = [scan for scan in ("supine", "prone") if not self.run.volumes[scan]]
        self.status(f"Loaded {folder}: {len(self.findings)} findings" +
                    (f"; no {' and no '.join(missing)} CT found" if missing else ""))

    def showSideBySide(self):
        """Supine in the left 3D view, prone in the right, each volume-rendered in its view only."""
        layoutManager = slicer.app.layoutManager()
        layoutManager.setLayout(slicer.vtkMRMLLayoutNode.SlicerLayoutDual3DView)
        self.views = (layoutManager.threeDWidget(0).mrmlViewNode(), layoutManager.threeDWidget(1).mrmlViewNode())
        vr = slicer.modules.volumerendering.logic()
        for scan, view in zip(("supine", "prone"), self.views):
            volume = self.nodes.get(scan + "Volume")
            if volume is None:
                continue
            display = vr.CreateDefaultVolumeRenderingNodes(volume)
            display.RemoveAllViewNodeIDs()
            display.AddViewNodeID(view.GetID())
            self._wallTransfer(display.GetVolumePropertyNode().GetVolumeProperty())
            display.SetVisibility(True)

    @staticmethod
    def _wallTransfer(volumeProperty):
        opacity = vtk.vtkPiecewiseFunction()
        for x, y in WALL_OPACITY:
            opacity.AddPoint(x, y)
        colour = vtk.vtkColorTransferFunction()
        for x, rgb in WALL_COLOUR:
            colour.AddRGBPoint(x, *rgb)
        volumeProperty.SetScalarOpacity(opacity)
        volumeProperty.SetColor(colour)
        volumeProperty.ShadeOn()

    # Cameras.
    def cameraNodes(self):
        logic = slicer.modules.cameras.logic()
        return tuple(logic.GetViewActiveCameraNode(v) for v in self.views)

    @staticmethod
    def pose(cameraNode):
        """The camera node's pose in LPS (the scene is RAS)."""
        return ras_to_lps(CameraPose(cameraNode.GetPosition(), cameraNode.GetFocalPoint(), cameraNode.GetViewUp()))

    @staticmethod
    def setPose(cameraNode, lpsPose):
        p = lps_to_ras(lpsPose)
        cameraNode.SetPosition(p.position.tolist())
        cameraNode.SetFocalPoint(p.focal_point.tolist())
        cameraNode.SetViewUp(p.view_up.tolist())
        cameraNode.ResetClippingRange()

    def startLinking(self):
        if self.linker is None or self.views is None or self._observed:
            return
        supine = self.cameraNodes()[0]
        self._observed = (supine, supine.AddObserver(vtk.vtkCommand.ModifiedEvent, self._onSupineCamera))
        self.updateProneCamera()

    def stopLinking(self):
        if self._observed:
            node, tag = self._observed
            node.RemoveObserver(tag)
            self._observed = None
        self._timer.stop()

    def linked(self):
        return self._observed is not None

    def _onSupineCamera(self, caller, event):
        if not self._timer.isActive():
            self._timer.start()

    def updateProneCamera(self):
        """Maps the supine camera to the prone view (kept as it was when the supine view axis or up
        axis leaves the colon, e.g. looking out of an open end)."""
        if self.linker is None or self.views is None:
            return
        supine, prone = self.cameraNodes()
        try:
            _, pronePose = self.linker.link_camera(self.pose(supine))
        except ValueError as e:
            self.status(f"Prone view not updated: {e}")
            return
        self.setPose(prone, pronePose)

    def jumpToFinding(self, index):
        """Both views to the finding: the supine camera 25 mm before it on the centreline, looking at
        it (as ColonEndoluminalViews), and its prone twin."""
        if self.views is None:
            return
        label, supineLps, _, _ = self.findings[index]
        supinePose, pronePose = self.linker.link_finding(np.array(supineLps), 25.0)
        supine, prone = self.cameraNodes()
        wasLinked = self.linked()
        self.stopLinking()
        self.setPose(supine, supinePose)
        self.setPose(prone, pronePose)
        if wasLinked:
            self.startLinking()
        self.status(f"Finding {label}")


class ColonMapViewerTest(ScriptedLoadableModuleTest):
    """Runs inside 3D Slicer only (it needs the scene, the views and volume rendering). On a
    synthetic run whose registration shifts the wall by 10 mm (LPS x), every linked prone camera is
    the supine one shifted by 10 mm: checked after moving the supine camera, after jumping to a
    finding, and not followed once unlinked."""

    def setUp(self):
        slicer.mrmlScene.Clear()

    def runTest(self):
        self.setUp()
        self.test_LinkedCamerasFollowTheRegistration()

    def _makeRun(self, folder):
        import json
        from ColonMapViewerLib.SyntheticRegistration import tube_registration, write_vtp
        write_vtp(tube_registration(shift=(10.0, 0.0, 0.0)), os.path.join(folder, "registration.vtp"))
        os.makedirs(os.path.join(folder, "cleansing"), exist_ok=True)
        ct = np.full((40, 40, 40), 200, dtype=np.int16)
        ct[:, 10:30, 10:30] = -1000  # an air channel
        for scan in ("supine", "prone"):
            node = slicer.util.addVolumeFromArray(ct, name=scan)
            slicer.util.saveNode(node, os.path.join(folder, "cleansing", f"{scan}_cleansed.nrrd"))
            slicer.mrmlScene.RemoveNode(node)
        with open(os.path.join(folder, "summary.json"), "w") as f:
            json.dump({"inputs": {}, "findings": [{"label": "F1", "supine": [15.9, 0.0, 150.0],
                                                   "prone": [25.9, 0.0, 150.0], "uncertaintyMm": 2.0}]}, f)

    def _assertShifted(self, supineNode, proneNode):
        s = ColonMapViewerLogic.pose(supineNode)
        p = ColonMapViewerLogic.pose(proneNode)
        self.assertLess(np.linalg.norm(p.position - s.position - [10.0, 0.0, 0.0]), 0.01)
        d = lambda c: (c.focal_point - c.position) / np.linalg.norm(c.focal_point - c.position)
        self.assertLess(np.linalg.norm(d(p) - d(s)), 1e-3)

    def test_LinkedCamerasFollowTheRegistration(self):
        import tempfile
        self.delayDisplay("ColonMapViewer: linked cameras on a synthetic run")
        folder = tempfile.mkdtemp(prefix="ColonMapViewerTest-")
        self._makeRun(folder)
        logic = ColonMapViewerLogic()
        logic.load(folder)
        self.assertEqual(len(logic.findings), 1)
        self.assertIn("supineVolume", logic.nodes)
        logic.showSideBySide()
        logic.startLinking()
        supine, prone = logic.cameraNodes()
        # Move the supine camera (RAS): inside the tube, looking along it and a little sideways.
        ColonMapViewerLogic.setPose(supine, CameraPose([1.0, 2.0, 100.0], [3.0, -4.0, 140.0], [0.0, 1.0, 0.3]))
        self.delayDisplay("waiting for the throttled update", UPDATE_INTERVAL_MS * 4)
        self._assertShifted(supine, prone)
        logic.jumpToFinding(0)
        self._assertShifted(supine, prone)
        logic.stopLinking()
        before = ColonMapViewerLogic.pose(prone).position.copy()
        ColonMapViewerLogic.setPose(supine, CameraPose([0.0, 0.0, 60.0], [0.0, 5.0, 90.0], [1.0, 0.0, 0.0]))
        self.delayDisplay("unlinked", UPDATE_INTERVAL_MS * 4)
        self.assertLess(np.linalg.norm(ColonMapViewerLogic.pose(prone).position - before), 1e-9)
        self.delayDisplay("ColonMapViewer test passed")
