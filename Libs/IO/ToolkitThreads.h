#pragma once
// Before a module runs work on several threads (ColonSupineProne's two scans at once): ITK and
// VTK build some global state on first use (object factory lists, IO factory registration, the
// thread pools' defaults), which two threads starting at once could build twice. This builds it
// on the calling thread.
namespace colonmap::io {

void PrepareToolkitsForThreads();

}  // namespace colonmap::io
