#include "Views/SurfaceRenderer.h"

#include "Core/Error.h"
#include "Views/EndoluminalRenderer.h"  // OpenRenderDisplay
#include "Views/RenderWindowGrab.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <array>
#include <string>

namespace colonmap::views {

struct SurfaceRenderer::Impl {
  RenderDisplay display;  // first: outlives the window that uses it
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkLight> light;
};

SurfaceRenderer::SurfaceRenderer(const SurfaceRenderOptions& options) : options_(options) {
  if (options_.width < 16 || options_.height < 16 || options_.width > 4096 || options_.height > 4096)
    throw Error("3D picture size " + std::to_string(options_.width) + "x" + std::to_string(options_.height) +
                ": must be 16..4096 pixels each way");
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.display.display = OpenRenderDisplayOrThrow("3D rendering");  // a throw here frees impl_ with the object
  m.window->SetDisplayId(m.display.display);
  m.actor->SetMapper(m.mapper);
  vtkProperty* p = m.actor->GetProperty();
  p->SetInterpolationToGouraud();
  p->SetAmbient(options_.ambient);
  p->SetDiffuse(options_.diffuse);
  p->SetSpecular(0.0);
  p->SetColor(1, 1, 1);
  p->SetAmbientColor(1, 1, 1);
  p->SetDiffuseColor(1, 1, 1);
  m.renderer->AddActor(m.actor);
  m.renderer->SetBackground(options_.background[2] / 255.0, options_.background[1] / 255.0, options_.background[0] / 255.0);
  m.renderer->AutomaticLightCreationOff();
  m.renderer->TwoSidedLightingOn();
  m.light->SetLightTypeToHeadlight();
  m.light->SetIntensity(1.0);
  m.renderer->AddLight(m.light);
  m.window->SetOffScreenRendering(1);
  m.window->SetSize(options_.width, options_.height);
  m.window->SetMultiSamples(0);
  m.window->AddRenderer(m.renderer);
  const std::lock_guard<std::mutex> lock(RenderWindowSetupMutex());
  m.window->Start();  // the X window and its context, now and not at the first Render()
}

SurfaceRenderer::~SurfaceRenderer() {
  if (!impl_) return;
  const std::lock_guard<std::mutex> lock(RenderWindowSetupMutex());
  impl_->window->Finalize();
}

ColourImage SurfaceRenderer::Render(const SurfaceScene& scene, const SurfaceCamera& camera) {
  Impl& m = *impl_;
  const Eigen::Index n = scene.V.rows(), nf = scene.F.rows();
  const bool textured = scene.st.rows() > 0;
  if (scene.V.cols() != 3 || scene.F.cols() != 3 || scene.normals.rows() != n || scene.normals.cols() != 3)
    throw Error("3D picture: the surface's vertices, faces and normals disagree");
  if ((scene.F.array() < 0).any() || (scene.F.array() >= n).any()) throw Error("3D picture: a face refers to a missing vertex");
  if (textured ? (scene.st.rows() != n || scene.st.cols() != 2 || scene.texture.width < 1 || scene.texture.height < 1)
               : static_cast<Eigen::Index>(scene.faceColours.size()) != nf)
    throw Error("3D picture: the surface has neither one colour per face nor texture coordinates per vertex");

  vtkNew<vtkPolyData> poly;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    points->SetPoint(i, scene.V(i, 0), scene.V(i, 1), scene.V(i, 2));
    normals->SetTuple3(i, scene.normals(i, 0), scene.normals(i, 1), scene.normals(i, 2));
  }
  poly->SetPoints(points);
  poly->GetPointData()->SetNormals(normals);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(nf + 1);
  connectivity->SetNumberOfValues(3 * nf);
  for (Eigen::Index f = 0; f <= nf; ++f) offsets->SetValue(f, 3 * f);
  for (Eigen::Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) connectivity->SetValue(3 * f + k, scene.F(f, k));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  poly->SetPolys(polys);

  vtkNew<vtkTexture> texture;
  if (textured) {
    vtkNew<vtkFloatArray> tcoords;
    tcoords->SetNumberOfComponents(2);
    tcoords->SetNumberOfTuples(n);
    for (Eigen::Index i = 0; i < n; ++i) tcoords->SetTuple2(i, scene.st(i, 0), scene.st(i, 1));
    poly->GetPointData()->SetTCoords(tcoords);
    // Tile row y at texture coordinate t = (y + 0.5) / height: image row y as VTK row y.
    vtkNew<vtkImageData> tile;
    tile->SetDimensions(scene.texture.width, scene.texture.height, 1);
    tile->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    unsigned char* dst = static_cast<unsigned char*>(tile->GetScalarPointer());
    for (int y = 0; y < scene.texture.height; ++y)
      for (int x = 0; x < scene.texture.width; ++x) {
        const Bgr c = scene.texture.At(x, y);
        unsigned char* d = dst + (static_cast<std::size_t>(y) * scene.texture.width + x) * 3;
        d[0] = c[2];
        d[1] = c[1];
        d[2] = c[0];
      }
    texture->SetInputData(tile);
    texture->InterpolateOff();
    texture->RepeatOn();
    texture->EdgeClampOff();
    texture->MipmapOff();
    m.actor->SetTexture(texture);
    m.mapper->ScalarVisibilityOff();
  } else {
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetName("Colours");
    colours->SetNumberOfComponents(3);
    colours->SetNumberOfTuples(nf);
    for (Eigen::Index f = 0; f < nf; ++f) {
      const Bgr& c = scene.faceColours[static_cast<std::size_t>(f)];
      colours->SetTypedTuple(f, std::array<unsigned char, 3>{c[2], c[1], c[0]}.data());
    }
    poly->GetCellData()->SetScalars(colours);
    m.actor->SetTexture(nullptr);
    m.mapper->ScalarVisibilityOn();
    m.mapper->SetScalarModeToUseCellData();
    m.mapper->SetColorModeToDirectScalars();
  }
  m.mapper->SetInputData(poly);

  vtkCamera* cam = m.renderer->GetActiveCamera();
  cam->ParallelProjectionOn();
  cam->SetPosition(camera.pose.position.data());
  cam->SetFocalPoint(camera.pose.focalPoint.data());
  cam->SetViewUp(camera.pose.viewUp.data());
  cam->SetParallelScale(camera.parallelScale);
  cam->SetClippingRange(camera.nearClip, camera.farClip);
  m.window->Render();

  const std::vector<unsigned char> rgb = GrabRgbTopRowFirst(m.window, options_.width, options_.height, "3D picture");
  ColourImage out(options_.width, options_.height, {0, 0, 0});
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const unsigned char* s = rgb.data() + (static_cast<std::size_t>(y) * out.width + x) * 3;
      out.Set(x, y, {s[2], s[1], s[0]});  // RGB -> BGR
    }
  // Let go of the mesh now rather than at the next picture.
  m.mapper->RemoveAllInputs();
  m.actor->SetTexture(nullptr);
  return out;
}

}  // namespace colonmap::views
