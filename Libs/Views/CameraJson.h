#pragma once
// cameras.json (DESIGN §2.0): the views ColonEndoluminalViews made, so a host viewer (Slicer) can
// link its own cameras. Per view: label, image, supine and prone {position, focalPoint, viewUp}
// in LPS mm, the wall points the axes hit, and for findings the supine finding, its mapped prone
// position and the angle between the prone view axis and the direction to it. The same file (or
// any list of {label, position, focalPoint, viewUp}) is accepted as --cameras input.
#include "Views/CameraLink.h"

#include <string>
#include <vector>

namespace colonmap::views {

struct NamedCamera {
  std::string label;
  CameraPose pose;
};

// Reads {"views": [{"label", "supine": {position, focalPoint, viewUp}}, ...]} (our own output),
// {"views": [{"label", "position", "focalPoint", "viewUp"}]} or a bare list of such objects.
// Throws colonmap::InputError(what, path, ...) for unreadable JSON, a missing field or no views.
std::vector<NamedCamera> ReadCameras(const std::string& path, const std::string& what);

struct ViewRecord {
  std::string label, image;
  LinkedView view;
};

// The text of cameras.json (deterministic: fixed key order, no times).
std::string CamerasJsonText(const std::vector<ViewRecord>& views, double viewAngleDeg, int width, int height);

// A file-name-safe form of a label ("P 1/a" -> "P_1_a"; empty -> fallback).
std::string SafeLabel(const std::string& label, const std::string& fallback);

}  // namespace colonmap::views
