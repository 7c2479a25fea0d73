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
  // Makes VTK's threading back end without resetting its thread count (Initialize() would, and
  // in a host's process that count is the host's).
  vtkSMPTools::GetEstimatedNumberOfThreads();
}

}  // namespace colonmap::io
