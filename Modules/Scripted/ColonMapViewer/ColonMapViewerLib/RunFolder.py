"""What ColonMapViewer loads from a ColonSupineProne output folder (docs/modules/ColonSupineProne.md):
file paths only, so that it is tested outside 3D Slicer. No `slicer` import."""
import json
import os


class RunFolder:
    """The files of one ColonSupineProne run. Paths are None when the run did not make them (a run
    with --skipViews, without findings, or on label maps)."""

    def __init__(self, folder):
        self.folder = os.path.abspath(folder)
        self.registration = self._file("registration.vtp")
        if self.registration is None:
            raise ValueError(f"'{folder}': no registration.vtp (not a ColonSupineProne output folder)")
        summary_path = self._file("summary.json")
        self.summary = {}
        if summary_path:
            try:
                with open(summary_path) as f:
                    self.summary = json.load(f)
            except (OSError, ValueError) as e:
                raise ValueError(f"'{summary_path}': not readable JSON ({e})") from e
        inputs = self.summary.get("inputs", {})
        # The cleansed CTs (tagged fluid turned to air) show the wall best; without cleansing (label
        # map input) the CTs the run was given, when they are still where they were.
        self.volumes = {}
        for scan in ("supine", "prone"):
            cleansed = self._file("cleansing", f"{scan}_cleansed.nrrd")
            given = inputs.get(scan)
            if cleansed is None and given and not inputs.get("labelMaps") and os.path.isfile(given):
                cleansed = os.path.abspath(given)
            self.volumes[scan] = cleansed
        self.surfaces = {"supine": self._file("surface", "supine_surface.vtp"),
                         "prone": self._file("surface", "prone_surface.vtp")}
        findings = inputs.get("findings")
        self.markups = {"findings": os.path.abspath(findings) if findings and os.path.isfile(findings) else None,
                        "findings_prone": self._file("transfer", "findings_prone.mrk.json")}
        self.table = self._file("evaluation", "errors.tsv")
        self.cameras = self._file("views", "cameras.json")

    def _file(self, *parts):
        path = os.path.join(self.folder, *parts)
        return path if os.path.isfile(path) else None

    def findings(self):
        """[(label, supine LPS, prone LPS, description)] from summary.json's findings table."""
        out = []
        for f in self.summary.get("findings", []):
            if "supine" not in f:
                continue
            words = []
            if "uncertaintyMm" in f:
                words.append(f"uncertainty {float(f['uncertaintyMm']):.1f} mm")
            if f.get("reliable") is False:
                words.append("not reliable")
            if f.get("segment"):
                words.append(f"segment {f['segment']}")
            out.append((str(f.get("label", "")), [float(x) for x in f["supine"]],
                        [float(x) for x in f["prone"]] if "prone" in f else None, ", ".join(words)))
        return out
