#include "IO/ToolkitThreads.h"

#include "IO/ItkImageBridge.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkXMLPolyDataReader.h>

namespace colonmap::io {

void PrepareToolkitsForThreads() {
  detail::ItkPrepareForThreads();
  vtkNew<vtkPolyData> mesh;  // vtkObjectFactory's list, made on the first New()
  vtkNew<vtkXMLPolyDataReader> reader;
  vtkSMPTools::Initialize();
}

}  // namespace colonmap::io
