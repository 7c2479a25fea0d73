#include "Views/EndoluminalRenderer.h"

#include "Core/Error.h"
#include "Views/RenderWindowGrab.h"
#include "Views/StoppableRayCastMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>

namespace colonmap::views {

struct EndoluminalRenderer::Impl {
  RenderDisplay display;  // first: outlives the window that uses it
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<StoppableRayCastMapper> mapper;
  vtkNew<vtkVolume> volume;
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  vtkNew<vtkColorTransferFunction> colour;
  vtkNew<vtkLight> light;
  vtkNew<vtkLight> ring[4];

  // The picture being rendered: its progress, how far it got, and what stopped it (Cancelled or
  // another error of the sink, rethrown once VTK has returned: nothing is thrown through VTK).
  ProgressSink* progress = nullptr;
  double reported = 0.0;
  std::exception_ptr stopped;

  // Called by VTK on the rendering thread: from the gradient pass (every 8 slices of its first
  // thread) and from the ray casting's abort checks (at most every 0.2 s).
  void Poll(double fraction) {
    if (!progress || stopped) return;
    reported = std::max(reported, fraction);
    try {
      progress->Report(reported);
    } catch (...) {
      stopped = std::current_exception();
      mapper->Stop();             // the rest of the gradient pass: nothing to compute
      window->SetAbortRender(1);  // the ray casting: ends at its next row
    }
  }
  void OnGradients(vtkObject*, unsigned long, void* data) {
    Poll(0.8 * std::clamp(data ? *static_cast<double*>(data) : 0.0, 0.0, 1.0));
  }
  void OnAbortCheck(vtkObject*, unsigned long, void*) { Poll(0.9); }
};

EndoluminalRenderer::EndoluminalRenderer(const EndoluminalRenderOptions& options) : options_(options) {
  if (options_.width < 16 || options_.height < 16 || options_.width > 4096 || options_.height > 4096)
    throw Error("image size " + std::to_string(options_.width) + "x" + std::to_string(options_.height) +
                ": must be 16..4096 pixels each way");
  if (!(options_.viewAngleDeg >= 10 && options_.viewAngleDeg <= 170))
    throw Error("view angle " + std::to_string(options_.viewAngleDeg) + ": must be 10..170 degrees");
  if (!(options_.cropRadiusMm > 5)) throw Error("crop radius: must be more than 5 mm");
  if (options_.sampleDistanceMm < 0) throw Error("sample distance: must be >= 0 (0: automatic)");
  const VolumeRenderPreset preset = EndoluminalPreset(options_.preset);
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.display.display = OpenRenderDisplayOrThrow("rendering");  // a throw here frees impl_ with the object
  m.window->SetDisplayId(m.display.display);
  for (const auto& p : preset.opacity) m.opacity->AddPoint(p[0], p[1]);
  for (const auto& c : preset.colour) m.colour->AddRGBPoint(c[0], c[1], c[2], c[3]);
  m.property->SetScalarOpacity(m.opacity);
  m.property->SetColor(m.colour);
  m.property->SetInterpolationTypeToLinear();
  m.property->ShadeOn();
  m.property->SetAmbient(preset.ambient);
  m.property->SetDiffuse(preset.diffuse);
  m.property->SetSpecular(preset.specular);
  m.property->SetSpecularPower(preset.specularPower);
  m.volume->SetMapper(m.mapper);
  m.volume->SetProperty(m.property);
  // Fixed sampling: VTK's automatic adjustment follows the previous frame's time, which would
  // make the pictures depend on the machine's load.
  m.mapper->AutoAdjustSampleDistancesOff();
  m.mapper->LockSampleDistanceToInputSpacingOff();
  m.mapper->SetImageSampleDistance(1.0);
  m.renderer->AddVolume(m.volume);
  m.renderer->SetBackground(0, 0, 0);
  m.renderer->AutomaticLightCreationOff();
  // An endoscope's light sits at the camera, so the walls running along the view axis are the
  // brightest. VTK's ray caster shades with directional lights only: a headlight leaves those
  // walls black (normal across the light), so four camera lights tilted 45 degrees off the axis
  // (up, down, left, right) stand in for the point light, each lighting the wall on its side.
  m.light->SetLightTypeToHeadlight();
  m.light->SetIntensity(0.45);
  m.renderer->AddLight(m.light);
  const double ring[4][2] = {{0, -1}, {0, 1}, {-1, 0}, {1, 0}};
  for (int i = 0; i < 4; ++i) {
    // Camera-light coordinates: the camera at (0, 0, 1) looking at the origin, up +y.
    m.ring[i]->SetLightTypeToCameraLight();
    m.ring[i]->SetPosition(ring[i][0], ring[i][1], 1);
    m.ring[i]->SetFocalPoint(0, 0, 0);
    m.ring[i]->SetIntensity(0.25);
    m.renderer->AddLight(m.ring[i]);
  }
  m.window->SetOffScreenRendering(1);
  m.window->SetSize(options_.width, options_.height);
  m.window->SetMultiSamples(0);
  m.window->AddRenderer(m.renderer);
  m.mapper->AddObserver(vtkCommand::VolumeMapperComputeGradientsProgressEvent, &m, &Impl::OnGradients);
  m.window->AddObserver(vtkCommand::AbortCheckEvent, &m, &Impl::OnAbortCheck);
  const std::lock_guard<std::mutex> lock(RenderWindowSetupMutex());
  m.window->Start();  // the X window and its context, now and not at the first Render()
}

EndoluminalRenderer::~EndoluminalRenderer() {
  if (!impl_) return;
  const std::lock_guard<std::mutex> lock(RenderWindowSetupMutex());
  impl_->window->Finalize();
}

RgbImage EndoluminalRenderer::Render(const Volume<short>& ct, const CameraPose& camera, const std::string& what,
                                     ProgressSink* progress) {
  Impl& m = *impl_;
  if (ct.NumberOfVoxels() == 0) throw Error(what + ": empty image");
  const Eigen::Vector3d ci = ct.PhysicalToIndex(camera.position);
  for (int a = 0; a < 3; ++a)
    if (!(ci(a) >= -0.5 && ci(a) <= ct.size[a] - 0.5)) throw Error(what + ": the camera lies outside the image");

  // Crop a box of half size cropRadius, its centre half a radius ahead of the camera: nothing
  // behind the camera is seen, so the box reaches 1.5 radii ahead and one radius to the sides.
  // Its size (the gradient estimation over it) is most of the render time.
  const Eigen::Vector3d ahead =
      ct.PhysicalToIndex(camera.position + 0.5 * options_.cropRadiusMm * (camera.focalPoint - camera.position).normalized());
  long lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double r = options_.cropRadiusMm / ct.spacing(a);
    lo[a] = std::max(0L, static_cast<long>(std::floor(ahead(a) - r)));
    hi[a] = std::min(static_cast<long>(ct.size[a]) - 1, static_cast<long>(std::ceil(ahead(a) + r)));
    if (lo[a] > hi[a]) throw Error(what + ": the view lies outside the image");
  }
  vtkNew<vtkImageData> image;
  image->SetDimensions(hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1);
  image->SetSpacing(ct.spacing(0), ct.spacing(1), ct.spacing(2));
  image->SetOrigin(lo[0] * ct.spacing(0), lo[1] * ct.spacing(1), lo[2] * ct.spacing(2));
  image->AllocateScalars(VTK_SHORT, 1);
  short* dst = static_cast<short*>(image->GetScalarPointer());
  const long nx = hi[0] - lo[0] + 1;
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j) {
      std::memcpy(dst, &ct.voxels[ct.Offset(lo[0], j, k)], nx * sizeof(short));
      dst += nx;
    }
  m.mapper->SetInputData(image);
  const double sample = options_.sampleDistanceMm > 0 ? options_.sampleDistanceMm : 0.5 * ct.spacing.minCoeff();
  m.mapper->SetSampleDistance(sample);
  m.mapper->SetInteractiveSampleDistance(sample);

  // The camera in the image's axis-aligned frame: x = D^T (p - origin).
  const Eigen::Matrix3d Dt = ct.direction.transpose();
  const Eigen::Vector3d pos = Dt * (camera.position - ct.origin), focal = Dt * (camera.focalPoint - ct.origin);
  const Eigen::Vector3d up = Dt * camera.viewUp;
  vtkCamera* cam = m.renderer->GetActiveCamera();
  cam->SetPosition(pos.data());
  cam->SetFocalPoint(focal.data());
  cam->SetViewUp(up.data());
  cam->SetViewAngle(options_.viewAngleDeg);
  cam->ParallelProjectionOff();
  cam->SetClippingRange(std::max(0.05, 0.25 * ct.spacing.minCoeff()), 4.0 * options_.cropRadiusMm);
  m.progress = progress;
  m.reported = 0.0;
  m.window->Render();
  m.progress = nullptr;
  if (m.stopped) {  // the picture is unfinished: drop it, and be ready for the next one
    const std::exception_ptr stopped = m.stopped;
    m.stopped = nullptr;
    m.mapper->Rearm();
    m.mapper->RemoveAllInputs();
    std::rethrow_exception(stopped);
  }

  const std::vector<unsigned char> rgb = GrabRgbTopRowFirst(m.window, options_.width, options_.height, what);
  RgbImage out;
  out.width = options_.width;
  out.height = options_.height;
  out.rgb.resize(rgb.size());
  const bool mirror = ct.direction.determinant() < 0;  // a left-handed image: undo the mirror
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const int sx = mirror ? out.width - 1 - x : x;
      const unsigned char* s = rgb.data() + (static_cast<std::size_t>(y) * out.width + sx) * 3;
      std::copy(s, s + 3, &out.rgb[(static_cast<std::size_t>(y) * out.width + x) * 3]);
    }
  // Drop the cropped copy now rather than at the next view.
  m.mapper->RemoveAllInputs();
  return out;
}

}  // namespace colonmap::views
