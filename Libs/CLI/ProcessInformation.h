#pragma once
// SlicerExecutionModel's ModuleProcessInformation, C layout (DESIGN §3.1a). When Slicer loads a
// module into its own process it passes a pointer to one with --processinformationaddress.
namespace colonmap::cli {

extern "C" {
struct ModuleProcessInformation {
  unsigned char Abort;  // set to 1 by the host to cancel
  float Progress;       // overall, 0..1
  float StageProgress;  // current stage, 0..1
  char ProgressMessage[1024];
  void (*ProgressCallbackFunction)(void*);
  void* ProgressCallbackClientData;
  double ElapsedTime;   // seconds
};
}

static_assert(sizeof(void*) != 8 || sizeof(ModuleProcessInformation) == 1064,
              "ModuleProcessInformation must keep SlicerExecutionModel's layout");

// Parses "0x7ffd..." (as printed by %p). Returns nullptr for an empty or malformed address.
ModuleProcessInformation* ProcessInformationFromAddress(const char* address);

}  // namespace colonmap::cli
